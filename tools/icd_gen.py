#!/usr/bin/env python3
"""Writes the packet dictionary of the Kestrel FSW link from the one packet
table (icd/packets.yaml, docs/icd.md "Packet dictionary"):

  icd/generated/kestrel_dictionary.json   JSON dictionary (every packet, field,
                                           type, unit, offset rule, CRC)
  icd/generated/kestrel.xtce.xml          OMG XTCE 1.2 SpaceSystem
  icd/generated/cosmos/cmd.txt, tlm.txt   OpenC3/COSMOS definitions (fixed
                                           layouts for the table's cosmos_counts)
  icd/generated/kestrel_icd.h             the table's constants for C

Usage:
  icd_gen.py [--root DIR]                 write the files
  icd_gen.py --check [--root DIR]         exit 1 naming every stale file
  icd_gen.py --check-docs [--root DIR]    docs/icd.md's tables against the table
  icd_gen.py --check-app [--root DIR]     the cFS application's message ids, command
                                           codes and lengths against the table (exit
                                           77 when apps/cfs/kestrel_acs is not there)
  icd_gen.py --counts n_rw=4,n_css=6,n_thr=8,n_mtq=0 --cosmos-out DIR
                                           COSMOS files for another configuration
Python 3 standard library and PyYAML only.
"""
import argparse
import json
import os
import re
import sys
import xml.sax.saxutils as sx

import yaml

TYPES = {  # name: (bytes, signed)
    "u8": (1, False), "u16": (2, False), "u32": (4, False), "u64": (8, False),
    "i16": (2, True), "f64": (8, None)}
HEADER_SIZE = 14  # primary 6 + secondary 8
CRC_SIZE = 2


class TableError(Exception):
    pass


# ---- the table ------------------------------------------------------------

def check_fields(where, fields, allow_counts=True):
    names = set()
    counts = {}
    for i, f in enumerate(fields):
        w = "%s.fields[%d]" % (where, i)
        for key in ("name", "type"):
            if key not in f:
                raise TableError("%s: missing '%s'" % (w, key))
        if f["type"] not in TYPES:
            raise TableError("%s (%s): unknown type '%s'" % (w, f["name"], f["type"]))
        known = {"name", "type", "count", "unit", "flag", "value", "max", "enum", "bits", "bits_cap", "elements",
                 "max_value", "desc"}
        extra = set(f) - known
        if extra:
            raise TableError("%s (%s): unknown key(s) %s" % (w, f["name"], ", ".join(sorted(extra))))
        if f["name"] in names and f["name"] != "reserved" and f["name"] != "spare":
            raise TableError("%s: duplicate name '%s'" % (w, f["name"]))
        names.add(f["name"])
        c = f.get("count", 1)
        if isinstance(c, str):
            if not allow_counts or c not in counts:
                raise TableError("%s (%s): count '%s' is not an earlier count field" % (w, f["name"], c))
        elif not isinstance(c, int) or c < 1:
            raise TableError("%s (%s): bad count %r" % (w, f["name"], c))
        if "elements" in f and len(f["elements"]) != c:
            raise TableError("%s (%s): %d elements for count %r" % (w, f["name"], len(f["elements"]), c))
        if "max" in f:
            counts[f["name"]] = f["max"]


def load_table(path):
    with open(path, encoding="utf-8") as fh:
        t = yaml.safe_load(fh)
    for key in ("icd_version", "crc", "primary_header", "secondary_header", "packets", "capacities", "enums", "cfs"):
        if key not in t:
            raise TableError("%s: missing top-level key '%s'" % (path, key))
    bits = sum(f["bits"] for f in t["primary_header"])
    if bits != 48:
        raise TableError("primary_header: %d bits, not 48" % bits)
    apids = set()
    for p in t["packets"]:
        if p["apid"] in apids:
            raise TableError("packet %s: duplicate APID 0x%X" % (p["name"], p["apid"]))
        apids.add(p["apid"])
        check_fields("packet " + p["name"], p["fields"])
        for f in p["fields"]:
            if "max" in f and f["max"] not in t["capacities"]:
                raise TableError("packet %s field %s: unknown capacity %s" % (p["name"], f["name"], f["max"]))
            if "enum" in f and f["enum"] not in t["enums"]:
                raise TableError("packet %s field %s: unknown enum %s" % (p["name"], f["name"], f["enum"]))
    return t


def lin_add(a, b, k=1):
    out = {"const": a["const"] + k * b["const"], "per": dict(a["per"])}
    for n, c in b["per"].items():
        out["per"][n] = out["per"].get(n, 0) + k * c
    out["per"] = {n: c for n, c in out["per"].items() if c}
    return out


def lin_str(e):
    s = str(e["const"])
    for n, c in e["per"].items():
        s += " + %d*%s" % (c, n)
    return s


def layout(fields, base=0):
    """Fields with their offset rules (linear in the counts) and the size."""
    off = {"const": base, "per": {}}
    out = []
    seen = {}
    for f in fields:
        g = dict(f)
        g["id"] = f["name"]  # unique: reserved and spare fields are numbered
        if f["name"] in ("reserved", "spare"):
            seen[f["name"]] = seen.get(f["name"], 0) + 1
            g["id"] = "%s%d" % (f["name"], seen[f["name"]])
        size, _ = TYPES[f["type"]]
        c = f.get("count", 1)
        g["count"] = c
        g["size"] = size
        g["offset"] = off
        step = {"const": size * c, "per": {}} if isinstance(c, int) else {"const": 0, "per": {c: size}}
        off = lin_add(off, step)
        out.append(g)
    return out, lin_add(off, {"const": -base, "per": {}})


