"""Python in the loop (docs/python.md, "Python in the loop"): a Python flight
software through the FSW endpoint seam and Python force/torque effectors,
run by ctest with PYTHONPATH at the build tree's python/ folder.

Environment (set by ctest): KESTREL_CLI, KESTREL_SOURCE_DIR.
"""
import json
import os
import re
import subprocess
import tempfile
import unittest

import numpy as np

import kestrel
import kestrel.fsw as fsw

SRC = os.environ.get("KESTREL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("KESTREL_CLI", "kestrel")
S1 = os.path.join(SRC, "scenarios", "s1_sun_pointing.yaml")

# The FSW actuator message as recorded (harness/src/core/telemetry_columns.cpp):
# every column whose quantity comes from fsw_actuators / plant commands.
COMMAND_RE = re.compile(r"^(Lr_B_|wheel_cmd_)")


def s1(duration=5.0):
    return kestrel.Scenario.load(S1, {"duration": duration})


class AcsInPython:
    """The C application fsw_acs through its binding (kestrel.fsw.Acs),
    configured as a run of the scenario configures the C FSW."""

    rate_hz = 10.0

    def __init__(self, sc):
        self.acs = fsw.Acs.from_scenario(sc)
        self.acs.init()
        self.calls = 0

    def __call__(self, sensors):
        self.calls += 1
        status, act, health = self.acs.cycle(**sensors)
        return act


# S1's wheel geometry: a pyramid, every spin axis at z component G_Z; the
# azimuths 45/135/225/315 deg make sum(g g^T) diagonal.
J_S = 0.0795775  # [kg*m^2]
G_Z = 0.642787610


def resting_scenario(duration):
    """S1 at rest with Balanced wheels at 0 rpm and no friction: what the
    Python FSW zero_fsw leaves uncontrolled."""
    text = open(S1).read()
    text = text.replace("model: fully_coupled", "model: balanced")
    text = re.sub(r"Omega_0_rpm: \d+", "Omega_0_rpm: 0", text)
    text = text.replace("omega_BN_B: [0.001, -0.01, 0.03]", "omega_BN_B: [0.0, 0.0, 0.0]")
    return kestrel.Scenario.from_text(text, "s1_at_rest.yaml", {"duration": duration})


def zero_fsw(sensors):
    return {}


class PythonFsw(unittest.TestCase):
    def test_reproduces_the_c_fsw(self):
        sc = s1(5.0)
        c = kestrel.run(sc)
        py = AcsInPython(sc)
        p = kestrel.run(sc, fsw=py)
        self.assertTrue(c.complete and p.complete, p.failure)
        self.assertEqual(py.calls, 51)  # 10 Hz over [0, 5] s, both ends
        self.assertEqual(c.columns, p.columns)
        cmd = [i for i, n in enumerate(c.columns) if COMMAND_RE.match(n)]
        self.assertEqual(len(cmd), 7, c.columns)
        # the same C code with the same configuration and inputs: bit-identical
        # commands, hence the same plant, hence the same truth
        np.testing.assert_array_equal(c.data[:, cmd], p.data[:, cmd])
        self.assertTrue(np.any(c.data[:, cmd] != 0.0))
        np.testing.assert_array_equal(c["truth/omega_BN_B"] if "truth/omega_BN_B" in c else c["omega_BN_B"],
                                      p["truth/omega_BN_B"] if "truth/omega_BN_B" in p else p["omega_BN_B"])

    def test_repeatable(self):
        sc = s1(2.0)
        a = kestrel.run(sc, fsw=AcsInPython(sc))
        b = kestrel.run(sc, fsw=AcsInPython(sc))
        np.testing.assert_array_equal(a.data, b.data)

    def test_exception_stops_the_run_with_its_traceback(self):
        sc = s1(5.0)
        inner = AcsInPython(sc)

        def failing_fsw(sensors):
            if sensors["t_ns"] >= 2_000_000_000:
                raise ZeroDivisionError("boom in the flight code")
            return inner(sensors)

        r = kestrel.run(sc, fsw=failing_fsw)
        self.assertFalse(r.complete)
        self.assertIn("t = 2.0", r.failure)
        self.assertIn("Traceback", r.failure)
        self.assertIn("ZeroDivisionError: boom in the flight code", r.failure)
        self.assertIn("failing_fsw", r.failure)
        # the rows before the failing tick are kept: t = 0 .. 1.9 s at 10 Hz
        self.assertEqual(len(r), 20)
        self.assertAlmostEqual(r.t[-1], 1.9, places=12)
        # the same through a stepped Run
        run = kestrel.Run(sc, fsw=failing_fsw)
        self.assertFalse(run.step(10**9))
        self.assertIn("ZeroDivisionError", run.failure)
        self.assertEqual(len(run.results()), 20)

    def test_bad_output_names_the_field(self):
        sc = s1(1.0)
        cases = [
            (lambda s: {"Lr_B": np.zeros(2)}, "Lr_B: shape (3,)"),
            (lambda s: {"u_s": [0.0, float("nan"), 0.0, 0.0], "wheels_active": 1}, "u_s: not finite"),
            (lambda s: {"no_such": 1.0}, "unknown actuator field 'no_such'"),
            (lambda s: [0.0, 0.0, 0.0], "not a dict"),
        ]
        for f, want in cases:
            r = kestrel.run(sc, fsw=f)
            self.assertFalse(r.complete)
            self.assertIn(want, r.failure)
            self.assertIn("t = 0.0", r.failure)
            self.assertEqual(len(r), 0)

    def test_refused_before_the_run(self):
        sc = s1(1.0)
        with self.assertRaisesRegex(TypeError, "fsw: a callable"):
            kestrel.run(sc, fsw=3)

        class FiveHz:
            rate_hz = 5.0

            def __call__(self, s):
                return {}

        with self.assertRaisesRegex(ValueError, "not the scenario's FSW rate"):
            kestrel.run(sc, fsw=FiveHz())
        with self.assertRaisesRegex(ValueError, "out_dir"):
            kestrel.run(sc, fsw=zero_fsw, out_dir=tempfile.mkdtemp())
        # a Python FSW takes no FSW commands (mode, reference): refused like
        # for any endpoint that takes none
        run = kestrel.Run(sc, fsw=zero_fsw)
        with self.assertRaisesRegex(ValueError, "takes no commands"):
            run.apply_event("fsw", "mode_inertial")

    def test_manifest_names_it_and_the_cli_refuses_a_rerun(self):
        sc = s1(1.0)
        r = kestrel.run(sc, fsw=AcsInPython(sc))
        m = json.loads(r.manifest)
        self.assertEqual(m["python_in_loop"], {"fsw": "python:" + __name__ + ".AcsInPython"})
        self.assertIn("scenario", m)
        with self.assertRaisesRegex(ValueError, "without Python in the loop"):
            r.write(tempfile.mkdtemp())
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "manifest.json")
            with open(path, "w") as f:
                f.write(r.manifest)
            out = subprocess.run([CLI, "run", path, "-o", os.path.join(d, "out")], capture_output=True, text=True,
                                 timeout=120)
            self.assertNotEqual(out.returncode, 0)
            self.assertIn("Python objects in the loop", out.stderr + out.stdout)
            self.assertIn("AcsInPython", out.stderr + out.stdout)
            self.assertFalse(os.path.exists(os.path.join(d, "out")))
        # a run without Python in the loop has no such key
        self.assertNotIn("python_in_loop", json.loads(kestrel.run(sc).manifest))


