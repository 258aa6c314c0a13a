#!/usr/bin/env python3
"""Mutation sampling of the flight library: would the FSW tests notice if the
code were wrong?

Generates textual mutants of fsw_c/src/*.c (arithmetic, relational and
logical operators, literals, deleted statements, zeroed call results),
draws a seeded sample, and for each mutant rebuilds a scratch copy of the
project incrementally and runs the FSW tests (ctest -L fsw).  A mutant is
"killed" when a test fails (or the build fails: "stillborn", not counted),
"survived" when every test passes, "timeout" when the tests hang (counted
as killed).  Writes a CSV of every mutant and prints a per-module table.
Survivors listed in tools/mutation_equivalents.csv (file, line, original,
mutant, reason) are reported as equivalent, with their reason, and left out
of the score.  Python 3 standard library only; the source tree is never
touched (the scratch copy is under build/mutation/).

  tools/mutate.py --sample 100 --seed 1            # one documented command
  tools/mutate.py --sample 150 --seed 7 --csv out.csv --module rw_map.c
  tools/mutate.py --rerun build/mutation/mutants.csv --csv rerun.csv   # survivors only, after new tests
  tools/mutate.py --sample 150 --seed 7 --sanitize  # ASan + UBSan build: a memory error kills
"""
import argparse
import csv
import os
import random
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COPY = ["CMakeLists.txt", "CMakePresets.json", "cmake", "fsw_c", "test", "tools", "toolchains", "scripts"]

# (name, regex on one line of code, replacement); each match is one mutant
OPERATORS = [
    ("arith +->-", r"(?<=[\w\)\]]) \+ (?=[\w\(])", " - "),
    ("arith -->+", r"(?<=[\w\)\]]) - (?=[\w\(])", " + "),
    ("arith *->/", r"(?<=[\w\)\]]) \* (?=[\w\(])", " / "),
    ("arith /->*", r"(?<=[\w\)\]]) / (?=[\w\(])", " * "),
    ("rel <-><=", r" < ", " <= "),
    ("rel <=-><", r" <= ", " < "),
    ("rel >->=", r" > ", " >= "),
    ("rel >=->>", r" >= ", " > "),
    ("rel ==->!=", r" == ", " != "),
    ("rel !=->==", r" != ", " == "),
    ("logic &&->||", r" && ", " || "),
    ("logic ||->&&", r" \|\| ", " && "),
    ("literal 0->1", r"(?<![\w.])0u?(?![\w.])", "1"),
    ("literal 1->0", r"(?<![\w.])1u?(?![\w.])", "0"),
    ("literal 2->3", r"(?<![\w.])2u?(?![\w.])", "3"),
    ("literal x.y->0", r"(?<![\w.])\d+\.\d+(?:e[-+]?\d+)?f?(?![\w.])", "0.0"),
    ("negate cond", r"if \((?!!)", "if (!"),
]


def code_lines(path):
    """Lines that are code (not comments, preprocessor or blank), with numbers."""
    out, in_comment = [], False
    with open(path) as f:
        for n, line in enumerate(f, 1):
            s = line.strip()
            if in_comment:
                if "*/" in s:
                    in_comment = False
                continue
            if s.startswith("/*"):
                in_comment = "*/" not in s
                continue
            if not s or s.startswith("#") or s.startswith("//") or s.startswith("*"):
                continue
            out.append((n, line))
    return out


def mutants_of(path):
    rel = os.path.relpath(path, ROOT)
    ms = []
    for n, line in code_lines(path):
        code = line.split("/*")[0]
        for name, rx, rep in OPERATORS:
            for m in re.finditer(rx, code):
                new = code[: m.start()] + rep + code[m.end():]
                ms.append({"file": rel, "line": n, "op": name, "original": line.rstrip("\n"),
                           "mutant": new.rstrip("\n") + line[len(code):].rstrip("\n")})
        s = code.strip()
        braced = "{" in s and s.endswith("}") and s.count("{") == s.count("}")  # if (c) { x; } on one line
        if ((s.endswith(";") and "{" not in s) or braced) \
                and not s.startswith(("return", "case", "default", "break", "}")):
            ms.append({"file": rel, "line": n, "op": "delete statement", "original": line.rstrip("\n"),
                       "mutant": "/* deleted */"})
        for m in re.finditer(r"= (fsw_\w+)\(", code):  # zero a call result (the call stays)
            new = code[: m.start()] + "= 0 * " + code[m.start() + 2:]
            ms.append({"file": rel, "line": n, "op": "zero call result", "original": line.rstrip("\n"),
                       "mutant": new.rstrip("\n")})
    return ms