def dictionary(t):
    pk = []
    for p in t["packets"]:
        fields, size = layout(p["fields"])
        pk.append({"name": p["name"], "apid": p["apid"], "type": p["type"], "direction": p["direction"],
                   "struct": p["struct"], "desc": p["desc"], "payload_size": size,
                   "payload_offset": HEADER_SIZE, "fields": fields})
    cfs = dict(t["cfs"])
    for key in ("command_header", "telemetry_header"):
        h = dict(cfs[key])
        h["fields"], _ = layout(h["fields"])
        cfs[key] = h

    def resolved(item, what, header):
        """A cFS message or command code with its payload's offsets (after header)."""
        item = dict(item)
        if "fields" in item:
            check_fields("cfs %s %s" % (what, item["name"]), item["fields"], allow_counts=False)
            item["fields"], size = layout(item["fields"], cfs[header]["size"])
            item["payload_size"] = size["const"]
        return item
    cfs["commands"] = [dict(c, codes=[resolved(cc, "command", "command_header") for cc in c["codes"]])
                       for c in cfs["commands"]]
    cfs["telemetry"] = [resolved(m, "telemetry", "telemetry_header") for m in cfs["telemetry"]]
    return {
        "format": "kestrel-packet-dictionary", "format_version": 1, "name": t["name"],
        "icd_version": t["icd_version"], "byte_order": t["byte_order"],
        "source": "icd/packets.yaml (generated by tools/icd_gen.py; do not edit)",
        "types": {n: {"size": s, "kind": "float" if sg is None else ("signed" if sg else "unsigned"),
                      "encoding": "IEEE-754 binary64" if sg is None else
                      ("two's complement" if sg else "unsigned binary")} for n, (s, sg) in TYPES.items()},
        "offset_rule": "offset = const + sum(per[count] * value of that count field); fields in wire order",
        "capacities": t["capacities"], "crc": t["crc"], "primary_header": t["primary_header"],
        "secondary_header": layout(t["secondary_header"], 6)[0], "header_size": HEADER_SIZE,
        "crc_size": CRC_SIZE, "enums": {k: {str(n): v for n, v in e.items()} for k, e in t["enums"].items()},
        "packets": pk, "cfs": cfs, "cosmos_counts": t["cosmos_counts"]}


# ---- XTCE 1.2 ---------------------------------------------------------------

def x(s):
    return sx.escape(str(s), {'"': "&quot;"})


def xtce_name(s):
    return re.sub(r"[^A-Za-z0-9_]", "_", s)


