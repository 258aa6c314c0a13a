"""`pip install .` of the source tree into a virtual environment, offline
(docs/python.md, "Install"): --no-index --no-build-isolation with Debian's
setuptools and wheel, the venv made with --system-site-packages so that
Debian's NumPy and pandas are seen.  The module is the one this CMake tree
built (KESTREL_PREBUILT_DIR=KESTREL_BUILD_TREE: setup.py packages it instead
of compiling it again; the from-scratch build's time is in docs/python.md).
The package's files are copied to a temporary folder first (the CMake
sources are not needed to package a built module).  Then, from outside the
source tree: import kestrel from the venv, a 5 s S1
run, to_pandas(), the installed files and the declared dependencies.

Environment (ctest): KESTREL_SOURCE_DIR, KESTREL_BUILD_TREE.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

SRC = os.path.abspath(os.environ.get("KESTREL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")))
TREE = os.environ.get("KESTREL_BUILD_TREE", os.path.join(SRC, "build", "host-release"))

CHECK = r"""
import json, os, sys, importlib.metadata as md
import kestrel
sc = kestrel.Scenario.load(sys.argv[1], {"duration": 5.0})
res = kestrel.run(sc)
df = res.to_pandas()
pkg = os.path.dirname(kestrel.__file__)
print(json.dumps({
    "file": kestrel.__file__, "version": kestrel.__version__, "rows": len(df), "t_last": float(df.index[-1]),
    "omega_x0": float(df["omega_BN_B_x"].iloc[0]), "omega_x0_res": float(res["truth/omega_BN_B"][0, 0]),
    "unit": df.attrs["units"]["omega_BN_B_x"], "files": sorted(os.listdir(pkg)),
    "requires": md.requires("kestrel"), "dist_version": md.version("kestrel")}))
"""


def package_source(tmp):
    """The package's files of the source tree copied to tmp/src: with
    KESTREL_PREBUILT_DIR the build needs no CMake sources, and setuptools'
    in-tree files (build/, kestrel.egg-info) stay out of the source tree."""
    dst = os.path.join(tmp, "src")
    for f in ("pyproject.toml", "setup.py", "MANIFEST.in", "README.md"):
        os.makedirs(dst, exist_ok=True)
        shutil.copy(os.path.join(SRC, f), dst)
    shutil.copytree(os.path.join(SRC, "python", "kestrel"), os.path.join(dst, "python", "kestrel"),
                    ignore=shutil.ignore_patterns("__pycache__"))
    return dst


def have_tools():
    try:
        import setuptools  # noqa: F401
        import wheel  # noqa: F401
        import venv  # noqa: F401
        import pandas  # noqa: F401
    except ImportError:
        return False
    return True


@unittest.skipUnless(have_tools(), "python3-setuptools, python3-wheel, python3-venv, python3-pandas "
                     "(scripts/install-deps.sh host)")
class PipInstallTest(unittest.TestCase):
    def test_pip_install_into_venv_offline(self):
        with tempfile.TemporaryDirectory() as tmp:
            venv = os.path.join(tmp, "venv")
            # Debian's pip drives the venv's interpreter (--python): no copy of pip in the venv
            subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", venv],
                           check=True, timeout=120)
            py = os.path.join(venv, "bin", "python")
            pip = [sys.executable, "-m", "pip", "--python", py]
            env = dict(os.environ, KESTREL_PREBUILT_DIR=TREE, PIP_NO_INDEX="1", PIP_DISABLE_PIP_VERSION_CHECK="1")
            env.pop("PYTHONPATH", None)  # the venv's kestrel, not the build tree's
            p = subprocess.run(pip + ["install", "--no-index", "--no-build-isolation", package_source(tmp)],
                               env=env, capture_output=True, text=True, timeout=240, cwd=tmp)
            self.assertEqual(p.returncode, 0, p.stdout[-3000:] + p.stderr[-3000:])
            p = subprocess.run([py, "-c", CHECK, os.path.join(SRC, "scenarios", "s1_sun_pointing.yaml")],
                               env=env, capture_output=True, text=True, timeout=120, cwd=tmp)
            self.assertEqual(p.returncode, 0, p.stderr[-3000:])
            r = json.loads(p.stdout)
            self.assertTrue(r["file"].startswith(venv), r["file"])  # installed, not the source or build tree
            self.assertEqual(r["rows"], 51)  # 5 s at 10 Hz, t = 0 .. 5
            self.assertEqual(r["t_last"], 5.0)
            self.assertEqual(r["omega_x0"], r["omega_x0_res"])
            self.assertEqual(r["omega_x0"], 0.001)  # scenarios/s1_sun_pointing.yaml: initial omega_BN_B
            self.assertEqual(r["unit"], "rad/s")
            for f in ("__init__.py", "_pandas.py", "__init__.pyi", "fsw.pyi", "py.typed"):
                self.assertIn(f, r["files"])
            self.assertTrue(any(f.startswith("_kestrel.") and f.endswith(".so") for f in r["files"]), r["files"])
            self.assertIn("numpy", r["requires"])
            self.assertTrue(any(q.startswith("pandas") and q.replace('"', "'").endswith("extra == 'pandas'")
                                for q in r["requires"]),
                            r["requires"])
            self.assertEqual(r["dist_version"], r["version"])
            p = subprocess.run(pip + ["uninstall", "-y", "kestrel"], env=env, capture_output=True,
                               text=True, timeout=120)
            self.assertEqual(p.returncode, 0, p.stderr)

    def test_prebuilt_dir_without_module_is_refused(self):
        # KESTREL_PREBUILT_DIR at a folder with no module: a clear error, nothing built
        with tempfile.TemporaryDirectory() as tmp:
            src = package_source(tmp)
            env = dict(os.environ, KESTREL_PREBUILT_DIR=tmp)
            lib = os.path.join(tmp, "lib")
            p = subprocess.run([sys.executable, "setup.py", "-q", "build_ext", "--build-lib", lib,
                                "--build-temp", os.path.join(tmp, "temp")], env=env, capture_output=True,
                               text=True, timeout=240, cwd=src)
            self.assertNotEqual(p.returncode, 0)
            self.assertIn("no _kestrel", p.stdout + p.stderr)
            self.assertIn(tmp, p.stdout + p.stderr)
            self.assertFalse(os.path.isdir(os.path.join(lib, "kestrel")) and os.listdir(os.path.join(lib, "kestrel")))


if __name__ == "__main__":
    unittest.main()