def load_equivalents():
    """The recorded equivalent mutants: a list of rows (file, line, original, mutant, reason)."""
    p = os.path.join(ROOT, "tools", "mutation_equivalents.csv")
    if not os.path.exists(p):
        return []
    with open(p) as f:
        return [r | {"line": int(r["line"])} for r in csv.DictReader(f)]


def same_code(text):
    """A line's code for matching records: without blanks and braces (a body braced for MISRA
    rule 15.6 is the same statement, and its mutants the same mutants)."""
    return re.sub(r"[\s{}]", "", text)


def equivalent_line(row, src_lines):
    """Where a recorded equivalent mutant is in today's source: its recorded line when that line
    still reads its original code, else the one line that does (the code moved), else None (the
    original code is gone or on several lines: the record must be renewed by hand)."""
    want = same_code(row["original"])
    n = row["line"]
    if 1 <= n <= len(src_lines) and same_code(src_lines[n - 1]) == want:
        return n
    hits = [i + 1 for i, l in enumerate(src_lines) if same_code(l) == want]
    return hits[0] if len(hits) == 1 else None


def equivalents_by_place(rows):
    """{(file, line today, mutant text): reason} for the records that still match the source."""
    eq, cache = {}, {}
    for r in rows:
        if r["file"] not in cache:
            path = os.path.join(ROOT, r["file"])
            cache[r["file"]] = open(path).read().split("\n") if os.path.exists(path) else []
        n = equivalent_line(r, cache[r["file"]])
        if n is not None:
            eq[(r["file"], n, same_code(r["mutant"]))] = r["reason"]
    return eq


def check_equivalents(fix):
    """Every record's original text must still be in its file, on one line; with fix, the CSV's
    line numbers are renewed to where the text is now (written whole through a temporary file)."""
    rows = load_equivalents()
    bad, moved = [], 0
    for r in rows:
        path = os.path.join(ROOT, r["file"])
        src = open(path).read().split("\n") if os.path.exists(path) else []
        n = equivalent_line(r, src)
        if n is None:
            bad.append(f"{r['file']}:{r['line']}: {r['original'].strip()!r} is not on exactly one line")
        elif not any(m["line"] == n and same_code(m["mutant"]) == same_code(r["mutant"])
                     for m in mutants_of(path)):
            bad.append(f"{r['file']}:{n}: no mutant {r['mutant'].strip()!r} is made of that line today")
        elif n != r["line"] or src[n - 1].rstrip("\n") != r["original"]:
            moved += 1
            print(f"moved: {r['file']}:{r['line']} -> {n}")
            r["line"] = n
            r["original"] = src[n - 1].rstrip("\n")
            r["mutant"] = next(m["mutant"] for m in mutants_of(path) if m["line"] == n
                               and same_code(m["mutant"]) == same_code(r["mutant"]))
    for b in bad:
        print("stale: " + b)
    if fix and moved:
        p = os.path.join(ROOT, "tools", "mutation_equivalents.csv")
        with open(p + ".tmp", "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=["file", "line", "original", "mutant", "reason"], lineterminator="\n")
            w.writeheader()
            w.writerows(rows)
        os.replace(p + ".tmp", p)
    print(f"{len(rows)} recorded equivalent mutants: {len(rows) - len(bad)} found ({moved} moved), "
          f"{len(bad)} stale")
    return 1 if bad else 0


def run(cmd, cwd, timeout):
    try:
        p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout)
        return p.returncode, p.stdout.decode(errors="replace")
    except subprocess.TimeoutExpired:
        return None, "timeout"


