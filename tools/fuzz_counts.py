#!/usr/bin/env python3
"""Long-run fuzz counts of the flight library, and whether they still hold.

test/fuzz/fsw/counts.csv has one row per FSW harness (test/fuzz/fsw/
fuzz_<name>.cpp): the executions of its last long run, the commit whose
sources that run compiled, the seeds, the date, and every file of the tree
the harness binary is compiled from: the flight sources it links, the
headers they and the harness include, the harness and its shared decoders.
A count holds for a later tree only if none of those files changed since
that commit.  (The build rules, test/fuzz/CMakeLists.txt, are not part of
it: the harnesses are built with the same instrumentation throughout.)

  report [--root R] [--min N]
      the Markdown table of every harness: executions, commit, seeds, and
      "current" or "stale (changed: ...)"; exit 1 when a harness has no row,
      its count is below --min (default 10**7) or stale.  Needs git.
  links --build DIR [--root R] [--print]
      checks each row's file list against what DIR's harness binary is
      built from: the members of the instrumented flight library it links
      (nm: a member of libkestrel_fsw_fuzz.a is linked when one of its
      global definitions is in the binary) and the files the compiler read
      for them and for the harness (ninja -t deps); exit 1 on any
      difference.  --print writes each harness's list instead.  Needs no git.
  self-test
      report's checks on a scratch repository with planted faults (a changed
      source, header or decoder, a low count, a missing row); exit 0 only if
      each is caught.
Exit 0 = pass, 1 = a count does not hold (or a list is wrong), 2 = usage.
"""
import argparse
import csv
import io
import os
import subprocess
import sys
import tempfile

COUNTS = "test/fuzz/fsw/counts.csv"
HARNESS_DIR = "test/fuzz/fsw"
FIELDS = ["harness", "executions", "commit", "seeds", "date", "files"]


def read_counts(path):
    """{harness: row}; raises ValueError on a malformed file."""
    rows = {}
    with open(path, encoding="utf-8", newline="") as f:
        lines = [ln for ln in f if ln.strip() and not ln.lstrip().startswith("#")]
    reader = csv.DictReader(io.StringIO("".join(lines)))
    if reader.fieldnames != FIELDS:
        raise ValueError(f"{path}: header must be {','.join(FIELDS)}")
    for r in reader:
        h = r["harness"].strip()
        if h in rows:
            raise ValueError(f"{path}: harness {h} listed twice")
        try:
            r["executions"] = int(r["executions"])
        except ValueError:
            raise ValueError(f"{path}: {h}: executions {r['executions']!r} is not an integer")
        r["files"] = r["files"].split()
        rows[h] = r
    return rows


def harnesses(root):
    d = os.path.join(root, HARNESS_DIR)
    return sorted(f[len("fuzz_"):-len(".cpp")] for f in os.listdir(d)
                  if f.startswith("fuzz_") and f.endswith(".cpp"))


def git(root, *args):
    return subprocess.run(["git", "-C", root, *args], capture_output=True, text=True)


def changed_since(root, commit, paths):
    """Paths among `paths` that differ between `commit` and the work tree."""
    r = git(root, "cat-file", "-e", commit + "^{commit}")
    if r.returncode != 0:
        return None  # commit unknown (e.g. a shallow clone)
    r = git(root, "diff", "--name-only", commit, "--", *paths)
    return [p for p in r.stdout.split() if p]


def spaced(n):
    """10000000 -> '10 000 000' (the docs' digit grouping)."""
    return format(n, ",").replace(",", " ")


def report(root, counts, minimum, out):
    names = harnesses(root)
    problems, failing = [], set()
    lines = ["| Harness | Executions | Commit | Seeds | Date | On this tree |",
             "| --- | ---: | --- | --- | --- | --- |"]
    for h in names:
        row = counts.get(h)
        fails = len(problems)
        if row is None:
            failing.add(h)
            problems.append(f"fuzz_fsw_{h}: no row in {COUNTS}")
            lines.append(f"| `fuzz_fsw_{h}` | – | – | – | – | **no recorded run** |")
            continue
        changed = changed_since(root, row["commit"], row["files"])
        if changed is None:
            state = f"**unknown** (commit {row['commit']} not in this clone)"
            problems.append(f"fuzz_fsw_{h}: commit {row['commit']} not in this clone")
        elif changed:
            state = "**stale** (changed since: " + ", ".join(changed) + ")"
            problems.append(f"fuzz_fsw_{h}: stale, changed since {row['commit']}: {', '.join(changed)}")
        else:
            state = "current"
        n = row["executions"]
        if n < minimum:
            state += f"; **below {spaced(minimum)}**"
            problems.append(f"fuzz_fsw_{h}: {n} executions, below {minimum}")
        if len(problems) > fails:
            failing.add(h)
        lines.append(f"| `fuzz_fsw_{h}` | {spaced(n)} | {row['commit'][:7]} | {row['seeds']} | {row['date']} | {state} |")
    for h in sorted(set(counts) - set(names)):
        problems.append(f"{COUNTS}: row {h} names no harness in {HARNESS_DIR}")
    summary = (f"fuzz_counts: {len(names) - len(failing)} of {len(names)} harnesses hold at least "
               f"{spaced(minimum)} executions on this tree's sources")
    text = "\n".join(lines) + "\n\n" + summary + "\n" + "".join(f"  {p}\n" for p in problems)
    out.write(text)
    return 1 if problems else 0


