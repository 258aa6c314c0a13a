"""Reaching into a run between steps (docs/python.md, "Reaching into a
run"): Run.get_state() reads the plant's truth, Run.set_state() writes it as
event actions (device spacecraft, a wheel's speed), Run.settable() lists
what can be set.  Expected values from the scenario's parameters by hand
(the change of the total angular momentum a wheel speed step makes), twin
runs and the CLI replaying the manifest.

Environment (set by ctest): KESTREL_CLI, KESTREL_SOURCE_DIR.
"""

import json
import os
import subprocess
import tempfile
import unittest

import numpy as np

import kestrel

SRC = os.environ.get("KESTREL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("KESTREL_CLI", "kestrel")
S1 = os.path.join(SRC, "scenarios", "s1_sun_pointing.yaml")
S2 = os.path.join(SRC, "scenarios", "s2_mars_orbit_insertion.yaml")
# 1 s of S1 recorded at every tick (100 rows); no environment torques (mu 0)
SHORT = {"duration": 1.0, "rates.record_divisor": 1}
# balanced wheels: no imbalance momentum, the spin momentum J_s (Omega + g.omega) alone
BALANCED = dict(SHORT, **{"wheel_defaults.model": "balanced"})


def dcm_NB(sigma):
    """[NB] of the MRP sigma_BN (independent of the plant's code)."""
    s = np.asarray(sigma, dtype=float)
    s2 = s @ s
    sx = np.array([[0, -s[2], s[1]], [s[2], 0, -s[0]], [-s[1], s[0], 0]])
    BN = np.eye(3) + (8 * sx @ sx - 4 * (1 - s2) * sx) / (1 + s2) ** 2
    return BN.T


class RunReachTest(unittest.TestCase):
    def setUp(self):
        self.sc = kestrel.Scenario.load(S1, SHORT)

    def test_get_state_is_the_plant_now(self):
        r = kestrel.Run(self.sc)
        s0 = r.get_state()
        d = self.sc.to_dict()
        # before the first tick: the scenario's initial wheel speeds
        np.testing.assert_array_equal(s0["wheel_speeds"], [w["Omega_0"] for w in d["wheels"]])
        self.assertEqual(s0["propellant"].shape, (0,))
        r.step(37)
        s = r.get_state()
        self.assertAlmostEqual(s["t"], 0.37, places=12)
        for k in ("attitude", "omega", "position", "velocity"):
            self.assertEqual(s[k].shape, (3,), k)
        # the last recorded row is the plant at the start of tick 36 or later:
        # get_state is newer than the row (tick 37), not the row itself
        row = r.state()
        self.assertNotEqual(row["omega_BN_B_x"], s["omega"][0])

    def test_set_omega_holds_at_the_boundary(self):
        r = kestrel.Run(self.sc)
        r.step(40)
        w = np.array([0.02, -0.015, 0.01])
        before = r.get_state()
        r.set_state(omega=w)
        # in effect when the next tick starts: the plant is untouched until then
        np.testing.assert_array_equal(r.get_state()["omega"], before["omega"])
        r.step(1)
        after = r.get_state()["omega"]
        # one tick (0.01 s) later: the set rate moved only by what the wheels'
        # torques (<= 4 * u_max = 0.8 N*m: 0.8 * 0.01 / 600 = 1.3e-5 rad/s on
        # the smallest hub inertia 600 kg*m^2) and the gyroscopic term (|w|^2
        # * dt < 1e-5) can do -- far below the step of 0.03 rad/s set
        self.assertLess(np.max(np.abs(after - w)), 5e-5)
        self.assertGreater(np.max(np.abs(after - before["omega"])), 0.01)
        self.assertEqual([a["what"] for a in r.applied],
                         ["spacecraft omega_BN_B_x 0.02", "spacecraft omega_BN_B_y -0.015",
                          "spacecraft omega_BN_B_z 0.01"])

    def test_wheel_speed_step_changes_momentum_by_J_dOmega_g(self):
        sc = kestrel.Scenario.load(S1, BALANCED)
        d = sc.to_dict()
        k = 50
        a = kestrel.Run(sc)
        b = kestrel.Run(sc)
        a.step(k)
        b.step(k)
        s = b.get_state()
        np.testing.assert_array_equal(s["wheel_speeds"], a.get_state()["wheel_speeds"])
        dOmega = np.array([0.0, 25.0, 0.0, -10.0])
        b.set_state(wheel_speeds=s["wheel_speeds"] + dOmega)
        a.run_to_end()
        b.run_to_end()
        # the total momentum is conserved in both runs (wheel torques are
        # internal; no external torque), so from the step on they differ by
        # [NB] sum_i J_s dOmega_i g_i, the attitude that of the step instant
        dH_B = sum(w["J_s"] * dO * np.array(w["axis"]) for w, dO in zip(d["wheels"], dOmega))
        dH_N = dcm_NB(s["attitude"]) @ dH_B
        ta = a.results()["t"][:, 0]
        Ha = a.results()["H_C_N"]
        Hb = b.results()["H_C_N"]
        after = ta >= (k + 1) * 0.01 - 1e-9
        before = ta < (k - 1) * 0.01
        self.assertGreater(after.sum(), 40)
        np.testing.assert_array_equal(Hb[before], Ha[before])
        np.testing.assert_allclose(Hb[after] - Ha[after], np.tile(dH_N, (after.sum(), 1)), rtol=0, atol=1e-9)
        self.assertGreater(np.linalg.norm(dH_N), 1.0)

    def test_bad_values_are_refused_and_nothing_is_set(self):
        r = kestrel.Run(self.sc)
        r.step(5)
        cases = [
            (dict(omega=[0.0, float("nan"), 0.0]), "omega[1] is not finite"),
            (dict(omega=[0.0, 0.0]), "omega takes 3 numbers"),
            (dict(attitude="up"), "attitude takes 3 numbers"),
            (dict(wheel_speeds=[1.0, 2.0, 3.0]), "wheel_speeds takes 4 numbers"),
            (dict(omega=[0.0, 0.0, 0.0], wheel_speeds=[1.0, 2.0, 3.0, 700.0]),
             "wheel_speeds[3]: 'speed' needs |value| <= the wheel's Omega_max"),
            (dict(propellant=1.0), "propellant: 'propellant_mass' needs a propellant tank"),
            (dict(position=[0.0, 0.0, 0.0], velocity=[1.0, float("inf"), 0.0]), "velocity[1] is not finite"),
        ]
        for kw, msg in cases:
            with self.assertRaises(ValueError, msg=str(kw)) as cm:
                r.set_state(**kw)
            self.assertIn(msg, str(cm.exception))
        with self.assertRaises(TypeError):
            r.set_state(rates=[0.0, 0.0, 0.0])
        self.assertEqual(r.applied, [])
        n_events = len(json.loads(r.results().manifest)["scenario"].get("events", []))
        # nothing was applied: a twin run steps to the same state
        twin = kestrel.Run(self.sc)
        twin.step(5)
        r.step(10)
        twin.step(10)
        for key in ("attitude", "omega", "wheel_speeds"):
            np.testing.assert_array_equal(r.get_state()[key], twin.get_state()[key])
        self.assertEqual(n_events, len(json.loads(twin.results().manifest)["scenario"].get("events", [])))

    def test_propellant_within_the_tank(self):
        r = kestrel.Run(kestrel.Scenario.load(S2, {"duration": 1.0}))
        load = r.get_state()["propellant"][0]
        with self.assertRaises(ValueError) as cm:
            r.set_state(propellant=load + 1.0)
        self.assertIn("propellant: 'propellant_mass' needs a value <= the tank's load", str(cm.exception))
        r.set_state(propellant=load / 2)
        r.step(1)
        # no burn in the first second: the propellant stays as set
        self.assertAlmostEqual(r.get_state()["propellant"][0], load / 2, delta=1e-9 * load)

    def test_attitude_beyond_one_is_its_shadow_set(self):
        r = kestrel.Run(self.sc)
        r.step(3)
        sig = np.array([0.9, -0.6, 0.5])  # |sigma|^2 = 1.42
        r.set_state(attitude=sig)
        r.step(1)
        got = r.get_state()["attitude"]
        shadow = -sig / (sig @ sig)
        # the same attitude after one tick of slow rotation (< 0.001 rad)
        np.testing.assert_allclose(dcm_NB(got), dcm_NB(shadow), atol=1e-3)
        self.assertLessEqual(got @ got, 1.0)

    def test_manifest_replays_through_the_cli(self):
        import h5py

        r = kestrel.Run(self.sc)
        r.step(30)
        r.set_state(omega=[0.01, 0.0, -0.02], wheel_speeds=[50.0, -40.0, 30.0, 0.0], attitude=[0.1, 0.2, 0.3])
        r.step(20)
        r.set_state(position=[7.0e6, 0.0, 0.0], velocity=[0.0, 7.5e3, 0.0])
        self.assertTrue(r.run_to_end())
        res = r.results()
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "manifest.json")
            with open(path, "w") as f:
                f.write(res.manifest)
            out = subprocess.run([CLI, "run", path, "-o", os.path.join(d, "out")], capture_output=True, text=True,
                                 timeout=120)
            self.assertEqual(out.returncode, 0, out.stderr)
            compared = 0
            with h5py.File(os.path.join(d, "out", "results.h5"), "r") as f:
                for key in res.quantities:
                    if key in f:
                        np.testing.assert_array_equal(f[key][...], res[key], err_msg=key)  # bit for bit
                        compared += 1
            self.assertGreater(compared, 10)
        # and the set really changed the run: it differs from the plain one
        plain = kestrel.run(self.sc)
        self.assertFalse(np.array_equal(plain["truth/omega_BN_B"], res["truth/omega_BN_B"]))

    def test_settable_lists_the_actions(self):
        r = kestrel.Run(self.sc)
        st = r.settable()
        pairs = {(x["device"], x["action"]) for x in st}
        for a in ("sigma_BN_x", "omega_BN_B_z", "r_N_y", "v_N_x"):
            self.assertIn(("spacecraft", a), pairs)
        self.assertIn(("rw1", "speed"), pairs)
        self.assertIn(("fsw", "gain_K"), pairs)
        self.assertNotIn(("spacecraft", "propellant_mass"), pairs)  # S1 has no tank
        om = [x for x in st if x["action"] == "omega_BN_B_x"][0]
        self.assertEqual(om["unit"], "rad/s")
        self.assertTrue(om["takes_value"])
        self.assertIn("omega_BN_B", om["description"])
        s2 = {(x["device"], x["action"]) for x in kestrel.Run(kestrel.Scenario.load(S2)).settable()}
        self.assertIn(("spacecraft", "propellant_mass"), s2)


