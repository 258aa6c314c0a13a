"""kestrel.fsw: every flight algorithm and fsw_acs through the Python bindings.

Expected values come from closed forms of the modules' documented laws
(docs/fsw/<module>.md) or from small NumPy implementations written here, never
from the module's own output.  Each module also gets a configuration that its
check refuses (ConfigError naming the field) and a NaN input (the documented
error status with the safe output).  Runs in about a second.
"""
import math
import os
import re
import unittest

import numpy as np

import kestrel
from kestrel import fsw

THR_MAP_NNLS = 1  # FSW_THR_MAP_NNLS (fsw/thr_map.h)
SRC = os.environ.get("KESTREL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def skew(v):
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def mrp_to_dcm(s):
    """[BN] of an MRP (Schaub & Junkins): I + (8 S^2 - 4 (1 - s.s) S) / (1 + s.s)^2."""
    s = np.asarray(s, float)
    S, q = skew(s), s @ s
    return np.eye(3) + (8 * S @ S - 4 * (1 - q) * S) / (1 + q) ** 2


def pyramid(n=4, el_deg=40.0):
    el = math.radians(el_deg)
    return np.array([[math.cos(el) * math.cos(math.radians(45 + 90 * i)),
                      math.cos(el) * math.sin(math.radians(45 + 90 * i)), math.sin(el)] for i in range(n)])


def null_projector(G):
    """Projector on the null space of the 3 x n matrix G (columns: wheel axes)."""
    return np.eye(G.shape[1]) - np.linalg.pinv(G) @ G


class Mixin:
    """Shared checks: a refused configuration names its field; a NaN input gives the safe output."""

    def assert_refused(self, m, field, status=fsw.E_CONFIG):
        with self.assertRaises(fsw.ConfigError) as e:
            m.check()
        self.assertIsInstance(e.exception, ValueError)
        self.assertEqual(e.exception.field, field)
        self.assertEqual(e.exception.status, status)
        self.assertIn(field, str(e.exception))
        with self.assertRaises(fsw.ConfigError):
            m.init()

    def assert_safe(self, m, zero_outputs, status=fsw.E_BAD_INPUT, **inputs):
        s, out = m.update(**inputs)
        self.assertEqual(s, status, fsw.Status(s).name)
        for k in zero_outputs:
            np.testing.assert_array_equal(out[k], 0.0, err_msg=k)
        return out


class GuidanceTest(unittest.TestCase, Mixin):
    def test_guid_inertial(self):
        m = fsw.GuidInertial(sigma_R0N=[0.1, -0.2, 0.3])
        self.assertEqual(m.init(), fsw.OK)
        s, out = m.update()
        self.assertEqual(s, fsw.OK)
        np.testing.assert_array_equal(out["sigma_RN"], [0.1, -0.2, 0.3])
        np.testing.assert_array_equal(out["omega_RN_N"], 0.0)
        # |sigma| > 1 is shadow-switched: -s / |s|^2 (same attitude)
        m = fsw.GuidInertial(sigma_R0N=[2.0, 0.0, 0.0])
        m.init()
        np.testing.assert_allclose(m.update()[1]["sigma_RN"], [-0.5, 0, 0], rtol=0, atol=1e-15)
        self.assert_refused(fsw.GuidInertial(sigma_R0N=[np.nan, 0, 0]), "sigma_R0N")

    def test_guid_orbit_nadir(self):
        mu = 3.986004418e14
        r = np.array([7.0e6, 0.0, 0.0])
        v = np.array([0.0, math.sqrt(mu / 7.0e6) * 0.6, math.sqrt(mu / 7.0e6) * 0.8])
        m = fsw.GuidOrbit(variant=0, mu=mu)
        self.assertEqual(m.init(), fsw.OK)
        s, out = m.update(r_N=r, v_N=v, valid=1)
        self.assertEqual(s, fsw.OK)
        h = np.cross(r, v)
        R3 = -r / np.linalg.norm(r)
        R2 = -h / np.linalg.norm(h)
        RN = np.array([np.cross(R2, R3), R2, R3])  # rows: the orbit frame in N
        np.testing.assert_allclose(mrp_to_dcm(out["sigma_RN"]), RN, rtol=0, atol=1e-12)
        np.testing.assert_allclose(out["omega_RN_N"], h / (r @ r), rtol=1e-12)
        np.testing.assert_allclose(out["omega_dot_RN_N"], 0.0, atol=1e-20)  # r.v = 0
        self.assert_safe(m, ["sigma_RN", "omega_RN_N", "omega_dot_RN_N"], r_N=[np.nan, 0, 0], v_N=v, valid=1)
        self.assert_refused(fsw.GuidOrbit(variant=0, mu=mu, sigma_BdR=[0, np.inf, 0]), "sigma_BdR")

    def sunsafe(self):
        return fsw.GuidSunsafe(s_cmd_B=[0, 0, 1], min_unit_mag=0.1, small_angle=1e-4,
                               omega_search_B=[0, 0, 0.005], sun_axis_spin_rate=0.0)

    def test_guid_sunsafe(self):
        m = self.sunsafe()
        self.assertEqual(m.init(), fsw.OK)
        w = np.array([0.01, -0.02, 0.003])
        s, out = m.update(sun_B=[1.0, 0, 0], omega_BN_B=w)
        self.assertEqual(s, fsw.OK)
        self.assertAlmostEqual(out["sun_angle_err"], math.pi / 2, places=12)
        self.assertEqual(out["sun_valid"], 1)
        # the error rotates +z toward +x: about +y by 90 deg, sigma = tan(theta/4) e
        np.testing.assert_allclose(out["sigma_BR"], [0, -math.tan(math.pi / 8), 0], rtol=0, atol=1e-12)
        np.testing.assert_allclose(out["omega_BR_B"], w, rtol=0, atol=1e-15)  # no spin commanded
        # no heading: the search spin
        s, out = m.update(sun_B=[0, 0, 0], omega_BN_B=w)
        self.assertEqual(out["sun_valid"], 0)
        np.testing.assert_allclose(out["omega_BR_B"], w - [0, 0, 0.005], rtol=0, atol=1e-15)
        self.assert_safe(m, ["sigma_BR", "omega_BR_B", "sun_angle_err"], sun_B=[np.nan, 0, 1], omega_BN_B=w)
        bad = self.sunsafe()
        bad.min_unit_mag = -0.1
        self.assert_refused(bad, "min_unit_mag")

    def test_att_track(self):
        m = fsw.AttTrack()
        self.assertEqual(m.init(), fsw.OK)
        sBN, sRN = np.array([0.1, 0.2, -0.1]), np.array([0.05, 0.0, 0.1])
        wBN = np.array([0.01, 0.0, -0.02])
        s, out = m.update(sigma_BN=sBN, omega_BN_B=wBN, sigma_RN=sRN)
        self.assertEqual(s, fsw.OK)
        BR = mrp_to_dcm(sBN) @ mrp_to_dcm(sRN).T
        np.testing.assert_allclose(mrp_to_dcm(out["sigma_BR"]), BR, rtol=0, atol=1e-12)
        np.testing.assert_allclose(out["omega_BR_B"], wBN, rtol=0, atol=1e-15)  # the reference is at rest
        self.assert_safe(m, ["sigma_BR", "omega_BR_B"], sigma_BN=[np.nan, 0, 0])
        self.assert_refused(fsw.AttTrack(sigma_R0R=[0, 0, np.nan]), "sigma_R0R")

    def css(self):
        n = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1.0]])
        return fsw.CssSun(num_css=6, n_hat_B=n, scale=[2.0] * 6, lit_threshold=0.1), n

    def test_css_sun(self):
        m, n = self.css()
        self.assertEqual(m.init(), fsw.OK)
        sun = np.array([0.6, 0.48, 0.64])  # unit
        reading = 2.0 * np.maximum(0.0, n @ sun)
        s, out = m.update(reading=reading)
        self.assertEqual(s, fsw.OK)
        self.assertEqual((out["num_lit"], out["mode"], out["sun_valid"]), (3, 3, 1))
        np.testing.assert_allclose(out["sun_hat_B"], sun, rtol=0, atol=1e-12)
        # one lit sensor: its normal (ONE), status W_SINGULAR
        s, out = m.update(reading=2.0 * np.maximum(0.0, n @ [1.0, 0, 0]))
        self.assertEqual((s, out["mode"]), (fsw.W_SINGULAR, 1))
        np.testing.assert_array_equal(out["sun_hat_B"], [1.0, 0, 0])
        self.assert_safe(m, ["sun_hat_B", "sun_valid", "num_lit"], reading=[np.nan, 0, 0, 0, 0, 0])
        bad, _ = self.css()
        bad.scale = [2.0, 2.0, -2.0, 2.0, 2.0, 2.0]
        self.assert_refused(bad, "scale")
        bad, _ = self.css()
        bad.num_css = fsw.MAX_CSS + 1
        self.assert_refused(bad, "num_css", fsw.E_CAPACITY)