class Xtce:
    def __init__(self, d):
        self.d = d
        self.ptypes = {}   # type name -> xml
        self.params = []   # xml lines
        self.conts = []

    def base_type(self, f):
        """Name of the (scalar) parameter type of a field, creating it."""
        unit = f.get("unit", "")
        if "enum" in f:
            name = "%s_%s_Type" % (f["enum"], f["type"])
        else:
            name = "%s%s_Type" % (f["type"], "_" + xtce_name(unit) if unit and unit != "-" else "")
        if name in self.ptypes:
            return name
        size, signed = TYPES[f["type"]]
        bits = 8 * size
        units = '<xtce:UnitSet><xtce:Unit>%s</xtce:Unit></xtce:UnitSet>' % x(unit) if unit else "<xtce:UnitSet/>"
        if signed is None:
            xml = ('<xtce:FloatParameterType name="%s" sizeInBits="64">%s'
                   '<xtce:FloatDataEncoding encoding="IEEE754_1985" sizeInBits="64"/></xtce:FloatParameterType>'
                   % (name, units))
        else:
            enc = '<xtce:IntegerDataEncoding encoding="%s" sizeInBits="%d"/>' % (
                "twosComplement" if signed else "unsigned", bits)
            if "enum" in f:
                items = "".join('<xtce:Enumeration value="%s" label="%s"/>' % (v, x(l))
                                for v, l in sorted(self.d["enums"][f["enum"]].items(), key=lambda kv: int(kv[0])))
                xml = ('<xtce:EnumeratedParameterType name="%s">%s%s<xtce:EnumerationList>%s'
                       '</xtce:EnumerationList></xtce:EnumeratedParameterType>' % (name, units, enc, items))
            else:
                xml = ('<xtce:IntegerParameterType name="%s" signed="%s" sizeInBits="%d">%s%s'
                       '</xtce:IntegerParameterType>' % (name, "true" if signed else "false", bits, units, enc))
        self.ptypes[name] = xml
        return name

    def bits_type(self, bits):
        name = "uint%d_bits_Type" % bits
        self.ptypes.setdefault(name, '<xtce:IntegerParameterType name="%s" signed="false" sizeInBits="%d">'
                               '<xtce:UnitSet/><xtce:IntegerDataEncoding encoding="unsigned" sizeInBits="%d"/>'
                               '</xtce:IntegerParameterType>' % (name, bits, bits))
        return name

    def array_type(self, f, prefix):
        base = self.base_type(f)
        c = f["count"]
        if isinstance(c, int):
            name = "%s_x%d_Type" % (base[:-5], c)
            end = '<xtce:FixedValue>%d</xtce:FixedValue>' % (c - 1)
        else:
            name = "%s_%s_%s_Type" % (base[:-5], prefix, c)
            end = ('<xtce:DynamicValue><xtce:ParameterInstanceRef parameterRef="%s_%s"/>'
                   '<xtce:LinearAdjustment intercept="-1"/></xtce:DynamicValue>' % (prefix, c))
        self.ptypes.setdefault(name, '<xtce:ArrayParameterType name="%s" arrayTypeRef="%s"><xtce:DimensionList>'
                               '<xtce:Dimension><xtce:StartingIndex><xtce:FixedValue>0</xtce:FixedValue>'
                               '</xtce:StartingIndex><xtce:EndingIndex>%s</xtce:EndingIndex></xtce:Dimension>'
                               '</xtce:DimensionList></xtce:ArrayParameterType>' % (name, base, end))
        return name

    def param(self, name, ptype, desc="", unit=None):
        d = ' shortDescription="%s"' % x(desc) if desc else ""
        self.params.append('<xtce:Parameter name="%s" parameterTypeRef="%s"%s/>' % (name, ptype, d))

    def fields(self, prefix, fields):
        """Parameters of a field list; returns the entry list XML."""
        entries = []
        for f in fields:
            n = f["id"]
            pname = "%s_%s" % (prefix, n)
            if f["count"] == 1:
                t = self.base_type(f)
            else:
                t = self.array_type(f, prefix)
            desc = f.get("desc", "")
            if "value" in f:
                desc = (desc + "; " if desc else "") + "always %s" % f["value"]
            if "max_value" in f:
                desc = (desc + "; " if desc else "") + "at most %s" % f["max_value"]
            if f.get("flag"):
                desc = (desc + "; " if desc else "") + "flag 0/1"
            if "bits" in f:
                desc = (desc + "; " if desc else "") + "bit i: " + f["bits"]
            if "elements" in f:
                desc = (desc + "; " if desc else "") + "elements " + ", ".join(f["elements"])
            self.param(pname, t, desc)
            entries.append('<xtce:ParameterRefEntry parameterRef="%s"/>' % pname)
        return "".join(entries)

    def build(self):
        d = self.d
        # Kestrel link header (CCSDS primary + t_ns) and CRC
        hdr = []
        for f in d["primary_header"]:
            self.param("KS_" + f["name"], self.bits_type(f["bits"]), f.get("desc", ""))
            hdr.append('<xtce:ParameterRefEntry parameterRef="KS_%s"/>' % f["name"])
        self.param("KS_t_ns", self.base_type({"type": "u64", "unit": "ns"}), d["secondary_header"][0]["desc"])
        hdr.append('<xtce:ParameterRefEntry parameterRef="KS_t_ns"/>')
        self.param("KS_crc", self.base_type({"type": "u16"}),
                   "%s over every byte before it (poly 0x%04X, init 0x%04X)" %
                   (d["crc"]["name"], d["crc"]["poly"], d["crc"]["init"]))
        self.conts.append('<xtce:SequenceContainer name="KestrelHeader" shortDescription="CCSDS primary header and '
                          't_ns of every link packet"><xtce:EntryList>%s</xtce:EntryList></xtce:SequenceContainer>'
                          % "".join(hdr))
        self.conts.append('<xtce:SequenceContainer name="KestrelPacket" abstract="true"><xtce:EntryList>'
                          '<xtce:ContainerRefEntry containerRef="KestrelHeader"/></xtce:EntryList>'
                          '</xtce:SequenceContainer>')
        for p in d["packets"]:
            pre = p["name"]
            entries = self.fields(pre, p["fields"])
            self.conts.append('<xtce:SequenceContainer name="%s_payload" shortDescription="%s"><xtce:EntryList>%s'
                              '</xtce:EntryList></xtce:SequenceContainer>' % (pre, x(p["desc"]), entries))
            self.conts.append(
                '<xtce:SequenceContainer name="%s" shortDescription="APID 0x%03X %s"><xtce:EntryList>'
                '<xtce:ContainerRefEntry containerRef="%s_payload"/><xtce:ParameterRefEntry parameterRef="KS_crc"/>'
                '</xtce:EntryList><xtce:BaseContainer containerRef="KestrelPacket"><xtce:RestrictionCriteria>'
                '<xtce:ComparisonList><xtce:Comparison parameterRef="KS_apid" value="%d"/>'
                '<xtce:Comparison parameterRef="KS_type" value="%d"/></xtce:ComparisonList>'
                '</xtce:RestrictionCriteria></xtce:BaseContainer></xtce:SequenceContainer>'
                % (pre, p["apid"], x(p["desc"]), pre, p["apid"], p["type"]))
        # cFS wrapping
        cfs = d["cfs"]
        th = []
        for f in cfs["telemetry_header"]["fields"]:
            self.param("CFS_TLM_" + f["name"], self.base_type({"type": f["type"], "unit": f.get("unit", "")}),
                       f.get("desc", ""))
            th.append('<xtce:ParameterRefEntry parameterRef="CFS_TLM_%s"/>' % f["name"])
        self.conts.append('<xtce:SequenceContainer name="CfsTlmHeader" abstract="true"><xtce:EntryList>%s'
                          '</xtce:EntryList></xtce:SequenceContainer>' % "".join(th))
        for m in cfs["telemetry"]:
            if "embeds" in m:
                entries = ('<xtce:ContainerRefEntry containerRef="KestrelHeader"/>'
                           '<xtce:ContainerRefEntry containerRef="%s_payload"/>'
                           '<xtce:ParameterRefEntry parameterRef="KS_crc"/>' % m["embeds"])
            else:
                entries = self.fields(m["name"], m["fields"])
            self.conts.append(
                '<xtce:SequenceContainer name="%s" shortDescription="%s"><xtce:EntryList>%s</xtce:EntryList>'
                '<xtce:BaseContainer containerRef="CfsTlmHeader"><xtce:RestrictionCriteria>'
                '<xtce:Comparison parameterRef="CFS_TLM_stream_id" value="%d"/></xtce:RestrictionCriteria>'
                '</xtce:BaseContainer></xtce:SequenceContainer>' % (m["name"], x(m["desc"]), entries, m["mid"]))
        return self.commands()

    def commands(self):
        d = self.d
        atypes = {}
        args_xml = []

        def atype(f):
            unit = f.get("unit", "")
            size, signed = TYPES[f["type"]]
            name = "%s%s_ArgType" % (f["type"], "_" + xtce_name(unit) if unit and unit != "-" else "")
            units = '<xtce:UnitSet><xtce:Unit>%s</xtce:Unit></xtce:UnitSet>' % x(unit) if unit else "<xtce:UnitSet/>"
            if signed is None:
                xml = ('<xtce:FloatArgumentType name="%s" sizeInBits="64">%s<xtce:FloatDataEncoding '
                       'encoding="IEEE754_1985" sizeInBits="64"/></xtce:FloatArgumentType>' % (name, units))
            else:
                xml = ('<xtce:IntegerArgumentType name="%s" signed="%s" sizeInBits="%d">%s<xtce:IntegerDataEncoding '
                       'encoding="%s" sizeInBits="%d"/></xtce:IntegerArgumentType>'
                       % (name, "true" if signed else "false", 8 * size, units,
                          "twosComplement" if signed else "unsigned", 8 * size))
            atypes[name] = xml
            return name

        def arglist(fields, fixed):
            args, entries = [], []
            for f in fields:
                n = f["id"]
                tname = atype(f)
                for i in range(f["count"]):
                    an = n if f["count"] == 1 else "%s_%d" % (n, i)
                    if "value" in f:
                        fixed.append('<xtce:FixedValueEntry name="%s" binaryValue="%0*X" sizeInBits="%d"/>'
                                     % (an, 2 * f["size"], f["value"], 8 * f["size"]))
                        entries.append(fixed[-1])
                        continue
                    args.append('<xtce:Argument name="%s" argumentTypeRef="%s"/>' % (an, tname))
                    entries.append('<xtce:ArgumentRefEntry argumentRef="%s"/>' % an)
            return "".join(args), "".join(entries)

        mc = []
        # the link command packet (APID 0x102): fixed length
        cmdp = next(p for p in d["packets"] if p["name"] == "command")
        hdr_args = ('<xtce:Argument name="seq_count" argumentTypeRef="uint14_ArgType"/>'
                    '<xtce:Argument name="t_ns" argumentTypeRef="u64_ns_ArgType"/>')
        atypes["uint14_ArgType"] = ('<xtce:IntegerArgumentType name="uint14_ArgType" signed="false" sizeInBits="14">'
                                    '<xtce:UnitSet/><xtce:IntegerDataEncoding encoding="unsigned" sizeInBits="14"/>'
                                    '</xtce:IntegerArgumentType>')
        atype({"type": "u64", "unit": "ns"})
        atype({"type": "u16"})
        a, e = arglist(cmdp["fields"], [])
        plen = HEADER_SIZE - 6 + cmdp["payload_size"]["const"] + CRC_SIZE - 1
        mc.append(
            '<xtce:MetaCommand name="LINK_COMMAND" shortDescription="APID 0x102 link command packet; the ground '
            'system appends the CRC (%s)"><xtce:ArgumentList>%s%s'
            '<xtce:Argument name="crc" argumentTypeRef="u16_ArgType"/></xtce:ArgumentList><xtce:CommandContainer '
            'name="LINK_COMMAND_Container"><xtce:EntryList>'
            '<xtce:FixedValueEntry name="pri1" binaryValue="%04X" sizeInBits="16"/>'
            '<xtce:FixedValueEntry name="seq_flags" binaryValue="03" sizeInBits="2"/>'
            '<xtce:ArgumentRefEntry argumentRef="seq_count"/>'
            '<xtce:FixedValueEntry name="length" binaryValue="%04X" sizeInBits="16"/>'
            '<xtce:ArgumentRefEntry argumentRef="t_ns"/>%s<xtce:ArgumentRefEntry argumentRef="crc"/>'
            '</xtce:EntryList></xtce:CommandContainer></xtce:MetaCommand>'
            % (d["crc"]["name"], hdr_args, a, (1 << 12) | (1 << 11) | cmdp["apid"], plen, e))
        # the cFS ground commands
        cfs = d["cfs"]
        for c in cfs["commands"]:
            for cc in c["codes"]:
                if "fields" not in cc:
                    continue  # the link wrapper: a whole packet, sent by the link, not by hand
                a, e = arglist(cc["fields"], [])
                total = cfs["command_header"]["size"] + cc["payload_size"]
                mc.append(
                    '<xtce:MetaCommand name="%s_%s" shortDescription="MID 0x%04X CC %d; the ground system sets the '
                    'checksum (XOR of every byte = 0xFF)"><xtce:ArgumentList>%s'
                    '<xtce:Argument name="checksum" argumentTypeRef="u8_ArgType"/></xtce:ArgumentList>'
                    '<xtce:CommandContainer name="%s_%s_Container"><xtce:EntryList>'
                    '<xtce:FixedValueEntry name="stream_id" binaryValue="%04X" sizeInBits="16"/>'
                    '<xtce:FixedValueEntry name="sequence" binaryValue="C000" sizeInBits="16"/>'
                    '<xtce:FixedValueEntry name="length" binaryValue="%04X" sizeInBits="16"/>'
                    '<xtce:FixedValueEntry name="function_code" binaryValue="%02X" sizeInBits="8"/>'
                    '<xtce:ArgumentRefEntry argumentRef="checksum"/>%s</xtce:EntryList></xtce:CommandContainer>'
                    '</xtce:MetaCommand>'
                    % (cfs["app"], cc["name"], c["mid"], cc["cc"], a, cfs["app"], cc["name"], c["mid"], total - 7,
                       cc["cc"], e))
        atype({"type": "u8"})
        return atypes, mc

    def text(self):
        atypes, mc = self.build()
        d = self.d
        lines = ['<?xml version="1.0" encoding="UTF-8"?>',
                 '<!-- Generated by tools/icd_gen.py from icd/packets.yaml: do not edit. -->',
                 '<xtce:SpaceSystem xmlns:xtce="http://www.omg.org/spec/XTCE/20180204" '
                 'xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" '
                 'xsi:schemaLocation="http://www.omg.org/spec/XTCE/20180204 '
                 'https://www.omg.org/spec/XTCE/20180204/SpaceSystem.xsd" name="%s">' % d["name"],
                 '<xtce:Header version="ICD %d" classification="NotClassified"/>' % d["icd_version"],
                 '<xtce:TelemetryMetaData>', '<xtce:ParameterTypeSet>']
        lines += [self.ptypes[k] for k in sorted(self.ptypes)]
        lines += ['</xtce:ParameterTypeSet>', '<xtce:ParameterSet>'] + self.params + ['</xtce:ParameterSet>',
                                                                                       '<xtce:ContainerSet>']
        lines += self.conts + ['</xtce:ContainerSet>', '</xtce:TelemetryMetaData>', '<xtce:CommandMetaData>',
                               '<xtce:ArgumentTypeSet>']
        lines += [atypes[k] for k in sorted(atypes)]
        lines += ['</xtce:ArgumentTypeSet>', '<xtce:MetaCommandSet>'] + mc + ['</xtce:MetaCommandSet>',
                                                                              '</xtce:CommandMetaData>',
                                                                              '</xtce:SpaceSystem>']
        return "\n".join(lines) + "\n"


