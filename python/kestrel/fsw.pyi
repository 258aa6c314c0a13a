# Type stub of kestrel.fsw (thin bindings of single fsw_c algorithms and of
# the flight application fsw_acs, written by hand; test/python/test_package.py
# checks its names against the module's, class by class).
# Config fields are attributes: scalars as float/int, arrays as NumPy (float64;
# a field of n entries is sized by its capacity, MAX_RW, MAX_THR, ...).
from enum import IntEnum
from typing import Any, ClassVar, Dict, List, Mapping, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

_Out = Union[npt.NDArray[np.float64], float, int]

class Status(IntEnum):
    """FswStatus of fsw_c: errors negative, warnings positive, OK zero"""
    OK = 0
    W_SINGULAR = 1
    W_SAT = 2
    W_RATE = 3
    E_NULL_ARG = -1
    E_CONFIG = -2
    E_CAPACITY = -3
    E_SINGULAR = -4
    E_BAD_INPUT = -5
    E_TIME = -6
    E_UNSUPPORTED = -7
    E_NOT_INIT = -8

OK: Status
E_NULL_ARG: Status
E_CONFIG: Status
E_CAPACITY: Status
E_SINGULAR: Status
E_BAD_INPUT: Status
E_TIME: Status
E_UNSUPPORTED: Status
E_NOT_INIT: Status
W_SINGULAR: Status
W_SAT: Status
W_RATE: Status
MAX_RW: int
MAX_THR: int
MAX_CSS: int
MAX_MTQ: int
REAL_IS_FLOAT: bool

def status_name(status: int) -> str: ...
def stage_name(stage: int) -> str: ...

class ConfigError(ValueError):
    """check() or init() refused: .status and .field (the bad field's name, or None)"""
    status: Optional[Status]
    field: Optional[str]

class _Algorithm:
    inputs: ClassVar[List[str]]
    outputs: ClassVar[List[str]]
    def __init__(self, **config: Any) -> None: ...
    def check(self) -> Status: ...
    def init(self) -> Status: ...
    def reset(self) -> None: ...
    def update(self, **inputs: npt.ArrayLike) -> Tuple[Status, Dict[str, _Out]]: ...
    @property
    def initialized(self) -> bool: ...
    @property
    def config(self) -> Dict[str, _Out]: ...
    @property
    def state(self) -> Dict[str, _Out]: ...

class AttTrack(_Algorithm):
    """Attitude tracking error (docs/fsw/att_track.md)"""
    sigma_R0R: npt.NDArray[np.float64]  # [-] nominal reference rel. the corrected one

class Bdot(_Algorithm):
    """B-dot detumbling with magnetorquers (docs/fsw/bdot.md)"""
    variant: int  # 0 DERIV (magnetometer derivative), 1 GYRO
    k_bdot: float  # gain, > 0
    normalize: int  # 0: g = k_bdot; 1: g = k_bdot / |B|^2
    tau_f: float  # [s] derivative filter time constant (DERIV)
    max_missed: int  # cycles a dipole is held over missed samples
    m_max_B: npt.NDArray[np.float64]  # [A*m^2] per-axis dipole limit
    omega_done: float  # [rad/s] detumbled threshold
    omega_reenter: float  # [rad/s] re-entry threshold, > omega_done
    t_persist: float  # [s] time below omega_done before detumbled

class CssSun(_Algorithm):
    """Sun heading from coarse sun sensors, weighted least squares (docs/fsw/css_sun.md)"""
    num_css: int  # sensors, 1..MAX_CSS
    n_hat_B: npt.NDArray[np.float64]  # (num_css, 3) unit normals, B
    scale: npt.NDArray[np.float64]  # (num_css) reading at normal incidence, > 0
    lit_threshold: float  # [-] a sensor is lit above it, [0, 1)