class ControlTest(unittest.TestCase, Mixin):
    def test_mrp_fb_zero_reference(self):
        # no wheels, zero reference (omega_RN = 0), no integral, law 0: Lr = -K sigma - P omega
        I = np.diag([900.0, 800.0, 600.0])
        m = fsw.MrpFb(K=1.44, P=36.0, K_i=-1.0, I_B=I)
        self.assertEqual(m.init(), fsw.OK)
        sig, w = np.array([0.1, -0.05, 0.2]), np.array([0.004, -0.002, 0.003])
        s, out = m.update(t_ns=0, sigma_BR=sig, omega_BR_B=w)
        self.assertEqual(s, fsw.OK)
        np.testing.assert_allclose(out["torque_B"], -1.44 * sig - 36.0 * w, rtol=0, atol=1e-15)
        self.assert_safe(m, ["torque_B"], t_ns=1, sigma_BR=[0, np.nan, 0])
        self.assert_refused(fsw.MrpFb(K=1.44, P=-36.0, I_B=I), "P")

    def test_trq_lpf(self):
        h, wc = 0.5, 1.0
        m = fsw.TrqLpf(h=h, omega_c=wc)
        self.assertEqual(m.init(), fsw.OK)
        # pre-warped Tustin (docs/fsw/trq_lpf.md): hw = 2 tan(omega_c h / 2),
        # y_k = (hw (x_k + x_{k-1}) + (2 - hw) y_{k-1}) / (2 + hw); first call x_{-1} = x_0, y_{-1} = 0
        hw = 2 * math.tan(wc * h / 2)
        s, out = m.update(Lr_B=[1.0, 0, 0], t_ns=0)
        self.assertEqual(s, fsw.OK)
        y0 = 2 * hw / (2 + hw)
        self.assertAlmostEqual(out["LrF_B"][0], y0, places=15)
        s, out = m.update(Lr_B=[1.0, 0, 0], t_ns=500_000_000)
        self.assertAlmostEqual(out["LrF_B"][0], (2 * hw + (2 - hw) * y0) / (2 + hw), places=15)
        self.assert_safe(m, ["LrF_B"], Lr_B=[np.nan, 0, 0], t_ns=1_000_000_000)
        self.assert_refused(fsw.TrqLpf(h=-0.5, omega_c=1.0), "h")