# ---- OpenC3 / COSMOS ---------------------------------------------------------

COSMOS_TYPE = {"u8": "UINT", "u16": "UINT", "u32": "UINT", "u64": "UINT", "i16": "INT", "f64": "FLOAT"}


def cosmos_items(fields, counts, prefix=""):
    out = []
    for f in fields:
        n = f["id"]
        n = (prefix + n).upper()
        c = f["count"] if isinstance(f["count"], int) else counts[f["count"]]
        bits = 8 * f["size"]
        desc = f.get("desc", f["name"]).replace('"', "'")
        if "max" in f:
            out.append('  APPEND_ITEM %s %d %s "%s (this definition: %d)"' % (n, bits, COSMOS_TYPE[f["type"]], desc,
                                                                             counts[f["name"]]))
        elif c == 1:
            out.append('  APPEND_ITEM %s %d %s "%s"' % (n, bits, COSMOS_TYPE[f["type"]], desc))
        elif c > 0:
            out.append('  APPEND_ARRAY_ITEM %s %d %s %d "%s"' % (n, bits, COSMOS_TYPE[f["type"]], bits * c, desc))
        else:
            continue
        unit = f.get("unit")
        if unit and unit != "-":
            out.append("    UNITS %s %s" % (unit, unit))
        if "enum" in f and c == 1:
            enum = f["enum"]
            out += ["    STATE %s %s" % (lab, v) for v, lab in sorted(ENUMS[enum].items(), key=lambda kv: int(kv[0]))]
    return out


