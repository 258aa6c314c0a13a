#!/usr/bin/python3
"""The scenario JSON Schema for editors (docs/scenario-schema.md), checked with
Debian's python3-jsonschema and python3-yaml:

  * `kestrel schema` prints exactly the committed scenarios/kestrel-scenario.schema.json
    (so the copy editors point at cannot fall behind the key table);
  * it is a valid draft-07 schema;
  * every shipped scenario, and every scenario the tests run (test/harness/data),
    validates: the schema refuses nothing the harness accepts;
  * every STRUCTURAL case of the bad-scenario corpus (an unknown key, a value of
    the wrong type or length, a missing required key or section, both spellings
    of one key, a list where a map belongs or the reverse) is refused, each
    for the reason the case is about (the error's path names the spoiled key).

The corpus's semantic cases (ranges such as a negative mass, a non-unit axis,
a non-positive-definite inertia; rules across keys; --set mistakes) are
`kestrel validate`'s and are only counted here.

Usage: scenario_schema_test.py KESTREL SOURCE_DIR
"""
import copy
import json
import os
import re
import subprocess
import sys


try:
    import jsonschema
    import yaml
except ImportError as e:  # scripts/install-deps.sh host installs python3-jsonschema and python3-yaml
    print(f"scenario_schema_test: {e}: skipped")
    sys.exit(77)

# Structural cases of test/harness/bad_scenarios: file -> a word the schema's
# error must hold (the spoiled key in its JSON path or message; 'object' for
# a document that is not a map of keys).
STRUCTURAL = {
    # unknown keys
    "01_unknown_top_key.yaml": "durtion",
    "02_unknown_nested_key.yaml": "Kp",
    "44_tachometer_misspelt.yaml": "tachometr",
    "144_mc_parameter_of_another_dist.yaml": "angle_std_deg",
    # wrong types, lengths and kinds
    "04_mass_is_text.yaml": "mass",
    "08_vector_wrong_length.yaml": "com",
    "13_divisor_float.yaml": "record_divisor",
    "14_seed_negative.yaml": "seed",
    "16_wheel_model_unknown.yaml": "model",
    "21_wheels_not_list.yaml": "wheels",
    "23_fsw_mode_unknown.yaml": "mode",
    "27_bool_wrong_type.yaml": "hdf5",
    "30_section_not_map.yaml": "outputs",
    "40_sensors_noise_not_bool.yaml": "noise",
    "45_gyro_lsb_text.yaml": "lsb",
    "51_nesting_too_deep.yaml": "description",
    "63_empty_mass.yaml": "mass",
    "64_empty_com.yaml": "com",
    "65_empty_dt_last_in_section.yaml": "dt",
    "136_events_not_list.yaml": "events",
    "137_mc_unknown_dist.yaml": "dist",
    "171_j2_not_a_switch.yaml": "j2",
    "34_empty_file.yaml": "object",
    "70_top_level_list.yaml": "object",
    "71_top_level_scalar.yaml": "object",
    "72_only_comments.yaml": "object",
    # missing required keys, both spellings of one key, a threshold missing
    "15_missing_duration.yaml": "duration",
    "19_rpm_and_si_both.yaml": "Omega_0",
    "143_mc_criterion_without_threshold.yaml": "criteria",
    # list capacities and the integer bounds of the key table
    "46_too_many_thrusters.yaml": "thrusters",
    "26_control_law_out_of_range.yaml": "control_law",
    "42_gyro_divisor_zero.yaml": "divisor",
    "83_seed_overflow.yaml": "seed",
    "84_divisor_huge.yaml": "fsw_divisor",
    "150_plant_substeps_zero.yaml": "plant_substeps",
}


class Yaml12Loader(yaml.SafeLoader):
    """YAML 1.2's numbers, as the harness (yaml-cpp) and editors read them:
    1e-3 is a number (PyYAML's YAML 1.1 would read a string)."""