class WheelTest(unittest.TestCase, Mixin):
    G = pyramid()  # rows: spin axes

    def test_rw_map_min_norm(self):
        m = fsw.RwMap(num_rw=4, gs_hat_B=self.G, num_axes=3, ctrl_axes_B=np.eye(3), mode=0)
        self.assertEqual(m.init(), fsw.OK)
        Lr = np.array([0.01, -0.02, 0.005])
        s, out = m.update(Lr_B=Lr)
        self.assertEqual(s, fsw.OK)
        np.testing.assert_allclose(out["u_s"][:4], -np.linalg.pinv(self.G.T) @ Lr, rtol=0, atol=1e-15)
        self.assert_safe(m, ["u_s"], Lr_B=[np.nan, 0, 0])
        self.assert_refused(fsw.RwMap(num_rw=fsw.MAX_RW + 1, num_axes=3), "num_rw", fsw.E_CAPACITY)

    def test_rw_sat_bounds(self):
        m = fsw.RwSat(num_rw=4, u_max=[0.2, 0.1, 0.2, 0.2], mode=1)  # clip
        self.assertEqual(m.init(), fsw.OK)
        s, out = m.update(u_s=[0.5, -0.5, 0.1, -0.1])
        self.assertEqual(s, fsw.W_SAT)
        np.testing.assert_array_equal(out["u_s"][:4], [0.2, -0.1, 0.1, -0.1])
        self.assert_safe(m, ["u_s"], u_s=[np.nan, 0, 0, 0])
        self.assert_refused(fsw.RwSat(num_rw=4, u_max=[0.2, 0.2, np.nan, 0.2]), "u_max")

    def rw_null(self, **kw):
        cfg = dict(num_rw=4, gs_hat_B=self.G, k_null=0.002, u_max=[0.2] * 4)
        cfg.update(kw)
        return fsw.RwNull(**cfg)

    def test_rw_null_keeps_body_torque(self):
        m = self.rw_null(scale_to_fit=0)
        self.assertEqual(m.init(), fsw.OK)
        u_c, Om, Od = np.array([0.01, -0.02, 0.0, 0.005]), np.array([10.0, -40.0, 5.0, 0.0]), np.zeros(4)
        s, out = m.update(u_s=u_c, Omega=Om, Omega_des=Od)
        self.assertEqual(s, fsw.OK)
        # u = u_c + P_null (-k (Omega - Omega_des)): the body torque G u is that of u_c
        want = u_c + null_projector(self.G.T) @ (-0.002 * (Om - Od))
        np.testing.assert_allclose(out["u_s"][:4], want, rtol=0, atol=1e-15)
        self.assertEqual(out["kappa"], 1.0)
        self.assert_safe(m, ["u_s"], u_s=u_c, Omega=[np.nan, 0, 0, 0])
        self.assert_refused(self.rw_null(k_null=-0.002), "k_null")

    def test_rw_null_regen_keeps_body_torque(self):
        m = fsw.RwNullRegen(num_rw=4, gs_hat_B=self.G, k_P=0.001, u_max=[0.2] * 4, mode=0)
        self.assertEqual(m.init(), fsw.OK)
        u_c, Om = np.array([0.01, -0.02, 0.0, 0.005]), np.array([10.0, -40.0, 5.0, 0.0])
        s, out = m.update(u_s=u_c, Omega=Om)
        self.assertGreaterEqual(s, 0)
        np.testing.assert_allclose(self.G.T @ out["u_s"][:4], self.G.T @ u_c, rtol=0, atol=1e-15)
        self.assertAlmostEqual(out["power"], float(out["u_s"][:4] @ Om), places=12)
        self.assert_safe(m, ["u_s"], u_s=u_c, Omega=[0, np.nan, 0, 0])
        self.assert_refused(fsw.RwNullRegen(num_rw=4, gs_hat_B=self.G, k_P=0.001, u_max=[0.2, -0.2, 0.2, 0.2]),
                            "u_max")

    def test_rw_bias_moves_only_in_the_null_space(self):
        m = fsw.RwBias(num_rw=4, gs_hat_B=self.G, Omega_bias=[100.0, -100.0, 100.0, -100.0], Omega_keepout=20.0,
                       Omega_hyst=5.0)
        self.assertEqual(m.init(), fsw.OK)
        Om = np.array([50.0, -10.0, 30.0, 0.0])
        s, out = m.update(Omega=Om)
        self.assertGreaterEqual(s, 0)
        self.assertEqual(out["nullity"], 1)
        # the desired speeds keep the wheel momentum: G^T (Omega_des - Omega) = 0
        np.testing.assert_allclose(self.G.T @ (out["Omega_des"][:4] - Om), 0.0, atol=1e-10)
        self.assert_safe(m, ["Omega_des"], Omega=[np.nan, 0, 0, 0])
        bad = fsw.RwBias(num_rw=4, gs_hat_B=self.G, Omega_bias=[100.0] * 4, Omega_keepout=-20.0, Omega_hyst=5.0)
        self.assert_refused(bad, "Omega_keepout")

    def speed_filter(self):
        return fsw.RwSpeedFilter(num_rw=2, u_max=[0.2, 0.2], J_s=[0.1, 0.1], noise=[0.01, 0.01], k_reject=3,
                                 n_recover=2, n_stale=0, n_window=0, resid_tol=[0.0, 0.0])

    def test_rw_speed_filter_passes_clean_speeds(self):
        m = self.speed_filter()
        self.assertEqual(m.init(), fsw.OK)
        for k in range(3):
            s, out = m.update(Omega_meas=[10.0 + 0.1 * k, -5.0], t_ns=k * 100_000_000)
            self.assertEqual(s, fsw.OK)
            np.testing.assert_array_equal(out["Omega"][:2], [10.0 + 0.1 * k, -5.0])
            self.assertEqual(out["rejected"], 0)
        # a NaN sample is rejected, not an error (documented): the last good speed held, bit 1 set
        s, out = m.update(Omega_meas=[10.3, np.nan], t_ns=300_000_000)
        self.assertEqual(s, fsw.OK)
        np.testing.assert_array_equal(out["Omega"][:2], [10.3, -5.0])
        self.assertEqual(out["rejected"], 0b10)
        # a mask entry not 0/1: E_BAD_INPUT with the held speeds, no state advanced
        s, out = m.update(Omega_meas=[10.4, -5.0], avail=[2, 0], t_ns=400_000_000)
        self.assertEqual(s, fsw.E_BAD_INPUT)
        np.testing.assert_array_equal(out["Omega"][:2], [10.3, -5.0])
        bad = self.speed_filter()
        bad.noise = [0.01, np.nan]
        self.assert_refused(bad, "noise")

    def test_rw_volt_feed_forward(self):
        m = fsw.RwVolt(num_rw=2, V_min=0.5, V_max=10.0, K_V=0.0, u_max=[0.2, 0.1], J_s=[0.1, 0.1])
        self.assertEqual(m.init(), fsw.OK)
        s, out = m.update(u_s=[0.1, -0.05], t_ns=0)
        self.assertEqual(s, fsw.OK)
        # V = (V_max - V_min)/u_max u, then +-V_min
        np.testing.assert_allclose(out["V"][:2], [9.5 / 0.2 * 0.1 + 0.5, -(9.5 / 0.1 * 0.05 + 0.5)], rtol=1e-15)
        self.assert_safe(m, ["V"], u_s=[np.nan, 0], t_ns=1)
        self.assert_refused(fsw.RwVolt(num_rw=2, V_min=0.5, V_max=np.inf, u_max=[0.2, 0.1], J_s=[0.1, 0.1]), "V_max")

    def test_count_fixed_after_init_and_module_keeps_working(self):
        m = fsw.RwMap(num_rw=4, gs_hat_B=self.G, num_axes=3, ctrl_axes_B=np.eye(3), mode=0)
        m.init()
        before = m.update(Lr_B=[0.01, 0.0, 0.0])[1]["u_s"]
        for name, value in (("num_rw", 36), ("num_rw", 100000), ("num_axes", 37)):
            with self.assertRaises(ValueError) as e:
                setattr(m, name, value)
            self.assertIn(name, str(e.exception))
            self.assertIn("init()", str(e.exception))
        self.assertEqual((m.num_rw, m.num_axes), (4, 3))
        s, after = m.update(Lr_B=[0.01, 0.0, 0.0])
        self.assertEqual(s, fsw.OK)
        np.testing.assert_array_equal(after["u_s"], before)


