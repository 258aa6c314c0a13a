"""Kestrel: scenarios, closed-loop runs, Monte Carlo campaigns and the FSW
algorithms (docs/python.md).

The compiled part is the extension ``kestrel._kestrel`` (pybind11 over the
C++ harness); this package re-exports its names, so ``kestrel.run``,
``kestrel.Scenario``, ``kestrel.fsw`` ... are the extension's objects, and
adds :meth:`Results.to_pandas` (``kestrel._pandas``, pandas imported only
when called).
"""
import sys as _sys

from . import _kestrel
from ._kestrel import *  # noqa: F401,F403  (the extension's public names)
from ._kestrel import __version__, fsw  # noqa: F401
from ._pandas import to_pandas as _to_pandas
from ._run_set import run_set as _run_set

# `import kestrel.fsw` / `from kestrel.fsw import MrpFb`
_sys.modules[__name__ + ".fsw"] = fsw

_kestrel.Results.to_pandas = _to_pandas
_kestrel.Run.set = _run_set

__all__ = [n for n in dir(_kestrel) if not n.startswith("_")]


def _rename(module, public):
    # the extension's classes, exceptions and functions as kestrel.X and
    # kestrel.fsw.X (their repr, help() and pickling names), not kestrel._kestrel.X
    fsw.__name__ = public + ".fsw"
    for m, name in ((module, public), (fsw, public + ".fsw")):
        for n in dir(m):
            o = getattr(m, n)
            if getattr(o, "__module__", None) in (module.__name__, module.__name__ + ".fsw"):
                try:
                    o.__module__ = name
                except (AttributeError, TypeError):
                    pass


_rename(_kestrel, __name__)
del _rename
__doc__ = _kestrel.__doc__ or __doc__