ENUMS = {}


def cosmos(d, counts):
    ENUMS.update(d["enums"])
    crc = d["crc"]
    note = ("# Generated by tools/icd_gen.py from icd/packets.yaml: do not edit.\n"
            "# Fixed layouts for %s (tools/icd_gen.py --counts writes others).\n"
            "# Kestrel link packets carry a %s (poly 0x%04X, init 0x%04X) in their last 2 bytes:\n"
            "# on the interface to kestrel-fsw (target KESTREL, not the cFS one): PROTOCOL READ_WRITE CrcProtocol "
            "CRC FALSE ERROR -16 16 BIG_ENDIAN 0x%04X 0x%04X "
            "FALSE FALSE\n" % (", ".join("%s = %d" % kv for kv in counts.items()), crc["name"], crc["poly"],
                               crc["init"], crc["poly"], crc["init"]))
    def link_header(p, ids):
        ident = "APPEND_ID_ITEM" if ids else "APPEND_ITEM"
        t = (" %d" % p["type"]) if ids else ""
        a = (" 0x%03X" % p["apid"]) if ids else ""
        pre = "" if ids else "KS_"
        return ['  APPEND_ITEM %sCCSDS_VERSION 3 UINT "CCSDS packet version"' % pre,
                '  %s %sCCSDS_TYPE 1 UINT%s "1 to the FSW, 0 from it"' % (ident, pre, t),
                '  APPEND_ITEM %sCCSDS_SHF 1 UINT "secondary header flag"' % pre,
                '  %s %sCCSDS_APID 11 UINT%s "APID"' % (ident, pre, a),
                '  APPEND_ITEM %sCCSDS_SEQFLAGS 2 UINT "sequence flags (3)"' % pre,
                '  APPEND_ITEM %sCCSDS_SEQCNT 14 UINT "sequence count"' % pre,
                '  APPEND_ITEM %sCCSDS_LENGTH 16 UINT "packet data length"' % pre,
                '  APPEND_ITEM %sT_NS 64 UINT "sample time"' % pre, '    UNITS ns ns']

    tlm = [note]
    for p in d["packets"]:
        tlm.append('TELEMETRY KESTREL %s BIG_ENDIAN "APID 0x%03X %s"' % (p["name"].upper(), p["apid"], p["desc"]))
        tlm += link_header(p, True)
        tlm += cosmos_items(p["fields"], counts)
        tlm.append('  APPEND_ITEM CRC 16 UINT "%s"' % crc["name"])
        tlm.append("")
    cfs = d["cfs"]
    th = ['  APPEND_ID_ITEM CCSDS_STREAMID 16 UINT 0x%04X "cFS message id"',
          '  APPEND_ITEM CCSDS_SEQUENCE 16 UINT "sequence flags and count"',
          '  APPEND_ITEM CCSDS_LENGTH 16 UINT "total bytes - 7"',
          '  APPEND_ITEM CCSDS_SECONDS 32 UINT "cFE time, seconds"',
          '  APPEND_ITEM CCSDS_SUBSECS 16 UINT "cFE time, 2^-16 s"',
          '  APPEND_ITEM CCSDS_SPARE 32 UINT "spare"']
    for m in cfs["telemetry"]:
        tlm.append('TELEMETRY %s %s BIG_ENDIAN "MID 0x%04X %s"' % (cfs["app"], m["name"].replace("KESTREL_ACS_", "")
                                                                  .replace("_TLM_MID", ""), m["mid"], m["desc"]))
        tlm += [th[0] % m["mid"]] + th[1:]
        if "embeds" in m:
            p = next(q for q in d["packets"] if q["name"] == m["embeds"])
            tlm += link_header(p, False)
            tlm += cosmos_items(p["fields"], counts, "KS_")
            tlm.append('  APPEND_ITEM KS_CRC 16 UINT "%s"' % crc["name"])
        else:
            tlm += cosmos_items(m["fields"], counts)
        tlm.append("")
    cmd = [note.replace("Kestrel link packets carry a", "A Kestrel link packet (LINK_COMMAND) carries a")
           .replace("in their last", "in its last")]
    cmdp = next(p for p in d["packets"] if p["name"] == "command")
    cmd.append('COMMAND KESTREL LINK_COMMAND BIG_ENDIAN "APID 0x102 %s"' % cmdp["desc"])
    plen = HEADER_SIZE - 6 + cmdp["payload_size"]["const"] + CRC_SIZE - 1
    cmd += ['  APPEND_PARAMETER CCSDS_VERSION 3 UINT 0 0 0 "CCSDS packet version"',
            '  APPEND_PARAMETER CCSDS_TYPE 1 UINT 1 1 1 "telecommand"',
            '  APPEND_PARAMETER CCSDS_SHF 1 UINT 1 1 1 "secondary header flag"',
            '  APPEND_ID_PARAMETER CCSDS_APID 11 UINT 0x102 0x102 0x102 "APID"',
            '  APPEND_PARAMETER CCSDS_SEQFLAGS 2 UINT 3 3 3 "unsegmented"',
            '  APPEND_PARAMETER CCSDS_SEQCNT 14 UINT 0 16383 0 "sequence count"',
            '  APPEND_PARAMETER CCSDS_LENGTH 16 UINT %d %d %d "packet data length"' % (plen, plen, plen),
            '  APPEND_PARAMETER T_NS 64 UINT MIN MAX 0 "sample time [ns]"']
    cmd += cmd_params(cmdp["fields"])
    cmd.append('  APPEND_PARAMETER CRC 16 UINT MIN MAX 0 "%s (CrcProtocol fills it)"' % crc["name"])
    cmd.append("")
    for c in cfs["commands"]:
        for cc in c["codes"]:
            block = "fields" not in cc  # a whole link packet: variable length, a block
            n = 0 if block else cfs["command_header"]["size"] + cc["payload_size"] - 7
            length = "MIN MAX 0" if block else "%d %d %d" % (n, n, n)
            what = ": one whole link packet (%s)" % ", ".join(cc["embeds"]) if block else ""
            cmd.append('COMMAND %s %s BIG_ENDIAN "MID 0x%04X CC %d%s"'
                       % (cfs["app"], cc["name"], c["mid"], cc["cc"], what))
            cmd += ['  APPEND_ID_PARAMETER CCSDS_STREAMID 16 UINT 0x%04X 0x%04X 0x%04X "cFS message id"'
                    % ((c["mid"],) * 3),
                    '  APPEND_PARAMETER CCSDS_SEQUENCE 16 UINT MIN MAX 0xC000 "sequence flags and count"',
                    '  APPEND_PARAMETER CCSDS_LENGTH 16 UINT %s "total bytes - 7"' % length,
                    '  APPEND_ID_PARAMETER CCSDS_FC 8 UINT %d %d %d "command code"' % ((cc["cc"],) * 3),
                    '  APPEND_PARAMETER CCSDS_CHECKSUM 8 UINT MIN MAX 0 "XOR of every byte = 0xFF"']
            if block:
                cmd += ['  APPEND_PARAMETER PACKET 0 BLOCK "" "the link packet, CRC included"', ""]
                continue
            cmd += cmd_params(cc["fields"])
            cmd.append("")
    return "\n".join(cmd), "\n".join(tlm)


