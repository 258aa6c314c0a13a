#!/usr/bin/env python3
"""Compare KESTREL_ACS in cFS with kestrel-fsw, packet for packet.

    kestrel-fsw --udp 127.0.0.1:50555 --config s1.img --watchdog-ms 0 &
    kestrel_acs_compare.py --fsw 127.0.0.1:50555 [--cycles 300]

Both must run the same configuration (the table loaded in cFS made from the
image kestrel-fsw reads) from a fresh start.  Each cycle's sensor packet goes
to both: wrapped in 0x18F1 to ci_lab, and as is to kestrel-fsw.  The actuator
(0x181) and health (0x182) packets that come back (0x08F1/0x08F2 from to_lab,
unwrapped at byte 16) must be identical byte for byte, sequence counts and
CRCs included.  Exit status 0 when every packet matched.
"""
import argparse
import socket
import struct
import sys
import time

from kestrel_acs_send import cfs_cmd, icd_sensor


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fsw", required=True, help="kestrel-fsw's HOST:PORT")
    ap.add_argument("--host", default="127.0.0.1", help="ci_lab's host")
    ap.add_argument("--port", type=int, default=1234, help="ci_lab's UDP port")
    ap.add_argument("--tlm-port", type=int, default=1235, help="to_lab's destination port here")
    ap.add_argument("--n-rw", type=int, default=4)
    ap.add_argument("--n-css", type=int, default=8)
    ap.add_argument("--cycles", type=int, default=300)
    a = ap.parse_args(argv)
    fh, fp = a.fsw.rsplit(":", 1)

    rx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    rx.bind(("127.0.0.1", a.tlm_port))
    rx.settimeout(2.0)
    tx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    kf = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    kf.settimeout(2.0)
    kf.connect((fh, int(fp)))
    tx.sendto(cfs_cmd(0x1880, 6, b"127.0.0.1".ljust(16, b"\0")), (a.host, a.port))
    for mid in (0x08F1, 0x08F2):
        tx.sendto(cfs_cmd(0x1880, 2, struct.pack("=IBBBx", mid, 0, 0, 32)), (a.host, a.port))
    time.sleep(0.5)

    same = [0, 0]
    for k in range(a.cycles):
        t = 100_000_000 * (k + 1)
        pkt = icd_sensor(t, k % 16384, a.n_rw, a.n_css, k)
        tx.sendto(cfs_cmd(0x18F1, 0, pkt), (a.host, a.port))
        got = {}
        try:
            while len(got) < 2:
                d = rx.recv(65536)
                mid = struct.unpack(">H", d[:2])[0]
                if mid in (0x08F1, 0x08F2) and struct.unpack(">Q", d[22:30])[0] == t:
                    got[mid] = d[16:]
        except socket.timeout:
            print(f"cycle {k}: no reply from cFS", file=sys.stderr)
            return 1
        kf.send(pkt)
        ref = {}
        try:
            while len(ref) < 2:
                d = kf.recv(65536)
                apid = struct.unpack(">H", d[:2])[0] & 0x7FF
                if apid in (0x181, 0x182):
                    ref[apid] = d
        except socket.timeout:
            print(f"cycle {k}: no reply from kestrel-fsw", file=sys.stderr)
            return 1
        same[0] += got[0x08F1] == ref[0x181]
        same[1] += got[0x08F2] == ref[0x182]
    print(f"{a.cycles} cycles: actuator packets identical {same[0]}/{a.cycles}, "
          f"health packets identical {same[1]}/{a.cycles}")
    return 0 if same == [a.cycles, a.cycles] else 1


if __name__ == "__main__":
    sys.exit(main())
