"""The package kestrel (docs/python.md, "Install" and "Results as pandas"):
Results.to_pandas() against the Results' own arrays, the type stubs against
the module's names, the package's files.

Environment (ctest): PYTHONPATH at the build's python/ folder,
KESTREL_SOURCE_DIR.
"""
import ast
import enum
import os
import unittest

import numpy as np

import kestrel
import kestrel.fsw as fsw

SRC = os.environ.get("KESTREL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
S1 = os.path.join(SRC, "scenarios", "s1_sun_pointing.yaml")
PKG = os.path.join(SRC, "python", "kestrel")

try:
    import pandas as pd
except ImportError:  # python3-pandas: scripts/install-deps.sh host
    pd = None


@unittest.skipIf(pd is None, "python3-pandas not installed (scripts/install-deps.sh host)")
class ToPandasTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # 3 s of S1: 31 rows at 10 Hz
        cls.res = kestrel.run(kestrel.Scenario.load(S1, {"duration": 3.0}))
        cls.df = cls.res.to_pandas()

    def test_index_is_time(self):
        self.assertEqual(self.df.index.name, "t")
        self.assertEqual(len(self.df), 31)
        np.testing.assert_array_equal(self.df.index.to_numpy(), self.res.t)
        self.assertEqual(self.df.index[10], 1.0)  # 10 Hz rows: t = k / 10 s
        self.assertEqual(self.df.attrs["units"]["t"], "s")

    def test_columns_are_the_flat_columns_values_bit_equal(self):
        cols = self.res.columns
        self.assertEqual(cols[0], "t")
        self.assertEqual(list(self.df.columns), cols[1:])
        self.assertEqual(len(set(self.df.columns)), len(self.df.columns), "unique names")
        np.testing.assert_array_equal(self.df.to_numpy(), self.res.data[:, 1:])
        for c in ("omega_BN_B_x", "meas_omega_BN_B_z", "q_BN_0", "pointing_error_deg"):
            np.testing.assert_array_equal(self.df[c].to_numpy(), self.res.column(c))

    def test_vectors_split_and_units(self):
        # the truth's and the measured rate: two quantities, six distinct columns
        np.testing.assert_array_equal(self.df[["omega_BN_B_x", "omega_BN_B_y", "omega_BN_B_z"]].to_numpy(),
                                      self.res["truth/omega_BN_B"])
        np.testing.assert_array_equal(self.df[["meas_omega_BN_B_x", "meas_omega_BN_B_y", "meas_omega_BN_B_z"]]
                                      .to_numpy(), self.res["fsw_sensors/omega_BN_B"])
        u, q = self.df.attrs["units"], self.df.attrs["quantities"]
        self.assertEqual(u["omega_BN_B_x"], "rad/s")
        self.assertEqual(u["pointing_error_deg"], "deg")
        self.assertEqual(q["omega_BN_B_y"], "truth/omega_BN_B")
        self.assertEqual(q["meas_omega_BN_B_y"], "fsw_sensors/omega_BN_B")
        self.assertEqual(self.df.attrs["frames"]["omega_BN_B_x"], "B")
        for c in self.df.columns:
            self.assertEqual(u[c], self.res.units[c])

    def test_multiindex(self):
        dm = self.res.to_pandas(multiindex=True)
        self.assertEqual(list(dm.columns.names), ["quantity", "column", "unit"])
        np.testing.assert_array_equal(dm["truth/omega_BN_B"].to_numpy(), self.res["truth/omega_BN_B"])
        self.assertEqual(list(dm["truth/omega_BN_B"].columns.get_level_values("unit")), ["rad/s"] * 3)
        np.testing.assert_array_equal(dm.to_numpy(), self.df.to_numpy())

    def test_copy_and_stepped_run(self):
        df = self.res.to_pandas()
        df.iloc[0, 0] = -1.0
        self.assertNotEqual(self.res.data[0, 1], -1.0)  # the frame owns its values
        r = kestrel.Run(kestrel.Scenario.load(S1, {"duration": 3.0}))
        r.step(100)  # ticks 0..99 (dt 0.01 s), a row every 10th: t = 0.0 .. 0.9
        self.assertEqual(list(r.results().to_pandas().index), [k / 10 for k in range(10)])

    def test_documented_names_of_results(self):
        # docs/python.md, "Runs": the quantity names res[...] takes
        self.assertEqual(self.res["truth/omega_BN_B"].shape, (31, 3))
        with self.assertRaises(KeyError) as e:
            self.res["omega_BN_B"]  # two messages record it: the message says which
        self.assertIn("truth/omega_BN_B", str(e.exception))
        self.assertIn("fsw_sensors/omega_BN_B", str(e.exception))


def stub_names(path):
    """{name: set of member names or None} of a .pyi: module-level names, and
    for each public class the names its body (and its stub base classes) declare."""
    tree = ast.parse(open(path, encoding="utf-8").read(), path)
    classes, top = {}, {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            members = set()
            for b in node.body:
                if isinstance(b, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    members.add(b.name)
                elif isinstance(b, ast.AnnAssign) and isinstance(b.target, ast.Name):
                    members.add(b.target.id)
                elif isinstance(b, ast.Assign):  # an enum's member: OK = 0
                    members |= {t.id for t in b.targets if isinstance(t, ast.Name)}
            for base in node.bases:
                if isinstance(base, ast.Name) and base.id in classes:
                    members |= classes[base.id]
            classes[node.name] = members
            top[node.name] = members
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            top[node.name] = None
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            top[node.target.id] = None
        elif isinstance(node, ast.ImportFrom) and node.module is None:  # from . import fsw as fsw
            for a in node.names:
                top[a.asname or a.name] = None
    return {k: v for k, v in top.items() if not k.startswith("_") or k == "__version__"}


def stub_enum_values(path, name):
    """{member: value} of the stub's enum class `name` (its NAME = literal lines)."""
    tree = ast.parse(open(path, encoding="utf-8").read(), path)
    cls = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == name)
    return {t.id: ast.literal_eval(b.value) for b in cls.body if isinstance(b, ast.Assign)
            for t in b.targets if isinstance(t, ast.Name)}


def public(obj):
    return {n for n in dir(obj) if not n.startswith("_")}


class StubTest(unittest.TestCase):
    """The hand-written stubs name what the module has, no more, no less."""

    def check(self, module, stub):
        names = stub_names(os.path.join(PKG, stub))
        have = public(module) | {"__version__"} if hasattr(module, "__version__") else public(module)
        self.assertEqual(set(names), have, "%s: names of the stub vs the module" % stub)
        for n, members in names.items():
            obj = getattr(module, n)
            if members is None or not isinstance(obj, type) or issubclass(obj, BaseException):
                continue
            if issubclass(obj, enum.Enum):  # its members and their values (int's methods are int's)
                self.assertEqual(stub_enum_values(os.path.join(PKG, stub), n),
                                 {k: v.value for k, v in obj.__members__.items()}, "%s: enum %s" % (stub, n))
                continue
            base = public(object)
            want = {m for m in members if not m.startswith("_")}
            self.assertEqual(want, public(obj) - base, "%s: members of class %s" % (stub, n))
            for dunder in ("__getitem__", "__contains__", "__len__"):
                self.assertEqual(dunder in members, dunder in vars(obj), "%s: %s.%s" % (stub, n, dunder))

    def test_package_stub(self):
        self.check(kestrel, "__init__.pyi")

    def test_fsw_stub(self):
        self.check(fsw, "fsw.pyi")

    def test_stub_parser_finds_a_difference(self):
        # the comparison can fail: a stub class that declares a member too many
        import tempfile
        with tempfile.NamedTemporaryFile("w", suffix=".pyi", delete=False) as f:
            f.write("class _B:\n    def check(self) -> int: ...\nclass A(_B):\n    x: int\n    def y(self) -> None: ...\n"
                    "def g() -> None: ...\nOK: int\nfrom . import fsw as fsw\nclass E:\n    A = 1\n")
        try:
            self.assertEqual(stub_names(f.name), {"A": {"check", "x", "y"}, "g": None, "OK": None, "fsw": None,
                                                   "E": {"A"}})
            self.assertEqual(stub_enum_values(f.name, "E"), {"A": 1})
        finally:
            os.unlink(f.name)


class PackageTest(unittest.TestCase):
    def test_layout_and_names(self):
        here = os.path.dirname(kestrel.__file__)
        for f in ("__init__.py", "_pandas.py", "__init__.pyi", "fsw.pyi", "py.typed"):
            self.assertTrue(os.path.isfile(os.path.join(here, f)), f)
        self.assertTrue(kestrel._kestrel.__file__.startswith(here))
        # the extension's objects under the package's names
        self.assertEqual(kestrel.Results.__module__, "kestrel")
        self.assertEqual(fsw.MrpFb.__module__, "kestrel.fsw")
        self.assertEqual(kestrel.ScenarioError.__module__, "kestrel")
        self.assertIs(kestrel.fsw, fsw)
        self.assertEqual(fsw.__name__, "kestrel.fsw")

    def test_version_is_the_projects(self):
        # pyproject.toml's version = CMake's project(VERSION) = kestrel.__version__
        import re
        with open(os.path.join(SRC, "pyproject.toml"), encoding="utf-8") as f:
            v = re.search(r'^version = "([^"]+)"', f.read(), re.M).group(1)
        with open(os.path.join(SRC, "CMakeLists.txt"), encoding="utf-8") as f:
            c = re.search(r"project\(kestrel VERSION (\S+)", f.read()).group(1)
        self.assertEqual(v, c)
        self.assertEqual(kestrel.__version__.split("+")[0].split("-")[0], v)


if __name__ == "__main__":
    unittest.main()
