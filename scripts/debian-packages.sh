# Sourced by the set-up scripts: `install_missing_packages WHAT PACKAGE...` installs the Debian
# packages among PACKAGE... that are not installed (with sudo when not root), or says to install
# WHAT with the system's package manager where there is no apt-get.

install_missing_packages() {
  local what="$1"
  shift
  local missing=()
  for package in "$@"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$package")
    fi
  done
  if ((${#missing[@]} == 0)); then
    return 0
  fi
  if ! command -v apt-get >/dev/null; then
    echo "error: install $what (${missing[*]} on Debian) with your package manager" >&2
    exit 1
  fi
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  echo "setup: installing ${missing[*]}"
  $sudo apt-get update -qq
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
}
