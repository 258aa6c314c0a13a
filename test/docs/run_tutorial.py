#!/usr/bin/env python3
"""Runs the commands of docs/tutorial.md as written (test docs_tutorial).

Every ```sh block preceded by the line <!-- tutorial-test --> is taken, in
page order, into one bash script (set -euo pipefail), which runs in a fresh
temporary folder that looks like the repository root: a link to each
top-level entry of the source tree, and build/host-release linked to this
build.  The only change to the commands is the UDP port of step 5 (5005 ->
a free port, so that parallel tests cannot collide).  Then the results the
page describes are checked against figures computed here:

  * S1 and my_sat end pointed at the Sun (final error < 0.1 deg),
  * the campaign's summary.csv has one row per run, each pass or FAIL,
  * the flight program's torque request is the MRP law for its inputs,
    Lr = -K sigma - P omega (no gyroscopic term: omega is along a principal
    axis), and its four wheel torques deliver it: [Gs] u = -Lr,
  * the link run lost no cycle (link_missing = 0).

  run_tutorial.py --source SRC --build BUILD [--keep]
Exit 0 = the tutorial works; 1 = a command or a check failed.
"""
import argparse
import csv
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile

MARK = "<!-- tutorial-test -->"


def tested_blocks(text):
    lines = text.splitlines()
    blocks, i = [], 0
    while i < len(lines):
        if lines[i].strip() == MARK:
            j = i + 1
            while j < len(lines) and not lines[j].strip():
                j += 1
            if j >= len(lines) or lines[j].strip() != "```sh":
                raise SystemExit("line %d: %s not followed by a ```sh block" % (i + 1, MARK))
            k = j + 1
            while k < len(lines) and lines[k].strip() != "```":
                k += 1
            blocks.append("\n".join(lines[j + 1:k]))
            i = k
        i += 1
    return blocks


def free_udp_port():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def make_root(tmp, source, build):
    for name in os.listdir(source):
        if name in ("build", "results", ".git") or name.startswith("build-"):
            continue
        os.symlink(os.path.join(source, name), os.path.join(tmp, name))
    os.makedirs(os.path.join(tmp, "build"))
    os.symlink(build, os.path.join(tmp, "build", "host-release"))


def summary_value(path, key):
    with open(path, encoding="utf-8") as f:
        for line in f:
            m = re.match(r"\s*%s\s*=\s*([-+0-9.eE]+)" % re.escape(key), line)
            if m:
                return float(m.group(1))
    raise AssertionError("%s: no %s" % (path, key))


def check(tmp, output):
    problems = []

    def expect(cond, what):
        if not cond:
            problems.append(what)

    for run in ("s1", "my_sat"):
        err = summary_value(os.path.join(tmp, "results", run, "summary.txt"), "final_pointing_error_deg")
        expect(err < 0.1, "%s: final pointing error %g deg, not < 0.1" % (run, err))
        expect(os.path.getsize(os.path.join(tmp, "results", run, "report.html")) > 10000, run + ": no report")
    with open(os.path.join(tmp, "results", "s1_mc", "summary.csv"), encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    expect(len(rows) == 8, "campaign: %d rows, expected 8" % len(rows))
    expect(all(r["status"] in ("pass", "FAIL") for r in rows), "campaign: a status other than pass/FAIL")
    expect(sorted(int(r["index"]) for r in rows) == list(range(8)), "campaign: run indices not 0..7")

    # The flight program: sigma_BR = (0, 0, 0.1), omega_BR = (0.01, 0, 0),
    # K = 0.5, P = 6 -> Lr = (-0.06, 0, -0.05); printed to 4 and 5 decimals.
    m = re.search(r"Lr = \(([-0-9.]+), ([-0-9.]+), ([-0-9.]+)\) N\*m", output)
    u = [float(x) for x in re.findall(r"wheel \d: u_s = ([-+0-9.]+) N\*m", output)]
    expect(m is not None and len(u) == 4, "flight_app: output not found")
    if m and len(u) == 4:
        lr = [float(x) for x in m.groups()]
        expect(all(abs(a - b) < 1e-4 for a, b in zip(lr, (-0.06, 0.0, -0.05))), "flight_app: Lr = %s" % lr)
        c, s = 0.541675220, 0.642787610
        gs = [(c, c, s), (-c, c, s), (-c, -c, s), (c, -c, s)]
        delivered = [sum(gs[i][k] * u[i] for i in range(4)) for k in range(3)]
        expect(all(abs(d + l) < 1e-4 for d, l in zip(delivered, lr)),
               "flight_app: [Gs] u = %s, not -Lr = %s" % (delivered, [-x for x in lr]))
    expect(summary_value(os.path.join(tmp, "results", "s1_link", "summary.txt"), "link_missing") == 0,
           "link run: cycles without a reply")
    expect("refused, exit status 3" in output, "validate did not refuse u_max = -1 with exit status 3")
    return problems


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--keep", action="store_true", help="keep the temporary folder")
    a = ap.parse_args()
    source, build = os.path.abspath(a.source), os.path.abspath(a.build)
    with open(os.path.join(source, "docs", "tutorial.md"), encoding="utf-8") as f:
        blocks = tested_blocks(f.read())
    if len(blocks) < 6:
        print("docs/tutorial.md: %d tested blocks, expected at least 6" % len(blocks))
        return 1
    script = "set -euo pipefail\n" + "\n".join(blocks).replace("127.0.0.1:5005", "127.0.0.1:%d" % free_udp_port())
    tmp = tempfile.mkdtemp(prefix="kestrel_tutorial_")
    env = dict(os.environ)
    if "CMAKE_C_COMPILER_LAUNCHER" not in env and shutil.which("ccache"):
        # The flight build compiles the library again; with ccache, paths taken
        # relative to the temporary root make the next run's compiles hits.
        env.update(CMAKE_C_COMPILER_LAUNCHER="ccache", CCACHE_BASEDIR=tmp, CCACHE_NOHASHDIR="1")
    try:
        make_root(tmp, source, build)
        proc = subprocess.Popen(["bash", "-c", script], cwd=tmp, env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True, start_new_session=True)
        try:
            output, _ = proc.communicate(timeout=300)
        finally:
            try:
                os.killpg(proc.pid, signal.SIGKILL)  # anything the script left running (its own group)
            except ProcessLookupError:
                pass
        print(output)
        if proc.returncode != 0:
            print("the tutorial's commands failed (exit status %d)" % proc.returncode)
            return 1
        problems = check(tmp, output)
        for p in problems:
            print("FAIL: " + p)
        print("%d tested blocks ran; %s" % (len(blocks), "all checks passed" if not problems else "checks failed"))
        return 1 if problems else 0
    finally:
        if a.keep:
            print("kept " + tmp)
        else:
            shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
