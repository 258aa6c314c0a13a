#!/usr/bin/env python3
"""Seed corpus of fuzz_fsw_link, written from docs/icd.md alone (an
implementation independent of fsw_link.c): one packet per APID, an empty and
a full sensor packet, and a framed byte stream.  Run from this folder.
(config_image_s1 in the corpus is not written here: it is the output of
`kestrel fsw-config scenarios/s1_sun_pointing.yaml`, a valid configuration
image for the fuzzer to mutate.)"""
import binascii, os, struct

def packet(apid, tc, seq, t_ns, payload):
    w0 = (tc << 12) | (1 << 11) | apid
    w1 = (3 << 14) | (seq % 16384)
    body = struct.pack('>HHHQ', w0, w1, 8 + len(payload) + 2 - 1, t_ns) + payload
    return body + struct.pack('>H', binascii.crc_hqx(body, 0xFFFF))

def sensor(nrw, ncss):
    p = struct.pack('>BBBB', nrw, ncss, 1, 0) + struct.pack('>9d', 0.1, 0.2, 0.3, 0.01, -0.02, 0.03, 0, 0, 0.5)
    p += struct.pack('>%dd' % nrw, *[100.0 * i for i in range(nrw)]) + bytes([i % 2 for i in range(nrw)])
    p += struct.pack('>%dd' % ncss, *[0.5] * ncss) + bytes(ncss)
    return packet(0x101, 1, 1, 100000000, p)

seeds = {
    'sensor_4rw_8css': sensor(4, 8),
    'sensor_empty': sensor(0, 0),
    'cmd_inertial': packet(0x102, 1, 2, 5, bytes([1, 0, 0, 0])),
    'actuator_4rw_2thr': packet(0x181, 0, 3, 7, bytes([4, 2, 1, 0]) + struct.pack('>15d', *range(15))),
    'health': packet(0x182, 0, 4, 9, struct.pack('>hBBBBBBII', 0, 1, 0, 0, 1, 3, 11, 10, 1)
                     + struct.pack('>11h', *([0] * 11)) + struct.pack('>11d', *([0.0] * 11))
                     + struct.pack('>7Ih', 0, 0, 0, 0, 0, 0, 10, 0)),
    'link_status': packet(0x183, 0, 5, 9, struct.pack('>9IHBB', 10, 1, 2, 3, 4, 1, 2, 1, 9, 9, 0, 0)),
}
seeds['stream'] = b'\x00\x1a\xcf' + b''.join(b'\x1a\xcf\xfc\x1d' + s for s in seeds.values())
os.makedirs('corpus/fuzz_fsw_link', exist_ok=True)
for name, data in seeds.items():
    with open(os.path.join('corpus/fuzz_fsw_link', name), 'wb') as f:
        f.write(data)
