"""`pip install .` builds the Python package lienewton (python/lienewton) with the repository's CMake: core, the JSON
codec and the pybind11 module only (LIENEWTON_PYTHON_ONLY), Release, tuned for this CPU like the CLI (extra
CMake arguments: LIENEWTON_CMAKE_ARGS; LIENEWTON_CMAKE_BUILD_DIR: a configured build tree of this repository whose
_lienewton target is built and installed instead, as the test suite does with its own). Debian 12: python3-dev python3-numpy python3-pybind11 python3-venv cmake
(scripts/deps.sh build), then in a venv made with --system-site-packages:
    pip install --no-build-isolation --no-index .
"""
import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        given = os.environ.get("LIENEWTON_CMAKE_BUILD_DIR")
        build_dir = Path(given).resolve() if given else Path(self.build_temp).resolve() / "cmake"
        if not given:
            configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                         "-DLIENEWTON_PYTHON_ONLY=ON", f"-DPython3_EXECUTABLE={sys.executable}",
                         *shlex.split(os.environ.get("LIENEWTON_CMAKE_ARGS", ""))]
            subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "_lienewton", "-j", str(os.cpu_count() or 1)],
                       check=True)
        built = sorted((build_dir / "python" / "lienewton").glob("_lienewton*.so"))
        if not built:
            raise RuntimeError(f"CMake built no _lienewton module in {build_dir}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], target)


def version():
    for line in (ROOT / "CMakeLists.txt").read_text().splitlines():
        if line.startswith("project(lienewton VERSION"):
            return line.split()[2]
    raise RuntimeError("no version in CMakeLists.txt")


setup(
    name="lienewton",
    version=version(),
    description="Newton's method for nonlinear equations on Lie groups (Owren & Welfert), from Python",
    packages=["lienewton"],
    package_dir={"": "python"},
    ext_modules=[Extension("lienewton._lienewton", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    install_requires=["numpy"],
    python_requires=">=3.9",
    # Beside the CMake build tree, not in it: build/pip/temp.../cmake keeps its objects between installs.
    options={"build": {"build_base": "build/pip"}},
    zip_safe=False,
)
