#!/usr/bin/env python3
"""kestrel_acs_tbl.py writes a cFE table file as cFE's table services read it.

The expected layout is written out here from cFE's header definitions (file
header CFE_FS_Header_t: 8 x u32 then char[32]; table header
CFE_TBL_File_Hdr_t: 3 x u32 then char[40]; both big-endian on file) and read
back byte by byte, independently of the tool's own constants.  The tool's
output for S1 was also compared with the table file cFE's build makes with
elf2cfetbl from fsw/tables/kestrel_acs_cfg.c: identical, 16,120 bytes
(2026-12-06).  Bad input (not an image, an image too large) is refused.

    test_kestrel_acs_tbl.py SOURCE_ROOT
"""
import os
import subprocess
import sys
import tempfile

FAIL = []


def check(cond, what):
    if not cond:
        FAIL.append(what)
        print("FAIL:", what)


def be32(b, off):
    return (b[off] << 24) | (b[off + 1] << 16) | (b[off + 2] << 8) | b[off + 3]


def main() -> int:
    root = sys.argv[1]
    tool = os.path.join(root, "apps/cfs/kestrel_acs/tools/kestrel_acs_tbl.py")
    # a stand-in image: the tool checks only the magic and the size (the
    # application's validation judges the rest)
    image = b"KCFG" + bytes(range(256)) * 10 + b"\x12\x34"
    with tempfile.TemporaryDirectory() as d:
        img, out = os.path.join(d, "x.img"), os.path.join(d, "x.tbl")
        open(img, "wb").write(image)
        subprocess.run([sys.executable, tool, img, out], check=True)
        f = open(out, "rb").read()
        # cFE file header, 64 bytes
        check(f[0:4] == b"cFE1", "ContentType 'cFE1'")
        check(be32(f, 4) == 8, "SubType 8 (table image)")
        check(be32(f, 8) == 64, "Length 64")
        check(be32(f, 12) == 0x42, "SpacecraftID default 0x42")
        check(be32(f, 16) == 1, "ProcessorID default 1")
        check(f[32:64].rstrip(b"\0") == b"Kestrel ACS configuration", "Description")
        # table header, 52 bytes at 64
        check(be32(f, 64) == 0 and be32(f, 68) == 0, "Reserved, Offset 0")
        check(be32(f, 72) == 4 + 16000, "NumBytes = sizeof(KestrelAcsConfigTable) = 16004")
        check(f[76:116] == b"KESTREL_ACS.Config" + bytes(40 - 18), "TableName, NUL-padded to 40")
        # data at 116: image_length little-endian (default), the image, zeros
        check(len(f) == 116 + 16004, f"file size 16120 (got {len(f)})")
        n = len(image)
        check(f[116:120] == bytes([n & 0xFF, (n >> 8) & 0xFF, 0, 0]), "image_length little-endian")
        check(f[120:120 + n] == image, "image bytes")
        check(set(f[120 + n:]) <= {0}, "zero padding")
        subprocess.run([sys.executable, tool, "--data-endian", "big", img, out], check=True)
        f = open(out, "rb").read()
        check(f[116:120] == bytes([0, 0, (n >> 8) & 0xFF, n & 0xFF]), "image_length big-endian (--data-endian big)")
        # refusals
        open(img, "wb").write(b"NOPE" + image[4:])
        r = subprocess.run([sys.executable, tool, img, out], capture_output=True, text=True)
        check(r.returncode == 1 and "not a Kestrel configuration image" in r.stderr, "a non-image refused")
        open(img, "wb").write(b"KCFG" + bytes(16000))
        r = subprocess.run([sys.executable, tool, img, out], capture_output=True, text=True)
        check(r.returncode == 1 and "must be 1..16000" in r.stderr, "an image above 16000 bytes refused")
    print("kestrel_acs_tbl: " + ("FAILED" if FAIL else "all checks passed"))
    return 1 if FAIL else 0


if __name__ == "__main__":
    sys.exit(main())
