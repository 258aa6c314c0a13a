#!/usr/bin/env python3
"""Talk to a running KESTREL_ACS through ci_lab and to_lab (a smoke check).

    kestrel_acs_send.py [--host 127.0.0.1] [--port 1234] [--tlm-port 1235]
                        [--n-rw 4] [--n-css 8] [--cycles 3]

Enables to_lab's output to this machine (TO_LAB_OUTPUT_ENABLE, CC 6 on
0x1880), subscribes it to KESTREL_ACS's telemetry (TO_LAB_ADD_PKT, CC 2,
0x08F0..0x08F2), sends a NOOP (0x18F0 CC 0), a few Kestrel ICD sensor
packets wrapped in 0x18F1, a command of the wrong length, and a housekeeping
request (0x18F2), then prints the housekeeping fields and the actuator
packets it receives.  The defaults fit scenario S1 (4 wheels, 8 CSS).
Exit status 0 when the housekeeping shows the NOOP, the refused command and
the cycles, and an actuator packet answered each sensor packet.
"""
import argparse
import socket
import struct
import sys
import time


def crc16(data: bytes, crc: int = 0xFFFF) -> int:
    """CRC-16/CCITT-FALSE (docs/icd.md)."""
    for b in data:
        crc ^= b << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1021) & 0xFFFF if crc & 0x8000 else (crc << 1) & 0xFFFF
    return crc


def cfs_cmd(mid: int, cc: int, payload: bytes = b"", seq: int = 0) -> bytes:
    """A cFS command: CCSDS primary header, function code, XOR checksum."""
    length = 8 + len(payload)
    hdr = struct.pack(">HHH", mid, 0xC000 | (seq & 0x3FFF), length - 7)
    msg = bytearray(hdr + bytes([cc & 0x7F, 0]) + payload)
    x = 0xFF
    for b in msg:
        x ^= b
    msg[7] = x
    return bytes(msg)


def icd_sensor(t_ns: int, seq: int, n_rw: int, n_css: int, k: int) -> bytes:
    """A Kestrel ICD sensor packet (APID 0x101) with a plausible sample."""
    p = struct.pack(">BBBB", n_rw, n_css, 1, 0)
    p += struct.pack(">3d", 0.05, -0.02, 0.01 * k)      # sigma_BN
    p += struct.pack(">3d", 0.001, -0.002, 0.0005)      # omega_BN_B
    p += struct.pack(">3d", 0.0, 0.0, 0.0)              # r_CoM_B
    p += struct.pack(f">{n_rw}d", *[10.0 + i for i in range(n_rw)])
    p += bytes(n_rw)                                     # rw_avail
    p += struct.pack(f">{n_css}d", *[0.3 if i % 2 == 0 else 0.0 for i in range(n_css)])
    p += bytes(n_css)                                    # css_avail
    p += struct.pack(">Q", 0)                            # thr_avail
    p += struct.pack(">9d", *([0.0] * 9))                # B_B, r_N, v_N
    p += bytes([0, 0])                                   # mag_valid, orbit_valid
    hdr = struct.pack(">HHH", 0x1800 | 0x101, 0xC000 | seq, 8 + len(p) + 2 - 1) + struct.pack(">Q", t_ns)
    body = hdr + p
    return body + struct.pack(">H", crc16(body))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--host", default="127.0.0.1")
    ap.add_argument("--port", type=int, default=1234)
    ap.add_argument("--tlm-port", type=int, default=1235)
    ap.add_argument("--n-rw", type=int, default=4)
    ap.add_argument("--n-css", type=int, default=8)
    ap.add_argument("--cycles", type=int, default=3)
    a = ap.parse_args(argv)

    rx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    rx.bind(("127.0.0.1", a.tlm_port))
    rx.settimeout(0.2)
    tx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)

    def send(msg: bytes) -> None:
        tx.sendto(msg, (a.host, a.port))
        time.sleep(0.05)

    send(cfs_cmd(0x1880, 6, b"127.0.0.1".ljust(16, b"\0")))        # TO_LAB_OUTPUT_ENABLE
    # TO_LAB_ADD_PKT: to_lab reads its payload as a native struct (CFE_SB_MsgId_t
    # is a uint32 in the host's byte order, then priority, reliability,
    # buffer limit and one pad byte)
    for mid in (0x08F0, 0x08F1, 0x08F2):
        send(cfs_cmd(0x1880, 2, struct.pack("=IBBBx", mid, 0, 0, 32)))
    time.sleep(2.0)  # to_lab takes its commands at its own wakeup (sch_lab, 1 Hz)
    send(cfs_cmd(0x18F0, 0))                                          # NOOP
    send(cfs_cmd(0x18F0, 2, b"\x01\x00\x00"))                         # SET_MODE, 3 bytes: refused
    # t_ns must increase across calls (the FSW refuses a time that does not):
    # the wall clock gives a base later than any earlier call's
    t0 = time.time_ns() // 100_000_000 * 100_000_000
    for k in range(a.cycles):
        send(cfs_cmd(0x18F1, 0, icd_sensor(t0 + 100_000_000 * k, k, a.n_rw, a.n_css, k)))
    send(cfs_cmd(0x18F2, 0))                                          # housekeeping

    hk, acts = None, []
    end = time.time() + 3.0
    while time.time() < end:
        try:
            d = rx.recv(65536)
        except socket.timeout:
            continue
        mid = struct.unpack(">H", d[:2])[0]
        if mid == 0x08F0:
            hk = struct.unpack(">BBBBIIIiI", d[16:40])
        elif mid == 0x08F1:
            pkt = d[16:]
            apid = struct.unpack(">H", pkt[:2])[0] & 0x7FF
            t_ns = struct.unpack(">Q", pkt[6:14])[0]
            crc_ok = crc16(pkt[:-2]) == struct.unpack(">H", pkt[-2:])[0]
            lr = struct.unpack(">3d", pkt[14 + 8:14 + 32]) if len(pkt) >= 48 else ()
            acts.append((apid, t_ns, crc_ok))
            print(f"actuator packet: APID 0x{apid:03X}, t_ns {t_ns}, {len(pkt)} bytes, CRC "
                  f"{'ok' if crc_ok else 'BAD'}, payload[8:32] {lr}")
    if hk is None:
        print("no housekeeping packet received (is core-cpu1 running with KESTREL_ACS?)", file=sys.stderr)
        return 1
    names = ("command_count", "command_error_count", "mode", "config_loaded", "cycles", "cycle_errors",
             "link_rejected", "last_status", "table_rejects")
    print("housekeeping: " + ", ".join(f"{n}={v}" for n, v in zip(names, hk)))
    ok = hk[0] >= 1 and hk[1] >= 1 and hk[4] >= a.cycles and len(acts) >= a.cycles and all(c for _, _, c in acts)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
