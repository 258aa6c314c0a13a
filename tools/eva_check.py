#!/usr/bin/env python3
"""Absence of run-time errors in the flight library with Frama-C Eva
(docs/eva.md).

Every driver test/proofs/eva/<name>.c is analysed twice:
  envelope   -main eva_main_envelope, Eva's default float model: the
             configuration values check accepts, bounded by the operating
             envelope where the contract only says "finite"; a NaN or an
             infinity produced by any operation is an alarm;
  any        -main eva_main_any, -warn-special-float none: every accepted
             finite value up to the largest double, and every real sensor
             input also NaN or +-infinity; undefined behaviour (bounds,
             signed overflow, uninitialised reads, float-to-int conversion,
             C library preconditions) is an alarm.
A driver names the library sources it needs on a line
`eva-sources: a.c b.c` (relative to fsw_c/src), and may add Eva options on
a line `eva-options: ...` (both analyses) and on a line
`eva-options-envelope: ...` or `eva-options-any: ...` (that analysis only).
Each analysis is bounded
in time.  The alarms (every property of Frama-C's report whose status is
Unknown or Invalid) are compared with the justified ones of
test/proofs/eva/alarms.txt, one a line:
    driver/analysis | file:function | kind | justification
The check fails on an alarm that is not recorded, on a record that no
alarm matches (stale), on a driver whose entries are not all reached, on a
Frama-C failure and on a timeout.  Then each contract of test/proofs/wp/*.h
is proven with WP (real model, CVC4) on the function its 'wp-target:' line
names, with the WP options of its 'wp-options:' line if it has one; a goal
not proven fails.  Prints a summary table.  --self-test runs the planted
faults of test/proofs/eva_selftest/ and the planted wrong contracts of
test/proofs/wp_selftest/, and passes only if each one is caught.
Exit 0 = pass, 1 = failure, 2 = usage, 77 = Frama-C not installed (skipped).
"""
import argparse
import concurrent.futures
import csv
import os
import re
import subprocess
import sys
import time

ANALYSES = {
    "envelope": ["-main", "eva_main_envelope"],
    "any": ["-main", "eva_main_any", "-warn-special-float", "none"],
}
COMMON = ["-machdep", "x86_64", "-eva", "-eva-auto-loop-unroll", "128",
          "-eva-split-return", "full", "-eva-slevel", "30", "-eva-msg-key=-final-states,-summary",
          "-kernel-warn-key", "CERT:EXP:46=inactive", "-eva-warn-key", "garbled-mix=error"]
ALARM_STATUS = re.compile(r"^(Unknown|Invalid)")
# declared behaviour of specified functions, not checks of the analysed code
NOT_ALARMS = {"assigns clause", "from clause", "postcondition", "termination clause"}
ENTRY = re.compile(r"Frama_C_show_each_eva_entry_(\w+):\s*(.*)$")
WALL_FACTOR = 10  # wall-time bound of an analysis, in multiples of its CPU bound (a loaded machine)


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--root", default=os.path.join(os.path.dirname(__file__), ".."))
    ap.add_argument("--frama-c", default="frama-c")
    ap.add_argument("--work", default=None, help="folder for logs and reports (default: a temporary one)")
    ap.add_argument("--only", nargs="*", default=None,
                    help="drivers (name) or single analyses (name/envelope, name/any); default: all")
    ap.add_argument("--timeout", type=float, default=120.0,
                    help="CPU seconds per analysis (and %d times that of wall time)" % WALL_FACTOR)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--prover", default="cvc4", help="WP prover (Why3 name)")
    ap.add_argument("--no-wp", action="store_true", help="skip the WP proofs")
    ap.add_argument("--self-test", action="store_true",
                    help="run the planted faults of test/proofs/eva_selftest/ and pass only if each is caught")
    return ap.parse_args()


def read_records(path):
    """alarms.txt -> {(driver/analysis, file:function, kind): justification}"""
    recs = {}
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            parts = [p.strip() for p in line.split("|", 3)]
            if len(parts) != 4 or not all(parts):
                raise SystemExit(f"{path}:{n}: want 'driver/analysis | file:function | kind | justification'")
            key = tuple(parts[:3])
            if key in recs:
                raise SystemExit(f"{path}:{n}: duplicate record {key}")
            recs[key] = parts[3]
    return recs


