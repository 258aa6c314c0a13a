#!/usr/bin/env python3
"""Writes the committed seed corpora of the FSW harnesses (corpus/<harness>/).

The harnesses decode every value as a perturbation of a nominal one and read
a byte of 0 (or the end of the input) as "nominal" (fuzz_input.h), so:
  nominal          empty input: the nominal config and sequence;
  v<k>             the nominal config of variant k (first byte: mode, pulser,
                   force sign ... for the harnesses that have variants);
  v<k>-mild-<j>    variant k with mostly nominal bytes and some modest
                   scalings / relative steps (a nominal run that differs in
                   details: reaches the ordinary paths and the warnings);
  v<k>-special-<j> the same with a few special values (NaN, inf, denormals,
                   huge/tiny, time backwards, counts at capacity).
Deterministic (fixed random seed): rerun after changing the harness list.
Usage: python3 test/fuzz/fsw/make_seeds.py
"""
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))
# harness -> number of variants selected by the first byte (1: no variant byte)
VARIANTS = {
    "trq_lpf": 1, "rw_sat": 2, "rw_volt": 2, "rw_speed_filter": 1, "rw_map": 2,
    "rw_null": 2, "rw_null_regen": 2, "thr_map": 4, "thr_pulse_rem": 2,
    "thr_pulse_schmitt": 2, "thr_pulse_round": 2, "css_sun": 1,
    "guid_sunsafe": 1, "guid_inertial": 1, "att_track": 1, "mrp_fb": 2, "acs": 4,
    "thr_momentum": 1,
    "mtq_map": 2, "mtq_desat": 1,
    "bdot": 2,
    "rw_bias": 1, "guid_orbit": 2,
}
# Variants added to a harness later: harness -> (first, end), written after
# all of the above so that the earlier seeds keep their bytes.  acs 4..15:
# bit 2 of the first byte (issue 14 paths) and bit 3 (issue 38: rods, orbit,
# momentum policies).
LATE_VARIANTS = {"acs": (4, 16)}


def seed_bytes(rng, variant, has_variant, n, p_mild, p_special):
    out = bytearray([variant]) if has_variant else bytearray()
    for _ in range(n):
        r = rng.random()
        if r < p_special:
            out.append(rng.randrange(192, 224))
        elif r < p_special + p_mild:
            out.append(rng.randrange(128, 192))
        else:
            out.append(rng.randrange(0, 128))
    return bytes(out)


def main():
    rng = random.Random(13)
    for name, nv in VARIANTS.items():
        d = os.path.join(HERE, "corpus", name)
        os.makedirs(d, exist_ok=True)
        files = {"nominal": b""}
        for v in range(nv):
            if nv > 1:
                files["v%d" % v] = bytes([v])
            for j in range(3):
                files["v%d-mild-%d" % (v, j)] = seed_bytes(rng, v, nv > 1, rng.randrange(48, 400), 0.12, 0.0)
            files["v%d-special-0" % v] = seed_bytes(rng, v, nv > 1, rng.randrange(48, 400), 0.08, 0.02)
        write(d, files)
    for name, (v0, v1) in LATE_VARIANTS.items():
        files = {}
        for v in range(v0, v1):
            files["v%d" % v] = bytes([v])
            for j in range(3):
                files["v%d-mild-%d" % (v, j)] = seed_bytes(rng, v, True, rng.randrange(48, 400), 0.12, 0.0)
            files["v%d-special-0" % v] = seed_bytes(rng, v, True, rng.randrange(48, 400), 0.08, 0.02)
        write(os.path.join(HERE, "corpus", name), files)
    for name, files in crafted().items():
        write(os.path.join(HERE, "corpus", name), files)


def crafted():
    """Hand-made seeds of issue 39 (no random bytes: the others keep theirs).

    rw_speed_filter signed-zero-*: four wheels, n_stale = 3 (byte 195), torque
    test off, 12 calls; wheel 0 reads +0.0 (special byte 196) and -0.0 (197):
    alternating (no repeat to the bit: never stale) or one sign (latched at the
    third repeat).
    acs cross-limit-*: first byte with bit 4 (fuzz_acs.cpp, issue 39) and the
    issue 14 bit (speed filter on): four factors on the filter's u_max follow
    (byte 128 + 17: x 1e-6; 136: x 0.999999; 137: x 1.000001), the case
    fsw_acs_check must refuse by name.
    """
    def speed_filter(zeros):
        cfg = bytes([0] + [0] * 12 + [0, 0, 200, 195, 0] + [0] * 4 + [11])
        step = lambda z: bytes([0, z, 0, 0, 0] + [0] * 4 + [0] * 4 + [0, 0])
        return cfg + b"".join(step(z) for z in zeros)
    return {
        "rw_speed_filter": {
            "signed-zero-alternating": speed_filter([196, 197] * 6),
            "signed-zero-repeated": speed_filter([197] * 12),
        },
        "acs": {
            # x 1e-6 on every wheel (the finding's 2.8e-4 against 0.2 N m)
            "cross-limit-0": bytes([20, 145, 145, 145, 145]),
            # x 0.999999 on the last wheel: just below, refused
            "cross-limit-1": bytes([20, 0, 0, 0, 136]),
            # x 1.000001 on the first: just above, accepted; the Schmitt/power
            # variant 21 and the full configuration 28 likewise
            "cross-limit-2": bytes([20, 137, 0, 0, 0]),
            "cross-limit-3": bytes([21, 145, 0, 0, 0]),
            "cross-limit-4": bytes([28 | 4, 145, 145, 145, 145]),
        },
    }


def write(d, files):
    for f, b in files.items():
        with open(os.path.join(d, f), "wb") as fh:
            fh.write(b)


if __name__ == "__main__":
    main()
