"""Run.set(path, value): a scenario key changed during a run (docs/python.md,
"Reaching into a run").

A key is settable during a run when an event action sets it to a value
(docs/events.md, "Scenario parameters settable during a run"). The value is
first set on a copy of the run's scenario, so it gets the checks and the
messages of ``--set`` and ``Scenario.set`` (``kestrel.ScenarioError`` naming
the key); then the action is added at this tick boundary like
``Run.apply_event``, so the run's manifest replays it.
"""
import re

_WHEEL = re.compile(r"^wheels(?:\[(\d+)\]|\.(\d+))\.(u_max|Omega_0|Omega_0_rpm)$")
_FSW_GAIN = {"fsw.mrp_fb.K": "gain_K", "fsw.mrp_fb.P": "gain_P"}
_STATE = {"spacecraft.initial.sigma_BN": "attitude", "spacecraft.initial.omega_BN_B": "omega"}
SETTABLE_KEYS = ("wheels[i].u_max", "wheels[i].Omega_0", "wheels[i].Omega_0_rpm", "fsw.mrp_fb.K", "fsw.mrp_fb.P",
                 "fsw.mode", "fsw.actuation", "fsw.inertial.sigma_R0N", "spacecraft.initial.sigma_BN",
                 "spacecraft.initial.omega_BN_B")


def run_set(run, path, value):
    """Sets a scenario key during the run, at this tick boundary.

    Settable keys: wheels[i].u_max [N m], wheels[i].Omega_0 [rad/s] (or
    Omega_0_rpm), fsw.mrp_fb.K, fsw.mrp_fb.P, fsw.mode, fsw.actuation,
    fsw.inertial.sigma_R0N, spacecraft.initial.sigma_BN and
    spacecraft.initial.omega_BN_B (the attitude and rate now). The value is
    checked as ``--set`` checks it (kestrel.ScenarioError with its message);
    another key raises ValueError naming the settable ones.
    """
    sc = run.scenario
    sc.set(path, value)  # --set's checks and messages; the run is untouched on error
    m = _WHEEL.match(path)
    if m:
        i = int(m.group(1) if m.group(1) is not None else m.group(2))
        name = sc.get("wheels[%d].name" % i)
        if m.group(3) == "u_max":
            run.apply_event(name, "torque_limit", float(sc.get("wheels[%d].u_max" % i)))
        else:
            run.apply_event(name, "speed", float(sc.get("wheels[%d].Omega_0" % i)))
    elif path in _FSW_GAIN:
        run.apply_event("fsw", _FSW_GAIN[path], float(sc.get(path)))
    elif path in ("fsw.mode", "fsw.actuation"):
        run.apply_event("fsw", path.split(".")[1] + "_" + str(sc.get(path)))
    elif path == "fsw.inertial.sigma_R0N":
        for axis, v in zip("xyz", sc.get(path)):
            run.apply_event("fsw", "reference_" + axis, float(v))
    elif path in _STATE:
        run.set_state(**{_STATE[path]: sc.get(path)})
    else:
        raise ValueError("Run.set: %s is not settable during a run; the settable keys: %s (every event action: "
                         "Run.settable(); every other key is set before the run)" % (path, ", ".join(SETTABLE_KEYS)))
