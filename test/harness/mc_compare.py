#!/usr/bin/env python3
"""Two Monte Carlo campaign folders hold the same results (mc_resume_test.sh).

  mc_compare.py A B

The same files in both (a journal or scratch file left behind differs).
The campaign's summary files (summary.csv, mc_runs.json, mc_report_data.json,
mc_report.html, mc_manifest.json) byte for byte, the wall-clock figures
("wall_seconds": x) blanked; every .h5 file dataset for dataset and
attribute for attribute (HDF5 files hold object times in their bytes);
every other file of a run folder as results_digest.py digests it (its
wall-clock lines and keys left out).  Exit 1 naming each difference.
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results_digest  # noqa: E402

WALL = re.compile(rb'"wall_seconds":\s*[-+0-9.eE]+')
SUMMARY = {"summary.csv", "mc_runs.json", "mc_report_data.json", "mc_report.html", "mc_manifest.json"}


def files(d):
    out = set()
    for root, dirs, names in os.walk(d):
        for n in names + [x for x in dirs if not os.listdir(os.path.join(root, x))]:
            out.add(os.path.relpath(os.path.join(root, n), d))
    return out


def item(d, rel):
    p = os.path.join(d, rel)
    if rel.endswith(".h5"):
        out = {}
        results_digest.digest_h5(p, out, rel)
        return out
    if rel in SUMMARY:
        with open(p, "rb") as f:
            return WALL.sub(b'"wall_seconds":0', f.read())
    if rel.endswith(".html"):
        return None  # a run's page: its report_data.json is compared
    return results_digest.digest_text(p)


def main():
    a, b = sys.argv[1], sys.argv[2]
    fa, fb = files(a), files(b)
    bad = 0
    for rel in sorted(fa ^ fb):
        print(f"only in {a if rel in fa else b}: {rel}")
        bad += 1
    for rel in sorted(fa & fb):
        if item(a, rel) != item(b, rel):
            print(f"differs: {rel}")
            bad += 1
    print(f"mc_compare: {len(fa & fb)} files compared, {bad} differences")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
