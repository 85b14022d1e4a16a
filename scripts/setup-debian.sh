#!/usr/bin/env bash
# Installs everything DriftLab needs to build, run and test on Debian 12 (bookworm).
# Idempotent: when every package is already installed it changes nothing and needs no
# network; otherwise it runs `apt-get update` and installs the missing ones (as root,
# or through sudo).
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  qtbase5-dev libqt5sql5-sqlite libqt5svg5-dev libqt5opengl5-dev
  libqt5datavisualization5-dev libqt5serialport5-dev libqt5serialbus5-dev
  libqwt-qt5-dev libeigen3-dev libopencv-dev libsqlite3-dev
  libceres-dev libnlopt-cxx-dev libzip-dev zlib1g-dev libmodbus-dev qt5-image-formats-plugins
  xvfb xauth fonts-dejavu-core sqlite3 python3 socat ccache poppler-utils clang libclang-rt-14-dev
  linuxcnc-uspace postgresql libqt5sql5-psql libpq-dev libssl-dev
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup-debian: all ${#PACKAGES[@]} packages are installed" >&2
  exit 0
fi

SUDO=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup-debian: run as root or install sudo" >&2; exit 1; }
  SUDO=(sudo)
fi
echo "setup-debian: installing ${missing[*]}" >&2
"${SUDO[@]}" apt-get update
DEBIAN_FRONTEND=noninteractive "${SUDO[@]}" apt-get install -y --no-install-recommends "${PACKAGES[@]}"
