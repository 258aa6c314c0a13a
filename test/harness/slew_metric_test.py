#!/usr/bin/env python3
"""The headline metric after a commanded slew, in every output of the program.

test/harness/data/slew_137.yaml commands, at t = 1 s, a 137 deg slew from
sun-safe pointing to the inertial reference sigma_R0N = (0.1, -0.05, 0.2).
The flight software tracks it; measured against the scenario's initial
reference (the Sun axis) the craft would end 91.5 deg off, the angle of the
reference's z axis from the Sun, computed here from the MRP.  Every output
must say the slew ended with a small error:

  * `kestrel run`'s line: "final pointing error X deg (principal angle from
    the inertial reference)", X < 0.05;
  * summary.txt and report_data.json: final_pointing_error_deg < 0.05, equal
    to the last recorded pointing_error_deg of results.h5, described as
    measured from the commanded reference;
  * the event triggers on pointing_error_deg: `slewing` (above 120 deg) at
    the first tick after the command, `settled` (below 0.1 deg) after it;
  * `kestrel mc` of the same file: both runs pass the criteria slew_done
    (final below 0.05 deg) and held (max after 25 s below 0.1 deg).

The same craft without the command (--set events=[]) is labelled with the
Sun-axis angle and keeps the summary's plain description.

  slew_metric_test.py KESTREL SCENARIO WORKDIR
"""
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys


def run(args):
    r = subprocess.run(args, capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        sys.exit(f"{' '.join(args)}: exit {r.returncode}\n{r.stdout}\n{r.stderr}")
    return r


def summary(path):
    """summary.txt -> {key: (value, description)}"""
    out = {}
    with open(path) as f:
        for line in f:
            m = re.match(r"^(\w+) = (\S+) .*?# (.*)$", line.rstrip("\n"))
            if m:
                out[m.group(1)] = (float(m.group(2)), m.group(3))
    return out


def sun_angle_of_mrp_deg(s):
    """The angle of the z axis of the frame of MRP s from N x: [RN] row 3, column 1."""
    s2 = sum(x * x for x in s)
    # [RN](3,1) = (8 s3 s1 + 4 (1 - s2) s2_y) / (1 + s2)^2 (Schaub & Junkins' MRP DCM)
    c31 = (8.0 * s[2] * s[0] + 4.0 * (1.0 - s2) * s[1]) / (1.0 + s2) ** 2
    return math.degrees(math.acos(c31))


def main():
    kestrel, scenario, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    bad = []

    def check(ok, what):
        print(("ok   " if ok else "FAIL ") + what)
        if not ok:
            bad.append(what)

    old = sun_angle_of_mrp_deg((0.1, -0.05, 0.2))
    check(abs(old - 91.526) < 1e-3, f"the initial reference would say {old:.3f} deg at the end")

    out = os.path.join(work, "run")
    r = run([kestrel, "run", scenario, "-o", out])
    m = re.search(r"final pointing error (\S+) deg \(([^)]*)\)", r.stdout)
    check(m is not None, "kestrel run prints the final pointing error with what it measures")
    if m:
        line_deg = float(m.group(1))
        check(line_deg < 0.05, f"run line: {line_deg} deg < 0.05")
        check(m.group(2) == "principal angle from the inertial reference", f"run line labels it: {m.group(2)}")
    check("warning" not in r.stderr, "no warning")

    s = summary(os.path.join(out, "summary.txt"))
    v, what = s["final_pointing_error_deg"]
    check(v < 0.05, f"summary.txt: final_pointing_error_deg {v} < 0.05")
    check(what.startswith("principal angle from the inertial reference at the end of the run"),
          f"summary.txt describes it: {what}")

    try:
        import h5py  # Debian's python3-h5py (/usr/bin/python3)
    except ImportError:
        print("slew_metric_test: h5py is missing (scripts/install-deps.sh host installs python3-h5py)")
        return 77
    with h5py.File(os.path.join(out, "results.h5"), "r") as f:
        pe = f["metrics/pointing_error"][...].reshape(-1)
        t = f["t"][...].reshape(-1)
    check(abs(pe[-1] - v) <= 1e-9 * max(1.0, abs(v)), f"summary = last recorded row ({pe[-1]})")
    i_cmd = int(round(1.0 / (t[1] - t[0])))
    check(abs(pe[i_cmd] - 137.0) < 0.1, f"results.h5: {pe[i_cmd]:.3f} deg at the command (t = {t[i_cmd]})")

    with open(os.path.join(out, "report_data.json")) as f:
        rd = json.load(f)
    rv = rd["summary"]["final_pointing_error_deg"]
    check(rv["value"] == v or abs(rv["value"] - v) <= 1e-9 * abs(v), f"report_data.json: {rv['value']}")
    check(rv["what"] == what, "report_data.json describes it as summary.txt")
    ev = {e["name"]: e["t"] for e in rd["events"]}
    check(abs(ev.get("slewing", -1) - 1.01) < 1e-9, f"trigger above 120 deg fired at {ev.get('slewing')} s")
    check(5.0 < ev.get("settled", -1) < 25.0, f"trigger below 0.1 deg fired at {ev.get('settled')} s")

    mc = os.path.join(work, "mc")
    run([kestrel, "mc", scenario, "-o", mc])
    with open(os.path.join(mc, "summary.csv")) as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == 2, "kestrel mc: 2 runs")
    for row in rows:
        check(row["status"] == "pass", f"run {row['index']}: {row['status']} {row['reason']}")
        check(float(row["slew_done [deg]"]) < 0.05, f"run {row['index']}: slew_done {row['slew_done [deg]']}")

    plain = os.path.join(work, "plain")
    r = run([kestrel, "run", scenario, "-o", plain, "--set", "events=[]"])
    check("(Sun-axis angle)" in r.stdout, "without the command the run line says Sun-axis angle")
    v0, what0 = summary(os.path.join(plain, "summary.txt"))["final_pointing_error_deg"]
    check(v0 < 0.05 and what0 == "pointing error at the end of the run", f"... and holds the Sun: {v0}, '{what0}'")

    if bad:
        print(f"slew_metric_test: {len(bad)} failed")
        return 1
    shutil.rmtree(work, ignore_errors=True)
    print("slew_metric_test: all passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
