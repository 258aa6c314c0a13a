#!/usr/bin/env python3
"""MISRA C:2012 gate of the flight code (docs/misra-deviations.md).

Runs cppcheck's MISRA addon over every C source of the flight library
(fsw_c/src/*.c) and of the flight programs (flight/posix/*.c except the
*_test.c programs, flight/m4f/*.c), one translation unit per file, C99, with
the library's include folders and its default build-time capacities.  The
sources are globbed, so a new file is checked without editing this script.

Each finding is (file, line, column, rule); a finding inside a header that
several sources include is counted once.  The findings are compared with the
recorded deviations (tools/misra_deviations.txt), one record per rule and
scope: a file relative to the repository root, or "all" for the findings of
that rule not covered by a file record.  The check fails (exit 1)
  - on any finding of a mandatory rule (those can never be deviated),
  - when a rule/scope has more findings than its record allows (every
    finding of that rule/scope is listed as file:line:rule), or has no
    record at all,
  - when a record allows more than is found (a stale record: lower it, so the
    count only ever goes down),
  - on any message of cppcheck that is not a MISRA finding (a syntax error, a
    failed addon, a real defect found by cppcheck's own checks),
  - when the deviation table of docs/misra-deviations.md does not list exactly
    the records (rule, scope, count) of the deviation file.

  misra_check.py [--root DIR] [--jobs N] [--cppcheck PATH] [--deviations FILE]
  misra_check.py --counts        # the findings per rule and file, no verdict
  misra_check.py --self-test     # shows that each kind of failure is caught

Exit 0: every finding is recorded; 1: a violation (each printed); 2: usage
or cppcheck missing.
"""
import argparse
import collections
import os
import re
import shutil
import subprocess
import sys
import tempfile

# MISRA C:2012 mandatory rules (with Amendments 1-2): zero findings, no deviation.
MANDATORY = frozenset({"9.1", "12.5", "13.6", "17.3", "17.4", "17.6", "19.1",
                       "21.13", "21.17", "21.18", "21.19", "21.20",
                       "22.2", "22.4", "22.5", "22.6"})
SOURCE_GLOBS = (("fsw_c/src", ".c"), ("flight/posix", ".c"), ("flight/m4f", ".c"))
EXCLUDE_SUFFIX = "_test.c"  # host test programs next to the flight code
INCLUDE_DIRS = ("fsw_c/include", "fsw_c/src", "flight/posix/include")
# The library's default capacities (fsw_c/include/fsw/fsw_config.h, CMake's
# KESTREL_FSW_MAX_RW / KESTREL_FSW_MAX_THR): one configuration is analysed.
DEFINES = ("FSW_MAX_RW=36", "FSW_MAX_THR=36")
TEMPLATE = "@@{file}|{line}|{column}|{id}|{severity}|{message}"
TESTED_VERSION = "2.10"


def sources(root):
    out = []
    for folder, ending in SOURCE_GLOBS:
        d = os.path.join(root, folder)
        if not os.path.isdir(d):
            continue
        for name in sorted(os.listdir(d)):
            if name.endswith(ending) and not name.endswith(EXCLUDE_SUFFIX):
                out.append(os.path.join(folder, name))
    return out


def run_cppcheck(cppcheck, root, files, jobs):
    """Findings as a sorted list of (file, line, column, rule); other messages."""
    # the addon's .dump / .ctu-info files go to a scratch folder, not next to the sources
    with tempfile.TemporaryDirectory(prefix="misra_check_") as scratch:
        cmd = [cppcheck, "--addon=misra", "--std=c99", "--language=c", "-q",
               "-j", str(jobs), "--suppress=missingIncludeSystem",
               "--cppcheck-build-dir=" + scratch, "--template=" + TEMPLATE]
        cmd += ["-I" + d for d in INCLUDE_DIRS]
        cmd += ["-D" + d for d in DEFINES]
        cmd += files
        proc = subprocess.run(cmd, cwd=root, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              universal_newlines=True, check=False)
    findings, other = set(), []
    for line in proc.stdout.splitlines():
        if not line.startswith("@@"):
            if line.strip() and not line.startswith("Checking ") and "files checked" not in line:
                other.append(line)
            continue
        path, lineno, col, ident, _sev, msg = line[2:].split("|", 5)
        path = os.path.relpath(os.path.join(root, path), root)
        m = re.fullmatch(r"misra-c2012-(\d+\.\d+)", ident)
        if m:
            findings.add((path, int(lineno), int(col), m.group(1)))
        else:
            other.append("%s:%s: %s: %s" % (path, lineno, ident, msg))
    if proc.returncode != 0 and not other:
        other.append("cppcheck exited with status %d" % proc.returncode)
    return sorted(findings), other


