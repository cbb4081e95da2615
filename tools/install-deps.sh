#!/usr/bin/env bash
# Installs the Debian packages narrows needs to build, test and plot (only those missing).
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  openmpi-bin libopenmpi-dev libhdf5-openmpi-dev hdf5-tools
  libeigen3-dev libfftw3-dev libtoml11-dev libcli11-dev librandom123-dev
  nlohmann-json3-dev
  libgtest-dev googletest libcgal-dev
  python3 python3-numpy python3-h5py python3-matplotlib python3-scipy
  clang-format
)

missing=()
for pkg in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  if [[ "$status" != "install ok installed" ]]; then
    missing+=("$pkg")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all present"
else
  echo "install-deps: installing ${missing[*]}"
  sudo=()
  if ((EUID != 0)); then
    if command -v sudo >/dev/null 2>&1; then
      sudo=(sudo)
    else
      echo "install-deps: not root and no sudo; install as root: ${missing[*]}" >&2
      exit 1
    fi
  fi
  "${sudo[@]}" apt-get update
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y --no-install-recommends "${missing[@]}"
fi

# The tools in this directory run under the system interpreter, not a pyenv/venv one.
if ! /usr/bin/python3 -c 'import numpy, h5py, matplotlib'; then
  echo "install-deps: /usr/bin/python3 cannot import numpy, h5py and matplotlib" >&2
  exit 1
fi
