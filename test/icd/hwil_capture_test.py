#!/usr/bin/env python3
"""The packets of a real HWIL run decoded with the dictionary alone
(docs/icd.md, "Packet dictionary"; issue: "tested by decoding the packets of a
real HWIL run with an independent decoder that reads only the dictionary").

kestrel-fsw serves S1 (with FSW commands from scenario events at 20 s, so all
five APIDs travel), then S3 detumbling on its rods (ICD version 2's
magnetometer, rod dipoles and momentum telemetry), on loopback UDP;
`kestrel run --fsw udp:` flies each in lockstep through a relay written
here (harness -> relay -> kestrel-fsw and back), which records every
datagram and, in S1, loses the replies to the 101st sensor packet (the
harness sends it again after 0.25 s).  Each datagram is decoded by
dict_decoder.py, which reads only icd/generated/kestrel_dictionary.json, and:

- every CRC verifies and every packet decodes (nothing is injected);
- sequence counts advance by one per APID and sender (a retransmission
  repeats its bytes exactly; the FSW end answers it with that cycle's
  replies, counted in its rx_stale, no second cycle), t_ns strictly increases per cycle, and every
  sensor packet is answered by 0x181, 0x182, 0x183 with its t_ns;
- the decoded values equal the run's recorded results (telemetry.csv, %.17g,
  which round-trips binary64) at the same time, bit for bit: the FSW's
  inputs (meas_sigma_BN, meas_omega_BN_B, meas_att_valid), its commands
  (Lr_B, wheel_cmd = u_s), its health (sigma_BR, omega_BR_B, fsw_status,
  fsw_safe_output, per-stage status, sun_B, sun_valid, css_num_lit; in S3
  mode, policy, detumbled, rate_est, h_w_B, tau_mtq_B, the dump figures, the
  failed and latched wheel bits, mag_valid), the commands of the events
  (mode, reference, gains) and the FSW end's final link counters;
- cycles in the last link status = sensor packets = recorded rows (S3
  recorded at its control rate for this);
- with rods, some rod dipole command and some valid magnetometer field are
  not zero (the version-2 fields carry the run's data).

Exit 77 (skipped) when a program is missing.  Bounded: 40 s and 30 s of
simulated time (about 2 s of wall time), every wait has a timeout.
"""
import argparse
import csv
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
DURATION = 40.0     # [s] S1
S3_DURATION = 30.0  # [s] S3 detumbling


class Relay(threading.Thread):
    """harness -> relay (port A) -> upstream socket -> kestrel-fsw, and back.
    With lose_after = n, the 3 datagrams that answer the n-th upstream one are
    lost (not forwarded, not logged): the harness retransmits."""

    def __init__(self, fsw_addr, lose_after=None):
        super().__init__(daemon=True)
        self.down = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.down.bind(("127.0.0.1", 0))
        self.up = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.up.connect(fsw_addr)
        self.harness = None
        self.log = []  # (direction, bytes): "up" to the FSW, "down" from it
        self.stop = False
        self.lose_after, self.n_up, self.to_lose, self.lost = lose_after, 0, 0, 0

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
                    self.n_up += 1
                    if self.n_up == self.lose_after:
                        self.to_lose = 3
                    self.up.send(data)
                elif self.to_lose > 0:
                    self.to_lose -= 1
                    self.lost += 1
                elif self.harness is not None:
                    self.log.append(("down", data))
                    self.down.sendto(data, self.harness)


def bits(x):
    return struct.unpack(">Q", struct.pack(">d", x))[0]


def fail(msg):
    print("FAIL: " + msg, file=sys.stderr)
    return 1


class Failed(Exception):
    pass