class GuidInertial(_Algorithm):
    """Inertial three-axis pointing guidance (docs/fsw/guid_inertial.md); update() takes no input"""
    sigma_R0N: npt.NDArray[np.float64]  # [-] commanded inertial attitude (MRP)

class GuidOrbit(_Algorithm):
    """Orbit-referenced guidance, nadir or velocity pointing (docs/fsw/guid_orbit.md)"""
    variant: int  # 0 NADIR, 1 VELOCITY
    sigma_BdR: npt.NDArray[np.float64]  # [-] desired body attitude rel. the orbit frame
    mu: float  # [m^3/s^2] gravitational parameter (VELOCITY)

class GuidSunsafe(_Algorithm):
    """Sun-safe pointing guidance (docs/fsw/guid_sunsafe.md)"""
    s_cmd_B: npt.NDArray[np.float64]  # [-] body axis to point at the Sun
    min_unit_mag: float  # [-] smallest |sun_B| taken as a heading
    small_angle: float  # [rad] below it the error is zero
    omega_search_B: npt.NDArray[np.float64]  # [rad/s] search rate without a heading
    sun_axis_spin_rate: float  # [rad/s] spin about the Sun line

class MrpFb(_Algorithm):
    """MRP feedback control law (docs/fsw/mrp_fb.md)"""
    K: float  # [N*m] attitude gain
    P: float  # [N*m*s] rate gain
    K_i: float  # [1/(kg*m^2)] integral gain; <= 0 disables
    integral_limit: float  # [N*m*s] per-component bound on int_sigma
    control_law_type: int  # 0 or 1
    known_torque_B: npt.NDArray[np.float64]  # [N*m] known external torque
    I_B: npt.NDArray[np.float64]  # [kg*m^2] inertia about the CoM, B
    num_rw: int  # wheels in H, 0..MAX_RW
    gs_hat_B: npt.NDArray[np.float64]  # (num_rw, 3) spin axes
    J_s: npt.NDArray[np.float64]  # [kg*m^2] (num_rw) wheel spin inertias

class MtqDesat(_Algorithm):
    """Wheel momentum unloading with magnetorquers (docs/fsw/mtq_desat.md)"""
    num_rw: int  # wheels, 1..MAX_RW
    gs_hat_B: npt.NDArray[np.float64]  # (num_rw, 3) spin axes
    J_s: npt.NDArray[np.float64]  # [kg*m^2] (num_rw) spin inertias
    k_desat: float  # [1/s] momentum feedback gain
    h_target_B: npt.NDArray[np.float64]  # [N*m*s] target wheel momentum
    tau_max: float  # [N*m] requested torque limit
    h_deadband: float  # [N*m*s] no request below it

class MtqMap(_Algorithm):
    """Magnetorquer mapping, torque or dipole to rod commands (docs/fsw/mtq_map.md)"""
    num_mtq: int  # rods, 1..MAX_MTQ
    gt_hat_B: npt.NDArray[np.float64]  # (num_mtq, 3) rod axes
    m_max: npt.NDArray[np.float64]  # [A*m^2] (num_mtq) dipole limits
    duty_max: float  # [-] largest duty (sensing time-sharing)

class RwBias(_Algorithm):
    """Wheel speed biasing away from zero crossings (docs/fsw/rw_bias.md)"""
    num_rw: int  # wheels, 4..MAX_RW
    gs_hat_B: npt.NDArray[np.float64]  # (num_rw, 3) spin axes
    Omega_bias: npt.NDArray[np.float64]  # [rad/s] (num_rw) preferred speeds
    Omega_keepout: float  # [rad/s] keep-out band half-width about 0
    Omega_hyst: float  # [rad/s] hysteresis of the band

class RwMap(_Algorithm):
    """Reaction-wheel torque mapping (docs/fsw/rw_map.md)"""
    num_rw: int  # 1..MAX_RW
    gs_hat_B: npt.NDArray[np.float64]  # (num_rw, 3) spin axes
    num_axes: int  # controlled axes 0..3
    ctrl_axes_B: npt.NDArray[np.float64]  # (num_axes, 3) control axes, rows
    mode: int  # 0 min-norm, 1 power
    eps_P: float  # [rad^2/s^2] power mode