def driver_line(path, key):
    """The words after 'key:' on a driver's line, or None without such a line."""
    with open(path, encoding="utf-8") as f:
        for line in f:
            m = re.search(key + r":\s*(.*?)\s*(\*/)?$", line)
            if m:
                return m.group(1).split()
    return None


def driver_sources(path):
    """The library sources (relative to fsw_c/src) of a driver's 'eva-sources:' line."""
    srcs = driver_line(path, "eva-sources")
    if srcs is None:
        raise SystemExit(f"{path}: no 'eva-sources:' line")
    return srcs


def driver_includes(path):
    """WP contracts (test/proofs/wp/*.h) whose preconditions Eva checks at the calls."""
    return driver_line(path, "eva-include") or []


def driver_options(path, analysis):
    """Extra Eva options of a driver's 'eva-options:' line (e.g. -eva-min-loop-unroll 33 for a loop
    Eva's automatic unrolling does not take because it returns from inside), then those of its
    'eva-options-<analysis>:' line, for that analysis only."""
    return (driver_line(path, "eva-options") or []) + (driver_line(path, "eva-options-" + analysis) or [])


def driver_entries(path):
    """The entries a driver marks with EVA_ENTRY, in its file and in the headers of its
    folder that it includes (a body shared by the drivers of one module's parts), not
    eva_driver.h (which defines the macro)."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    for h in re.findall(r'#include "(\w+\.h)"', text):
        hp = os.path.join(os.path.dirname(path), h)
        if h != "eva_driver.h" and os.path.exists(hp):
            with open(hp, encoding="utf-8") as f:
                text += f.read()
    return sorted(set(re.findall(r"EVA_ENTRY\((\w+)", text)))


def cpu_so_far(pid):
    """CPU seconds a running process has used (Linux /proc), or None where unknown."""
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return None


def run_timed(cmd, log, cwd, timeout, env=None):
    """Run cmd with its output to log; (exit code or None on timeout, CPU seconds it used).
    The CPU time is the analysis's own cost, independent of what else shares the machine:
    the bound is timeout seconds of CPU, and WALL_FACTOR times that of wall time (where the
    CPU time cannot be read, the wall time alone)."""
    proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, cwd=cwd, env=env)
    t_end = time.monotonic() + WALL_FACTOR * timeout
    while True:
        pid, status, ru = os.wait4(proc.pid, os.WNOHANG)
        if pid == proc.pid:
            proc.returncode = os.waitstatus_to_exitcode(status)
            return proc.returncode, ru.ru_utime + ru.ru_stime
        cpu = cpu_so_far(proc.pid)
        if time.monotonic() > (t_end if cpu is not None else t_end - (WALL_FACTOR - 1) * timeout) or \
                (cpu is not None and cpu > timeout):
            proc.kill()
            _, _, ru = os.wait4(proc.pid, 0)
            proc.returncode = -9
            return None, ru.ru_utime + ru.ru_stime
        time.sleep(0.05)


def run_one(args, root, work, name, analysis):
    drv = os.path.join(args.eva_dir, name + ".c")
    srcs = [os.path.join(root, "fsw_c", "src", s) for s in driver_sources(drv)]
    csv_path = os.path.join(work, f"{name}.{analysis}.csv")
    log_path = os.path.join(work, f"{name}.{analysis}.log")
    inc = "-I{0} -I{1} -I{2}".format(os.path.join(root, "fsw_c", "include"), os.path.join(root, "fsw_c", "src"),
                                      os.path.join(root, "test", "proofs", "eva"))  # eva_driver.h
    # the envelope analysis only: in the any analysis a non-finite input
    # reaches the calls on paths Eva cannot cut (it does not narrow a value
    # by a finiteness test)
    for h in (driver_includes(drv) if analysis == "envelope" else []):
        inc += " -include " + os.path.join(root, "test", "proofs", "wp", h)
    cmd = [args.frama_c, "-cpp-extra-args=" + inc] + COMMON + driver_options(drv, analysis) + ANALYSES[analysis] + [drv] + srcs + \
          ["-report-csv", csv_path]
    t0 = time.monotonic()
    res = {"name": name, "analysis": analysis, "alarms": [], "entries": {}, "error": None}
    with open(log_path, "w", encoding="utf-8") as log:
        rc, res["cpu"] = run_timed(cmd, log, root, args.timeout)
    if rc is None:
        res["error"] = f"timeout: over {args.timeout:.0f} s of CPU or {WALL_FACTOR * args.timeout:.0f} s of wall time"
    res["time"] = time.monotonic() - t0
    if rc is None:
        return res
    if rc != 0 or not os.path.exists(csv_path):
        res["error"] = f"frama-c exit {rc} (log: {log_path})"
        return res
    with open(log_path, encoding="utf-8") as f:
        for line in f:
            if "Neither code nor specification for function fsw_" in line or "[kernel] User Error" in line:
                res["error"] = f"{line.strip()} (a library source missing from eva-sources?)"
            m = ENTRY.search(line)
            if m:
                res["entries"].setdefault(m.group(1), set()).add(m.group(2).strip())
    with open(csv_path, encoding="utf-8") as f:
        for row in csv.DictReader(f, delimiter="\t"):
            if not ALARM_STATUS.match(row["status"]) or row["property kind"] in NOT_ALARMS:
                continue
            path = os.path.join(row["directory"], row["file"])
            if not row["directory"].startswith("FRAMAC_SHARE"):
                path = os.path.relpath(os.path.join(root, path), root)
            loc = f"{path}:{row['function']}"
            res["alarms"].append((loc, row["property kind"], f"{row['file']}:{row['line']}",
                                  row["property"]))
    return res


def wp_targets(wp_dir):
    """<wp_dir>/*.h -> [(header path, source, function)] from their 'wp-target:' lines."""
    out = []
    for h in sorted(os.listdir(wp_dir)) if os.path.isdir(wp_dir) else []:
        if not h.endswith(".h"):
            continue
        with open(os.path.join(wp_dir, h), encoding="utf-8") as f:
            m = re.search(r"wp-target:\s*(\S+)\s+(\w+)", f.read())
        if not m:
            raise SystemExit(f"{wp_dir}/{h}: no 'wp-target: file.c function' line")
        out.append((os.path.join(wp_dir, h), m.group(1), m.group(2)))
    return out


def run_wp(args, root, work, target, env):
    """Prove one contract with WP (real model, CVC4, and the header's 'wp-options:'): every goal
    must be proven."""
    path, src, fct = target
    h = os.path.basename(path)
    inc = "-I{0} -I{1} -include {2}".format(os.path.join(root, "fsw_c", "include"),
                                          os.path.join(root, "fsw_c", "src"), path)
    cmd = [args.frama_c, "-machdep", "x86_64", "-cpp-extra-args=" + inc,
           "-kernel-warn-key", "CERT:EXP:46=inactive", "-kernel-warn-key", "annot:missing-spec=inactive",
           os.path.join(root, "fsw_c", "src", src), "-wp", "-wp-fct", fct, "-wp-model", "real",
           "-wp-prover", args.prover, "-wp-timeout", "20"] + (driver_line(path, "wp-options") or [])
    log_path = os.path.join(work, f"wp.{h}.log")
    t0 = time.monotonic()
    with open(log_path, "w", encoding="utf-8") as log:
        rc, cpu = run_timed(cmd, log, root, args.timeout, env)
    dt = time.monotonic() - t0
    if rc is None:
        return f"{h}: timeout (log: {log_path})", 0, 0, dt, cpu
    with open(log_path, encoding="utf-8") as f:
        m = re.search(r"Proved goals:\s*(\d+)\s*/\s*(\d+)", f.read())
    if not m:
        return f"{h}: no WP result (log: {log_path})", 0, 0, dt, cpu
    proved, total = int(m.group(1)), int(m.group(2))
    err = None if proved == total and total > 0 else f"{h}: {proved}/{total} goals proven (log: {log_path})"
    return err, proved, total, dt, cpu