Yaml12Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"""^(?:[-+]?(?:[0-9][0-9_]*)\.[0-9_]*(?:[eE][-+]?[0-9]+)?
                  |[-+]?(?:[0-9][0-9_]*)(?:[eE][-+]?[0-9]+)
                  |\.[0-9_]+(?:[eE][-+]?[0-9]+)?
                  |[-+]?\.(?:inf|Inf|INF)
                  |\.(?:nan|NaN|NAN))$""", re.X),
    list("-+0123456789."))


NOT_READ = object()


def load(path):
    with open(path, encoding="utf-8") as f:
        return yaml.load(f, Loader=Yaml12Loader)


def errors(validator, doc):
    return sorted(validator.iter_errors(doc), key=lambda e: list(e.absolute_path))


def where(e):
    return "/".join(str(p) for p in e.absolute_path) or "(top level)"


def derived_cases(v, src):
    """Shipped scenarios changed by one structural step, each expectation
    written from the file format (docs/harness.md), not from the schema."""
    out = []
    s1 = load(os.path.join(src, "scenarios", "s1_sun_pointing.yaml"))
    # the wheel keys of wheel_defaults written into every wheel: still valid...
    merged = copy.deepcopy(s1)
    defaults = merged.pop("wheel_defaults")
    merged["wheels"] = [{**defaults, **w} for w in merged["wheels"]]
    # ...and then a wheel without its spin inertia is refused (no default to take it from)
    no_js = copy.deepcopy(merged)
    del no_js["wheels"][0]["J_s"]
    # with wheel_defaults present, a wheel may leave J_s out (s1 itself does)
    ev = load(os.path.join(src, "scenarios", "s1_wheel_failure.yaml"))
    typo = copy.deepcopy(ev)
    typo["events"][0]["actions"][0]["valeu"] = 1.0
    # attitude keys: the MRP or one other form (quaternion, 3-2-1 Euler angles, axis-angle), never two
    def inertial(form):
        return {**s1, "fsw": {**s1["fsw"], "inertial": form}}
    init_aa = copy.deepcopy(s1)
    del init_aa["spacecraft"]["initial"]["sigma_BN"]
    init_aa["spacecraft"]["initial"]["sigma_BN_axis_angle"] = {"axis": [0, 0, 1], "angle_deg": 30}
    ref = copy.deepcopy(ev)
    ref["events"][0]["actions"] = [{"device": "fsw", "action": "reference", "sigma_R0N_quaternion": [1, 0, 0, 0]}]
    cases = [("s1_wheel_failure, an event's reference as a quaternion", ref, None),
             ("s1, fsw.inertial.sigma_R0N_quaternion", inertial({"sigma_R0N_quaternion": [1, 0, 0, 0]}), None),
             ("s1, fsw.inertial.sigma_R0N_euler_321_deg", inertial({"sigma_R0N_euler_321_deg": [1, 2, 3]}), None),
             ("s1, spacecraft.initial.sigma_BN_axis_angle", init_aa, None),
             ("s1, sigma_R0N and sigma_R0N_quaternion",
              inertial({"sigma_R0N": [0, 0, 0], "sigma_R0N_quaternion": [1, 0, 0, 0]}), "sigma_R0N_quaternion"),
             ("s1, sigma_R0N_quaternion of 3 numbers", inertial({"sigma_R0N_quaternion": [1, 0, 0]}),
              "sigma_R0N_quaternion"),
             ("s1, sigma_R0N_axis_angle without angle_deg", inertial({"sigma_R0N_axis_angle": {"axis": [1, 0, 0]}}),
              "angle_deg"),
             ("s1, wheel_defaults merged into the wheels", merged, None),
             ("s1, merged, wheels[0] without J_s", no_js, "J_s"),
             ("s1_wheel_failure, events[0].actions[0].valeu", typo, "valeu"),
             ("s1, fsw.mode: 7", {**s1, "fsw": {**s1["fsw"], "mode": 7}}, "mode"),
             ("s1, spacecraft.inertia 2x2", {**s1, "spacecraft": {**s1["spacecraft"], "inertia": [[1, 0], [0, 1]]}},
              "inertia"),
             ("s1, monte_carlo.runs: 0", {**s1, "monte_carlo": {"runs": 0}}, "runs"),
             ("s1 without fsw", {k: x for k, x in s1.items() if k != "fsw"}, "fsw")]
    for name, doc, key in cases:
        errs = errors(v, doc)
        print(f"derived {name}: " + ("; ".join(f"{where(e)}: {e.message[:80]}" for e in errs[:2]) or "valid"))
        if key is None and errs:
            out.append(f"derived case '{name}' should be valid: {where(errs[0])}: {errs[0].message}")
        if key is not None and not any(key in where(e) or key in e.message for e in errs):
            out.append(f"derived case '{name}' not refused for '{key}'")
    return out