def fly(a, tmp, name, text, duration, sets, lose_after):
    """One HWIL run of the scenario text through the relay: (datagrams, csv rows, wall time)."""
    scen = os.path.join(tmp, name + ".yaml")
    with open(scen, "w", encoding="utf-8") as fh:
        fh.write(text)
    img = os.path.join(tmp, name + ".img")
    sets = [w for kv in ["duration=%g" % duration] + sets for w in ("--set", kv)]
    subprocess.run([a.kestrel, "fsw-config", scen, "-o", img] + sets, check=True, timeout=60,
                   stdout=subprocess.DEVNULL)
    fsw = subprocess.Popen([a.fsw, "--udp", "127.0.0.1:0", "--config", img, "--quiet"], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
    relay = None
    try:
        r, _, _ = select.select([fsw.stdout], [], [], 30)
        ready = fsw.stdout.readline() if r else ""
        pre = "kestrel-fsw: ready udp "
        if not ready.startswith(pre):
            raise Failed("kestrel-fsw did not start: %r" % ready)
        host, port = ready[len(pre):].strip().rsplit(":", 1)
        relay = Relay((host, int(port)), lose_after)
        relay.start()
        out = os.path.join(tmp, name)
        t0 = time.monotonic()
        run = subprocess.run([a.kestrel, "run", scen, "--fsw", "udp:127.0.0.1:%d" % relay.port(), "-o", out,
                              "--csv", "--link-timeout", "30"] + sets, capture_output=True, text=True, timeout=120)
        wall = time.monotonic() - t0
        if run.returncode != 0:
            raise Failed("kestrel run failed (%d): %s" % (run.returncode, run.stderr[-2000:]))
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
        return relay.log, list(csv.reader(fh)), wall, relay.lost


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

    def scenario(name):
        with open(os.path.join(a.root, "scenarios", name), encoding="utf-8") as fh:
            return fh.read()
    # S1 with commands over the link at 20 s (inertial pointing at a new
    # reference with new gains): all five APIDs.  S3 detumbling on its rods:
    # the magnetometer in, rod dipoles out, the momentum telemetry.
    s1 = scenario("s1_sun_pointing.yaml") + (
        "\nevents:\n  - {t: 20, actions: [{device: fsw, action: mode_inertial}, "
        "{device: fsw, action: reference_z, value: 0.1}, {device: fsw, action: gain_K, value: 5.0}]}\n")
    # (name, scenario, duration, APIDs that must travel, columns that must be compared, --set,
    #  the upstream datagram whose replies are lost: S1's 101st sensor packet)
    runs = [("s1_commands", s1, DURATION, ("sensor", "command", "actuator", "health", "link_status"),
             ("sun_B_x", "css_num_lit", "wheel_cmd_3"), [], 101),
            ("s3_detumble", scenario("s3_detumble_hold.yaml"), S3_DURATION, ("sensor", "actuator", "health",
                                                                              "link_status"),
             ("fsw_rate_est", "fsw_tau_mtq_B_z", "fsw_h_w_B_x", "mag_valid", "fsw_detumbled"),
             ["rates.record_divisor=1"], None)]
    status = 0
    with tempfile.TemporaryDirectory() as tmp:
        for name, text, duration, apids, columns, sets, lose_after in runs:
            try:
                log, rows, wall, lost = fly(a, tmp, name, text, duration, sets, lose_after)
            except Failed as e:
                return fail("%s: %s" % (name, e))
            print("== %s" % name)
            status |= check(d, log, rows, wall, apids, columns, name == "s1_commands", lost)
    return status


def column_index(header):
    return {h.split(" [")[0]: i for i, h in enumerate(header)}


def check(d, log, rows, wall, apids, columns, commanded, lost):
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
    for name in apids:
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
    # replies lost: the harness sent the sensor packet again, byte for byte, and
    # the FSW end answered it with the same replies, counted as stale, no cycle
    if lost and (retrans < 1 or final["rx_stale"] != retrans):
        problems.append("%d replies lost: %d retransmissions, rx_stale %d" % (lost, retrans, final["rx_stale"]))
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
    n_rw = sensors[0]["fields"]["n_rw"]
    seen = set()
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
        # recorded only when the FSW detumbles, points at nadir or manages momentum (S3)
        pairs += [("fsw_mode", hl["mode"]), ("fsw_policy", hl["policy"]), ("fsw_detumbled", hl["detumbled"]),
                  ("fsw_rate_est", hl["rate_est"]), ("fsw_dump_phase", hl["dump_phase"]), ("fsw_dumps", hl["dumps"]),
                  ("fsw_prop_used", hl["prop_used"]), ("mag_valid", sf["mag_valid"])]
        pairs += [("fsw_%s_B_%s" % (q, ax), hl["%s_B" % q][i]) for q in ("h_w", "tau_mtq") for i, ax in enumerate("xyz")]
        pairs += [("fsw_rw_%s_%d" % (q, i), (hl["rw_" + q] >> i) & 1) for q in ("failed", "latched") for i in range(n_rw)]
        optional = ("fsw_mode", "fsw_policy", "fsw_detumbled", "fsw_rate_est", "fsw_dump", "fsw_prop", "fsw_h_w",
                    "fsw_tau", "fsw_rw_", "mag_", "sun_", "css_")
        pairs = [(n, v) for n, v in pairs if n in col or not n.startswith(optional)]
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
            seen.add(name)
        compared += 1
    if compared != len(data) or compared < 30:
        problems.append("only %d of %d rows matched a sensor packet" % (compared, len(data)))
    for name in columns:
        if name not in seen:
            problems.append("column %s never compared" % name)
    # the event's commands, as the packet carries them
    cmds = [p["fields"] for _, p, _ in decoded if p["packet"] == "command"]
    if commanded:
        c = cmds[0] if cmds else {}
        if (c.get("mode"), c.get("set_ref"), c.get("set_gains"), c.get("K")) != (1, 1, 1, 5.0) \
                or bits(c["sigma_R0N"][2]) != bits(0.1):
            problems.append("command packet: %s" % c)
    mtq = {p["fields"]["n_mtq"] for _, p, _ in decoded if p["packet"] == "actuator"}
    if max(mtq) > 0:  # ICD version 2's fields carry the run's data: rod dipoles out, the field in
        if not any(x != 0.0 for _, p, _ in decoded if p["packet"] == "actuator" for x in p["fields"]["m_cmd"]):
            problems.append("rods configured, every m_cmd 0")
        if not any(s["fields"]["mag_valid"] and any(s["fields"]["B_B"]) for s in sensors):
            problems.append("rods configured, no valid magnetometer field")
    print("%d sensor packets (%d retransmissions), %d command packets, n_rw %d, n_mtq %s; %d rows compared, %d "
          "values (%d columns) compared bit for bit" % (len(sensors), retrans, len(cmds), n_rw, sorted(mtq), compared,
                                                values, len(seen)))
    if problems:
        return fail("\n  ".join(problems[:20]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
