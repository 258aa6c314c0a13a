#!/usr/bin/env python3
"""Seed corpus of fuzz_fsw_link, written from docs/icd.md alone (an
implementation independent of fsw_link.c), ICD version 2: one packet per
APID (two actuator packets: wheels and thrusters, and rods), an empty and a
full sensor packet, and a framed byte stream.  Run from this folder.
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
    p += struct.pack('>Q', 0b101)                                   # thr_avail: thrusters 0 and 2 out
    p += struct.pack('>9d', 2e-5, -1e-5, 3e-5, 6.9e6, 0, 0, 0, 7.6e3, 0)  # B_B, r_N, v_N
    p += bytes([1, 1])                                              # mag_valid, orbit_valid
    return packet(0x101, 1, 1, 100000000, p)

def actuator(nrw, nthr, nmtq):
    p = bytes([nrw, nthr, nmtq, 1, 0, 1]) + struct.pack('>H', 0)
    p += struct.pack('>%dd' % (3 + 2 * nrw + 2 * nthr + nmtq), *range(3 + 2 * nrw + 2 * nthr + nmtq))
    return packet(0x181, 0, 3, 7, p)

# ICD version 2 (docs/icd.md): payload sizes 158 + 9 n_rw + 9 n_css, 46,
# 32 + 16 n_rw + 16 n_thr + 8 n_mtq, 254 and 40 bytes.
seeds = {
    'sensor_4rw_8css': sensor(4, 8),
    'sensor_empty': sensor(0, 0),
    'cmd_inertial': packet(0x102, 1, 2, 5, bytes([1, 0, 0, 0]) + struct.pack('>5d', 0, 0, 0, 0, 0) + bytes([1, 2])),
    'actuator_4rw_2thr': actuator(4, 2, 0),
    'actuator_3mtq': actuator(0, 0, 3),
    'health': packet(0x182, 0, 4, 9, struct.pack('>hBBBBBBII', 0, 1, 0, 0, 1, 3, 16, 10, 1)
                     + struct.pack('>16h', *([0] * 16)) + struct.pack('>11d', *([0.0] * 11))
                     + struct.pack('>7Ih', 0, 0, 0, 0, 0, 0, 10, 0) + struct.pack('>QQ', 1, 0)
                     + bytes([2, 1, 0, 0]) + struct.pack('>I', 3) + struct.pack('>8d', *([0.5] * 8))),
    'link_status': packet(0x183, 0, 5, 9, struct.pack('>9IHBB', 10, 1, 2, 3, 4, 1, 2, 1, 9, 9, 0, 2)),
}
seeds['stream'] = b'\x00\x1a\xcf' + b''.join(b'\x1a\xcf\xfc\x1d' + s for s in seeds.values())
os.makedirs('corpus/fuzz_fsw_link', exist_ok=True)
for name, data in seeds.items():
    with open(os.path.join('corpus/fuzz_fsw_link', name), 'wb') as f:
        f.write(data)
