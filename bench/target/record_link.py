#!/usr/bin/env python3
"""Records the packets a closed-loop run sends to the flight software.

    bench/target/record_link.py KESTREL KESTREL_FSW SCENARIO OUT_DIR [--set KEY=VALUE ...]

Writes the run's configuration image (`kestrel fsw-config`) to OUT_DIR/config.kcfg,
starts `kestrel-fsw` on a loopback UDP port with it, runs `kestrel run SCENARIO
--fsw udp:...` against a relay on another port, and writes every packet the
harness sent (sensor and command packets, in order) to OUT_DIR/uplink.bin, each
as a big-endian u16 length and the packet, and the scenario and its --set
values to OUT_DIR/recorded.txt.  SCENARIO is best given relative to the source
folder (scenarios/...), as the check reads it from there.  The Cortex-M4F
timing benchmark (bench/target/m4f_link_replay.c) replays every recording of
bench/target/data through fsw_link_node_receive.  The files are written to
temporary names and renamed when the run succeeded.

    bench/target/record_link.py --check KESTREL DATA_DIR [--root SOURCE_DIR]

(ctest m4f_recording_<name>) fails when DATA_DIR/config.kcfg is not the image
`kestrel fsw-config` writes today for the scenario and --set values of
DATA_DIR/recorded.txt (the scenario or the image's layout changed: record
again), or when DATA_DIR/uplink.bin is not a whole sequence of sensor packets
(APID 0x101, sequence counts 0, 1, 2, ...).
"""
import argparse
import os
import select
import socket
import struct
import subprocess
import sys
import tempfile


def relay(sock_h, sock_f, fsw_addr, run, packets):
    """Moves datagrams between the harness and kestrel-fsw until the run ends."""
    harness_addr = None
    while True:
        ready, _, _ = select.select([sock_h, sock_f], [], [], 0.2)
        for s in ready:
            data, addr = s.recvfrom(65536)
            if s is sock_h:
                harness_addr = addr
                packets.append(data)
                sock_f.sendto(data, fsw_addr)
            elif harness_addr is not None:
                sock_h.sendto(data, harness_addr)
        if not ready and run.poll() is not None:
            return run.returncode


def check(argv):
    ap = argparse.ArgumentParser(prog="record_link.py --check")
    ap.add_argument("kestrel")
    ap.add_argument("data_dir")
    ap.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    a = ap.parse_args(argv)
    scenario, set_values = read_recorded(os.path.join(a.data_dir, "recorded.txt"))
    a.scenario = scenario
    sets = [x for s in set_values for x in ("--set", s)]
    with tempfile.TemporaryDirectory() as tmp:
        image = os.path.join(tmp, "config.kcfg")
        subprocess.run([a.kestrel, "fsw-config", os.path.join(a.root, scenario), "-o", image] + sets, check=True,
                       stdout=subprocess.DEVNULL)
        with open(image, "rb") as f:
            want = f.read()
    with open(os.path.join(a.data_dir, "config.kcfg"), "rb") as f:
        have = f.read()
    if have != want:
        return f"record_link: {a.data_dir}/config.kcfg ({len(have)} bytes) is not the image of {a.scenario} " \
               f"({len(want)} bytes): record again (bench/target/record_link.py)"
    with open(os.path.join(a.data_dir, "uplink.bin"), "rb") as f:
        up = f.read()
    off = n = 0
    while off < len(up):
        if off + 2 > len(up):
            return f"record_link: uplink.bin: a record cut short at byte {off}"
        (ln,) = struct.unpack_from(">H", up, off)
        pkt = up[off + 2:off + 2 + ln]
        if len(pkt) != ln or ln < 6:
            return f"record_link: uplink.bin: record {n} at byte {off} cut short"
        apid = ((pkt[0] & 7) << 8) | pkt[1]
        seq = ((pkt[2] & 0x3F) << 8) | pkt[3]
        if apid != 0x101 or seq != n % 16384:
            return f"record_link: uplink.bin: record {n}: APID {apid:#x}, sequence count {seq} (expected 0x101, {n})"
        off += 2 + ln
        n += 1
    print(f"record_link: {a.data_dir}: the configuration image of {a.scenario} {' '.join(sets)}, "
          f"{n} sensor packets in sequence")
    return 0


def read_recorded(path):
    """The scenario and the --set values of a recording (its recorded.txt)."""
    scenario, sets = None, []
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            key, _, value = line.partition(" ")
            if key == "scenario" and scenario is None and value:
                scenario = value
            elif key == "set" and "=" in value:
                sets.append(value)
            else:
                sys.exit(f"record_link: {path}:{n}: expected 'scenario PATH' once, then 'set KEY=VALUE' lines")
    if scenario is None:
        sys.exit(f"record_link: {path}: no 'scenario PATH' line")
    return scenario, sets


def main():
    if sys.argv[1:2] == ["--check"]:
        sys.exit(check(sys.argv[2:]))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("kestrel")
    ap.add_argument("kestrel_fsw")
    ap.add_argument("scenario")
    ap.add_argument("out_dir")
    ap.add_argument("--set", action="append", default=[], dest="sets")
    a = ap.parse_args()
    sets = [x for s in a.sets for x in ("--set", s)]
    os.makedirs(a.out_dir, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        image = os.path.join(tmp, "config.kcfg")
        subprocess.run([a.kestrel, "fsw-config", a.scenario, "-o", image] + sets, check=True)
        fsw = subprocess.Popen([a.kestrel_fsw, "--udp", "127.0.0.1:0", "--config", image],
                               stdout=subprocess.PIPE, text=True)
        try:
            line = fsw.stdout.readline()
            if "ready" not in line:
                sys.exit(f"record_link: kestrel-fsw did not start: {line!r}")
            port = int(line.strip().rsplit(":", 1)[1])
            sock_h = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            sock_h.bind(("127.0.0.1", 0))
            sock_f = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
            sock_f.bind(("127.0.0.1", 0))
            run = subprocess.Popen([a.kestrel, "run", a.scenario, "-o", os.path.join(tmp, "run"), "--force",
                                    "--fsw", f"udp:127.0.0.1:{sock_h.getsockname()[1]}"] + sets)
            packets = []
            rc = relay(sock_h, sock_f, ("127.0.0.1", port), run, packets)
            if rc != 0:
                sys.exit(f"record_link: kestrel run failed ({rc})")
        finally:
            fsw.terminate()
            fsw.wait()
        tmp_up = os.path.join(a.out_dir, ".uplink.bin.tmp")
        with open(tmp_up, "wb") as f:
            for p in packets:
                f.write(struct.pack(">H", len(p)) + p)
        tmp_cfg = os.path.join(a.out_dir, ".config.kcfg.tmp")
        with open(image, "rb") as src, open(tmp_cfg, "wb") as dst:
            dst.write(src.read())
        tmp_rec = os.path.join(a.out_dir, ".recorded.txt.tmp")
        with open(tmp_rec, "w", encoding="utf-8") as f:
            f.write("# the run these packets come from (bench/target/record_link.py)\n")
            f.write(f"scenario {a.scenario}\n" + "".join(f"set {v}\n" for v in a.sets))
        os.replace(tmp_cfg, os.path.join(a.out_dir, "config.kcfg"))
        os.replace(tmp_up, os.path.join(a.out_dir, "uplink.bin"))
        os.replace(tmp_rec, os.path.join(a.out_dir, "recorded.txt"))
    print(f"record_link: {len(packets)} packets, {sum(map(len, packets))} bytes -> {a.out_dir}/uplink.bin")


if __name__ == "__main__":
    main()