class MagneticTest(unittest.TestCase, Mixin):
    def bdot(self, **kw):
        cfg = dict(variant=1, k_bdot=1e4, normalize=0, tau_f=0.0, max_missed=2, m_max_B=[50.0, 50.0, 50.0],
                   omega_done=0.001, omega_reenter=0.002, t_persist=10.0)
        cfg.update(kw)
        return fsw.Bdot(**cfg)

    def test_bdot_gyro_law_and_saturation(self):
        m = self.bdot()
        self.assertEqual(m.init(), fsw.OK)
        B, w = np.array([2e-5, -1e-5, 3e-5]), np.array([0.01, 0.02, -0.01])
        s, out = m.update(t_ns=0, B_B=B, B_valid=1, omega_BN_B=w, omega_valid=1)
        want = 1e4 * np.cross(w, B)  # m = g (omega x B), |m_i| << 50: unsaturated
        self.assertEqual(s, fsw.OK)
        np.testing.assert_allclose(out["m_B"], want, rtol=1e-14)
        self.assertAlmostEqual(out["rate_est"], np.linalg.norm(w), places=15)
        m = self.bdot(k_bdot=1e9)
        m.init()
        s, out = m.update(t_ns=0, B_B=B, B_valid=1, omega_BN_B=w, omega_valid=1)
        raw = 1e9 * np.cross(w, B)
        scale = min(50.0 / abs(x) for x in raw)
        self.assertEqual(s, fsw.W_SAT)
        np.testing.assert_allclose(out["m_B"], scale * raw, rtol=1e-14)
        self.assert_safe(m, ["m_B", "rate_est"], t_ns=1, B_B=[np.nan, 0, 0], B_valid=1, omega_BN_B=w, omega_valid=1)
        self.assert_refused(self.bdot(k_bdot=-1.0), "k_bdot")

    def test_mtq_map_torque_mode(self):
        m = fsw.MtqMap(num_mtq=3, gt_hat_B=np.eye(3), m_max=[100.0] * 3, duty_max=1.0)
        self.assertEqual(m.init(), fsw.OK)
        B, tau = np.array([2e-5, 0.0, 1e-5]), np.array([1e-4, 2e-4, -1e-4])
        s, out = m.update(tau_B=tau, B_B=B, B_valid=1)
        self.assertEqual(s, fsw.OK)
        mB = np.cross(B, tau) / (B @ B)
        b = B / np.linalg.norm(B)
        np.testing.assert_allclose(out["m_cmd"][:3], mB, rtol=1e-12)
        np.testing.assert_allclose(out["tau_ach_B"], tau - (tau @ b) * b, rtol=0, atol=1e-16)
        np.testing.assert_allclose(out["tau_par_B"], (tau @ b) * b, rtol=0, atol=1e-16)
        self.assert_safe(m, ["m_cmd", "duty", "tau_ach_B"], tau_B=[np.nan, 0, 0], B_B=B, B_valid=1)
        self.assert_refused(fsw.MtqMap(num_mtq=3, gt_hat_B=np.eye(3), m_max=[100.0, -100.0, 100.0], duty_max=1.0),
                            "m_max")

    def test_mtq_desat_cross_product_law(self):
        G = pyramid()
        m = fsw.MtqDesat(num_rw=4, gs_hat_B=G, J_s=[0.1] * 4, k_desat=0.01, tau_max=1.0, h_deadband=0.0)
        self.assertEqual(m.init(), fsw.OK)
        Om, B = np.array([100.0, -50.0, 20.0, 0.0]), np.array([2e-5, -1e-5, 3e-5])
        s, out = m.update(Omega=Om, B_B=B, B_valid=1)
        self.assertEqual(s, fsw.OK)
        h = 0.1 * G.T @ Om
        np.testing.assert_allclose(out["h_w_B"], h, rtol=1e-14)
        np.testing.assert_allclose(out["m_B"], 0.01 * np.cross(h, B) / (B @ B), rtol=1e-12)
        b = B / np.linalg.norm(B)
        np.testing.assert_allclose(out["tau_req_B"], -0.01 * (h - (h @ b) * b), rtol=0, atol=1e-15)
        self.assert_safe(m, ["m_B", "tau_req_B"], Omega=[np.nan, 0, 0, 0], B_B=B, B_valid=1)
        self.assert_refused(fsw.MtqDesat(num_rw=4, gs_hat_B=G, J_s=[0.1] * 4, k_desat=-0.01, tau_max=1.0),
                            "k_desat")


