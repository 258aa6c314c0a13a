#!/usr/bin/env python3
"""Make the KESTREL_ACS configuration table from a Kestrel configuration image.

    kestrel_acs_tbl.py IMAGE OUT.tbl      a cFE table file, loadable by cFE's
                                          table services (CFE_TBL_Load, or the
                                          ground LOAD command) as KESTREL_ACS.Config
    kestrel_acs_tbl.py --c-source IMAGE OUT.c
                                          the table's C source (fsw/tables), which
                                          cFE's build turns into the default table

IMAGE is what `kestrel fsw-config SCENARIO -o IMAGE` writes (the format of
fsw_link_config_encode).  The table data is { uint32 image_length; uint8
image[16000] } in the target's memory layout (cFE loads table data as a memory
image): image_length is written little-endian unless --data-endian big.

A cFE table file is two big-endian headers and the data:
    cFE file header (64 bytes): ContentType 'cFE1' = 0x63464531, SubType 8
        (table image), Length 64, SpacecraftID, ProcessorID, ApplicationID,
        TimeSeconds, TimeSubSeconds (u32 each), Description (char[32]);
    table header (52 bytes): Reserved, Offset, NumBytes (u32 each),
        TableName (char[40], "KESTREL_ACS.Config");
    NumBytes bytes of table data (the whole table: 16004 bytes).
The sizes are cFE's defaults (CFE_FS_HDR_DESC_MAX_LEN 32,
CFE_MISSION_TBL_MAX_FULL_NAME_LEN 40); a mission that changed them changes
the constants below.
"""
import argparse
import struct
import sys

IMAGE_MAX = 16000             # KESTREL_ACS_CONFIG_IMAGE_MAX (kestrel_acs_core.h)
TABLE_SIZE = 4 + IMAGE_MAX    # sizeof(KestrelAcsConfigTable)
TABLE_NAME = "KESTREL_ACS.Config"
FS_CONTENT_ID = 0x63464531    # 'cFE1'
FS_SUBTYPE_TBL_IMG = 8
FS_DESC_LEN = 32
FS_HDR_LEN = 32 + FS_DESC_LEN
TBL_NAME_LEN = 40
IMAGE_MAGIC = b"KCFG"


def table_data(image: bytes, endian: str) -> bytes:
    if len(image) == 0 or len(image) > IMAGE_MAX:
        raise ValueError(f"image of {len(image)} bytes: must be 1..{IMAGE_MAX}")
    fmt = "<I" if endian == "little" else ">I"
    return struct.pack(fmt, len(image)) + image + bytes(IMAGE_MAX - len(image))


def table_file(image: bytes, endian: str = "little", scid: int = 0x42, cpu: int = 1,
               desc: str = "Kestrel ACS configuration", time_s: int = 0) -> bytes:
    data = table_data(image, endian)
    d = desc.encode("ascii")[:FS_DESC_LEN - 1]
    fs_hdr = struct.pack(">8I", FS_CONTENT_ID, FS_SUBTYPE_TBL_IMG, FS_HDR_LEN, scid, cpu, 0, time_s, 0)
    fs_hdr += d + bytes(FS_DESC_LEN - len(d))
    name = TABLE_NAME.encode("ascii")
    tbl_hdr = struct.pack(">3I", 0, 0, len(data)) + name + bytes(TBL_NAME_LEN - len(name))
    return fs_hdr + tbl_hdr + data


def c_source(image: bytes, image_name: str) -> str:
    lines = [
        "/* KESTREL_ACS default configuration table: Kestrel scenario S1's",
        " * configuration image.  GENERATED, do not edit: from the Kestrel tree,",
        " *   kestrel fsw-config scenarios/s1_sun_pointing.yaml -o s1.img",
        " *   apps/cfs/kestrel_acs/tools/kestrel_acs_tbl.py --c-source s1.img \\",
        " *       apps/cfs/kestrel_acs/fsw/tables/kestrel_acs_cfg.c",
        f" * ({image_name}: {len(image)} bytes; test/cfs checks that it equals",
        " * what fsw-config writes for S1 today).  cFE's build (add_cfe_tables)",
        " * compiles it and elf2cfetbl writes /cf/kestrel_acs_cfg.tbl. */",
        '#include "cfe_tbl_filedef.h"',
        "",
        '#include "kestrel_acs_core.h"',
        "",
        "KestrelAcsConfigTable KESTREL_ACS_Config = {",
        f"    {len(image)}u,",
        "    {",
    ]
    for i in range(0, len(image), 16):
        lines.append("        " + ", ".join(f"0x{b:02X}" for b in image[i:i + 16]) + ",")
    lines += [
        "    }};",
        "",
        "CFE_TBL_FILEDEF(KESTREL_ACS_Config, KESTREL_ACS.Config, Kestrel ACS configuration, kestrel_acs_cfg.tbl)",
        "",
    ]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("image", help="Kestrel configuration image (kestrel fsw-config -o)")
    ap.add_argument("out", help="output .tbl (or .c with --c-source)")
    ap.add_argument("--c-source", action="store_true", help="write the table's C source instead")
    ap.add_argument("--data-endian", choices=("little", "big"), default="little",
                    help="byte order of image_length in the table data (the target's; default little)")
    ap.add_argument("--scid", type=lambda s: int(s, 0), default=0x42, help="spacecraft id (default 0x42)")
    ap.add_argument("--cpu", type=int, default=1, help="processor id (default 1)")
    a = ap.parse_args(argv)
    with open(a.image, "rb") as f:
        image = f.read()
    if image[:4] != IMAGE_MAGIC:
        print(f"kestrel_acs_tbl: {a.image}: not a Kestrel configuration image (no 'KCFG')", file=sys.stderr)
        return 1
    try:
        if a.c_source:
            out = c_source(image, a.image.split("/")[-1]).encode("ascii")
        else:
            out = table_file(image, a.data_endian, a.scid, a.cpu)
    except ValueError as e:
        print(f"kestrel_acs_tbl: {a.image}: {e}", file=sys.stderr)
        return 1
    with open(a.out, "wb") as f:
        f.write(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
