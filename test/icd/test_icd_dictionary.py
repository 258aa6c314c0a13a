#!/usr/bin/env python3
"""The packet dictionary against the flight codec, the docs and itself
(docs/icd.md, "Packet dictionary").

  --dump EXE   icd_codec_dump (fsw_link_encode_* of every APID, several
               counts, random values): every packet decoded by the
               dictionary-only decoder (dict_decoder.py) equals the values
               the program put in, bit for bit for reals.
Without --dump only the checks that need no build run.  Also: the decoder
refuses damaged packets (CRC, length, counts, flags, reserved bytes); the
docs check of tools/icd_gen.py catches planted faults; every reference of
the XTCE file resolves; the cFS wrapping decodes.
"""
import argparse
import copy
import json
import os
import struct
import subprocess
import sys
import unittest
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from dict_decoder import DecodeError, Dictionary  # noqa: E402

ARGS = None


def root():
    return ARGS.root


def gen():
    sys.path.insert(0, os.path.join(root(), "tools"))
    import icd_gen
    return icd_gen


def bits(x):
    return "0x%016x" % struct.unpack(">Q", struct.pack(">d", x))[0]


def comparable(v):
    if isinstance(v, float):
        return bits(v)
    if isinstance(v, list):
        return [comparable(x) for x in v]
    return v


def crc_ccitt_false(data):
    """Written here from the standard's parameters (independent of both)."""
    c = 0xFFFF
    for b in data:
        c ^= b << 8
        for _ in range(8):
            c = ((c << 1) ^ 0x1021) & 0xFFFF if c & 0x8000 else (c << 1) & 0xFFFF
    return c


def reseal(pkt):
    pkt = bytearray(pkt)
    pkt[-2:] = crc_ccitt_false(pkt[:-2]).to_bytes(2, "big")
    return bytes(pkt)


def cfs_command(cc, payload, mid=0x18F0):
    """A cFS command message, written here: primary header, function code,
    checksum making the XOR of every byte 0xFF."""
    body = bytearray(mid.to_bytes(2, "big") + (0xC000).to_bytes(2, "big") + (8 + len(payload) - 7).to_bytes(2, "big")
                     + bytes([cc, 0]) + payload)
    x = 0
    for b in body:
        x ^= b
    body[7] = x ^ 0xFF
    return bytes(body)