def main():
    kestrel, src = sys.argv[1], sys.argv[2]
    failures = []
    text = subprocess.run([kestrel, "schema"], check=True, capture_output=True, text=True).stdout
    committed_path = os.path.join(src, "scenarios", "kestrel-scenario.schema.json")
    with open(committed_path, encoding="utf-8") as f:
        committed = f.read()
    if text != committed:
        failures.append("scenarios/kestrel-scenario.schema.json differs from `kestrel schema`: "
                        "regenerate it with kestrel schema -o scenarios/kestrel-scenario.schema.json")
    schema = json.loads(text)
    jsonschema.Draft7Validator.check_schema(schema)
    v = jsonschema.Draft7Validator(schema)

    good = []
    for d in ("scenarios", os.path.join("test", "harness", "data")):
        good += [os.path.join(src, d, f) for f in sorted(os.listdir(os.path.join(src, d)))
                 if f.endswith(".yaml")]
    for p in good:
        errs = errors(v, load(p))
        print(f"valid   {os.path.relpath(p, src)}: {len(errs)} schema errors")
        for e in errs[:5]:
            failures.append(f"{os.path.relpath(p, src)}: {where(e)}: {e.message}")

    failures += derived_cases(v, src)

    bad_dir = os.path.join(src, "test", "harness", "bad_scenarios")
    refused = semantic = structural_refused = 0
    for f in sorted(os.listdir(bad_dir)):
        if not f.endswith(".yaml"):
            continue
        with open(os.path.join(bad_dir, f), "rb") as fh:
            raw = fh.read()
        doc = NOT_READ  # YAML-level cases (syntax, aliases, nesting, bytes): nothing for a schema to say
        if f in STRUCTURAL or not re.search(rb"[&*][A-Za-z0-9_]", raw):
            try:
                doc = load(os.path.join(bad_dir, f))  # None: an empty document
            except (yaml.YAMLError, RecursionError, ValueError):
                pass
        errs = errors(v, doc) if doc is not NOT_READ else []
        if f in STRUCTURAL:
            key = STRUCTURAL[f]
            named = [e for e in errs if key in where(e) or key in e.message]
            print(f"refused {f}: " + ("; ".join(f"{where(e)}: {e.message[:90]}" for e in errs[:3]) or "NOT REFUSED"))
            structural_refused += bool(named)
            if not named:
                failures.append(f"bad_scenarios/{f}: structural case not refused for '{key}' "
                                f"({len(errs)} other errors)")
        if b"# target:" in raw or b"# set:" in raw:
            continue  # a --set mistake on another file: not a file to validate
        refused += bool(errs)
        semantic += f not in STRUCTURAL
    for f in STRUCTURAL:
        if not os.path.exists(os.path.join(bad_dir, f)):
            failures.append(f"bad_scenarios/{f}: listed as structural but not in the corpus")
    print(f"schema: {len(good)} good scenarios checked, {structural_refused} of {len(STRUCTURAL)} structural bad "
          f"cases refused for their key; of the {len(STRUCTURAL) + semantic} cases that are files (not --set "
          f"mistakes) the schema refuses {refused}, the rest are kestrel validate's (ranges, cross-key rules, "
          f"YAML syntax)")
    for m in failures:
        print("FAIL:", m)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