def global_defs(path):
    """Global symbols defined in an object, archive or binary (nm)."""
    r = subprocess.run(["nm", "--defined-only", "-g", path], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"nm {path}: {r.stderr.strip()}")
    return r.stdout


def archive_members(lib):
    """{member name (e.g. rw_map.c): set of its global definitions}."""
    members, cur = {}, None
    for line in global_defs(lib).splitlines():
        if line.endswith(":") and line.strip():
            cur = line[:-1].strip()
            if cur.endswith(".o"):
                cur = cur[:-2]
            members.setdefault(cur, set())
            continue
        parts = line.split()
        if cur and len(parts) >= 3:  # nm -g --defined-only: every line is a global definition
            members[cur].add(parts[2])
    return members


def linked_members(lib_members, binary):
    syms = {ln.split()[-1] for ln in global_defs(binary).splitlines() if len(ln.split()) >= 3}
    return sorted(m for m, defs in lib_members.items() if defs & syms)


def ninja_deps(build):
    """{object path relative to build: [files the compiler read]} (ninja -t deps)."""
    r = subprocess.run(["ninja", "-C", build, "-t", "deps"], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"ninja -t deps in {build}: {r.stderr.strip()}")
    deps, cur = {}, None
    for line in r.stdout.splitlines():
        if line and not line[0].isspace():
            cur = line.split(":")[0]
            deps[cur] = []
        elif cur and line.strip():
            deps[cur].append(line.strip())
    return deps


def tree_files(root, build, paths):
    """The paths that are files of the source tree (not system or build headers), relative to root."""
    out = set()
    for p in paths:
        a = os.path.normpath(os.path.join(build, p))
        rel = os.path.relpath(a, root)
        if not rel.startswith("..") and not a.startswith(os.path.abspath(build) + os.sep):
            out.add(rel)
    return out


def files_of(root, build, members, deps, h):
    """Every tree file fuzz_fsw_<h> is built from."""
    binary = os.path.join(build, HARNESS_DIR, f"fuzz_fsw_{h}")
    files = set()
    objs = [f"fuzz_fsw_{h}.dir/fuzz_{h}.cpp.o"] + [f"kestrel_fsw_fuzz.dir/__/__/fsw_c/src/{m}.o"
                                                     for m in linked_members(members, binary)]
    for o in objs:
        hits = [k for k in deps if k.endswith("/" + o)]
        if len(hits) != 1:
            raise RuntimeError(f"{o}: {len(hits)} entries in ninja's deps of {build}")
        files |= tree_files(root, build, deps[hits[0]])
    return sorted(files)


def links(root, counts, build, show):
    lib = os.path.join(build, "test", "fuzz", "libkestrel_fsw_fuzz.a")
    if not os.path.exists(lib):
        print(f"fuzz_counts: {lib} not built (the host-clang preset builds it)", file=sys.stderr)
        return 2
    members = archive_members(lib)
    deps = ninja_deps(build)
    problems = 0
    for h in harnesses(root):
        if not os.path.exists(os.path.join(build, HARNESS_DIR, f"fuzz_fsw_{h}")):
            print(f"fuzz_counts: fuzz_fsw_{h}: not built in {build}")
            problems += 1
            continue
        have = files_of(root, build, members, deps, h)
        if show:
            print(h, " ".join(have))
            continue
        want = sorted(counts[h]["files"]) if h in counts else None
        if want is None:  # the report fails on it; this check has no list to compare
            print(f"fuzz_counts: fuzz_fsw_{h}: no row in {COUNTS} (no long run recorded)")
        elif have != want:
            print(f"fuzz_counts: fuzz_fsw_{h}: built from {' '.join(sorted(set(have) - set(want))) or '-'} "
                  f"not listed; listed but not used: {' '.join(sorted(set(want) - set(have))) or '-'}")
            problems += 1
    if not show:
        print(f"fuzz_counts: {len(harnesses(root))} harnesses, {problems} file lists wrong")
    return 1 if problems else 0


