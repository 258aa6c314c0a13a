"""Scenarios from code (docs/python.md, "Scenarios from code"):
Scenario.from_dict / to_dict round trips for every shipped scenario, the
file's checks and messages from a dict, and the attitude forms (quaternion,
3-2-1 Euler angles, axis-angle) from a dict, checked against closed forms
and by a run bit-identical to the same run written with the MRP.

Run by ctest with PYTHONPATH at the build tree's python/ folder (unittest
test cases, collected by pytest).
"""
import copy
import glob
import math
import os
import unittest

import numpy as np

import kestrel

SRC = os.environ.get("KESTREL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
S1 = os.path.join(SRC, "scenarios", "s1_sun_pointing.yaml")
SHIPPED = sorted(glob.glob(os.path.join(SRC, "scenarios", "*.yaml")))


def plain(x):
    """True when x is made of dict, list, str, bool, int and float only."""
    if isinstance(x, dict):
        return all(isinstance(k, str) and plain(v) for k, v in x.items())
    if isinstance(x, list):
        return all(plain(v) for v in x)
    return isinstance(x, (str, bool, int, float))


class DictRoundTripTest(unittest.TestCase):
    def test_every_shipped_scenario_round_trips(self):
        self.assertGreaterEqual(len(SHIPPED), 10)
        for path in SHIPPED:
            with self.subTest(scenario=os.path.basename(path)):
                sc = kestrel.Scenario.load(path)
                d = sc.to_dict()
                self.assertTrue(plain(d))
                again = kestrel.Scenario.from_dict(d)
                self.assertEqual(again, sc)
                self.assertEqual(again.to_dict(), d)
                self.assertEqual(again.to_json(), sc.to_json())
                self.assertEqual(again.has_monte_carlo, sc.has_monte_carlo)

    def test_to_dict_holds_effective_values(self):
        sc = kestrel.Scenario.load(S1)
        d = sc.to_dict()
        # s1_sun_pointing.yaml writes wheel speeds in rpm: the dict holds rad/s
        self.assertEqual(d["wheels"][0]["Omega_0"], sc.get("wheels[0].Omega_0"))
        self.assertAlmostEqual(d["wheels"][0]["Omega_0"], 100.0 * 2.0 * math.pi / 60.0, places=13)
        self.assertEqual(d["duration"], 600.0)
        self.assertEqual(d["fsw"]["mrp_fb"]["K"], sc.get("fsw.mrp_fb.K"))
        self.assertEqual(np.array(d["spacecraft"]["inertia"]).tolist(), sc.get("spacecraft.inertia").tolist())
        # a change through set() shows in the dict, and equality sees it
        other = sc.copy()
        other.set("fsw.mrp_fb.K", sc.get("fsw.mrp_fb.K") * 2.0)
        self.assertNotEqual(other, sc)
        self.assertEqual(other.to_dict()["fsw"]["mrp_fb"]["K"], 2.0 * d["fsw"]["mrp_fb"]["K"])
        self.assertEqual(kestrel.Scenario.from_dict(other.to_dict()), other)

    def test_dict_is_a_copy(self):
        sc = kestrel.Scenario.load(S1)
        d = sc.to_dict()
        d["duration"] = 1.0
        self.assertEqual(sc.duration, 600.0)

    def test_numpy_values_and_overrides(self):
        d = kestrel.Scenario.load(S1).to_dict()
        d["spacecraft"]["inertia"] = np.diag([10.0, 11.0, 12.0])
        d["spacecraft"]["initial"]["omega_BN_B"] = np.array([0.0, 0.0, np.float64(0.01)])
        d["seed"] = np.uint64(7)
        sc = kestrel.Scenario.from_dict(d, overrides={"duration": 10})
        self.assertEqual(sc.get("spacecraft.inertia").tolist(), np.diag([10.0, 11.0, 12.0]).tolist())
        self.assertEqual(sc.get("spacecraft.initial.omega_BN_B").tolist(), [0.0, 0.0, 0.01])
        self.assertEqual(sc.seed, 7)
        self.assertEqual(sc.duration, 10.0)


class DictErrorsTest(unittest.TestCase):
    def setUp(self):
        self.d = kestrel.Scenario.load(S1).to_dict()

    def issue_keys(self, d):
        with self.assertRaises(kestrel.ScenarioError) as cm:
            kestrel.Scenario.from_dict(d, "mine")
        for file, line, col, key, msg in cm.exception.issues:
            self.assertEqual(file, "mine")
            self.assertGreater(line, 0)
        self.assertIn("mine:", str(cm.exception))
        return {key: msg for _, _, _, key, msg in cm.exception.issues}

    def test_bad_value_names_the_key_path(self):
        self.d["spacecraft"]["inertia"] = [[1, 0, 0], [0, 1, 0], [0, 0, 5]]  # triangle inequality broken
        keys = self.issue_keys(self.d)
        self.assertIn("spacecraft.inertia", keys)

    def test_same_message_as_the_yaml_file(self):
        self.d["spacecraft"]["mass"] = -1.0
        keys = self.issue_keys(self.d)
        text = open(S1).read().replace("mass: 750.0", "mass: -1.0", 1)
        self.assertNotEqual(text, open(S1).read())
        with self.assertRaises(kestrel.ScenarioError) as cm:
            kestrel.Scenario.from_text(text, "s1.yaml")
        from_yaml = {key: msg for _, _, _, key, msg in cm.exception.issues}
        self.assertEqual(keys["spacecraft.mass"], from_yaml["spacecraft.mass"])

    def test_unknown_and_missing_keys(self):
        self.d["fsw"]["mrp_fb"]["KK"] = 1.0
        del self.d["spacecraft"]["mass"]
        keys = self.issue_keys(self.d)
        self.assertIn("fsw.mrp_fb.KK", keys)
        self.assertIn("spacecraft.mass", keys)
        self.assertIn("required", keys["spacecraft.mass"])

    def test_values_python_cannot_write(self):
        self.d["duration"] = float("nan")
        with self.assertRaises(ValueError):
            kestrel.Scenario.from_dict(self.d)
        self.d["duration"] = object()
        with self.assertRaises(TypeError):
            kestrel.Scenario.from_dict(self.d)
        with self.assertRaises(TypeError):
            kestrel.Scenario.from_dict([1, 2])


class AttitudeFormsTest(unittest.TestCase):
    def setUp(self):
        self.d = kestrel.Scenario.load(S1, {"duration": 2.0}).to_dict()
        self.d["fsw"]["mode"] = "inertial"

    def target(self, **form):
        d = copy.deepcopy(self.d)
        d["fsw"]["inertial"] = form
        return kestrel.Scenario.from_dict(d).get("fsw.inertial.sigma_R0N")

    def test_closed_forms(self):
        c, s = math.cos(math.radians(45)), math.sin(math.radians(45))
        t = math.tan(math.radians(22.5))
        np.testing.assert_allclose(self.target(sigma_R0N_quaternion=[c, 0, 0, s]), [0, 0, t], atol=1e-15)
        np.testing.assert_allclose(self.target(sigma_R0N_euler_321_deg=[90, 0, 0]), [0, 0, t], atol=1e-15)
        np.testing.assert_allclose(
            self.target(sigma_R0N_axis_angle={"axis": [0, 0, 1], "angle_deg": 90}), [0, 0, t], atol=1e-15)
        # 270 deg about z: the shadow set, -tan(22.5 deg)
        np.testing.assert_allclose(
            self.target(sigma_R0N_axis_angle={"axis": [0, 0, 1], "angle_deg": 270}), [0, 0, -t], atol=1e-15)

    def test_euler_321_against_composed_rotations(self):
        def r1(a):
            return np.array([[1, 0, 0], [0, math.cos(a), math.sin(a)], [0, -math.sin(a), math.cos(a)]])

        def r2(a):
            return np.array([[math.cos(a), 0, -math.sin(a)], [0, 1, 0], [math.sin(a), 0, math.cos(a)]])

        def r3(a):
            return np.array([[math.cos(a), math.sin(a), 0], [-math.sin(a), math.cos(a), 0], [0, 0, 1]])

        yaw, pitch, roll = 120.0, 35.0, -160.0
        sigma = self.target(sigma_R0N_euler_321_deg=[yaw, pitch, roll])
        self.assertLessEqual(np.linalg.norm(sigma), 1.0)
        t = np.array([[0, -sigma[2], sigma[1]], [sigma[2], 0, -sigma[0]], [-sigma[1], sigma[0], 0]])
        s2 = sigma @ sigma
        dcm = np.eye(3) + (8 * t @ t - 4 * (1 - s2) * t) / (1 + s2) ** 2
        expect = r1(math.radians(roll)) @ r2(math.radians(pitch)) @ r3(math.radians(yaw))
        np.testing.assert_allclose(dcm, expect, atol=1e-14)

    def test_two_forms_rejected_with_key_path(self):
        d = copy.deepcopy(self.d)
        d["fsw"]["inertial"] = {"sigma_R0N": [0, 0, 0], "sigma_R0N_quaternion": [1, 0, 0, 0]}
        with self.assertRaises(kestrel.ScenarioError) as cm:
            kestrel.Scenario.from_dict(d)
        self.assertIn("fsw.inertial.sigma_R0N_quaternion", [i[3] for i in cm.exception.issues])
        d["fsw"]["inertial"] = {"sigma_R0N_quaternion": [2, 0, 0, 0]}
        with self.assertRaises(kestrel.ScenarioError) as cm:
            kestrel.Scenario.from_dict(d)
        self.assertIn("|q| = 2", str(cm.exception))

    def test_run_bit_identical_to_the_mrp_written(self):
        # a rotation of 0.3 rad about (1, 2, 3)/|..| as a quaternion, for the
        # target and the initial attitude; the same run with the MRPs written
        e = np.array([1.0, 2.0, 3.0]) / math.sqrt(14.0)
        q = [math.cos(0.15)] + list(math.sin(0.15) * e)
        d = copy.deepcopy(self.d)
        d["fsw"]["inertial"] = {"sigma_R0N_quaternion": q}
        init = d["spacecraft"]["initial"]
        del init["sigma_BN"]
        init["sigma_BN_axis_angle"] = {"axis": [0, 1, 0], "angle_deg": 40}
        from_forms = kestrel.Scenario.from_dict(d)
        sigma_R = from_forms.get("fsw.inertial.sigma_R0N")
        sigma_B = from_forms.get("spacecraft.initial.sigma_BN")
        np.testing.assert_allclose(sigma_R, e * math.tan(0.075), atol=1e-15)
        np.testing.assert_allclose(sigma_B, [0, math.tan(math.radians(10)), 0], atol=1e-15)

        d2 = copy.deepcopy(self.d)
        d2["fsw"]["inertial"] = {"sigma_R0N": [float(x) for x in sigma_R]}
        d2["spacecraft"]["initial"]["sigma_BN"] = [float(x) for x in sigma_B]
        written = kestrel.Scenario.from_dict(d2)
        self.assertEqual(written, from_forms)
        a, b = kestrel.run(from_forms), kestrel.run(written)
        self.assertEqual(a.columns, b.columns)
        self.assertGreater(a.data.shape[0], 10)
        self.assertTrue(np.array_equal(a.data, b.data))
        # and the attitude did change the run (the test can fail)
        d2["fsw"]["inertial"] = {"sigma_R0N": [0.0, 0.0, 0.0]}
        c = kestrel.run(kestrel.Scenario.from_dict(d2))
        self.assertFalse(np.array_equal(a.data, c.data))


if __name__ == "__main__":
    unittest.main()