def read_deviations(path):
    """{(rule, scope): (count, rationale)}; errors as a list of strings."""
    records, errors = {}, []
    with open(path, encoding="utf-8") as f:
        for n, raw in enumerate(f, 1):
            line = raw.strip()
            if not line or line.startswith("#"):
                continue
            parts = [p.strip() for p in line.split("|", 3)]  # the rationale may hold '|'
            where = "%s:%d" % (path, n)
            if len(parts) != 4 or not re.fullmatch(r"\d+\.\d+", parts[0]) \
                    or not parts[2].isdigit() or not parts[3]:
                errors.append("%s: expected 'rule | file-or-all | count | rationale'" % where)
                continue
            rule, scope, count, why = parts[0], parts[1], int(parts[2]), parts[3]
            if rule in MANDATORY:
                errors.append("%s: rule %s is mandatory and cannot be deviated" % (where, rule))
            elif (rule, scope) in records:
                errors.append("%s: rule %s, scope %s recorded twice" % (where, rule, scope))
            else:
                records[(rule, scope)] = (count, why)
    return records, errors


# a row of the deviation table: | rule | all or `path/file` | count | ...
DOC_ROW_RE = re.compile(r"^\|\s*(\d+\.\d+)\s*\|\s*`?(all|[\w.-]+/[\w./-]+)`?\s*\|\s*(\d+)\s*\|", re.M)


def check_doc(doc, records):
    """The document's deviation table lists exactly the records (rule, scope, count)."""
    if not os.path.exists(doc):
        return ["%s: missing (it explains every recorded deviation)" % doc]
    with open(doc, encoding="utf-8") as f:
        rows = {(m.group(1), m.group(2).strip()): int(m.group(3)) for m in DOC_ROW_RE.finditer(f.read())}
    want = {k: v[0] for k, v in records.items()}
    problems = []
    for k in sorted(set(rows) | set(want)):
        if rows.get(k) != want.get(k):
            problems.append("%s: rule %s, scope %s: the table says %s, tools/misra_deviations.txt %s"
                            % (doc, k[0], k[1], rows.get(k, "nothing"), want.get(k, "nothing")))
    return problems


def compare(findings, records):
    """Problems (strings) of the findings against the records; [] = pass."""
    by_rule_file = collections.defaultdict(list)
    for f in findings:
        by_rule_file[(f[3], f[0])].append(f)
    # the findings each record covers: file records first, then "all"
    covered = collections.defaultdict(list)
    for (rule, path), items in by_rule_file.items():
        key = (rule, path) if (rule, path) in records else (rule, "all")
        covered[key].extend(items)
    problems = []
    for key in sorted(set(covered) | set(records), key=lambda k: (rule_key(k[0]), k[1])):
        rule, scope = key
        items = sorted(covered.get(key, []))
        if rule in MANDATORY:
            problems += ["%s:%d:%d: misra %s (mandatory rule: fix the code)" % (p, l, c, r)
                         for p, l, c, r in items]
            continue
        if key not in records:
            problems += ["%s:%d:%d: misra %s not recorded" % (p, l, c, r) for p, l, c, r in items]
            continue
        allowed = records[key][0]
        if len(items) > allowed:
            problems.append("rule %s, scope %s: %d findings, %d recorded; the findings:"
                            % (rule, scope, len(items), allowed))
            problems += ["  %s:%d:%d: misra %s" % (p, l, c, r) for p, l, c, r in items]
        elif len(items) < allowed:
            problems.append("rule %s, scope %s: stale record, allows %d but %d found: lower it to %d"
                            "%s" % (rule, scope, allowed, len(items), len(items),
                                    " (remove the line)" if not items else ""))
    return problems


def rule_key(rule):
    a, b = rule.split(".")
    return (int(a), int(b))


def print_counts(findings):
    per_rule = collections.Counter(f[3] for f in findings)
    per_rule_file = collections.Counter((f[3], f[0]) for f in findings)
    print("total %d findings in %d rules" % (len(findings), len(per_rule)))
    for rule in sorted(per_rule, key=rule_key):
        print("%-6s %5d%s" % (rule, per_rule[rule], "  MANDATORY" if rule in MANDATORY else ""))
        for (r, path), n in sorted(per_rule_file.items()):
            if r == rule:
                print("         %5d  %s" % (n, path))


def find_cppcheck(given):
    exe = shutil.which(given or "cppcheck")
    if not exe:
        print("misra_check: cppcheck not found (apt-get install cppcheck, or scripts/install-deps.sh)",
              file=sys.stderr)
        return None
    return exe


def check_version(cppcheck):
    out = subprocess.run([cppcheck, "--version"], stdout=subprocess.PIPE, universal_newlines=True,
                         check=False).stdout.strip()
    if TESTED_VERSION not in out:
        print("misra_check: warning: %s; the recorded counts were measured with cppcheck %s"
              % (out, TESTED_VERSION))
    return out