class RwNull(_Algorithm):
    """Reaction-wheel null motion toward desired speeds (docs/fsw/rw_null.md)"""
    num_rw: int  # wheels, 4..MAX_RW
    gs_hat_B: npt.NDArray[np.float64]  # (num_rw, 3) spin axes
    k_null: float  # [N*m*s] null-motion gain
    u_max: npt.NDArray[np.float64]  # [N*m] (num_rw) torque limits (scale_to_fit)
    scale_to_fit: int  # 0/1: shrink the null torque to the limits

class RwNullRegen(_Algorithm):
    """Null motion for power (docs/fsw/rw_null_regen.md)"""
    num_rw: int  # wheels, 4..MAX_RW
    gs_hat_B: npt.NDArray[np.float64]  # (num_rw, 3) spin axes
    k_P: float  # [N*m*s] gain
    u_max: npt.NDArray[np.float64]  # [N*m] (num_rw) torque limits
    mode: int  # the law (docs/fsw/rw_null_regen.md)

class RwSat(_Algorithm):
    """Reaction-wheel torque saturation (fsw_c/include/fsw/rw_sat.h)"""
    num_rw: int  # 1..MAX_RW
    u_max: npt.NDArray[np.float64]  # [N*m] (num_rw) torque limits
    mode: int  # 0 scale, 1 clip

class RwSpeedFilter(_Algorithm):
    """Tachometer screening: outliers, NaN, stale and torque-inconsistent readings (docs/fsw/rw_speed_filter.md)"""
    num_rw: int  # wheels, 1..MAX_RW
    u_max: npt.NDArray[np.float64]  # [N*m] (num_rw) torque limits
    J_s: npt.NDArray[np.float64]  # [kg*m^2] (num_rw) spin inertias
    noise: npt.NDArray[np.float64]  # [rad/s] (num_rw) tachometer noise
    k_reject: int  # rejections in a row that fail a wheel
    n_recover: int  # good samples that recover it
    n_stale: int  # identical samples that fail it
    n_window: int  # torque-consistency window (0 off)
    resid_tol: npt.NDArray[np.float64]  # [rad/s] (num_rw) window residual tolerance

class RwVolt(_Algorithm):
    """Wheel motor voltages from torques (docs/fsw/rw_volt.md)"""
    num_rw: int  # wheels, 1..MAX_RW
    V_min: float  # [V] smallest commanded |V| (dead zone)
    V_max: float  # [V] largest |V|
    K_V: float  # [V/(N*m)] volts per torque
    u_max: npt.NDArray[np.float64]  # [N*m] (num_rw) torque limits
    J_s: npt.NDArray[np.float64]  # [kg*m^2] (num_rw) spin inertias
    Omega_dot_max: npt.NDArray[np.float64]  # [rad/s^2] (num_rw) rate gate
    gate_rate: int  # 0/1: the acceleration gate

class ThrMap(_Algorithm):
    """Thruster force mapping, non-negative least squares (docs/fsw/thr_map.md)"""
    num_thr: int  # thrusters, 1..MAX_THR
    control_axes_B: npt.NDArray[np.float64]  # (axes, 3) control axes, rows (zero rows unused)
    r_thr_B: npt.NDArray[np.float64]  # [m] (num_thr, 3) locations
    gt_hat_B: npt.NDArray[np.float64]  # (num_thr, 3) force axes
    F_max: npt.NDArray[np.float64]  # [N] (num_thr) max thrust
    thr_force_sign: int  # +1 on-pulsing, -1 off-pulsing
    mode: int  # the mapping (docs/fsw/thr_map.md)
    ang_err_thresh: float  # [rad] direction-error threshold
    epsilon: float  # [-] rank tolerance