def write_csv(path, rows):
    """Write the CSV whole, through a temporary file renamed into place."""
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["file", "line", "op", "original", "mutant", "result", "equivalent"])
        w.writeheader()
        w.writerows(rows)
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sample", type=int, default=100, help="mutants to run (default 100)")
    ap.add_argument("--seed", type=int, default=1, help="sampling seed (default 1)")
    ap.add_argument("--module", action="append", help="only these sources (e.g. rw_map.c); repeatable")
    ap.add_argument("--csv", default=os.path.join(ROOT, "build", "mutation", "mutants.csv"))
    ap.add_argument("--timeout", type=float, default=300.0, help="seconds per mutant's test run")
    ap.add_argument("--list", action="store_true", help="only count the mutants per module")
    ap.add_argument("--workdir", default=os.path.join(ROOT, "build", "mutation"),
                    help="scratch copy and build (default build/mutation; two runs at once need two)")
    ap.add_argument("--rerun", metavar="CSV",
                    help="instead of sampling, run again the survivors of an earlier run's CSV "
                         "(e.g. after adding tests); --sample, --seed and --module are ignored")
    ap.add_argument("--sanitize", action="store_true",
                    help="build the scratch copy with AddressSanitizer + UBSan (KESTREL_SANITIZE, as the "
                         "host-debug-asan preset; aborting on the first report), optimised (-O1): "
                         "a mutant that reads or writes out of bounds is then killed, as in CI")
    ap.add_argument("--check-equivalents", action="store_true",
                    help="only check that every record of tools/mutation_equivalents.csv still names "
                         "its source line, or one line with its code (exit 1 if one is stale)")
    ap.add_argument("--fix-lines", action="store_true",
                    help="with --check-equivalents: renew the line numbers of records whose text moved")
    a = ap.parse_args()
    if a.check_equivalents:
        return check_equivalents(a.fix_lines)

    srcs = sorted(os.path.join(ROOT, "fsw_c", "src", f) for f in os.listdir(os.path.join(ROOT, "fsw_c", "src"))
                  if f.endswith(".c") and (not a.module or f in a.module))
    allm = [m for s in srcs for m in mutants_of(s)]
    if a.list:
        for s in srcs:
            rel = os.path.relpath(s, ROOT)
            print(f"{rel:32s} {sum(1 for m in allm if m['file'] == rel):6d}")
        print(f"{'total':32s} {len(allm):6d}")
        return 0
    if a.rerun:
        with open(a.rerun) as f:
            sample = [{k: r[k] for k in ("file", "op", "original", "mutant")} | {"line": int(r["line"])}
                      for r in csv.DictReader(f) if r["result"] == "survived"]
        for m in sample:  # the source line must still be the one that was mutated
            with open(os.path.join(ROOT, m["file"])) as f:
                src = f.read().split("\n")
            if m["line"] > len(src) or src[m["line"] - 1] != m["original"]:
                print(f"stale: {m['file']}:{m['line']} no longer reads {m['original'].strip()!r}")
                return 2
    else:
        rng = random.Random(a.seed)
        sample = rng.sample(allm, min(a.sample, len(allm)))
    sample.sort(key=lambda m: (m["file"], m["line"]))

    scratch = os.path.join(a.workdir, "src")
    build = os.path.join(a.workdir, "build")
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    for c in COPY:
        s = os.path.join(ROOT, c)
        (shutil.copytree if os.path.isdir(s) else shutil.copy2)(s, os.path.join(scratch, c))
    cfg = ["cmake", "-S", scratch, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
           "-DKESTREL_BUILD_SIM=OFF", "-DKESTREL_BUILD_HARNESS=OFF", "-DKESTREL_BUILD_BENCHMARKS=OFF",
           "-DKESTREL_INSTALL=OFF", "-DKESTREL_WERROR=OFF",
           f"-DKESTREL_SANITIZE={'ON' if a.sanitize else 'OFF'}"]
    if a.sanitize:  # -O1: instrumented code compiles and runs faster than at -O3, still optimised
        cfg += ["-DCMAKE_C_FLAGS_RELEASE=-O1 -DNDEBUG", "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG"]
    else:  # a workdir used with --sanitize before: back to the Release defaults
        cfg += ["-UCMAKE_C_FLAGS_RELEASE", "-UCMAKE_CXX_FLAGS_RELEASE"]
    rc, out = run(cfg, ROOT, 600)
    if rc != 0:
        print(out)
        return 2
    rc, out = run(["ninja", "-j2", "-C", build], ROOT, 1800)
    if rc != 0:
        print(out)
        return 2
    test = ["ctest", "--test-dir", build, "-L", "fsw", "-j2", "--stop-on-failure"]
    rc, out = run(test, ROOT, a.timeout)
    if rc != 0:
        print("the unmutated tests fail:\n" + out)
        return 2

    eq = equivalents_by_place(load_equivalents())
    os.makedirs(os.path.dirname(os.path.abspath(a.csv)), exist_ok=True)
    t0 = time.time()
    for i, m in enumerate(sample, 1):
        path = os.path.join(scratch, m["file"])
        with open(path) as f:
            lines = f.readlines()
        orig = lines[m["line"] - 1]
        lines[m["line"] - 1] = m["mutant"] + "\n"
        with open(path, "w") as f:
            f.writelines(lines)
        try:
            rc, _ = run(["ninja", "-j2", "-C", build], ROOT, 600)
            if rc != 0:
                m["result"] = "stillborn"
            else:
                rc, _ = run(test, ROOT, a.timeout)
                m["result"] = "timeout" if rc is None else ("killed" if rc != 0 else "survived")
        finally:
            lines[m["line"] - 1] = orig
            with open(path, "w") as f:
                f.writelines(lines)
        key = (m["file"], m["line"], same_code(m["mutant"]))
        m["equivalent"] = eq.get(key, "") if m["result"] == "survived" else ""
        if m["result"] == "survived" and m["mutant"].strip() == m["original"].strip():
            # e.g. "literal x.y->0" on a literal that is already 0.0: the same program
            m["equivalent"] = "identical text (the mutation does not change the line)"
        print(f"[{i}/{len(sample)}] {m['result']:9s} {m['file']}:{m['line']} {m['op']}: {m['mutant'].strip()}"
              + (f"  (equivalent: {m['equivalent']})" if m["equivalent"] else ""), flush=True)
        write_csv(a.csv, sample[:i])  # after every mutant: an interrupted run keeps what it measured
    run(["ninja", "-j2", "-C", build], ROOT, 600)  # back to the unmutated build

    write_csv(a.csv, sample)
    print(f"\n{'module':28s} {'mutants':>7s} {'killed':>6s} {'surv.':>5s} {'equiv.':>6s} {'still.':>6s}")
    tot = {"n": 0, "k": 0, "s": 0, "e": 0, "b": 0}
    for mod in sorted({m["file"] for m in sample}):
        ms = [m for m in sample if m["file"] == mod]
        k = sum(m["result"] in ("killed", "timeout") for m in ms)
        e = sum(bool(m["equivalent"]) for m in ms)
        s = sum(m["result"] == "survived" for m in ms) - e
        b = sum(m["result"] == "stillborn" for m in ms)
        for key, v in zip("nkseb", (len(ms), k, s, e, b)):
            tot[key] += v
        print(f"{os.path.basename(mod):28s} {len(ms):7d} {k:6d} {s:5d} {e:6d} {b:6d}")
    live = tot["k"] + tot["s"]
    score = 100.0 * tot["k"] / live if live else 100.0
    print(f"{'total':28s} {tot['n']:7d} {tot['k']:6d} {tot['s']:5d} {tot['e']:6d} {tot['b']:6d}")
    print(f"mutation score {score:.1f} % of the non-equivalent, compiling mutants "
          f"({'rerun of ' + a.rerun if a.rerun else f'seed {a.seed}'}{', ASan + UBSan' if a.sanitize else ''}, "
          f"{time.time() - t0:.0f} s); CSV {a.csv}")
    for m in sample:
        if m["result"] == "survived" and not m["equivalent"]:
            print(f"  survived: {m['file']}:{m['line']} {m['op']}: {m['mutant'].strip()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
