#!/usr/bin/env python3
"""KESTREL_ACS's committed default table (apps/cfs/kestrel_acs/fsw/tables/
kestrel_acs_cfg.c) holds exactly the configuration image that
`kestrel fsw-config scenarios/s1_sun_pointing.yaml` writes with this build,
and its image_length is that image's size.  When S1 or the image format
changes, regenerate the table as its header comment says.

    check_default_table.py KESTREL_EXE SOURCE_ROOT
"""
import os
import re
import subprocess
import sys
import tempfile


def table_bytes(path: str):
    text = open(path, encoding="ascii").read()
    m = re.search(r"KESTREL_ACS_Config\s*=\s*\{\s*(\d+)u\s*,\s*\{(.*?)\}\s*\}\s*;", text, re.S)
    if not m:
        raise SystemExit(f"{path}: no 'KESTREL_ACS_Config = {{ LEN, {{ bytes }} }};' initialiser")
    return int(m.group(1)), bytes(int(x, 16) for x in re.findall(r"0x([0-9A-Fa-f]{2})", m.group(2)))


def main() -> int:
    exe, root = sys.argv[1], sys.argv[2]
    src = os.path.join(root, "apps/cfs/kestrel_acs/fsw/tables/kestrel_acs_cfg.c")
    length, data = table_bytes(src)
    with tempfile.TemporaryDirectory() as d:
        img = os.path.join(d, "s1.img")
        subprocess.run([exe, "fsw-config", os.path.join(root, "scenarios/s1_sun_pointing.yaml"), "-o", img],
                       check=True, stdout=subprocess.DEVNULL)
        want = open(img, "rb").read()
    if length != len(want) or data != want:
        first = next((i for i in range(min(len(data), len(want))) if data[i] != want[i]), min(len(data), len(want)))
        print(f"{src}: differs from `kestrel fsw-config` S1 output (table {length} / {len(data)} bytes, image "
              f"{len(want)} bytes, first difference at byte {first}); regenerate it (see its header comment)")
        return 1
    print(f"default table = S1 image ({len(want)} bytes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
