# Type stub of kestrel.fsw (thin bindings of single fsw_c algorithms, written
# by hand; test/python/test_package.py checks its names against the module's).
# Config fields are attributes: scalars as float/int, arrays as NumPy.
from typing import Any, ClassVar, Dict, List, Tuple

import numpy as np
import numpy.typing as npt

OK: int
E_NULL_ARG: int
E_CONFIG: int
E_CAPACITY: int
E_SINGULAR: int
E_BAD_INPUT: int
E_TIME: int
E_UNSUPPORTED: int
E_NOT_INIT: int
W_SINGULAR: int
W_SAT: int
W_RATE: int
MAX_RW: int
REAL_IS_FLOAT: bool

def status_name(status: int) -> str: ...

class _Algorithm:
    inputs: ClassVar[List[str]]
    outputs: ClassVar[List[str]]
    def __init__(self, **config: Any) -> None: ...
    def check(self) -> int: ...
    def init(self) -> int: ...
    def reset(self) -> None: ...
    def update(self, **inputs: Any) -> Tuple[int, Dict[str, npt.NDArray[np.float64]]]: ...
    @property
    def config(self) -> Dict[str, Any]: ...
    @property
    def state(self) -> Dict[str, Any]: ...

class MrpFb(_Algorithm):
    K: float
    P: float
    K_i: float
    integral_limit: float
    control_law_type: int
    I_B: npt.NDArray[np.float64]
    known_torque_B: npt.NDArray[np.float64]
    num_rw: int
    gs_hat_B: npt.NDArray[np.float64]
    J_s: npt.NDArray[np.float64]

class RwMap(_Algorithm):
    mode: int
    num_rw: int
    gs_hat_B: npt.NDArray[np.float64]
    num_axes: int
    ctrl_axes_B: npt.NDArray[np.float64]
    eps_P: float

class RwSat(_Algorithm):
    mode: int
    num_rw: int
    u_max: npt.NDArray[np.float64]

class TrqLpf(_Algorithm):
    h: float
    omega_c: float

class AttTrack(_Algorithm):
    sigma_R0R: npt.NDArray[np.float64]