class ThrusterTest(unittest.TestCase, Mixin):
    R = np.array([[-0.8636, -0.8255, 1.7907], [-0.8255, -0.8636, 1.7907], [0.8255, 0.8636, 1.7907],
                  [0.8636, 0.8255, 1.7907], [-0.8636, -0.8255, -1.7907], [-0.8255, -0.8636, -1.7907],
                  [0.8255, 0.8636, -1.7907], [0.8636, 0.8255, -1.7907]])
    D = np.array([[1, 0, 0], [0, 1, 0], [0, -1, 0], [-1, 0, 0], [-1, 0, 0], [0, -1, 0], [0, 1, 0], [1, 0, 0.0]])

    def thr_map(self, **kw):
        cfg = dict(num_thr=8, control_axes_B=np.eye(3), r_thr_B=self.R, gt_hat_B=self.D, F_max=[1.0] * 8,
                   thr_force_sign=1, mode=0, ang_err_thresh=0.0, epsilon=1e-6)
        cfg.update(kw)
        return fsw.ThrMap(**cfg)

    def test_thr_map_delivers_the_torque(self):
        m = self.thr_map()
        self.assertEqual(m.init(), fsw.OK)
        Lr = np.array([0.0, 0.0, 0.05])
        s, out = m.update(Lr_B=Lr)
        self.assertGreaterEqual(s, 0)
        F = out["F"][:8]
        self.assertTrue(np.all(F >= 0.0))
        torque = sum(f * np.cross(r, d) for f, r, d in zip(F, self.R, self.D))
        np.testing.assert_allclose(torque, Lr, rtol=0, atol=1e-9)
        self.assert_safe(m, ["F"], Lr_B=[np.nan, 0, 0])
        self.assert_refused(self.thr_map(F_max=[1.0] * 7 + [np.nan]), "F_max")

    def test_thr_pulse_round(self):
        m = fsw.ThrPulseRound(num_thr=3, F_max=[1.0] * 3, period=0.5, resolution=0.01, t_min=0.02)
        self.assertEqual(m.init(), fsw.OK)
        s, out = m.update(F=[0.333, 0.03, 0.0])
        self.assertEqual(s, fsw.OK)
        # T F/F_max = 0.1665 -> 0.17 (q = 0.01); 0.015 -> 0.02 (round half to even of 1.5), kept (>= t_min)
        np.testing.assert_allclose(out["t_on"][:3], [0.17, 0.02, 0.0], rtol=0, atol=1e-15)
        self.assert_safe(m, ["t_on"], F=[np.nan, 0, 0])
        self.assert_refused(fsw.ThrPulseRound(num_thr=3, F_max=[1.0] * 3, period=-0.5, resolution=0.01), "period")

    def pulser(self, cls, **kw):
        return cls(num_thr=2, F_max=[2.0, 2.0], t_min=0.02, base_thrust_state=0, init_off_pulse_on_time=0.0, **kw)

    def test_thr_pulse_rem_and_schmitt_duty(self):
        for cls, extra in ((fsw.ThrPulseRem, {}), (fsw.ThrPulseSchmitt, dict(level_on=0.75, level_off=0.25))):
            m = self.pulser(cls, **extra)
            self.assertEqual(m.init(), fsw.OK)
            s, out = m.update(t_ns=0, F=[1.0, 0.5])
            np.testing.assert_array_equal(out["t_on"][:2], [0.0, 0.0])  # first call: b * init on-time = 0
            s, out = m.update(t_ns=500_000_000, F=[1.0, 0.5])  # period 0.5 s: t = F/F_max T
            self.assertEqual(s, fsw.OK, cls.__name__)
            np.testing.assert_allclose(out["t_on"][:2], [0.25, 0.125], rtol=1e-15)
            self.assert_safe(m, ["t_on"], t_ns=1_000_000_000, F=[np.nan, 0])
            bad = self.pulser(cls, **extra)
            bad.t_min = -0.02
            self.assert_refused(bad, "t_min")

    def thr_momentum(self, **kw):
        G = pyramid()
        cfg = dict(num_rw=4, gs_hat_B=G, J_s=[0.1] * 4, h_upper=10.0, h_lower=2.0, L_dump=0.5, t_pulse_max=0.5,
                   t_min_pulse=0.02, t_coast=1.0, dt_cycle=0.5, num_thr=8, F_max=[1.0] * 8, Isp=220.0)
        cfg.update(kw)
        return fsw.ThrMomentum(**cfg), G

    def test_thr_momentum_idle_below_the_band(self):
        m, G = self.thr_momentum()
        self.assertEqual(m.init(), fsw.OK)
        Om = np.array([100.0, -50.0, 20.0, 0.0])
        s, out = m.update(t_ns=0, Omega=Om, enable=1)
        self.assertEqual(s, fsw.OK)
        h = 0.1 * G.T @ Om
        np.testing.assert_allclose(out["h_w_B"], h, rtol=1e-14)
        self.assertAlmostEqual(out["h_norm"], np.linalg.norm(h), places=12)
        self.assertEqual(out["phase"], 0)
        np.testing.assert_array_equal(out["L_thr_B"], 0.0)
        self.assert_safe(m, ["L_thr_B", "h_w_B"], t_ns=1, Omega=[np.nan, 0, 0, 0], enable=1)
        bad, _ = self.thr_momentum(Isp=-220.0)
        self.assert_refused(bad, "Isp")


