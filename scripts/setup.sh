#!/usr/bin/env bash
# Installs what yarok needs besides Rust, once per machine; does nothing when all is present.
#  - EGL and Mesa (llvmpipe) for headless rendering, from Debian's packages;
#  - procps (`kill`, used by the Ctrl-C test);
#  - ffmpeg, which the demo's film (`--video`) is encoded with;
#  - pip, with which the first build fetches MuJoCo 4.0.1 from PyPI (see yarok-mjc/build.rs).
set -euo pipefail

source "$(dirname "$0")/debian-packages.sh"
install_missing_packages "the EGL and Mesa libraries" libegl1 libegl-mesa0 libgl1-mesa-dri procps
install_missing_packages "ffmpeg, for the demo's film" ffmpeg

if [ -z "${MUJOCO_DIR:-}" ] && ! python3 -m pip --version >/dev/null 2>&1; then
  echo "error: yarok fetches MuJoCo with pip: install it (Debian: apt-get install python3-pip)," >&2
  echo "       or set MUJOCO_DIR to a MuJoCo 4.0.1 folder holding lib/libmujoco.so.4.0.1" >&2
  exit 1
fi
