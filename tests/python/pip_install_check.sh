#!/usr/bin/env bash
# The package as a user installs it: `pip install .` of the repository into a fresh venv (Debian's NumPy and
# pybind11 through --system-site-packages; no index: nothing is downloaded), then a solve through the installed
# package equals the CLI's answer to the same request, timing fields aside.
#   pip_install_check.sh REPOSITORY PYTHON CLI
set -euo pipefail
repo=$1 python=$2 cli=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$python" -m venv --system-site-packages "$dir/venv"
# pip builds in the tree: setup.py's CMake build in build/pip, kept between runs like build/.
(cd "$repo" && "$dir/venv/bin/pip" install --no-build-isolation --no-index --quiet .)
cd "$dir"  # away from the repository's python/ folder: the installed package is the one imported
"$dir/venv/bin/python" - "$cli" <<'PY'
import json, subprocess, sys
import numpy as np
import lienewton
assert lienewton.__file__.startswith(sys.prefix), lienewton.__file__
request = lienewton.request_json(n=5, h=2, method="newton-group", differential="exact")
cli = json.loads(subprocess.run([sys.argv[1], "solve"], input=request, capture_output=True, text=True,
                                check=True).stdout)
r = lienewton.solve(json.loads(request))
assert isinstance(r.y, np.ndarray) and r.y.shape == (5, 5), r.y
assert r.y.tolist() == cli["y"] and r.status == cli["status"] and r.reason == cli["reason"], (r.status, cli["status"])
assert [t.residual for t in r.trace] == [t["residual"] for t in cli["trace"]]
print("installed lienewton", lienewton.__version__, "solve:", r.status, "same as the CLI")
PY