def golden_rows():
    """The recorded cycles of test/fsw_c/data/fsw_acs_golden.inc as lists."""
    text = open(os.path.join(SRC, "test", "fsw_c", "data", "fsw_acs_golden.inc")).read()
    text = "\n".join(l for l in text.splitlines() if not l.lstrip().startswith("//"))
    text = re.sub(r"(\d)u\b", r"\1", text).replace("{", "[").replace("}", "]")
    return eval("[" + text + "]")  # numbers and brackets only


class AcsTest(unittest.TestCase):
    """fsw_acs as a whole: the golden scenarios (test/fsw_c/acs_fixture.hpp, golden_config)."""

    def base_acs(self):
        a = fsw.Acs(initial_mode=fsw.AcsMode.SUN_SAFE, initial_actuation=fsw.AcsActuation.WHEELS)
        a.set("css.num_css", 6)
        a.set("css.n_hat_B", [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]])
        a.set("css.scale", [1.0] * 6)
        a.set("css.lit_threshold", 0.01)
        a.set("sunsafe.s_cmd_B", [0, 0, 1])
        a.set("sunsafe.min_unit_mag", 0.1)
        a.set("sunsafe.small_angle", 1e-4)
        a.set("sunsafe.omega_search_B", [0, 0, 0.005])
        a.set("inertial.sigma_R0N", [0.1, -0.05, 0.2])
        for k, v in (("K", 1.44), ("P", 36.0), ("K_i", -1.0), ("integral_limit", 0.0)):
            a.set("mrp_fb." + k, v)
        a.set("mrp_fb.I_B", np.diag([900.0, 800.0, 600.0]))
        a.set("lpf.h", 0.5)
        a.set("lpf.omega_c", 1.0)
        return a

    def golden_acs(self):
        a = self.base_acs()
        a.set_geometry(num_rw=4, gs_hat_B=pyramid(), J_s=[0.1] * 4, u_max=[0.2] * 4)
        a.set("rw_map.num_axes", 3)
        a.set("rw_map.ctrl_axes_B", np.eye(3))
        a.set("rw_map.eps_P", 1.0)
        a.set("rw_null.k_null", 0.002)
        a.set("rw_null.scale_to_fit", 1)
        a.set("rw_volt.V_max", 10.0)
        for k in ("use_null", "use_lpf", "use_volt"):
            a.set(k, 1)
        a.set("Omega_des", [20.0])
        return a

    def thruster_acs(self, pulser):
        a = self.base_acs()
        a.set("initial_mode", fsw.AcsMode.INERTIAL)
        a.set("initial_actuation", fsw.AcsActuation.THRUSTERS)
        a.set_geometry(num_thr=8, r_thr_B=ThrusterTest.R, gt_hat_B=ThrusterTest.D, F_max=[1.0] * 8)
        a.set("mrp_fb.K", 20.0)
        a.set("mrp_fb.P", 200.0)
        a.set("thr_map.control_axes_B", np.eye(3))
        a.set("thr_map.thr_force_sign", 1)
        a.set("thr_map.mode", THR_MAP_NNLS)
        a.set("pulser", pulser)
        for p in ("pulse_rem", "pulse_schmitt"):
            a.set(p + ".t_min", 0.02)
            a.set(p + ".init_off_pulse_on_time", 2.0)
        a.set("pulse_schmitt.level_on", 0.75)
        a.set("pulse_schmitt.level_off", 0.25)
        return a

    def test_golden_thruster_scenarios(self):
        for sc in (1, 2):  # remainder and Schmitt pulsers
            a = self.thruster_acs(sc - 1)
            self.assertEqual(a.init(), fsw.OK)
            rows = [r for r in golden_rows() if r[0] == sc]
            self.assertGreater(len(rows), 10)
            for (_, cycle, mode, t_ns, sigma, omega, css, Om, status, Lr, u, V, t_on) in rows:
                s, act, hlth = a.cycle(cmd=dict(mode=mode, actuation=1), t_ns=t_ns, att_valid=1, sigma_BN=sigma,
                                       omega_BN_B=omega, css=css, Omega=Om)
                self.assertEqual(int(s), status, (sc, cycle))
                np.testing.assert_allclose(act["Lr_B"], Lr, rtol=0, atol=1e-12, err_msg=str((sc, cycle)))
                np.testing.assert_allclose(act["t_on"][:8], t_on, rtol=0, atol=1e-12, err_msg=str((sc, cycle)))

    def test_golden_wheel_scenario(self):
        a = self.golden_acs()
        self.assertEqual(a.check(), fsw.OK)
        self.assertEqual(a.init(), fsw.OK)
        rows = [r for r in golden_rows() if r[0] == 0]
        self.assertGreater(len(rows), 40)
        for (_, cycle, mode, t_ns, sigma, omega, css, Om, status, Lr, u, V, t_on) in rows:
            s, act, hlth = a.cycle(cmd=dict(mode=mode, actuation=0), t_ns=t_ns, att_valid=1, sigma_BN=sigma,
                                   omega_BN_B=omega, css=css, Omega=Om)
            self.assertEqual(int(s), status, cycle)
            np.testing.assert_allclose(act["Lr_B"], Lr, rtol=0, atol=1e-12, err_msg=str(cycle))
            np.testing.assert_allclose(act["u_s"][:4], u, rtol=0, atol=1e-12, err_msg=str(cycle))
            np.testing.assert_allclose(act["V"][:4], V, rtol=0, atol=1e-12, err_msg=str(cycle))
        self.assertEqual(hlth["mode"], fsw.AcsMode.INERTIAL)
        self.assertEqual(hlth["cycles"], len(rows))

    def test_commands_bad_input_and_config(self):
        a = self.golden_acs()
        a.init()
        s, act, h = a.cycle(t_ns=0, att_valid=1, sigma_BN=[0.1, -0.05, 0.2], css=[0, 0, 0, 0, 1, 0])
        self.assertGreaterEqual(s, 0)
        self.assertEqual(h["mode"], fsw.AcsMode.SUN_SAFE)
        s, act, h = a.cycle(cmd=dict(mode=fsw.AcsMode.INERTIAL, set_gains=1, K=2.0, P=40.0), t_ns=500_000_000,
                            att_valid=1, sigma_BN=[0.1, -0.05, 0.2])
        self.assertGreaterEqual(s, 0)
        self.assertEqual((h["mode"], h["mode_changes"]), (fsw.AcsMode.INERTIAL, 1))
        # at the reference and at rest the commanded torque is zero
        np.testing.assert_allclose(act["Lr_B"], 0.0, atol=1e-15)
        s, act, h = a.cycle(t_ns=1_000_000_000, att_valid=1, sigma_BN=[np.nan, 0, 0])
        self.assertEqual(s, fsw.E_BAD_INPUT)
        self.assertEqual(h["safe_output"], 1)
        np.testing.assert_array_equal(act["u_s"], 0.0)
        with self.assertRaises(ValueError):
            a.set("rw_map.num_rw", 5)  # a count after init
        self.assertGreaterEqual(a.cycle(t_ns=1_000_000_000, att_valid=1, sigma_BN=[0.1, -0.05, 0.2])[0], 0)
        bad = self.golden_acs()
        bad.set("initial_mode", 17)
        with self.assertRaises(fsw.ConfigError) as e:
            bad.check()
        self.assertEqual(e.exception.field, "initial_mode")
        bad = self.golden_acs()
        bad.set("rw_sat.u_max", [0.2, 0.2, -0.2, 0.2])
        with self.assertRaises(fsw.ConfigError) as e:
            bad.init()
        self.assertIn("rw_sat", e.exception.field)
        with self.assertRaises(KeyError):
            bad.set("no_such.field", 1)


class ShapeTest(unittest.TestCase):
    def test_every_module_is_bound(self):
        headers = os.listdir(os.path.join(SRC, "fsw_c", "include", "fsw"))
        modules = sorted(h[:-2] for h in headers if h.endswith(".h") and not h.startswith("fsw_")
                         and h != "rw_common.h" and h != "thr_pulse_common.h")
        names = {"".join(p.capitalize() for p in mod.split("_")) for mod in modules}
        missing = sorted(n for n in names if not hasattr(fsw, n))
        self.assertEqual(missing, [])
        self.assertTrue(hasattr(fsw, "Acs"))
        self.assertEqual(fsw.Status(-2).name, "E_CONFIG")
        self.assertTrue(issubclass(fsw.ConfigError, ValueError))


if __name__ == "__main__":
    unittest.main()
