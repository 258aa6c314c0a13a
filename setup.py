"""Builds the extension kestrel._kestrel with CMake for `pip install .` and
`python3 -m build` (metadata in pyproject.toml; docs/python.md, "Install").

A dedicated CMake tree (setuptools' build_temp/cmake, or KESTREL_BUILD_DIR)
configured with the tests, benchmarks, fuzzing, processor-in-the-loop and
install rules off; only the target kestrel_python and the libraries it links
are built.  Environment:
  KESTREL_PREBUILT_DIR  a configured and built CMake tree (build/host-release):
                        its module is packaged, nothing is compiled
  KESTREL_BUILD_DIR     the CMake tree to (re)use instead of build_temp/cmake
  KESTREL_REPORT_BUNDLE ON: the interactive HTML report (npm ci, esbuild);
                        default OFF: the data-only page, no download
  KESTREL_CMAKE_ARGS    more CMake arguments (split on spaces)
  CMAKE_BUILD_PARALLEL_LEVEL, CMAKE_C(XX)_COMPILER_LAUNCHER (e.g. ccache): CMake's own
"""
import os
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def cmake_configure_args(build_dir):
    """The lean configure of the module: everything it does not link is off."""
    args = ["cmake", "-S", ROOT, "-B", build_dir,
            "-DCMAKE_BUILD_TYPE=Release",
            "-DKESTREL_BUILD_PYTHON=ON",
            "-DKESTREL_PYTHON_EXECUTABLE=" + sys.executable,
            "-DKESTREL_BUILD_TESTS=OFF", "-DKESTREL_BUILD_BENCHMARKS=OFF", "-DKESTREL_BUILD_FUZZ=OFF",
            "-DKESTREL_BUILD_PIL=OFF", "-DKESTREL_BUILD_FSW_M4F=OFF", "-DKESTREL_BUILD_M4F_TIMING=OFF",
            "-DKESTREL_INSTALL=OFF",
            "-DKESTREL_REPORT_BUNDLE=" + os.environ.get("KESTREL_REPORT_BUNDLE", "OFF")]
    if shutil.which("ninja"):
        args += ["-G", "Ninja"]
    return args + os.environ.get("KESTREL_CMAKE_ARGS", "").split()


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        name = "_kestrel" + sysconfig.get_config_var("EXT_SUFFIX")
        prebuilt = os.environ.get("KESTREL_PREBUILT_DIR")
        if prebuilt:
            tree = os.path.abspath(prebuilt)
        else:
            tree = os.path.abspath(os.environ.get("KESTREL_BUILD_DIR") or os.path.join(self.build_temp, "cmake"))
            if not os.path.exists(os.path.join(tree, "CMakeCache.txt")):
                subprocess.check_call(cmake_configure_args(tree))
            jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
            subprocess.check_call(["cmake", "--build", tree, "--target", "kestrel_python", "--parallel", jobs])
        built = os.path.join(tree, "python", "kestrel", name)
        if not os.path.exists(built):
            raise RuntimeError("kestrel: no %s in %s (a CMake tree with the target kestrel_python built for "
                               "this interpreter)" % (name, tree))
        dest = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(dest), exist_ok=True)
        shutil.copyfile(built, dest)


setup(packages=["kestrel"], package_dir={"kestrel": "python/kestrel"},
      package_data={"kestrel": ["py.typed", "*.pyi"]}, include_package_data=False,
      ext_modules=[Extension("kestrel._kestrel", sources=[])], cmdclass={"build_ext": CMakeBuild})