if __name__ == "__main__":
    unittest.main()


class RunSetTest(unittest.TestCase):
    """Run.set(path, value): --set's checks, then the event action the
    table of docs/events.md names; a twin run given that action through
    apply_event must give the same rows bit for bit."""

    def setUp(self):
        self.sc = kestrel.Scenario.load(S1, SHORT)

    def twins(self, path, value, device, action, action_value=None):
        a, b = kestrel.Run(self.sc), kestrel.Run(self.sc)
        a.step(30)
        b.step(30)
        a.set(path, value)
        b.apply_event(device, action, action_value)
        a.step(a.total_ticks - a.tick)
        b.step(b.total_ticks - b.tick)
        ra, rb = a.results(), b.results()
        for q in ra.columns:
            np.testing.assert_array_equal(ra[q], rb[q], q)
        return a

    def test_keys_map_to_their_actions(self):
        self.twins("wheels[1].u_max", 0.02, "rw2", "torque_limit", 0.02)
        self.twins("fsw.mrp_fb.K", 0.5, "fsw", "gain_K", 0.5)
        rpm = 1200.0
        a = self.twins("wheels[0].Omega_0_rpm", rpm, "rw1", "speed", rpm * 2 * np.pi / 60)
        # the change is in the run's scenario, which the manifest replays
        self.assertTrue(any(a2["action"] == "speed" for e in a.scenario.to_dict()["events"] for a2 in e["actions"]))

    def test_set_changes_the_run(self):
        a, b = kestrel.Run(self.sc), kestrel.Run(self.sc)
        a.step(30)
        b.step(30)
        a.set("fsw.mrp_fb.K", 3.0)
        a.step(70)
        b.step(70)
        self.assertFalse(np.array_equal(a.results()["wheel_cmd"], b.results()["wheel_cmd"]))

    def test_bad_value_has_the_message_of_scenario_set(self):
        r = kestrel.Run(self.sc)
        r.step(10)
        with self.assertRaises(kestrel.ScenarioError) as direct:
            self.sc.set("fsw.mrp_fb.K", -1.0)
        with self.assertRaises(kestrel.ScenarioError) as during:
            r.set("fsw.mrp_fb.K", -1.0)
        self.assertEqual(str(direct.exception), str(during.exception))
        self.assertEqual(len(r.scenario.to_dict().get("events", [])), len(self.sc.to_dict().get("events", [])))

    def test_a_key_fixed_for_the_run_is_refused(self):
        r = kestrel.Run(self.sc)
        with self.assertRaises(ValueError) as cm:
            r.set("spacecraft.inertia", np.eye(3) * 10)
        self.assertIn("not settable during a run", str(cm.exception))
        self.assertIn("wheels[i].u_max", str(cm.exception))