def main():
    args = parse_args()
    root = os.path.abspath(args.root)
    eva_dir = os.path.join(root, "test", "proofs", "eva_selftest" if args.self_test else "eva")
    args.eva_dir = eva_dir
    import shutil
    if shutil.which(args.frama_c) is None:
        print(f"eva_check: {args.frama_c} not found (Debian: apt-get install frama-c-base): skipped")
        return 77
    records = read_records(os.path.join(eva_dir, "alarms.txt"))
    all_drivers = sorted(f[:-2] for f in os.listdir(eva_dir) if f.endswith(".c"))
    if args.only is None:
        jobs = [(d, a) for d in all_drivers for a in ANALYSES]
    else:
        jobs = []
        for item in args.only:
            d, _, a = item.partition("/")
            if d not in all_drivers or (a and a not in ANALYSES):
                print(f"eva_check: no driver or analysis {item} in {eva_dir}", file=sys.stderr)
                return 2
            jobs += [(d, x) for x in ANALYSES if not a or x == a]
    drivers = sorted({d for d, _ in jobs})
    work = args.work
    if work is None:
        import tempfile
        work = tempfile.mkdtemp(prefix="kestrel-eva-")
    os.makedirs(work, exist_ok=True)
    t0 = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        results = list(pool.map(lambda j: run_one(args, root, work, *j), jobs))
    wall = time.monotonic() - t0

    failures = []
    seen = set()
    print(f"{'driver/analysis':34} {'entries':>7} {'alarms':>6} {'recorded':>8} {'time':>7} {'cpu':>7}")
    for r in results:
        tag = f"{r['name']}/{r['analysis']}"
        want = driver_entries(os.path.join(eva_dir, r["name"] + ".c"))
        if r["error"]:
            failures.append(f"{tag}: {r['error']}")
        else:
            missing = [e for e in want if e not in r["entries"]]
            if missing:
                failures.append(f"{tag}: entries never reached: {', '.join(missing)}")
        n_rec = 0
        for loc, kind, where, prop in r["alarms"]:
            key = (tag, loc, kind)
            if key in records:
                seen.add(key)
                n_rec += 1
            else:
                failures.append(f"{tag}: unrecorded alarm {kind} at {where} ({loc}): {prop}")
        shown = "; ".join(f"{k} {v}" for k, v in sorted((k, ",".join(sorted(v))) for k, v in r["entries"].items()))
        print(f"{tag:34} {len(r['entries']):>7} {len(r['alarms']):>6} {n_rec:>8} {r['time']:>6.1f}s {r['cpu']:>6.1f}s  {shown}")
    ran = {f"{r['name']}/{r['analysis']}" for r in results if not r["error"]}
    for key in records:
        if key[0] in ran and key not in seen:
            failures.append(f"stale record in alarms.txt (no such alarm any more): {' | '.join(key)}")
    if not args.no_wp and shutil.which("why3") is None:
        failures.append("WP: why3 not found (Debian: apt-get install why3 cvc4)")
    elif not args.no_wp:
        # Why3's prover configuration, made here so that no user file is needed
        env = dict(os.environ, WHY3CONFIG=os.path.join(work, "why3.conf"))
        subprocess.run(["why3", "config", "detect"], env=env, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL, check=False)
        wp_dir = os.path.join(root, "test", "proofs", "wp_selftest" if args.self_test else "wp")
        for target in wp_targets(wp_dir):
            err, proved, total, dt, cpu = run_wp(args, root, work, target, env)
            print(f"{'wp ' + target[1] + ':' + target[2]:34} goals {proved}/{total}{'':>8} {dt:>6.1f}s {cpu:>6.1f}s")
            if err:
                failures.append("WP " + err)
    n_entries = len({(r["name"], e) for r in results for e in r["entries"]})
    n_alarms = sum(len(r["alarms"]) for r in results)
    print(f"eva_check: {len(drivers)} drivers, {len(jobs)} analyses, {n_entries} entries reached, "
          f"{n_alarms} alarms ({len(seen)} records used), {wall:.1f} s wall, "
          f"{sum(r['cpu'] for r in results):.1f} s CPU of the analyses; logs in {work}")
    for f in failures:
        print("FAIL:", f)
    if args.self_test:
        wanted = {"unrecorded alarm": "unrecorded alarm", "stale record": "stale record",
                  "entries never reached": "entries never reached: never",
                  "WP goal not proven": "rw_sat_half_bound.h: 0/1 goals proven"}
        missed = [k for k, v in wanted.items() if not any(v in f for f in failures)]
        print("eva_check self-test:", "missed " + ", ".join(missed) if missed else "every planted fault caught")
        return 1 if missed else 0
    print("eva_check:", "FAILED" if failures else "OK")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
