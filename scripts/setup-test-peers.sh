#!/usr/bin/env bash
# Installs the third-party programs yarok's integration tests talk to, once per machine:
#  - ffmpeg (Debian's), which encodes the camera frames the decoders are checked against;
#  - OctoPrint's VirtualPrinter, a Marlin emulator, in a Python virtual environment of its own
#    (${YAROK_CACHE_DIR:-~/.cache/yarok}/peers). AGPL: the tests only run it as a separate
#    process, through scripts/peers/virtual_printer_bridge.py; nothing links or ships it.
set -euo pipefail

source "$(dirname "$0")/debian-packages.sh"
if ! command -v ffmpeg >/dev/null; then
  install_missing_packages "ffmpeg, for the camera tests" ffmpeg
fi

peers="${YAROK_CACHE_DIR:-$HOME/.cache/yarok}/peers"
if "$peers/bin/python" -c "import octoprint.plugins.virtual_printer" 2>/dev/null; then
  exit 0
fi
if ! python3 -c "import ensurepip" 2>/dev/null; then
  install_missing_packages "Python's venv module, for the printer emulator" python3-venv
fi
echo "setup: installing OctoPrint 1.11.8 (its VirtualPrinter) into $peers"
python3 -m venv "$peers"
"$peers/bin/pip" install -q --disable-pip-version-check "octoprint==1.11.8"
