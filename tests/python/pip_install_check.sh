#!/usr/bin/env bash
# The package as a user installs it: `pip install --no-index .` of the repository into a fresh venv, with build
# isolation (the in-tree backend asks for no build packages, so an empty isolated environment builds it; nothing is
# downloaded), then a solve through the installed package equals the CLI's answer to the same request, timing
# fields aside. Debian's Python (NumPy through --system-site-packages), then, when PATH has another python3 (pyenv's,
# whose setuptools has no bdist_wheel), that one too: it lacks NumPy, so it installs with --no-deps and imports
# Debian's NumPy where both are the same minor version (else it checks the installed files only).
#   pip_install_check.sh REPOSITORY PYTHON CLI
set -euo pipefail
repo=$1 python=$2 cli=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

check_solve() {  # check_solve VENV_PYTHON [PYTHONPATH]
  (cd "$dir" && PYTHONPATH=${2:-} "$1" - "$cli" <<'PY'
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
assert lienewton.SO3.exp(np.zeros(3)).log().tolist() == [0.0, 0.0, 0.0]
print("installed lienewton", lienewton.__version__, "for", sys.version.split()[0], "solve:", r.status,
      "same as the CLI")
PY
  )  # away from the repository's python/ folder: the installed package is the one imported
}

"$python" -m venv --system-site-packages "$dir/debian"
(cd "$repo" && "$dir/debian/bin/pip" install --no-index --quiet .)
check_solve "$dir/debian/bin/python"

other=$(command -v python3 || true)
if [[ -n "$other" && "$(realpath "$other")" != "$(realpath "$python")" ]] && "$other" -m venv "$dir/other" 2>/dev/null; then
  (cd "$repo" && "$dir/other/bin/pip" install --no-index --no-deps --quiet .)
  version() { "$1" -c 'import sys; print(sys.version_info[:2])'; }
  if "$dir/other/bin/python" -c 'import numpy' 2>/dev/null; then
    check_solve "$dir/other/bin/python"
  elif [[ "$(version "$other")" == "$(version "$python")" ]]; then
    check_solve "$dir/other/bin/python" "$("$python" -c 'import numpy, os; print(os.path.dirname(os.path.dirname(numpy.__file__)))')"
  else
    "$dir/other/bin/python" -m pip show -f lienewton | grep -q "_lienewton" && echo "installed lienewton for $other (no NumPy to import it with)"
  fi
fi
