#!/usr/bin/env python3
"""The packets of a real HWIL run decoded with the dictionary alone
(docs/icd.md, "Packet dictionary"; issue: "tested by decoding the packets of a
real HWIL run with an independent decoder that reads only the dictionary").

kestrel-fsw serves S1 (with FSW commands from scenario events at 20 s, so all
five APIDs travel) on loopback UDP; `kestrel run --fsw udp:` flies it in
lockstep through a relay written here (harness -> relay -> kestrel-fsw and
back), which records every datagram.  Each datagram is decoded by
dict_decoder.py, which reads only icd/generated/kestrel_dictionary.json, and:

- every CRC verifies and every packet decodes (nothing is injected);
- sequence counts advance by one per APID and sender (a retransmission
  repeats its bytes exactly), t_ns strictly increases per cycle, and every
  sensor packet is answered by 0x181, 0x182, 0x183 with its t_ns;
- the decoded values equal the run's recorded results (telemetry.csv, %.17g,
  which round-trips binary64) at the same time, bit for bit: the FSW's
  inputs (meas_sigma_BN, meas_omega_BN_B, meas_att_valid), its commands
  (Lr_B, wheel_cmd = u_s), its health (sigma_BR, omega_BR_B, fsw_status,
  fsw_safe_output, per-stage status, sun_B, sun_valid, css_num_lit), the
  commands of the events (mode, reference, gains) and the FSW end's final
  link counters;
- cycles in the last link status = sensor packets = rows - 1 x (control rate).

Exit 77 (skipped) when a program is missing.  Bounded: the run is 40 s of
simulated time (about 2 s of wall time), every wait has a timeout.
"""
import argparse
import csv
import math
import os
import select
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from dict_decoder import Dictionary  # noqa: E402

SKIP = 77
DURATION = 40.0


class Relay(threading.Thread):
    """harness -> relay (port A) -> upstream socket -> kestrel-fsw, and back."""

    def __init__(self, fsw_addr):
        super().__init__(daemon=True)
        self.down = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.down.bind(("127.0.0.1", 0))
        self.up = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.up.connect(fsw_addr)
        self.harness = None
        self.log = []  # (direction, bytes): "up" to the FSW, "down" from it
        self.stop = False

    def port(self):
        return self.down.getsockname()[1]

    def run(self):
        while not self.stop:
            r, _, _ = select.select([self.down, self.up], [], [], 0.05)
            for s in r:
                data, addr = s.recvfrom(65536)
                if s is self.down:
                    self.harness = addr
                    self.log.append(("up", data))
                    self.up.send(data)
                elif self.harness is not None:
                    self.log.append(("down", data))
                    self.down.sendto(data, self.harness)


def bits(x):
    return struct.unpack(">Q", struct.pack(">d", x))[0]


