#!/usr/bin/python3
"""Per-cycle cost of Python in the loop (docs/python.md, "Python in the loop"):
S1 at 10 Hz FSW, 100 Hz ticks, run in memory.

  PYTHONPATH=build/host-release/python /usr/bin/python3 bench/python/python_in_loop.py \
      scenarios/s1_sun_pointing.yaml [duration_s] [repetitions]

  - the C FSW (in process) against a Python FSW calling the same C
    application through kestrel.fsw.Acs (10 Hz): the difference per FSW cycle
  - a Python FSW returning {} (commands nothing): the cost of the seam
    alone (sensor dict out, actuator dict in)
  - no effector against a Python effector returning a constant torque at
    every tick: the difference per tick

Prints numbers only; not a test (speed figures are not asserted)."""
import sys
import time

import numpy as np

import kestrel
import kestrel.fsw as fsw


class AcsInPython:
    rate_hz = 10.0

    def __init__(self, sc):
        self.acs = fsw.Acs.from_scenario(sc)
        self.acs.init()

    def __call__(self, sensors):
        return self.acs.cycle(**sensors)[1]


ZERO = np.zeros(3)
TAU = np.array([0.0, 0.0, 1e-4])


def disturbance(t, state):
    return ZERO, TAU


def best(reps, f):
    out = []
    for _ in range(reps):
        t0 = time.perf_counter()
        r = f()
        out.append(time.perf_counter() - t0)
        assert r.complete, r.failure
    return min(out)


def main():
    path = sys.argv[1]
    duration = float(sys.argv[2]) if len(sys.argv) > 2 else 60.0
    reps = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    sc = kestrel.Scenario.load(path, {"duration": duration})
    ticks = sc.num_ticks
    cycles = ticks // sc.get("rates.fsw_divisor") + 1
    t_c = best(reps, lambda: kestrel.run(sc))
    t_py = best(reps, lambda: kestrel.run(sc, fsw=AcsInPython(sc)))
    t_nil = best(reps, lambda: kestrel.run(sc, fsw=lambda sensors: {}))
    t_eff = best(reps, lambda: kestrel.run(sc, effectors=[disturbance]))
    c, p = kestrel.run(sc), kestrel.run(sc, fsw=AcsInPython(sc))
    cmd = [i for i, n in enumerate(c.columns) if n.startswith(("Lr_B_", "wheel_cmd_", "omega_BN_B_", "sigma_BN_"))]
    same = np.array_equal(c.data[:, cmd], p.data[:, cmd])
    print("S1 %.0f s: %d ticks, %d FSW cycles (best of %d)" % (duration, ticks, cycles, reps))
    print("  C FSW, no effector          %8.3f s  (%6.2f us per tick)" % (t_c, 1e6 * t_c / ticks))
    print("  Python FSW (Acs, 10 Hz)     %8.3f s  overhead %7.1f us per FSW cycle" %
          (t_py, 1e6 * (t_py - t_c) / cycles))
    print("  Python FSW returning {}     %8.3f s  overhead %7.1f us per FSW cycle (the seam alone)" %
          (t_nil, 1e6 * (t_nil - t_c) / cycles))
    print("  Python effector every tick  %8.3f s  overhead %7.1f us per tick" % (t_eff, 1e6 * (t_eff - t_c) / ticks))
    print("  Python FSW commands and attitude == the C FSW's, bit for bit: %s" % same)


if __name__ == "__main__":
    main()
