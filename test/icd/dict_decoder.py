"""A decoder of Kestrel link packets that reads ONLY the generated packet
dictionary (icd/generated/kestrel_dictionary.json): no Kestrel code, no
constants of its own.  The header bit fields, the CRC parameters, the
payload layouts (types, counts, repeats, fixed values, flags, capacities)
and the cFS wrapping all come from the dictionary, as a ground system's
decoder would take them.  Python 3 standard library only.

    d = Dictionary(path)
    pkt = d.decode(data)        # dict: packet, apid, type, seq_count, t_ns, fields
    pkt = d.decode_cfs(data)    # a cFS message (telemetry or command)
DecodeError says why a packet is refused.
"""
import json
import struct


class DecodeError(Exception):
    pass


class Dictionary:
    def __init__(self, path):
        with open(path, encoding="utf-8") as fh:
            self.d = json.load(fh)
        if self.d.get("format") != "kestrel-packet-dictionary":
            raise DecodeError("%s: not a Kestrel packet dictionary" % path)
        if self.d["byte_order"] != "big-endian":
            raise DecodeError("byte order %s not supported" % self.d["byte_order"])
        self.by_key = {(p["apid"], p["type"]): p for p in self.d["packets"]}
        self.by_name = {p["name"]: p for p in self.d["packets"]}
        c = self.d["crc"]
        if self.crc(b"123456789") != c["check"]:
            raise DecodeError("the dictionary's CRC parameters do not give its check value")

    # ---- CRC from the dictionary's parameters (any width, reflected or not)
    def crc(self, data):
        c = self.d["crc"]
        w, poly, reg = c["width"], c["poly"], c["init"]
        top, mask = 1 << (w - 1), (1 << w) - 1

        def refl(v, n):
            return int(format(v, "0%db" % n)[::-1], 2)
        for byte in data:
            if c["reflect_in"]:
                byte = refl(byte, 8)
            reg ^= byte << (w - 8)
            for _ in range(8):
                reg = ((reg << 1) ^ poly) & mask if reg & top else (reg << 1) & mask
        if c["reflect_out"]:
            reg = refl(reg, w)
        return reg ^ c["xor_out"]

    # ---- scalar reads
    def read(self, typ, data, off):
        t = self.d["types"][typ]
        raw = data[off:off + t["size"]]
        if len(raw) != t["size"]:
            raise DecodeError("short payload")
        if t["kind"] == "float":
            return struct.unpack(">d", raw)[0]
        return int.from_bytes(raw, "big", signed=t["kind"] == "signed")

    def fields(self, fields, data, off, end):
        """Decodes a field list from data[off:end]; returns (values, next offset)."""
        vals = {}
        caps = self.d["capacities"]
        for f in fields:
            n = f["count"] if isinstance(f["count"], int) else vals[f["count"]]
            size = f["size"]
            if off + size * n > end:
                raise DecodeError("payload too short for %s" % f["name"])
            v = [self.read(f["type"], data, off + size * i) for i in range(n)]
            off += size * n
            for x in v:
                if f.get("flag") and x not in (0, 1):
                    raise DecodeError("flag %s = %d" % (f["name"], x))
                if "value" in f and x != f["value"]:
                    raise DecodeError("%s = %d, not %d" % (f["name"], x, f["value"]))
                if "max_value" in f and x > f["max_value"]:
                    raise DecodeError("%s = %d, above %d" % (f["name"], x, f["max_value"]))
            if "max" in f and v[0] > caps[f["max"]]:
                raise DecodeError("count %s = %d beyond %s = %d" % (f["name"], v[0], f["max"], caps[f["max"]]))
            if "bits_cap" in f and v[0] >> caps[f["bits_cap"]]:
                raise DecodeError("%s: a bit at or above %s" % (f["name"], f["bits_cap"]))
            vals[f["name"]] = v[0] if f["count"] == 1 else v
        return vals, off

    def header(self, data):
        """The primary header's bit fields, from the dictionary's list."""
        word = int.from_bytes(data[:6], "big")
        out, pos = {}, 48
        for f in self.d["primary_header"]:
            pos -= f["bits"]
            out[f["name"]] = (word >> pos) & ((1 << f["bits"]) - 1)
            if "value" in f and out[f["name"]] != f["value"]:
                raise DecodeError("header %s = %d, not %d" % (f["name"], out[f["name"]], f["value"]))
        return out

    def decode(self, data):
        data = bytes(data)
        hs, cs = self.d["header_size"], self.d["crc_size"]
        if len(data) < hs + cs:
            raise DecodeError("short packet (%d bytes)" % len(data))
        h = self.header(data)
        total = 6 + h["data_length"] + 1
        if total != len(data):
            raise DecodeError("length field says %d bytes, packet has %d" % (total, len(data)))
        if self.crc(data[:-cs]) != int.from_bytes(data[-cs:], "big"):
            raise DecodeError("CRC mismatch")
        p = self.by_key.get((h["apid"], h["type"]))
        if p is None:
            raise DecodeError("unknown APID 0x%X type %d" % (h["apid"], h["type"]))
        out = {"packet": p["name"], "apid": h["apid"], "type": h["type"], "seq_count": h["seq_count"]}
        for f in self.d["secondary_header"]:
            out[f["name"]] = self.read(f["type"], data, f["offset"]["const"])
        vals, end = self.fields(p["fields"], data, p["payload_offset"], total - cs)
        if end != total - cs:
            raise DecodeError("%s: %d payload bytes, the counts give %d" % (p["name"], total - cs - hs, end - hs))
        out["fields"] = vals
        return out

    def decode_cfs(self, data):
        """A cFS message of the dictionary's cfs section."""
        data = bytes(data)
        cfs = self.d["cfs"]
        sid = int.from_bytes(data[:2], "big")
        length = int.from_bytes(data[4:6], "big") + 7
        if length != len(data):
            raise DecodeError("cFS length field says %d bytes, message has %d" % (length, len(data)))
        for m in cfs["telemetry"]:
            if m["mid"] == sid:
                hdr, _ = self.fields(cfs["telemetry_header"]["fields"], data, 0, cfs["telemetry_header"]["size"])
                out = {"mid": sid, "name": m["name"], "header": hdr}
                if "embeds" in m:
                    out["packet"] = self.decode(data[cfs["telemetry_header"]["size"]:])
                    if out["packet"]["packet"] != m["embeds"]:
                        raise DecodeError("MID 0x%04X carries %s" % (sid, out["packet"]["packet"]))
                else:
                    out["fields"], end = self.fields(m["fields"], data, cfs["telemetry_header"]["size"], len(data))
                    if end != len(data):
                        raise DecodeError("MID 0x%04X: %d bytes, expected %d" % (sid, len(data), end))
                return out
        for m in cfs["commands"]:
            if m["mid"] == sid:
                size = cfs["command_header"]["size"]
                hdr, _ = self.fields(cfs["command_header"]["fields"], data, 0, size)
                x = 0
                for b in data:
                    x ^= b
                if x != 0xFF:
                    raise DecodeError("cFS command checksum: XOR is 0x%02X" % x)
                cc = next((c for c in m["codes"] if c["cc"] == hdr["function_code"]), None)
                if cc is None:
                    raise DecodeError("MID 0x%04X: unknown command code %d" % (sid, hdr["function_code"]))
                out = {"mid": sid, "name": cc["name"], "header": hdr}
                if "embeds" in cc:
                    out["packet"] = self.decode(data[size:])
                    if out["packet"]["packet"] not in cc["embeds"]:
                        raise DecodeError("MID 0x%04X carries %s" % (sid, out["packet"]["packet"]))
                else:
                    out["fields"], end = self.fields(cc["fields"], data, size, len(data))
                    if end != len(data):
                        raise DecodeError("%s: %d bytes, expected %d" % (cc["name"], len(data), end))
                return out
        raise DecodeError("unknown cFS message id 0x%04X" % sid)