class Dict(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.path = os.path.join(root(), "icd", "generated", "kestrel_dictionary.json")
        cls.d = Dictionary(cls.path)
        cls.packets = []
        if ARGS.dump:
            out = subprocess.run([ARGS.dump, "20261206"], check=True, capture_output=True, text=True).stdout
            cls.packets = [json.loads(line) for line in out.splitlines()]

    def test_codec_packets_decode_to_the_encoded_values(self):
        if not ARGS.dump:
            self.skipTest("no --dump")
        seen = {}
        for rec in self.packets:
            pkt = self.d.decode(bytes.fromhex(rec["hex"]))
            self.assertEqual(pkt["packet"], rec["packet"])
            exp = dict(rec["fields"])
            self.assertEqual(pkt["seq_count"], exp.pop("seq_count"))
            self.assertEqual(pkt["t_ns"], exp.pop("t_ns"))
            got = {k: comparable(v) for k, v in pkt["fields"].items()}
            self.assertEqual(got, exp, rec["packet"])
            seen[rec["packet"]] = seen.get(rec["packet"], 0) + 1
        # every APID, and the sensor/actuator at each of the 5 count sets, 4 times
        self.assertEqual(seen, {"sensor": 20, "actuator": 20, "command": 4, "health": 4, "link_status": 4})
        print("decoded %d packets of the flight codec, every field equal" % len(self.packets))

    def sample(self, name):
        if not ARGS.dump:
            self.skipTest("no --dump")
        return bytes.fromhex(next(r["hex"] for r in self.packets if r["packet"] == name and len(r["hex"]) > 400
                                  or r["packet"] == name and name not in ("sensor", "actuator")))

    def refused(self, pkt, why):
        with self.assertRaises(DecodeError) as cm:
            self.d.decode(pkt)
        self.assertIn(why, str(cm.exception))

    def test_damaged_packets_are_refused(self):
        s = self.sample("sensor")
        self.d.decode(s)
        for i in range(len(s) * 8):  # every single-bit flip: CRC (or header, length) refusal
            b = bytearray(s)
            b[i // 8] ^= 1 << (i % 8)
            with self.assertRaises(DecodeError):
                self.d.decode(bytes(b))
        self.refused(s[:-1], "length")
        self.refused(s[:10], "short")
        b = bytearray(s)
        b[14] = 37  # n_rw beyond FSW_MAX_RW = 36 (length fixed to match)
        self.refused(reseal(b), "n_rw")
        b = bytearray(s)
        b[16] = 2  # att_valid not a flag
        self.refused(reseal(b), "att_valid")
        b = bytearray(s)
        b[17] = 1  # reserved not 0
        self.refused(reseal(b), "reserved")
        b = bytearray(s)
        b[1] = 0x03  # APID 0x103: unknown
        self.refused(reseal(b), "APID")
        h = self.sample("health")
        b = bytearray(h)
        b[14 + 7] = 15  # stage count
        self.refused(reseal(b), "num_stages")
        b = bytearray(self.sample("link_status"))
        b[14 + 36:14 + 38] = (16384).to_bytes(2, "big")  # last_seq beyond the sequence counter
        self.refused(reseal(b), "last_seq")

    def test_thr_avail_bits_beyond_the_capacity_are_refused(self):
        s = bytearray(self.sample("sensor"))
        n_rw, n_css = s[14], s[15]
        off = 14 + 76 + 9 * n_rw + 9 * n_css
        s[off:off + 8] = (1 << 36).to_bytes(8, "big")
        self.refused(reseal(s), "thr_avail")

    def test_crc_check_value(self):
        self.assertEqual(self.d.crc(b"123456789"), 0x29B1)  # the standard's check value
        bad = copy.deepcopy(self.d.d)
        bad["crc"]["init"] = 0
        p = os.path.join(ARGS.tmp, "bad_dict.json")
        with open(p, "w") as fh:
            json.dump(bad, fh)
        with self.assertRaises(DecodeError):
            Dictionary(p)

    def test_cfs_wrapping(self):
        if not ARGS.dump:
            self.skipTest("no --dump")
        act = self.sample("actuator")
        # a cFS telemetry message 0x08F1: 16-byte header (primary 6, time 6, spare 4) + the packet
        msg = (0x08F1).to_bytes(2, "big") + (0xC000).to_bytes(2, "big") + (16 + len(act) - 7).to_bytes(2, "big")
        msg += (1234).to_bytes(4, "big") + (0x8000).to_bytes(2, "big") + bytes(4) + act
        m = self.d.decode_cfs(msg)
        self.assertEqual(m["name"], "KESTREL_ACS_ACTUATOR_TLM_MID")
        self.assertEqual(m["header"]["time_seconds"], 1234)
        self.assertEqual(m["packet"], self.d.decode(act))
        # housekeeping: 24 big-endian bytes
        hk = bytes([3, 1, 2, 1]) + b"".join(v.to_bytes(4, "big") for v in (100, 2, 5, 0xFFFFFFFB, 1))
        msg = (0x08F0).to_bytes(2, "big") + (0xC000).to_bytes(2, "big") + (16 + 24 - 7).to_bytes(2, "big")
        msg += bytes(10) + hk
        f = self.d.decode_cfs(msg)["fields"]
        self.assertEqual((f["command_count"], f["command_error_count"], f["mode"], f["config_loaded"], f["cycles"],
                          f["cycle_errors"], f["link_rejected"], f["last_status"], f["table_rejects"]),
                         (3, 1, 2, 1, 100, 2, 5, 0xFFFFFFFB, 1))
        # a ground command: SET_GAINS (CC 5), K = 2.5, P = 30, checksum XOR-to-0xFF
        cmd = bytearray(cfs_command(5, struct.pack(">dd", 2.5, 30.0)))
        c = self.d.decode_cfs(bytes(cmd))
        self.assertEqual((c["name"], c["fields"]["K"], c["fields"]["P"]), ("SET_GAINS", 2.5, 30.0))
        cmd[7] ^= 1
        with self.assertRaises(DecodeError):
            self.d.decode_cfs(bytes(cmd))
        # SET_MODE with a 5-byte payload: refused on its length
        with self.assertRaises(DecodeError):
            self.d.decode_cfs(cfs_command(2, bytes([1, 0, 0, 0, 0])))
        self.assertEqual(self.d.decode_cfs(cfs_command(2, bytes([1, 0, 0, 0])))["fields"]["mode"], 1)

    def test_generated_files_are_up_to_date(self):
        self.assertEqual(gen().main(["--root", root(), "--check"]), 0)

    def test_docs_tables_match_the_table(self):
        g = gen()
        with open(os.path.join(root(), "docs", "icd.md"), encoding="utf-8") as fh:
            text = fh.read()
        d = self.d.d
        self.assertEqual(g.check_docs(d, text), [])
        planted = [
            ("| 28 | f64 ×3 | omega_BN_B [rad/s] |", "| 29 | f64 ×3 | omega_BN_B [rad/s] |"),   # offset
            ("| 8 | u32 | cycles |", "| 8 | u16 | cycles |"),                               # type
            ("| 32 | f64 ×n_rw | u_s [N·m] |", "| 32 | f64 ×n_thr | u_s [N·m] |"),            # count
            ("| 45 | u8 | policy (", "| 45 | u8 | momentum (",),                                # name
            ("| 38 | u8 | link_safe (flag) |\n", ""),                                         # row gone
            ("| 0x183 | 0 | from the FSW | link status (the FSW end's link counters and the ICD version) | 40 |",
             "| 0x183 | 0 | from the FSW | link status (the FSW end's link counters and the ICD version) | 42 |"),
        ]
        for old, new in planted:
            self.assertIn(old, text)
            self.assertNotEqual(g.check_docs(d, text.replace(old, new)), [], "planted: " + new)

    def test_table_errors_are_reported(self):
        g = gen()
        import yaml
        with open(os.path.join(root(), "icd", "packets.yaml"), encoding="utf-8") as fh:
            t = yaml.safe_load(fh)
        cases = [("type", "f32", "unknown type 'f32'"), ("count", "n_thr", "count 'n_thr' is not an earlier"),
                 ("colour", "red", "unknown key(s) colour")]
        for key, val, msg in cases:
            bad = copy.deepcopy(t)
            bad["packets"][0]["fields"][7][key] = val  # sensor Omega
            p = os.path.join(ARGS.tmp, "icd", "packets.yaml")
            os.makedirs(os.path.dirname(p), exist_ok=True)
            with open(p, "w") as fh:
                yaml.safe_dump(bad, fh)
            with self.assertRaises(g.TableError) as cm:
                g.load_table(p)
            self.assertIn(msg, str(cm.exception))
            self.assertIn("packet sensor.fields[7] (Omega)", str(cm.exception))

    def test_cosmos_for_another_configuration(self):
        g = gen()
        out = os.path.join(ARGS.tmp, "cosmos")
        self.assertEqual(g.main(["--root", root(), "--counts", "n_thr=8,n_mtq=2", "--cosmos-out", out]), 0)
        with open(os.path.join(out, "tlm.txt")) as fh:
            tlm = fh.read()
        act = tlm[tlm.index("TELEMETRY KESTREL ACTUATOR"):tlm.index("TELEMETRY KESTREL HEALTH")]
        # 8 thrusters: F and t_on 8 x 64 bits; 2 rods: m_cmd 2 x 64; S1's 4 wheels kept
        for item in ("U_S 64 FLOAT 256", "F 64 FLOAT 512", "T_ON 64 FLOAT 512", "M_CMD 64 FLOAT 128"):
            self.assertIn("APPEND_ARRAY_ITEM " + item, act)
        self.assertEqual(g.main(["--root", root(), "--counts", "n_foo=3", "--cosmos-out", out]), 2)
        self.assertEqual(g.main(["--root", root(), "--counts", "n_rw=x", "--cosmos-out", out]), 2)

    def test_cfs_app_constants_check(self):
        g = gen()
        good = {"KESTREL_ACS_CMD_MID": 0x18F0, "KESTREL_ACS_LINK_MID": 0x18F1, "KESTREL_ACS_SEND_HK_MID": 0x18F2,
                "KESTREL_ACS_HK_TLM_MID": 0x08F0, "KESTREL_ACS_ACTUATOR_TLM_MID": 0x08F1,
                "KESTREL_ACS_HEALTH_TLM_MID": 0x08F2, "KESTREL_ACS_LINK_CC": 0, "KESTREL_ACS_HK_LEN": 24}
        for cc, (name, length) in enumerate([("NOOP", 0), ("RESET_COUNTERS", 0), ("SET_MODE", 4), ("SET_ACTUATION", 4),
                                             ("SET_REFERENCE", 24), ("SET_GAINS", 16), ("SET_MOMENTUM_POLICY", 4)]):
            good["KESTREL_ACS_%s_CC" % name] = cc
            good["KESTREL_ACS_%s_LEN" % name] = length
        app = os.path.join(ARGS.tmp, "app", g.APP_DIR, "fsw", "inc")
        os.makedirs(app, exist_ok=True)
        with open(os.path.join(app, "ids.h"), "w") as fh:
            fh.write("".join("#define %s 0x%Xu /* x */\n" % kv for kv in good.items()))
        self.assertEqual(g.check_app(self.d.d, g.app_defines(os.path.join(ARGS.tmp, "app"))), [])
        for name, value in (("KESTREL_ACS_SET_GAINS_LEN", 17), ("KESTREL_ACS_HEALTH_TLM_MID", 0x08F3),
                            ("KESTREL_ACS_SET_MODE_CC", 3)):
            bad = dict(good, **{name: value})
            self.assertEqual(g.check_app(self.d.d, bad), ["%s is %d (0x%X), the table says %d (0x%X)"
                                                          % (name, value, value, good[name], good[name])])
        del good["KESTREL_ACS_NOOP_CC"]
        self.assertEqual(g.check_app(self.d.d, good), ["KESTREL_ACS_NOOP_CC is not defined"])

    def test_xtce_references_resolve(self):
        ns = {"x": "http://www.omg.org/spec/XTCE/20180204"}
        tree = ET.parse(os.path.join(root(), "icd", "generated", "kestrel.xtce.xml"))
        r = tree.getroot()
        self.assertEqual(r.tag, "{%s}SpaceSystem" % ns["x"])
        types = {e.get("name") for e in r.find("x:TelemetryMetaData/x:ParameterTypeSet", ns)}
        params = {e.get("name") for e in r.findall(".//x:Parameter", ns)}
        conts = {e.get("name") for e in r.findall(".//x:SequenceContainer", ns)}
        atypes = {e.get("name") for e in r.find("x:CommandMetaData/x:ArgumentTypeSet", ns)}
        for e in r.iter():
            for attr, pool in (("parameterTypeRef", types), ("arrayTypeRef", types), ("parameterRef", params),
                               ("containerRef", conts), ("argumentTypeRef", atypes)):
                if e.get(attr) is not None:
                    self.assertIn(e.get(attr), pool, "%s=%s" % (attr, e.get(attr)))
        for p in self.d.d["packets"]:
            c = r.find(".//x:SequenceContainer[@name='%s']" % p["name"], ns)
            cmp_ = c.findall(".//x:Comparison", ns)
            self.assertEqual({(e.get("parameterRef"), int(e.get("value"))) for e in cmp_},
                             {("KS_apid", p["apid"]), ("KS_type", p["type"])})
        # a dynamic array: the wheel speeds are sized by the sensor packet's n_rw
        om = r.find(".//x:Parameter[@name='sensor_Omega']", ns).get("parameterTypeRef")
        arr = r.find(".//x:ArrayParameterType[@name='%s']" % om, ns)
        ref = arr.find(".//x:EndingIndex/x:DynamicValue/x:ParameterInstanceRef", ns)
        self.assertEqual(ref.get("parameterRef"), "sensor_n_rw")
        self.assertEqual(arr.find(".//x:LinearAdjustment", ns).get("intercept"), "-1")


def main():
    global ARGS
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True)
    ap.add_argument("--dump")
    ap.add_argument("--tmp", default=None)
    ARGS, rest = ap.parse_known_args()
    import tempfile
    with tempfile.TemporaryDirectory() as t:
        ARGS.tmp = ARGS.tmp or t
        prog = unittest.main(argv=[sys.argv[0]] + rest, exit=False, verbosity=2)
        return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
