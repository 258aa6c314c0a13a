#!/usr/bin/env python3
"""The harness's shape, checked: rooms include downwards only, and
(with --max-function-lines) no function is longer than the limit.

Rooms are listed, from the ground up, in harness/rooms.txt.  Every source
and header of the harness must sit in a room folder, src/<room>/ or
include/harness/<room>/.  A quoted include is resolved to the room it names
("harness/<room>/..." for a public header, "<room>/..." for a private one);
it must be the file's own room or one listed before it.  Includes of the
other components (fsw/, sim/, report/, and transport/: the C transport
module of the FSW link, flight/posix/include/transport/, kestrel::transport)
are allowed everywhere; any other quoted include is an error (a stale path).

Function lengths come from Universal Ctags (--fields=+ne): the lines from a
definition's first line to its closing brace.

  harness_shape_check.py [--root DIR] [--max-function-lines N]
  harness_shape_check.py --self-test      # shows that a violation is found

Exit 0: the shape holds; 1: a violation (each printed); 2: usage.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

OTHER_COMPONENTS = ("fsw/", "sim/", "report/", "transport/", "icd/")
SOURCE_ENDINGS = (".h", ".hpp", ".cpp", ".cc", ".c")
INCLUDE_RE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def read_rooms(harness):
    rooms = []
    with open(os.path.join(harness, "rooms.txt"), encoding="utf-8") as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line:
                rooms.append(line)
    return rooms


def room_of_file(rel):
    """rel: path below harness/.  Returns the room or None (loose file)."""
    parts = rel.split("/")
    if parts[0] == "src" and len(parts) >= 3:
        return parts[1]
    if parts[0] == "include" and len(parts) >= 4 and parts[1] == "harness":
        return parts[2]
    return None


def room_of_include(inc, rooms):
    parts = inc.split("/")
    if len(parts) >= 3 and parts[0] == "harness" and parts[1] in rooms:
        return parts[1]
    if len(parts) >= 2 and parts[0] in rooms:
        return parts[0]
    return None


def harness_files(harness):
    for top in ("src", "include"):
        base = os.path.join(harness, top)
        for d, _, files in os.walk(base):
            for n in sorted(files):
                if n.endswith(SOURCE_ENDINGS):
                    yield os.path.relpath(os.path.join(d, n), harness).replace(os.sep, "/")


def check_rooms(harness):
    rooms = read_rooms(harness)
    rank = {r: i for i, r in enumerate(rooms)}
    problems = []
    counts = {}
    for rel in harness_files(harness):
        room = room_of_file(rel)
        if room not in rank:
            problems.append(f"harness/{rel}: not in a room folder (rooms: {', '.join(rooms)})")
            continue
        with open(os.path.join(harness, rel), encoding="utf-8", errors="replace") as f:
            text = f.read()
        for m in INCLUDE_RE.finditer(text):
            inc = m.group(1)
            line = text.count("\n", 0, m.start()) + 1
            if inc.startswith(OTHER_COMPONENTS):
                continue
            target = room_of_include(inc, rooms)
            if target is None:
                problems.append(f"harness/{rel}:{line}: \"{inc}\" names no room (write harness/<room>/... or <room>/...)")
            elif rank[target] > rank[room]:
                problems.append(f"harness/{rel}:{line}: room '{room}' includes \"{inc}\" from '{target}', a room above it")
            else:
                counts[(room, target)] = counts.get((room, target), 0) + 1
    return rooms, counts, problems


def function_lengths(harness):
    out = subprocess.run(
        ["ctags", "-R", "--languages=C++,C", "--kinds-C++=f", "--kinds-C=f", "--fields=+ne",
         "--output-format=json", "-f", "-", "src", "include"],
        cwd=harness, capture_output=True, text=True, check=True).stdout
    rows = []
    for line in out.splitlines():
        d = json.loads(line)
        if d.get("_type") == "tag" and "end" in d:
            rows.append((d["end"] - d["line"] + 1, d["path"], d["line"], d["name"]))
    rows.sort(reverse=True)
    return rows


def check(root, max_lines):
    harness = os.path.join(root, "harness")
    rooms, counts, problems = check_rooms(harness)
    print(f"rooms, from the ground up: {' < '.join(rooms)}")
    for (a, b), n in sorted(counts.items(), key=lambda kv: (rooms.index(kv[0][0]), rooms.index(kv[0][1]))):
        if a != b:
            print(f"  {a:9s} -> {b:9s} {n:3d} include(s)")
    if max_lines:
        rows = function_lengths(harness)
        if not rows:
            problems.append("ctags found no function in harness/ (is Universal Ctags installed?)")
        else:
            n, path, line, name = rows[0]
            print(f"longest function: {name} ({n} lines, harness/{path}:{line}); limit {max_lines - 1}")
            for n, path, line, name in rows:
                if n >= max_lines:
                    problems.append(f"harness/{path}:{line}: {name} is {n} lines (at most {max_lines - 1})")
    for p in problems:
        print(p)
    print("harness shape: " + ("holds" if not problems else f"{len(problems)} violation(s)"))
    return 1 if problems else 0


def self_test():
    """A tree with an upward include, a loose file and a long function must fail."""
    with tempfile.TemporaryDirectory() as t:
        h = os.path.join(t, "harness")
        os.makedirs(os.path.join(h, "src", "low"))
        os.makedirs(os.path.join(h, "src", "high"))
        with open(os.path.join(h, "rooms.txt"), "w") as f:
            f.write("low\nhigh\n")
        with open(os.path.join(h, "src", "high", "a.cpp"), "w") as f:
            f.write('#include "low/b.h"\nint a() { return 1; }\n')
        with open(os.path.join(h, "src", "low", "b.h"), "w") as f:
            f.write('#include "fsw/fsw_acs.h"\nint b();\n')
        if check(t, 80) != 0:
            print("self-test: a clean tree was refused")
            return 1
        with open(os.path.join(h, "src", "low", "b.h"), "w") as f:
            f.write('#include "high/a.h"\nint b();\n')
        if check(t, 0) == 0:
            print("self-test: an upward include was not found")
            return 1
        with open(os.path.join(h, "src", "low", "b.h"), "w") as f:
            f.write("int b();\n")
        with open(os.path.join(h, "src", "loose.cpp"), "w") as f:
            f.write("int c() { return 0; }\n")
        if check(t, 0) == 0:
            print("self-test: a file outside the rooms was not found")
            return 1
        os.remove(os.path.join(h, "src", "loose.cpp"))
        with open(os.path.join(h, "src", "low", "long.cpp"), "w") as f:
            f.write("int d()\n{\n" + "  int x = 0;\n" * 80 + "  return 0;\n}\n")
        if shutil.which("ctags") and check(t, 80) == 0:
            print("self-test: a function of 84 lines passed a limit of 79")
            return 1
    print("self-test: every violation was found")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    ap.add_argument("--max-function-lines", type=int, default=0,
                    help="fail on a function of this many lines or more (0: not checked)")
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.self_test:
        return self_test()
    return check(os.path.abspath(a.root), a.max_function_lines)


if __name__ == "__main__":
    sys.exit(main())