def self_test():
    """Plant each fault in a scratch repository and require it to be caught."""
    failures = []
    with tempfile.TemporaryDirectory() as d:
        def sh(*a):
            subprocess.run(a, cwd=d, check=True, capture_output=True)
        for p in ("fsw_c/src", "fsw_c/include/fsw", HARNESS_DIR):
            os.makedirs(os.path.join(d, p))
        files = {"fsw_c/src/a.c": "int a;\n", "fsw_c/src/b.c": "int b;\n",
                 "fsw_c/include/fsw/a.h": "int a;\n", f"{HARNESS_DIR}/fuzz_input.h": "//\n",
                 f"{HARNESS_DIR}/fuzz_a.cpp": "//\n", f"{HARNESS_DIR}/fuzz_b.cpp": "//\n"}
        for p, t in files.items():
            with open(os.path.join(d, p), "w") as f:
                f.write(t)
        sh("git", "init", "-q")
        sh("git", "-c", "user.name=t", "-c", "user.email=t@t", "add", ".")
        sh("git", "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "base")
        base = git(d, "rev-parse", "HEAD").stdout.strip()

        common = f"fsw_c/include/fsw/a.h {HARNESS_DIR}/fuzz_input.h"

        def rows(a_n=10**7, b=True):
            s = (",".join(FIELDS) + "\n"
                 + f"a,{a_n},{base},1,2026-01-01,fsw_c/src/a.c {HARNESS_DIR}/fuzz_a.cpp {common}\n")
            if b:
                s += f"b,{10**7},{base},2,2026-01-01,fsw_c/src/b.c {HARNESS_DIR}/fuzz_b.cpp {common}\n"
            p = os.path.join(d, "counts.csv")
            with open(p, "w") as f:
                f.write(s)
            return read_counts(p)

        def verdict(counts):
            return report(d, counts, 10**7, io.StringIO())

        if verdict(rows()) != 0:
            failures.append("a clean tree with two full counts is not accepted")
        if verdict(rows(a_n=9_999_999)) != 1:
            failures.append("a count below the minimum is not caught")
        if verdict(rows(b=False)) != 1:
            failures.append("a harness without a row is not caught")
        for path in ("fsw_c/src/b.c", "fsw_c/include/fsw/a.h", f"{HARNESS_DIR}/fuzz_input.h"):
            with open(os.path.join(d, path), "a") as f:
                f.write("/* changed */\n")
            out = io.StringIO()
            if report(d, rows(), 10**7, out) != 1 or "fuzz_fsw_b: stale" not in out.getvalue():
                failures.append(f"a change to {path} does not make fuzz_fsw_b stale")
            sh("git", "checkout", "-q", "--", path)
        # a change to a source only the other harness links leaves this one current
        with open(os.path.join(d, "fsw_c/src/a.c"), "a") as f:
            f.write("/* changed */\n")
        out = io.StringIO()
        report(d, rows(), 10**7, out)
        if "fuzz_fsw_b: stale" in out.getvalue() or "fuzz_fsw_a: stale" not in out.getvalue():
            failures.append("a change to a.c is not charged to fuzz_fsw_a alone")
    for f in failures:
        print(f"fuzz_counts self-test: {f}")
    print(f"fuzz_counts self-test: {'FAIL' if failures else 'pass'} ({len(failures)} faults not caught)")
    return 1 if failures else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("command", choices=["report", "links", "self-test"])
    ap.add_argument("--root", default=".")
    ap.add_argument("--build", help="a build folder with the FSW fuzz harnesses (links)")
    ap.add_argument("--print", action="store_true", help="links: print each harness's file list")
    ap.add_argument("--min", type=int, default=10**7, help="executions a count must reach")
    args = ap.parse_args()
    if args.command == "self-test":
        return self_test()
    root = os.path.abspath(args.root)
    try:
        counts = read_counts(os.path.join(root, COUNTS))
    except (OSError, ValueError) as e:
        print(f"fuzz_counts: {e}", file=sys.stderr)
        return 2
    if args.command == "links":
        if not args.build:
            print("fuzz_counts: links needs --build DIR", file=sys.stderr)
            return 2
        return links(root, counts, os.path.abspath(args.build), args.print)
    return report(root, counts, args.min, sys.stdout)


if __name__ == "__main__":
    sys.exit(main())
