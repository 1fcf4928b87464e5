"""The PEP 517 build backend of `pip install .` (pyproject.toml names it, backend-path python/): it builds the
module with the repository's CMake and writes the wheel itself, so it needs nothing from pip's index or from the
Python it runs under (no setuptools, no wheel package: a Python whose setuptools cannot `bdist_wheel` installs too).

CMake builds only what the module is made of (-DLIENEWTON_PYTHON_ONLY=ON: core, the JSON codec and the pybind11
module; no HTTP, GL, tests or benchmarks), Release, tuned for this CPU like the CLI, in build/pip/<python tag>/, which
is kept between installs: only the first install compiles everything. It says beforehand how many C++ files it
compiles and how long that takes, and afterwards how long it took. pybind11's CMake files come from the Python that
runs the build if it has them, else from the system (Debian: pybind11-dev).

Environment: LIENEWTON_CMAKE_ARGS (more CMake arguments, e.g. -DLIENEWTON_NATIVE=OFF for a portable build),
LIENEWTON_CMAKE_BUILD_DIR (a configured build tree of this repository whose _lienewton target is built and packed
instead; the test suite uses its own), LIENEWTON_BUILD_JOBS (parallel jobs; default: the CPUs).
"""
import base64
import hashlib
import io
import os
import re
import shlex
import subprocess
import sys
import sysconfig
import tarfile
import time
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
NAME = "lienewton"
# Compiling one of the core's C++ files at -O3 takes about this long on one core (measured, docs/python.md): the
# estimate printed before a build.
SECONDS_PER_FILE = 25.0


def _version():
    for line in (ROOT / "CMakeLists.txt").read_text().splitlines():
        if line.startswith("project(lienewton VERSION"):
            return line.split()[2]
    raise RuntimeError("no version in CMakeLists.txt")


def _metadata():
    return "\n".join([
        "Metadata-Version: 2.1",
        f"Name: {NAME}",
        f"Version: {_version()}",
        "Summary: Newton's method for nonlinear equations on Lie groups (Owren & Welfert), from Python",
        "Requires-Python: >=3.9",
        "Requires-Dist: numpy",
        "License: MIT",
        "",
    ])


def _tag():
    """cpXY-cpXY-<platform>: the module is built for this interpreter's ABI and this machine."""
    interpreter = "cp" if sys.implementation.name == "cpython" else sys.implementation.name
    version = f"{sys.version_info.major}{sys.version_info.minor}"
    platform = re.sub(r"[-.]", "_", sysconfig.get_platform())
    return f"{interpreter}{version}", f"{interpreter}{version}", platform


def _say(text):
    """A line for the person running pip: pip shows a backend's output only with -v, so it also goes to the
    terminal when there is one."""
    print(f"lienewton: {text}", file=sys.stderr, flush=True)
    if sys.stderr.isatty():
        return
    try:
        with open("/dev/tty", "w") as tty:
            tty.write(f"lienewton: {text}\n")
    except OSError:
        pass  # no terminal (CI, a test): stderr only


def _files_to_compile(build_dir):
    """How many C++ files `make` would compile for the module (a dry run), or None when the generator is not make.
    The dry run fails where it would link libraries it did not build (-k goes on), so its status says nothing."""
    if not (build_dir / "Makefile").exists():
        return None
    out = subprocess.run(["make", "-n", "-k", "-C", str(build_dir), "_lienewton"], capture_output=True, text=True)
    return len(set(re.findall(r"\s-c\s+(\S+\.cpp)\b", out.stdout)))


def _build_module():
    """Builds _lienewton with CMake and returns the path of the shared object."""
    given = os.environ.get("LIENEWTON_CMAKE_BUILD_DIR")
    tag = "-".join(_tag()[:1] + _tag()[2:])
    build_dir = Path(given).resolve() if given else ROOT / "build" / "pip" / tag
    jobs = int(os.environ.get("LIENEWTON_BUILD_JOBS") or os.cpu_count() or 1)
    if not given:
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                        "-DLIENEWTON_PYTHON_ONLY=ON", f"-DPython3_EXECUTABLE={sys.executable}",
                        *shlex.split(os.environ.get("LIENEWTON_CMAKE_ARGS", ""))],
                       check=True, stdout=sys.stderr)
    files = _files_to_compile(build_dir)
    if files:
        minutes = files * SECONDS_PER_FILE / min(jobs, files) / 60
        _say(f"compiling {files} C++ file{'s' if files > 1 else ''} of the core, the codec and the module with {jobs} "
             f"job{'s' if jobs > 1 else ''} in {build_dir}: about {max(1, round(minutes))} min, then linking with LTO "
             "(later installs reuse the objects)")
    elif files == 0:
        _say(f"the module is up to date in {build_dir}")
    started = time.monotonic()
    subprocess.run(["cmake", "--build", str(build_dir), "--target", "_lienewton", "-j", str(jobs)], check=True,
                   stdout=sys.stderr)
    if files:
        _say(f"compiled in {time.monotonic() - started:.0f} s")
    built = sorted((build_dir / "python" / NAME).glob("_lienewton*.so"))
    if not built:
        raise RuntimeError(f"CMake built no _lienewton module in {build_dir}")
    return built[0]


def _dist_info():
    return f"{NAME}-{_version()}.dist-info"


def _write_dist_info(directory):
    info = Path(directory) / _dist_info()
    info.mkdir(parents=True, exist_ok=True)
    (info / "METADATA").write_text(_metadata())
    return info.name


def _record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


# PEP 517 hooks

def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    return _write_dist_info(metadata_directory)


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    module = _build_module()
    python, abi, platform = _tag()
    wheel_name = f"{NAME}-{_version()}-{python}-{abi}-{platform}.whl"
    info = _dist_info()
    files = {f"{NAME}/{p.name}": p.read_bytes() for p in sorted((ROOT / "python" / NAME).glob("*.py"))}
    # The suffix this interpreter imports extension modules by (e.g. .cpython-311-x86_64-linux-gnu.so).
    files[f"{NAME}/_lienewton{sysconfig.get_config_var('EXT_SUFFIX')}"] = module.read_bytes()
    files[f"{info}/METADATA"] = _metadata().encode()
    files[f"{info}/WHEEL"] = "\n".join(["Wheel-Version: 1.0", "Generator: lienewton_build", "Root-Is-Purelib: false",
                                        f"Tag: {python}-{abi}-{platform}", ""]).encode()
    record = [_record_line(name, data) for name, data in files.items()] + [f"{info}/RECORD,,"]
    Path(wheel_directory).mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(Path(wheel_directory) / wheel_name, "w", zipfile.ZIP_DEFLATED) as wheel:
        for name, data in files.items():
            wheel.writestr(name, data)
        wheel.writestr(f"{info}/RECORD", "\n".join(record) + "\n")
    return wheel_name


def build_sdist(sdist_directory, config_settings=None):
    """The repository's tracked files (git ls-files) as NAME-VERSION.tar.gz."""
    listed = subprocess.run(["git", "-C", str(ROOT), "ls-files", "-z"], capture_output=True, check=True).stdout
    base = f"{NAME}-{_version()}"
    archive = f"{base}.tar.gz"
    with tarfile.open(Path(sdist_directory) / archive, "w:gz") as tar:
        for name in filter(None, listed.decode().split("\0")):
            if (ROOT / name).is_file():
                tar.add(ROOT / name, arcname=f"{base}/{name}")
        info = tarfile.TarInfo(f"{base}/PKG-INFO")
        data = _metadata().encode()
        info.size = len(data)
        tar.addfile(info, io.BytesIO(data))
    return archive
