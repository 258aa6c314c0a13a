#!/usr/bin/env python3
"""Bit-for-bit digests of what `kestrel run` and `kestrel mc` write.

For every shipped reference scenario (S1, S2, S3, S1 in LEO, S3 detumble and
hold and each event scenario) and the shipped S1 Monte Carlo campaign, this runs the `kestrel` program as a user
does, then digests its results folder:

  * every HDF5 dataset's raw bytes, shape and type, and every attribute
    (results.h5, campaign.h5), read with h5py: the files' own bytes hold
    object times, so the bytes of the data are digested, not the file;
  * every text file (summary.txt, manifest.json, report_data.json,
    telemetry.csv, fsw_health.txt, dataflow.dot, the campaign's tables),
    line by line, leaving out only what measures the wall clock (wall_*
    figures, elapsed times), which no refactor can hold still;
  * the HTML pages are the report data and the bundled viewer, digested
    through report_data.json.

  results_digest.py --kestrel BIN --scenarios DIR --work DIR --check FILE
  results_digest.py --kestrel BIN --scenarios DIR --work DIR --write FILE

--check exits 1 and names each differing item when the digests differ from
FILE (written by --write from a build before a change).  The digests are of
the double-precision build on x86-64; other builds skip (exit 77).
"""
import argparse
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys

RUNS = [
    "s1_sun_pointing",
    "s1_wheel_failure",
    "s1_tach_frozen",
    "s1_gyro_dropout",
    "s2_mars_orbit_insertion",
    "s2_thruster_stuck",
    "s3_leo_smallsat",
    "s1_leo_environment",
    "s3_detumble_hold",
]
CAMPAIGN = ("s1_monte_carlo", ["--runs", "6", "-j", "1", "--seed", "7"])  # one thread: rows in run order

# Wall-clock figures: lines (text) and keys (JSON) left out of the digests.
WALL_LINE = re.compile(r"(wall|elapsed|runs_per_s|per_second|rt_factor|started|finished|host)", re.I)
WALL_KEYS = {"wall_seconds", "wall_s", "elapsed_s", "elapsed_seconds", "runs_per_second", "started",
             "finished", "host", "hostname", "date", "created"}


def sha(data):
    return hashlib.sha256(data).hexdigest()[:32]


def scrub_json(o):
    if isinstance(o, dict):
        return {k: scrub_json(v) for k, v in o.items() if k not in WALL_KEYS}
    if isinstance(o, list):
        return [scrub_json(v) for v in o]
    return o


def digest_text(path):
    with open(path, "rb") as f:
        raw = f.read()
    if path.endswith(".json"):
        try:
            o = json.loads(raw)
            return sha(json.dumps(scrub_json(o), sort_keys=True).encode())
        except ValueError:
            pass
    lines = [ln for ln in raw.split(b"\n") if not WALL_LINE.search(ln.decode("utf-8", "replace"))]
    return sha(b"\n".join(lines))


def value_bytes(v):
    """The bytes of a value; strings (also inside object arrays) as UTF-8."""
    import numpy as np
    if isinstance(v, str):
        return v.encode()
    if isinstance(v, bytes):
        return v
    a = np.asarray(v)
    if a.dtype.kind == "O":
        return "\x1f".join(x.decode() if isinstance(x, bytes) else str(x) for x in a.ravel()).encode()
    return a.tobytes()


def digest_h5(path, out, rel):
    import h5py
    import numpy as np

    def attrs(name, obj):
        for k in sorted(obj.attrs.keys()):
            if k in WALL_KEYS:
                continue
            b = value_bytes(obj.attrs[k])
            if k == "manifest":  # JSON text: the wall figures scrubbed as in manifest.json
                try:
                    b = json.dumps(scrub_json(json.loads(b)), sort_keys=True).encode()
                except ValueError:
                    pass
            out[f"{rel}:{name}@{k}"] = sha(b)

    with h5py.File(path, "r") as f:
        attrs("/", f)

        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                a = np.asarray(obj[()])
                out[f"{rel}:/{name}"] = sha(str((a.shape, a.dtype.str)).encode() + value_bytes(a))
            attrs("/" + name, obj)

        f.visititems(visit)


def digest_dir(d, prefix, out):
    for root, _, files in os.walk(d):
        for n in sorted(files):
            p = os.path.join(root, n)
            rel = prefix + "/" + os.path.relpath(p, d).replace(os.sep, "/")
            if n.endswith(".h5"):
                digest_h5(p, out, rel)
            elif n.endswith(".html"):
                continue
            else:
                out[rel] = digest_text(p)


def run(cmd, cwd):
    r = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd)
    if r.returncode not in (0, 6):  # 6: a campaign with failed runs is a result too
        sys.stderr.write(f"{' '.join(cmd)}: exit {r.returncode}\n{r.stdout}\n{r.stderr}\n")
        sys.exit(2)


def digests(kestrel, scenarios, work):
    # The manifests record the scenario path as given: the runs start in the
    # folder above `scenarios` and name it relatively, as in any checkout.
    kestrel, work = os.path.abspath(kestrel), os.path.abspath(work)
    top, sdir = os.path.split(os.path.abspath(scenarios).rstrip(os.sep))
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out = {}
    for name in RUNS:
        d = os.path.join(work, name)
        run([kestrel, "run", f"{sdir}/{name}.yaml", "-o", d, "--csv"], top)
        digest_dir(d, name, out)
    name, args = CAMPAIGN
    d = os.path.join(work, name + "_mc")
    run([kestrel, "mc", f"{sdir}/{name}.yaml", "-o", d] + args, top)
    digest_dir(d, name + "_mc", out)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--kestrel", required=True)
    ap.add_argument("--scenarios", required=True)
    ap.add_argument("--work", required=True)
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--check")
    g.add_argument("--write")
    a = ap.parse_args()
    try:
        import h5py  # noqa: F401
    except ImportError:
        print("results_digest: h5py is missing (scripts/install-deps.sh host installs python3-h5py)")
        return 77
    now = digests(a.kestrel, a.scenarios, a.work)
    if a.write:
        with open(a.write, "w") as f:
            f.write("# results_digest.py --write: item  sha256[:32]  (test/harness/results_digest.py)\n")
            for k in sorted(now):
                f.write(f"{k}  {now[k]}\n")
        print(f"results_digest: {len(now)} digests written to {a.write}")
        return 0
    want = {}
    with open(a.check) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            k, v = line.rsplit(None, 1)
            want[k.strip()] = v
    bad = 0
    for k in sorted(set(want) | set(now)):
        if want.get(k) != now.get(k):
            bad += 1
            print(f"DIFFERS {k}: expected {want.get(k, '(absent)')}, got {now.get(k, '(absent)')}")
    print(f"results_digest: {len(want) - bad} of {len(want)} items bit-identical"
          + ("" if not bad else f", {bad} differ"))
    if not bad:
        shutil.rmtree(a.work, ignore_errors=True)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