def self_test(cppcheck):
    """Each failure mode is caught, on synthetic findings and on a planted file."""
    failures = []

    def expect(name, problems, want_fail, needle=None):
        ok = bool(problems) == want_fail and (needle is None or any(needle in p for p in problems))
        if not ok:
            failures.append("%s: got %r" % (name, problems))

    f1 = [("a.c", 3, 5, "15.6"), ("a.c", 9, 5, "15.6"), ("b.c", 2, 1, "15.6"), ("b.c", 4, 1, "17.7")]
    rec = {("15.6", "all"): (3, "x"), ("17.7", "b.c"): (1, "y")}
    expect("exact records pass", compare(f1, rec), False)
    expect("an extra finding fails", compare(f1 + [("c.c", 1, 1, "15.6")], rec), True, "c.c:1:1")
    expect("an unrecorded rule fails", compare(f1 + [("a.c", 7, 2, "12.1")], rec), True,
           "a.c:7:2: misra 12.1 not recorded")
    expect("a file record does not cover another file",
           compare(f1 + [("a.c", 4, 1, "17.7")], rec), True, "a.c:4:1: misra 17.7")
    expect("a stale record fails", compare(f1[:3], rec), True, "stale record")
    expect("a mandatory finding fails", compare(f1 + [("a.c", 1, 1, "17.3")], rec), True, "mandatory")
    with tempfile.TemporaryDirectory() as tmp:
        dev = os.path.join(tmp, "dev.txt")
        with open(dev, "w", encoding="utf-8") as f:
            f.write("# comment\n15.6 | all | 2 | braces\n9.1 | all | 1 | no\n")
        recs, errs = read_deviations(dev)
        expect("a mandatory record is refused", errs, True, "mandatory")
        expect("a normal record is read", [] if recs == {("15.6", "all"): (2, "braces")} else ["bad"],
               False)
        with open(dev, "w", encoding="utf-8") as f:
            f.write("12.1 | src/a.c | 3 | x * y + z, a && b || c\n")
        recs, errs = read_deviations(dev)
        expect("a rationale may hold '|'", errs + ([] if recs == {("12.1", "src/a.c"): (3, "x * y + z, a && b || c")}
                                                   else ["bad %r" % recs]), False)
        doc = os.path.join(tmp, "doc.md")
        with open(doc, "w", encoding="utf-8") as f:
            f.write("| Rule | Scope | Count | Why |\n|---|---|---|---|\n| 12.1 | `src/a.c` | 2 | x |\n")
        expect("a document table that disagrees fails", check_doc(doc, recs), True, "the table says 2")
        # cppcheck itself finds a planted violation (15.6: an if without braces)
        os.makedirs(os.path.join(tmp, "fsw_c", "src"))
        with open(os.path.join(tmp, "fsw_c", "src", "planted.c"), "w", encoding="utf-8") as f:
            f.write("int planted(int x);\nint planted(int x)\n{\n  int y = 0;\n"
                    "  if (x > 0)\n    y = 1;\n  return y;\n}\n")
        found, other = run_cppcheck(cppcheck, tmp, sources(tmp), 1)
        expect("cppcheck finds the planted 15.6",
               [] if ("fsw_c/src/planted.c", 5, 3, "15.6") in found and not other
               else ["not found: %r %r" % (found, other)], False)
    for f in failures:
        print("self-test FAILED: " + f)
    if failures:
        return 1
    print("misra_check self-test: OK")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    ap.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--cppcheck")
    ap.add_argument("--deviations", help="default: <root>/tools/misra_deviations.txt")
    ap.add_argument("--counts", action="store_true", help="print the findings per rule and file")
    ap.add_argument("--self-test", action="store_true")
    args = ap.parse_args()
    root = os.path.abspath(args.root)
    cppcheck = find_cppcheck(args.cppcheck)
    if cppcheck is None:
        return 2
    if args.self_test:
        return self_test(cppcheck)
    version = check_version(cppcheck)
    files = sources(root)
    if not files:
        print("misra_check: no sources under %s" % root, file=sys.stderr)
        return 2
    findings, other = run_cppcheck(cppcheck, root, files, args.jobs)
    if args.counts:
        print_counts(findings)
        for o in other:
            print("cppcheck: " + o)
        return 0
    dev = args.deviations or os.path.join(root, "tools", "misra_deviations.txt")
    records, errors = read_deviations(dev)
    problems = errors + check_doc(os.path.join(root, "docs", "misra-deviations.md"), records)
    problems += ["cppcheck: " + o for o in other] + compare(findings, records)
    print("misra_check: %s, %d files, %d findings in %d rules, %d deviation records"
          % (version, len(files), len(findings), len({f[3] for f in findings}), len(records)))
    if problems:
        for p in problems:
            print(p)
        print("misra_check: FAILED (%d problems): fix the code, or record a deviation with its "
              "rationale in tools/misra_deviations.txt and docs/misra-deviations.md" % len(problems))
        return 1
    print("misra_check: OK (every finding recorded, no mandatory rule violated)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
