#!/usr/bin/env bash
# The Python environment yarok's Python package is tested in, once per machine: a venv in
# ${YAROK_CACHE_DIR:-~/.cache/yarok}/python with the build backend (maturin, MIT OR Apache-2.0),
# Gymnasium (MIT), pytest (MIT), mypy (MIT, which checks the extension's type stub) and
# auditwheel (MIT, which checks the wheel's libraries against the manylinux policy), pinned. `scripts/test.sh` then installs ./yarok-py into it.
set -euo pipefail

source "$(dirname "$0")/debian-packages.sh"
venv="${YAROK_CACHE_DIR:-$HOME/.cache/yarok}/python"
if [ ! -x "$venv/bin/python" ]; then
  if ! python3 -c "import ensurepip" 2>/dev/null; then
    install_missing_packages "Python's venv module, for the Python package's tests" python3-venv
  fi
  python3 -m venv "$venv"
fi
if ! "$venv/bin/python" -c "import maturin, gymnasium, pytest, mypy, auditwheel" 2>/dev/null; then
  echo "setup: installing maturin, gymnasium, pytest, mypy and auditwheel into $venv"
  "$venv/bin/pip" install -q --disable-pip-version-check "maturin==1.16.0" "gymnasium==1.2.2" \
    "pytest==8.4.2" "numpy==2.4.6" "mypy==2.4.1" "auditwheel==6.8.2"
fi
