"""The build step of pyproject.toml: the extension pounding._pounding is built by this project's
CMake (target _pounding) and copied into the wheel; everything else is declared in pyproject.toml.

Without options a Release tree without tests or benchmarks is configured and built under
setuptools' build folder (CMAKE_BUILD_PARALLEL_LEVEL sets the jobs). POUNDING_BUILD_DIR=DIR instead
packages the module a CMake tree has already built (`cmake --build DIR --target _pounding`), as
is: CTest's python_install does so with build/, so that CI compiles the C++ once.
"""

import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def require(module, package, why):
    """Stops with a message naming what is missing, instead of setuptools' own
    (`invalid command 'bdist_wheel'` without `wheel`)."""
    try:
        __import__(module)
    except ImportError:
        sys.exit(f"setup.py: Python {sys.version.split()[0]} ({sys.executable}) has no `{module}`, which {why}. "
                 f"On Debian: apt-get install {package}, and make the virtual environment with "
                 "`/usr/bin/python3 -m venv --system-site-packages DIR` so that it sees Debian's packages "
                 "(README, Installing).")


if any(command in sys.argv for command in ("bdist_wheel", "dist_info", "install", "develop", "editable_wheel")):
    require("wheel", "python3-wheel", "pip needs to build the package's wheel")
    require("numpy", "python3-numpy", "the module `pounding` needs (its results are numpy arrays)")


def version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(pounding VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, extension):
        given = os.environ.get("POUNDING_BUILD_DIR")
        build_dir = pathlib.Path(given).resolve() if given else pathlib.Path(self.build_temp).resolve() / "cmake"
        if not given:
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                            "-DPOUNDING_BUILD_TESTS=OFF", "-DPOUNDING_BUILD_BENCHMARKS=OFF",
                            "-DPOUNDING_BUILD_PYTHON=ON", f"-DPython_EXECUTABLE={sys.executable}"], check=True)
            jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
            subprocess.run(["cmake", "--build", str(build_dir), "--target", "_pounding", "-j", jobs], check=True)
        built = sorted((build_dir / "python" / "pounding").glob(f"_pounding{sysconfig.get_config_var('EXT_SUFFIX')}"))
        if len(built) != 1:
            sys.exit(f"setup.py: no module _pounding for Python {sys.version.split()[0]} in "
                     f"{build_dir}/python/pounding (cmake --build {build_dir} --target _pounding)")
        target = pathlib.Path(self.get_ext_fullpath(extension.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], target)


setup(version=version(),
      ext_modules=[Extension("pounding._pounding", sources=[])],
      cmdclass={"build_ext": CMakeBuild},
      # setuptools' own folder inside CMake's build/ (ignored by git), not beside it
      options={"build": {"build_base": "build/setuptools"}})
