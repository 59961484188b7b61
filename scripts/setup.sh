#!/usr/bin/env bash
# Installs what yarok needs besides Rust, once per machine; does nothing when all is present.
#  - EGL and Mesa (llvmpipe) for headless rendering, from Debian's packages;
#  - procps (`kill`, used by the Ctrl-C test);
#  - pip, with which the first build fetches MuJoCo 4.0.1 from PyPI (see yarok-mjc/build.rs).
set -euo pipefail

packages=(libegl1 libegl-mesa0 libgl1-mesa-dri procps)
missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done
if ((${#missing[@]})); then
  if ! command -v apt-get >/dev/null; then
    echo "error: install the EGL and Mesa libraries (${missing[*]} on Debian) with your package manager" >&2
    exit 1
  fi
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  echo "setup: installing ${missing[*]}"
  $sudo apt-get update -qq
  $sudo DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

if [ -z "${MUJOCO_DIR:-}" ] && ! python3 -m pip --version >/dev/null 2>&1; then
  echo "error: yarok fetches MuJoCo with pip: install it (Debian: apt-get install python3-pip)," >&2
  echo "       or set MUJOCO_DIR to a MuJoCo 4.0.1 folder holding lib/libmujoco.so.4.0.1" >&2
  exit 1
fi