def cmd_params(fields):
    out = []
    for f in fields:
        n = f["id"]
        bits = 8 * f["size"]
        t = COSMOS_TYPE[f["type"]]
        desc = f.get("desc", f["name"]).replace('"', "'")
        if f["count"] > 1:
            out.append('  APPEND_ARRAY_PARAMETER %s %d %s %d "%s"' % (n.upper(), bits, t, bits * f["count"], desc))
            continue
        dflt = f.get("value", 0)
        if t == "FLOAT":
            out.append('  APPEND_PARAMETER %s 64 FLOAT MIN MAX 0.0 "%s"' % (n.upper(), desc))
        else:
            hi = 1 if f.get("flag") else (1 << bits) - 1
            lo = dflt if "value" in f else 0
            hi = dflt if "value" in f else hi
            out.append('  APPEND_PARAMETER %s %d %s %d %d %d "%s"' % (n.upper(), bits, t, lo, hi, dflt, desc))
        if f.get("unit") and f["unit"] != "-":
            out.append("    UNITS %s %s" % (f["unit"], f["unit"]))
        if "enum" in f:
            out += ["    STATE %s %s" % (lab, v) for v, lab in sorted(ENUMS[f["enum"]].items(),
                                                                       key=lambda kv: int(kv[0]))]
    return out


# ---- C header ------------------------------------------------------------------

def c_header(d):
    """Constants of the table for C code: APIDs, payload sizes, header and CRC,
    capacities, the cFS message ids, command codes, payload lengths and
    housekeeping offsets (KESTREL_ICD_*, so it sits beside fsw_link.h)."""
    L = ["/* Generated by tools/icd_gen.py from icd/packets.yaml: do not edit.",
         " * The packet table's constants for C (docs/icd.md, \"Packet dictionary\");",
         " * test/icd/icd_constants_check.c holds fsw_link.h to them. */",
         "#ifndef KESTREL_ICD_H", "#define KESTREL_ICD_H", "",
         "#define KESTREL_ICD_VERSION %du" % d["icd_version"],
         "#define KESTREL_ICD_HEADER_SIZE %du /* primary 6 + t_ns 8 */" % d["header_size"],
         "#define KESTREL_ICD_CRC_SIZE %du" % d["crc_size"],
         "#define KESTREL_ICD_CRC_POLY 0x%04Xu /* %s */" % (d["crc"]["poly"], d["crc"]["name"]),
         "#define KESTREL_ICD_CRC_INIT 0x%04Xu" % d["crc"]["init"],
         "#define KESTREL_ICD_CRC_CHECK 0x%04Xu /* of \"123456789\" */" % d["crc"]["check"]]
    L += ["#define KESTREL_ICD_%s %du" % (k, v) for k, v in d["capacities"].items()]
    for p in d["packets"]:
        n = p["name"].upper()
        counts = [f["name"] for f in p["fields"] if "max" in f]
        e = p["payload_size"]
        expr = "%du" % e["const"] + "".join(" + %du * (size_t)(%s)" % (c, k) for k, c in e["per"].items())
        L += ["", "/* 0x%03X %s */" % (p["apid"], p["desc"]),
              "#define KESTREL_ICD_%s_APID 0x%03Xu" % (n, p["apid"]),
              "#define KESTREL_ICD_%s_TYPE %du" % (n, p["type"]),
              "#define KESTREL_ICD_%s_PAYLOAD(%s) (%s)" % (n, ", ".join(counts), expr) if counts else
              "#define KESTREL_ICD_%s_PAYLOAD %du" % (n, e["const"])]
    cfs = d["cfs"]
    L += ["", "/* cFS application %s: message ids, command codes, payload lengths [bytes] */" % cfs["app"],
          "#define KESTREL_ICD_CFS_CMD_HEADER_SIZE %du" % cfs["command_header"]["size"],
          "#define KESTREL_ICD_CFS_TLM_HEADER_SIZE %du" % cfs["telemetry_header"]["size"]]
    short = lambda name: name.replace("KESTREL_ACS_", "")  # noqa: E731
    for m in cfs["commands"] + cfs["telemetry"]:
        L.append("#define KESTREL_ICD_CFS_%s 0x%04Xu" % (short(m["name"]), m["mid"]))
    for m in cfs["commands"]:
        for cc in m["codes"]:
            L.append("#define KESTREL_ICD_CFS_%s_CC %du" % (cc["name"], cc["cc"]))
            if "fields" in cc:
                L.append("#define KESTREL_ICD_CFS_%s_LEN %du" % (cc["name"], cc["payload_size"]))
    for m in cfs["telemetry"]:
        if "fields" in m:
            base = cfs["telemetry_header"]["size"]
            tag = short(m["name"]).replace("_TLM_MID", "")
            L.append("#define KESTREL_ICD_CFS_%s_LEN %du" % (tag, m["payload_size"]))
            L += ["#define KESTREL_ICD_CFS_%s_OFF_%s %du /* %s */" % (tag, f["id"].upper(), f["offset"]["const"] - base,
                                                                  f["type"]) for f in m["fields"]]
    return "\n".join(L + ["", "#endif /* KESTREL_ICD_H */", ""])


