#!/usr/bin/env python3
"""No-heap / no-globals proof for the FSW archive.

Reads the archive with the target's own `nm` and fails when
  * an undefined symbol is not on the allowlist (libm, mem*, compiler
    helpers, the integrator's assert hook), which rules out malloc, free,
    printf and every other libc/OS dependency; or
  * a symbol is defined in a writable data section (D, d, B, b, C, G, g, S,
    s): the library must hold no mutable global or static data.
Prints a table of what it found.  Exit 0 = pass, 1 = violation, 2 = usage.
"""
import argparse
import re
import subprocess
import sys

ALLOW_UNDEFINED = [
    # libm (double and float variants) and classification helpers
    r"(sqrt|fabs|sin|cos|tan|asin|acos|atan|atan2|floor|ceil|rint|nearbyint|lrint|"
    r"frexp|ldexp|fmod|exp|log|pow|hypot|copysign|fmin|fmax|trunc|round)f?",
    r"__(fpclassify|finite|isinf|isnan|signbit)[fdl]?",
    # memory block functions the compiler may emit for struct copies; bcmp
    # is clang's lowering of a memcmp(...) == 0 test on hosts whose C
    # library has it (the same comparison, nothing more)
    r"mem(cpy|set|move|cmp)",
    r"bcmp",
    r"__aeabi_mem(cpy|set|move|clr)[48]?",
    # compiler runtime helpers (soft float, 64-bit division, ...)
    r"__aeabi_\w+",
    r"__[a-z]+[0-9]",           # libgcc: __adddf3, __fixdfsi, __udivdi3, __extendsfdf2, ...
    r"__gcc_\w+",
    # the integrator-provided assert hook (fsw_status.h)
    r"fsw_assert_failed",
    # stack protector, if a distribution enables it by default
    r"__stack_chk_(fail|guard)",
]
ALLOW_SANITIZER = [r"__(asan|ubsan|sanitizer|lsan)_\w*", r"__asan_\w+"]
WRITABLE_TYPES = set("DdBbCGgSs")


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--nm", required=True)
    ap.add_argument("--archive", required=True)
    ap.add_argument("--sanitize", action="store_true",
                    help="allow sanitizer runtime symbols and instrumentation data")
    a = ap.parse_args()

    try:
        out = subprocess.run([a.nm, "-P", "-A", a.archive], check=True,
                             capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"fsw_symbol_check: cannot run {a.nm}: {e}", file=sys.stderr)
        return 2

    allow = [re.compile("^(" + p + ")$") for p in
             ALLOW_UNDEFINED + (ALLOW_SANITIZER if a.sanitize else [])]
    undefined, defined_text, writable, bad = {}, 0, [], []
    defined = set()
    for line in out.splitlines():
        # POSIX format with -A: "archive[member]: name type [value [size]]"
        if ":" not in line:
            continue
        where, rest = line.split(": ", 1) if ": " in line else line.split(":", 1)
        f = rest.split()
        if len(f) < 2:
            continue
        name, typ = f[0], f[1]
        member = where[where.find("[") + 1:where.rfind("]")] if "[" in where else where
        if typ == "U":
            undefined.setdefault(name, set()).add(member)
            continue
        defined.add(name)
        if typ in "Tt":
            defined_text += 1
        elif typ in WRITABLE_TYPES and not a.sanitize:
            writable.append(f"{name} ({typ}, in {member})")
    # a reference between members of the archive is resolved inside it
    for name in list(undefined):
        if name in defined:
            del undefined[name]
    for name in sorted(undefined):
        if not any(p.match(name) for p in allow):
            bad.append(f"undefined symbol not allowed: {name} (in {', '.join(sorted(undefined[name]))})")
    for w in writable:
        bad.append(f"mutable data defined: {w}")

    print(f"FSW archive: {a.archive}")
    print(f"  functions defined: {defined_text}")
    print(f"  symbols the archive needs from outside ({len(undefined)}), all must be on the allowlist:")
    for name in sorted(undefined):
        ok = any(p.match(name) for p in allow)
        print(f"    {'ok ' if ok else 'BAD'} {name:28s} {', '.join(sorted(undefined[name]))}")
    print(f"  writable data symbols: {len(writable) if not a.sanitize else 'not checked (sanitizer build)'}")
    if bad:
        print("FAIL:")
        for b in bad:
            print("  " + b)
        return 1
    print("PASS: no heap, no stdio, no OS calls, no mutable global or static data")
    return 0


if __name__ == "__main__":
    sys.exit(main())