class ThrMomentum(_Algorithm):
    """Wheel momentum dumping with thrusters (docs/fsw/thr_momentum.md)"""
    num_rw: int  # wheels, 1..MAX_RW
    gs_hat_B: npt.NDArray[np.float64]  # (num_rw, 3) spin axes
    J_s: npt.NDArray[np.float64]  # [kg*m^2] (num_rw) spin inertias
    h_upper: float  # [N*m*s] a dump starts above it
    h_lower: float  # [N*m*s] a dump ends at it
    L_dump: float  # [N*m] dump torque
    t_pulse_max: float  # [s] longest pulse
    t_min_pulse: float  # [s] shortest pulse
    t_coast: float  # [s] coast between pulses
    dt_cycle: float  # [s] control period
    num_thr: int  # thrusters, 1..MAX_THR
    F_max: npt.NDArray[np.float64]  # [N] (num_thr) max thrust
    Isp: float  # [s] specific impulse

class _ThrPulseOnOff(_Algorithm):  # the fields ThrPulseRem and ThrPulseSchmitt share (not a runtime class)
    num_thr: int  # thrusters, 1..MAX_THR
    F_max: npt.NDArray[np.float64]  # [N] (num_thr) max thrust
    t_min: float  # [s] minimum on-time, > 0
    base_thrust_state: int  # 0 on-pulsing, 1 off-pulsing
    init_off_pulse_on_time: float  # [s] first-call on-time when off-pulsing

class ThrPulseRem(_ThrPulseOnOff):
    """Thruster pulsing with remainder tracking (docs/fsw/thr_pulse_rem.md)"""

class ThrPulseRound(_Algorithm):
    """Thruster pulsing by rounding (docs/fsw/thr_pulse_round.md)"""
    num_thr: int  # thrusters, 1..MAX_THR
    F_max: npt.NDArray[np.float64]  # [N] (num_thr) max thrust
    period: float  # [s] control period T
    resolution: float  # [s] on-time resolution q
    t_min: float  # [s] minimum on-time, 0..period
    carry_residual: int  # 0/1: carry the rounding error

class ThrPulseSchmitt(_ThrPulseOnOff):
    """Thruster pulsing with a Schmitt trigger (docs/fsw/thr_pulse_schmitt.md)"""
    level_on: float  # [-] duty level that switches on, <= 1
    level_off: float  # [-] duty level that switches off, < level_on

class TrqLpf(_Algorithm):
    """Control-torque low-pass filter, first-order Tustin (docs/fsw/trq_lpf.md)"""
    h: float  # [s] assumed call period
    omega_c: float  # [rad/s] cut-off


class AcsMode(IntEnum):
    SUN_SAFE = 0
    INERTIAL = 1
    DETUMBLE = 2
    NADIR = 3

class AcsActuation(IntEnum):
    WHEELS = 0
    THRUSTERS = 1

class AcsPolicy(IntEnum):
    NONE = 0
    THRUSTERS = 1
    MAGNETORQUERS = 2

class Acs:
    """The flight application fsw_acs as a whole; config fields named 'module.field'"""
    fields: ClassVar[List[str]]
    def __init__(self, **config: Any) -> None: ...
    @staticmethod
    def from_scenario(scenario: Any) -> Acs: ...  # kestrel.Scenario
    def get(self, name: str) -> _Out: ...
    def set(self, name: str, value: npt.ArrayLike) -> None: ...
    def set_geometry(self, **geometry: npt.ArrayLike) -> None: ...
    def check(self) -> Status: ...
    def init(self) -> Status: ...
    def reset(self) -> None: ...
    def cycle(self, cmd: Optional[Mapping[str, npt.ArrayLike]] = None,
              **sensors: npt.ArrayLike) -> Tuple[Status, Dict[str, _Out], Dict[str, _Out]]: ...
    @property
    def initialized(self) -> bool: ...
    @property
    def config(self) -> Dict[str, _Out]: ...