# ---- docs/icd.md ---------------------------------------------------------------

DOC_SECTIONS = {"sensor": "### 0x101 sensor", "command": "### 0x102 command", "actuator": "### 0x181 actuator",
                "health": "### 0x182 health", "link_status": "### 0x183 link status"}


def doc_table(text, heading):
    """Rows (offset, type, field text) of the first table after a heading."""
    i = text.find("\n" + heading)
    if i < 0:
        return None
    rows = []
    started = False
    for line in text[i + 1:].splitlines()[1:]:
        if line.startswith("#"):
            break
        if line.startswith("|"):
            started = True
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if cells[0] in ("Offset", "") or set(cells[0]) <= set("-: "):
                continue
            rows.append(cells)
        elif started:
            break
    return rows


def eval_offset(expr, counts):
    e = expr.replace("·", "*").replace("×", "*").replace(" ", "")
    if not re.fullmatch(r"[0-9a-z_+*]+", e):
        raise ValueError("offset '%s' not understood" % expr)
    return eval(e, {"__builtins__": {}}, dict(counts))  # noqa: S307 (digits, names, + and * only)


def doc_type(cell, counts):
    m = re.fullmatch(r"(u8|u16|u32|u64|i16|f64)(?:\s*×\s*([0-9a-z_]+))?", cell)
    if not m:
        raise ValueError("type '%s' not understood" % cell)
    c = m.group(2) or "1"
    return m.group(1), int(c) if c.isdigit() else counts[c]


def check_docs(d, text):
    """Every problem of docs/icd.md's packet tables against the dictionary."""
    problems = []
    samples = [{"n_rw": a, "n_css": b, "n_thr": c, "n_mtq": e} for a, b, c, e in
               [(0, 0, 0, 0), (4, 8, 0, 0), (3, 5, 8, 2), (36, 32, 36, 8)]]
    for p in d["packets"]:
        heading = DOC_SECTIONS[p["name"]]
        rows = doc_table(text, heading)
        if not rows:
            problems.append("%s: no table" % heading)
            continue
        for cnt in samples:
            fields = [(f, eval_lin(f["offset"], cnt), f["size"] * (f["count"] if isinstance(f["count"], int)
                                                                  else cnt[f["count"]])) for f in p["fields"]]
            end = eval_lin(p["payload_size"], cnt)
            i = 0  # the table's fields are taken in order, as many as the row's bytes
            for k, row in enumerate(rows):
                try:
                    off = eval_offset(row[0], cnt)
                    typ, cnum = doc_type(row[1], cnt)
                except (ValueError, KeyError) as e:
                    problems.append("%s row %d: %s" % (heading, k + 1, e))
                    break
                size = TYPES[typ][0] * cnum
                if i >= len(fields) or fields[i][1] != off:
                    problems.append("%s row '%s | %s': no field of the table starts at %d (counts %s)"
                                    % (heading, row[0], row[1], off, cnt))
                    break
                inside = [fields[i]]
                got = fields[i][2]
                i += 1
                while got < size and i < len(fields):
                    inside.append(fields[i])
                    got += fields[i][2]
                    i += 1
                if got != size:
                    problems.append("%s row '%s | %s | %s': %d bytes in the docs, %d in the table (counts %s)"
                                    % (heading, row[0], row[1], row[2][:30], size, got, cnt))
                for f, _, _ in inside:
                    if f["type"] != typ:
                        problems.append("%s row '%s': type %s in the docs, %s in the table for %s"
                                        % (heading, row[2][:30], typ, f["type"], f["name"]))
                    if not re.search(r"(?<![A-Za-z0-9_])%s(?![A-Za-z0-9_])" % re.escape(f["name"]), row[2]):
                        problems.append("%s row '%s': does not name the table's field '%s'"
                                        % (heading, row[2][:40], f["name"]))
            if i != len(fields):
                problems.append("%s: the table's fields from '%s' on are not in the docs"
                                % (heading, fields[i][0]["name"] if i < len(fields) else "?"))
            last = eval_offset(rows[-1][0], cnt) + doc_size(rows[-1][1], cnt)
            if last != end:
                problems.append("%s: the docs' payload ends at %d, the table's at %d (counts %s)"
                                % (heading, last, end, cnt))
    # the APID summary table
    for p in d["packets"]:
        m = re.search(r"^\| 0x%03X \| %d \| [^|]+\| [^|]+\| ([^|]+) \|$" % (p["apid"], p["type"]), text, re.M)
        if not m:
            problems.append("APID table: no row for 0x%03X of type %d" % (p["apid"], p["type"]))
            continue
        for cnt in samples:
            if eval_offset(m.group(1).strip(), cnt) != eval_lin(p["payload_size"], cnt):
                problems.append("APID table: P of 0x%03X is %s, the table gives %s"
                                % (p["apid"], m.group(1).strip(), lin_str(p["payload_size"])))
                break
    v = re.search(r"This page is \*\*ICD version (\d+)\*\*", text)
    if not v or int(v.group(1)) != d["icd_version"]:
        problems.append("docs/icd.md does not state ICD version %d" % d["icd_version"])
    return sorted(set(problems))