class PythonEffector(unittest.TestCase):
    # A Balanced wheel is in the hub inertia (J_s included); with no motor
    # torque and no friction its inertial spin stays put, so the body turns
    # with the hub inertia less the wheels' spin inertia along their axes:
    # I_eff = I_hub - J_s sum(g g^T), diagonal for the pyramid (docs/dynamics.md).
    I_z_eff = 600.0 - J_S * 4 * G_Z**2  # [kg*m^2]

    def test_constant_torque_spins_up_as_tau_over_I_t(self):
        sc = resting_scenario(10.0)
        calls = []

        def torque(t, state):
            calls.append(t)
            self.assertEqual(state["omega_BN_B"].shape, (3,))
            self.assertEqual(state["Omega"].shape, (4,))
            return np.zeros(3), np.array([0.0, 0.0, 0.6])

        r = kestrel.run(sc, fsw=zero_fsw, effectors=[torque])
        self.assertTrue(r.complete, r.failure)
        self.assertEqual(len(calls), 1000)  # every tick [0, 10) s at dt = 0.01 s
        self.assertAlmostEqual(calls[1], 0.01, places=15)
        w = r["truth/omega_BN_B"] if "truth/omega_BN_B" in r else r["omega_BN_B"]
        # about a principal axis from rest: omega_z = tau / I t exactly (Euler)
        np.testing.assert_allclose(w[:, 2], 0.6 / self.I_z_eff * r.t, rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(w[:, :2], 0.0, atol=1e-14)
        # without it, the body stays at rest
        r0 = kestrel.run(sc, fsw=zero_fsw)
        w0 = r0["truth/omega_BN_B"] if "truth/omega_BN_B" in r0 else r0["omega_BN_B"]
        np.testing.assert_allclose(w0, 0.0, atol=1e-15)
        self.assertEqual(json.loads(r.manifest)["python_in_loop"]["effectors"],
                         ["python:" + __name__ + ".PythonEffector.test_constant_torque_spins_up_as_tau_over_I_t."
                          "<locals>.torque"])

    def test_declared_rate(self):
        sc = resting_scenario(1.0)

        class Slow:
            rate_hz = 10.0

            def __init__(self):
                self.t = []

            def __call__(self, t, state):
                self.t.append(t)
                return [0.0] * 3, [0.0, 0.0, 0.6]

        s = Slow()
        r = kestrel.run(sc, fsw=zero_fsw, effectors=s)
        self.assertTrue(r.complete, r.failure)
        np.testing.assert_allclose(s.t, np.arange(10) * 0.1, atol=1e-12)

        class Odd:
            rate_hz = 30.0  # not a whole number of 0.01 s ticks

            def __call__(self, t, state):
                return [0.0] * 3, [0.0] * 3

        with self.assertRaisesRegex(ValueError, "not a whole number of ticks"):
            kestrel.run(sc, effectors=[Odd()])

    def test_exception_and_bad_output_stop_the_run(self):
        sc = resting_scenario(2.0)

        def failing(t, state):
            if t >= 1.0:
                raise RuntimeError("disturbance model broke")
            return np.zeros(3), np.zeros(3)

        r = kestrel.run(sc, fsw=zero_fsw, effectors=[failing])
        self.assertFalse(r.complete)
        self.assertIn("plant at t = 1.0", r.failure)
        self.assertIn("RuntimeError: disturbance model broke", r.failure)
        self.assertIn("Traceback", r.failure)
        self.assertEqual(len(r), 11)  # rows t = 0 .. 1.0 s (the row of t = 1 s precedes the plant step)
        for f, want in [(lambda t, s: (np.zeros(3), np.full(3, np.inf)), "torque_B: not finite"),
                        (lambda t, s: (np.zeros(2), np.zeros(3)), "force_B: shape (3,)"),
                        (lambda t, s: None, "not (force_B, torque_B)")]:
            r = kestrel.run(sc, fsw=zero_fsw, effectors=[f])
            self.assertFalse(r.complete)
            self.assertIn(want, r.failure)
        with self.assertRaisesRegex(TypeError, "effectors: callables"):
            kestrel.run(sc, effectors=[1])



def omega(res):
    return res["truth/omega_BN_B"] if "truth/omega_BN_B" in res else res["omega_BN_B"]


class PythonSensor(unittest.TestCase):
    def test_readings_recorded_at_every_row(self):
        sc = s1(3.0)
        times = []

        def doubled_rate(t, truth):
            times.append(t)
            return 2.0 * truth["omega_BN_B"]

        def clock(t, truth):
            return t

        r = kestrel.run(sc, sensors={"rate2": (doubled_rate, 3), "clock": (clock, 1)})
        self.assertTrue(r.complete, r.failure)
        self.assertEqual(len(times), len(r))  # one call per recorded row (10 Hz)
        self.assertEqual(r.columns[-4:], ["rate2_0", "rate2_1", "rate2_2", "clock"])
        # x2 is exact in binary floating point: the truth at the same row
        np.testing.assert_array_equal(r["python/rate2"], 2.0 * omega(r))
        np.testing.assert_array_equal(r["python/clock"][:, 0], r.t)
        self.assertEqual(json.loads(r.manifest)["python_in_loop"]["sensors"],
                         {"rate2": "python:" + __name__ + ".PythonSensor.test_readings_recorded_at_every_row."
                                   "<locals>.doubled_rate",
                          "clock": "python:" + __name__ + ".PythonSensor.test_readings_recorded_at_every_row."
                                   "<locals>.clock"})
        # the same through a stepped Run, and the loop's other rows unchanged by it
        run = kestrel.Run(sc, sensors={"rate2": (doubled_rate, 3)})
        run.step(10**9)
        np.testing.assert_array_equal(run.results()["python/rate2"], r["python/rate2"])
        plain = kestrel.run(sc)
        np.testing.assert_array_equal(plain.data, r.data[:, :-4])

    def test_exception_and_bad_reading_stop_the_run(self):
        sc = s1(3.0)

        def failing(t, truth):
            if t >= 1.0:
                raise KeyError("no such truth")
            return [0.0]

        r = kestrel.run(sc, sensors={"bad": (failing, 1)})
        self.assertFalse(r.complete)
        self.assertIn("at t = 1.0", r.failure)
        self.assertIn("Python sensor bad", r.failure)
        self.assertIn("KeyError: 'no such truth'", r.failure)
        self.assertEqual(len(r), 10)  # rows t = 0 .. 0.9 s
        for f, want in [(lambda t, x: np.zeros(2), "reading: shape (3,)"),
                        (lambda t, x: [0.0, np.nan, 0.0], "reading: not finite (element 1)")]:
            r = kestrel.run(sc, sensors={"s": (f, 3)})
            self.assertFalse(r.complete)
            self.assertIn(want, r.failure)
            self.assertEqual(len(r), 0)
        with self.assertRaisesRegex(TypeError, "reading, size: int"):
            kestrel.run(sc, sensors={"s": lambda t, x: 0.0})
        with self.assertRaisesRegex(ValueError, "not a column name"):
            kestrel.run(sc, sensors={"a/b": (lambda t, x: 0.0, 1)})
        with self.assertRaisesRegex(ValueError, "declared twice"):
            kestrel.run(sc, sensors={"t": (lambda t, x: 0.0, 1)})


if __name__ == "__main__":
    unittest.main()
