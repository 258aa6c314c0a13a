#!/usr/bin/env python3
"""Worst-case stack per public FSW function.

Inputs, produced by the FSW build:
  * GCC: `-fcallgraph-info=su` writes one .ci (VCG) file per object with each
    function's frame size and its call edges;
  * other compilers (Clang): `-fstack-usage` .su files give frame sizes and
    the call edges are read from the relocations of each function's own
    section (`-ffunction-sections`) with the target's objdump.
Public functions are the archive's global text symbols (read with nm).
Worst case = own frame + the deepest callee chain.  Calls that leave the
library (libm, mem*, compiler helpers, the integrator's assert hook) are
charged a fixed allowance, EXTERNAL_ALLOWANCE bytes, because their frames are
not in our build.  Dynamic frames (VLA/alloca) and recursion are errors.

Prints a table sorted by worst case and fails if any public function exceeds
--limit bytes.  Exit 0 = pass, 1 = over budget or unanalysable, 2 = usage.
"""
import argparse
import glob
import os
import re
import subprocess
import sys

EXTERNAL_ALLOWANCE = 256  # [bytes] charged for a call out of the library


def parse_ci(path, frames, edges, owner):
    node_re = re.compile(r'node: \{ title: "([^"]+)" label: "([^"]*)"')
    edge_re = re.compile(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"')
    unit = os.path.basename(path)
    for line in open(path, encoding="utf-8", errors="replace"):
        m = node_re.search(line)
        if m:
            name, label = m.group(1), m.group(2)
            fm = re.search(r"\\n(\d+) bytes \(([^)]*)\)", label)
            if fm:
                frames[(unit, name)] = (int(fm.group(1)), fm.group(2))
                owner.setdefault(name, []).append(unit)
            continue
        m = edge_re.search(line)
        if m:
            edges.setdefault((unit, m.group(1)), set()).add(m.group(2))


def parse_su_and_relocs(objdir, objdump, frames, edges, owner):
    for su in glob.glob(os.path.join(objdir, "**", "*.su"), recursive=True):
        unit = os.path.basename(su)[:-3]
        for line in open(su, encoding="utf-8", errors="replace"):
            f = line.rstrip("\n").split("\t")
            if len(f) < 3:
                continue
            name = f[0].split(":")[-1]
            frames[(unit, name)] = (int(f[1]), f[2])
            owner.setdefault(name, []).append(unit)
        obj = None
        for ext in (".o", ".obj"):
            cand = su[:-3] + ext
            if os.path.exists(cand):
                obj = cand
        if obj is None:
            continue
        out = subprocess.run([objdump, "-r", obj], check=True, capture_output=True, text=True).stdout
        current = None
        for line in out.splitlines():
            m = re.match(r"RELOCATION RECORDS FOR \[\.(?:rela?\.)?text\.([^\]]+)\]", line)
            if m:
                current = m.group(1)
                continue
            if line.startswith("RELOCATION RECORDS"):
                current = None
                continue
            f = line.split()
            if current and len(f) >= 3 and re.match(r"^[0-9a-fA-F]+$", f[0]):
                target = re.split(r"[-+]", f[2])[0]
                if target.startswith(".text."):
                    target = target[len(".text."):]
                if target and not target.startswith("."):
                    edges.setdefault((unit, current), set()).add(target)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--objdir", required=True, help="directory holding the FSW objects")
    ap.add_argument("--archive", required=True)
    ap.add_argument("--nm", required=True)
    ap.add_argument("--objdump", default="objdump")
    ap.add_argument("--limit", type=int, default=4096)
    a = ap.parse_args()

    frames, edges, owner = {}, {}, {}
    ci_files = glob.glob(os.path.join(a.objdir, "**", "*.ci"), recursive=True)
    if ci_files:
        method = "GCC -fcallgraph-info"
        for p in ci_files:
            parse_ci(p, frames, edges, owner)
    else:
        method = "-fstack-usage + relocations"
        parse_su_and_relocs(a.objdir, a.objdump, frames, edges, owner)
    if not frames:
        print(f"fsw_stack_report: no stack-usage data under {a.objdir}", file=sys.stderr)
        return 1

    nm = subprocess.run([a.nm, "-P", a.archive], check=True, capture_output=True, text=True).stdout
    public = sorted({f[0] for f in (l.split() for l in nm.splitlines()) if len(f) >= 2 and f[1] == "T"})

    errors = []
    memo = {}

    def resolve(unit, callee):
        if (unit, callee) in frames:
            return (unit, callee)
        units = owner.get(callee, [])
        return (units[0], callee) if units else None

    def worst(node, stack):
        if node in memo:
            return memo[node]
        if node in stack:
            errors.append("recursion: " + " -> ".join(n[1] for n in stack + [node]))
            return (0, [node[1]])
        own, kind = frames[node]
        if "dynamic" in kind and "bounded" not in kind:
            errors.append(f"unbounded dynamic stack in {node[1]} ({kind})")
        best, path = 0, []
        for callee in sorted(edges.get(node, ())):
            r = resolve(node[0], callee)
            if r is None:
                cost, cpath = EXTERNAL_ALLOWANCE, [callee + "*"]
            else:
                cost, cpath = worst(r, stack + [node])
            if cost > best:
                best, path = cost, cpath
        memo[node] = (own + best, [node[1]] + path)
        return memo[node]

    rows = []
    for name in public:
        r = resolve(None, name)
        if r is None:
            errors.append(f"no stack data for public function {name}")
            continue
        total, path = worst(r, [])
        rows.append((total, frames[r][0], name, path))
    rows.sort(key=lambda t: (-t[0], t[2]))

    print(f"Worst-case stack per public FSW function ({method}; "
          f"external calls charged {EXTERNAL_ALLOWANCE} B, marked *; limit {a.limit} B)")
    print(f"{'worst [B]':>10} {'own [B]':>8}  function  (deepest path)")
    for total, own, name, path in rows:
        flag = "  OVER" if total > a.limit else ""
        print(f"{total:10d} {own:8d}  {name}  ({' > '.join(path)}){flag}")
        if total > a.limit:
            errors.append(f"{name}: {total} B > {a.limit} B")
    if rows:
        print(f"largest: {rows[0][2]} = {rows[0][0]} B over {len(rows)} public functions")
    if errors:
        print("FAIL:")
        for e in sorted(set(errors)):
            print("  " + e)
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