def doc_size(cell, cnt):
    typ, c = doc_type(cell, cnt)
    return TYPES[typ][0] * c


def eval_lin(e, cnt):
    return e["const"] + sum(c * cnt[n] for n, c in e["per"].items())


# ---- the cFS application's constants -------------------------------------------

APP_DIR = os.path.join("apps", "cfs", "kestrel_acs")


def app_defines(root):
    """#define NAME <integer> of the application's headers."""
    out = {}
    for sub, _, files in os.walk(os.path.join(root, APP_DIR, "fsw")):
        for f in files:
            if f.endswith(".h"):
                with open(os.path.join(sub, f), encoding="utf-8") as fh:
                    pat = r"^#define\s+(KESTREL_ACS_\w+)\s+\(?(0[xX][0-9A-Fa-f]+|\d+)[uU]?\)?\s*(?:/\*.*)?$"
                    for m in re.finditer(pat, fh.read(), re.M):
                        out[m.group(1)] = int(m.group(2), 0)
    return out


def check_app(d, defs):
    """Every problem of the application's message ids, command codes and
    payload lengths (KESTREL_ACS_<NAME>_MID/_CC/_LEN, KESTREL_ACS_HK_LEN)."""
    cfs = d["cfs"]
    problems = []

    def expect(name, value):
        if name not in defs:
            problems.append("%s is not defined" % name)
        elif defs[name] != value:
            problems.append("%s is %d (0x%X), the table says %d (0x%X)" % (name, defs[name], defs[name], value, value))
    for m in cfs["commands"] + cfs["telemetry"]:
        expect(m["name"], m["mid"])
    for m in cfs["commands"]:
        # a bare request (one code, no payload: SEND_HK) needs no constants;
        # checked when the application defines them all the same
        bare = len(m["codes"]) == 1 and m["codes"][0].get("fields") == []
        for cc in m["codes"]:
            names = [("KESTREL_ACS_%s_CC" % cc["name"], cc["cc"])]
            if "fields" in cc:
                names.append(("KESTREL_ACS_%s_LEN" % cc["name"], cc["payload_size"]))
            for name, value in names:
                if not bare or name in defs:
                    expect(name, value)
    hk = next(m for m in cfs["telemetry"] if "fields" in m)
    expect("KESTREL_ACS_HK_LEN", hk["payload_size"])
    return problems


# ---- main ------------------------------------------------------------------

def render(root):
    t = load_table(os.path.join(root, "icd", "packets.yaml"))
    d = dictionary(t)
    cmd, tlm = cosmos(d, d["cosmos_counts"])
    return d, {"kestrel_dictionary.json": json.dumps(d, indent=1, sort_keys=False) + "\n",
               "kestrel.xtce.xml": Xtce(d).text(), "cosmos/cmd.txt": cmd, "cosmos/tlm.txt": tlm,
               "kestrel_icd.h": c_header(d)}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    ap.add_argument("--check", action="store_true", help="fail when a generated file is stale")
    ap.add_argument("--check-docs", action="store_true", help="docs/icd.md's tables against the table")
    ap.add_argument("--check-app", action="store_true", help="the cFS application's ids against the table")
    ap.add_argument("--counts", help="n_rw=..,n_css=..,n_thr=..,n_mtq=.. for the COSMOS files")
    ap.add_argument("--cosmos-out", help="folder for the COSMOS files of --counts")
    a = ap.parse_args(argv)
    try:
        d, files = render(a.root)
    except (TableError, KeyError, TypeError, yaml.YAMLError) as e:
        print("icd_gen: icd/packets.yaml: %s" % e, file=sys.stderr)
        return 2
    out = os.path.join(a.root, "icd", "generated")
    if a.counts:
        counts = dict(d["cosmos_counts"])
        for kv in a.counts.split(","):
            k, _, v = kv.partition("=")
            if k not in counts or not v.isdigit():
                print("icd_gen: --counts: bad entry '%s' (keys %s)" % (kv, ", ".join(counts)), file=sys.stderr)
                return 2
            counts[k] = int(v)
        cmd, tlm = cosmos(d, counts)
        os.makedirs(a.cosmos_out or ".", exist_ok=True)
        for name, text in (("cmd.txt", cmd), ("tlm.txt", tlm)):
            with open(os.path.join(a.cosmos_out or ".", name), "w", encoding="utf-8") as fh:
                fh.write(text)
        return 0
    if a.check_app:
        if not os.path.isdir(os.path.join(a.root, APP_DIR)):
            print("icd_gen: %s is not in this tree: nothing to check" % APP_DIR)
            return 77
        problems = check_app(d, app_defines(a.root))
        for p in problems:
            print("%s: %s" % (APP_DIR, p), file=sys.stderr)
        return 1 if problems else 0
    if a.check_docs:
        with open(os.path.join(a.root, "docs", "icd.md"), encoding="utf-8") as fh:
            problems = check_docs(d, fh.read())
        for p in problems:
            print("docs/icd.md: " + p, file=sys.stderr)
        return 1 if problems else 0
    stale = []
    for name, text in files.items():
        path = os.path.join(out, name)
        if a.check:
            try:
                with open(path, encoding="utf-8") as fh:
                    if fh.read() != text:
                        stale.append(name)
            except OSError:
                stale.append(name)
        else:
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(text)
    if stale:
        print("icd_gen: stale in icd/generated (run tools/icd_gen.py): %s" % ", ".join(stale), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