def fail(msg):
    print("FAIL: " + msg, file=sys.stderr)
    return 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True)
    ap.add_argument("--kestrel", required=True)
    ap.add_argument("--fsw", required=True)
    a = ap.parse_args()
    for exe in (a.kestrel, a.fsw):
        if not os.access(exe, os.X_OK):
            print("SKIP: %s not built" % exe)
            return SKIP
    d = Dictionary(os.path.join(a.root, "icd", "generated", "kestrel_dictionary.json"))
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(a.root, "scenarios", "s1_sun_pointing.yaml"), encoding="utf-8") as fh:
            text = fh.read()
        # commands over the link at 20 s: inertial pointing at a new reference with new gains
        text += ("\nevents:\n  - {t: 20, actions: [{device: fsw, action: mode_inertial}, "
                 "{device: fsw, action: reference_z, value: 0.1}, {device: fsw, action: gain_K, value: 5.0}]}\n")
        scen = os.path.join(tmp, "s1_commands.yaml")
        with open(scen, "w", encoding="utf-8") as fh:
            fh.write(text)
        img = os.path.join(tmp, "s1.img")
        subprocess.run([a.kestrel, "fsw-config", scen, "-o", img, "--set", "duration=%g" % DURATION], check=True,
                       timeout=60, stdout=subprocess.DEVNULL)
        fsw = subprocess.Popen([a.fsw, "--udp", "127.0.0.1:0", "--config", img, "--quiet"], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
        relay = None
        try:
            r, _, _ = select.select([fsw.stdout], [], [], 30)
            ready = fsw.stdout.readline() if r else ""
            pre = "kestrel-fsw: ready udp "
            if not ready.startswith(pre):
                return fail("kestrel-fsw did not start: %r" % ready)
            host, port = ready[len(pre):].strip().rsplit(":", 1)
            relay = Relay((host, int(port)))
            relay.start()
            out = os.path.join(tmp, "run")
            t0 = time.monotonic()
            run = subprocess.run([a.kestrel, "run", scen, "--fsw", "udp:127.0.0.1:%d" % relay.port(), "-o", out,
                                  "--csv", "--set", "duration=%g" % DURATION, "--link-timeout", "30"],
                                 capture_output=True, text=True, timeout=120)
            wall = time.monotonic() - t0
            if run.returncode != 0:
                return fail("kestrel run failed (%d): %s" % (run.returncode, run.stderr[-2000:]))
        finally:
            if relay is not None:
                relay.stop = True
                relay.join(5)
            fsw.send_signal(signal.SIGTERM)
            try:
                fsw.wait(10)
            except subprocess.TimeoutExpired:
                fsw.kill()
                fsw.wait()
        with open(os.path.join(out, "telemetry.csv"), newline="", encoding="utf-8") as fh:
            rows = list(csv.reader(fh))
        return check(d, relay.log, rows, wall)


def column_index(header):
    return {h.split(" [")[0]: i for i, h in enumerate(header)}


def check(d, log, rows, wall):
    problems = []
    decoded = []
    for direction, data in log:
        try:
            decoded.append((direction, d.decode(data), data))
        except Exception as e:  # noqa: BLE001 (every refusal is a failure here)
            problems.append("%s datagram of %d bytes refused: %s" % (direction, len(data), e))
    if problems:
        return fail("; ".join(problems[:5]))
    count = {}
    for direction, p, _ in decoded:
        count[p["packet"]] = count.get(p["packet"], 0) + 1
    print("captured %d datagrams in %.1f s: %s" % (len(log), wall,
                                                  ", ".join("%s %d" % kv for kv in sorted(count.items()))))
    for name in ("sensor", "command", "actuator", "health", "link_status"):
        if not count.get(name):
            problems.append("no %s packet captured" % name)

    # sequence counts per APID and direction; retransmissions repeat their bytes
    last = {}
    retrans = 0
    for direction, p, raw in decoded:
        key = (direction, p["apid"])
        if key in last:
            prev_seq, prev_raw = last[key]
            if raw == prev_raw:  # a retransmitted sensor packet, or the replies repeated for it
                retrans += direction == "up"
                continue
            if p["seq_count"] != (prev_seq + 1) % 16384:
                problems.append("APID 0x%X %s: sequence %d after %d" % (p["apid"], direction, p["seq_count"],
                                                                        prev_seq))
        last[key] = (p["seq_count"], raw)

    # lockstep: each new sensor packet answered by actuator, health, link status with its t_ns
    sensors = []
    replies = {}
    for direction, p, raw in decoded:
        if p["packet"] == "sensor":
            if not sensors or sensors[-1]["t_ns"] != p["t_ns"]:
                if sensors and p["t_ns"] <= sensors[-1]["t_ns"]:
                    problems.append("sensor t_ns %d not after %d" % (p["t_ns"], sensors[-1]["t_ns"]))
                sensors.append(p)
        elif direction == "down":
            replies.setdefault(p["t_ns"], {}).setdefault(p["packet"], p)
    for s in sensors:
        got = replies.get(s["t_ns"], {})
        for name in ("actuator", "health", "link_status"):
            if name not in got:
                problems.append("sensor packet t_ns %d: no %s reply" % (s["t_ns"], name))
    final = [p for direction, p, _ in decoded if p["packet"] == "link_status"][-1]["fields"]
    if final["cycles"] != len(sensors):
        problems.append("the FSW end ran %d cycles for %d sensor packets" % (final["cycles"], len(sensors)))
    if final["rx_crc"] + final["rx_rejected"] + final["missed"] != 0 or final["icd_version"] != 2:
        problems.append("final link status: %s" % final)

    # the run's recorded results at the same time, bit for bit
    col = column_index(rows[0])
    data = rows[1:]
    by_t = {}
    for r in data:
        by_t[round(float(r[col["t"]]) * 1e9)] = r
    stages = d.by_name["health"]["fields"]
    stage_names = next(f for f in stages if f["name"] == "stage_status")["elements"]
    compared = 0
    values = 0
    for s in sensors:
        r = by_t.get(s["t_ns"])
        if r is None:
            continue
        act = replies[s["t_ns"]]["actuator"]["fields"]
        hl = replies[s["t_ns"]]["health"]["fields"]
        sf = s["fields"]
        pairs = []
        for i, ax in enumerate("xyz"):
            pairs += [("meas_sigma_BN_" + ax, sf["sigma_BN"][i]), ("meas_omega_BN_B_" + ax, sf["omega_BN_B"][i]),
                      ("Lr_B_" + ax, act["Lr_B"][i]), ("sigma_BR_" + ax, hl["sigma_BR"][i]),
                      ("omega_BR_B_" + ax, hl["omega_BR_B"][i]), ("sun_B_" + ax, hl["sun_hat_B"][i])]
        pairs += [("meas_att_valid", sf["att_valid"]), ("fsw_status", hl["status"]),
                  ("fsw_safe_output", hl["safe_output"]), ("sun_valid", hl["sun_valid"]),
                  ("css_num_lit", hl["num_lit"])]
        pairs += [("wheel_cmd_%d" % i, u) for i, u in enumerate(act["u_s"])]
        pairs += [("fsw_stage_" + n, v) for n, v in zip(stage_names, hl["stage_status"])]
        for name, v in pairs:
            if name not in col:
                problems.append("telemetry.csv has no column %s" % name)
                continue
            rec = float(r[col[name]])
            if bits(rec) != bits(float(v)):
                if len(problems) < 20:
                    problems.append("t = %s s %s: recorded %r, packet %r" % (r[col["t"]], name, rec, v))
            values += 1
        compared += 1
    n_rw = sensors[0]["fields"]["n_rw"]
    if compared < len(data) - 1 or compared < 30:
        problems.append("only %d of %d rows matched a sensor packet" % (compared, len(data)))
    # the event's commands, as the packet carries them
    cmds = [p["fields"] for _, p, _ in decoded if p["packet"] == "command"]
    c = cmds[0]
    if (c["mode"], c["set_ref"], c["set_gains"], c["K"]) != (1, 1, 1, 5.0) or bits(c["sigma_R0N"][2]) != bits(0.1):
        problems.append("command packet: %s" % c)
    print("%d sensor packets (%d retransmissions), %d command packets, n_rw %d; %d rows compared, %d values "
          "compared bit for bit" % (len(sensors), retrans, len(cmds), n_rw, compared, values))
    if problems:
        return fail("\n  ".join(problems[:20]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
