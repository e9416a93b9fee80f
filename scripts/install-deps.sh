#!/usr/bin/env bash
# Installs the Debian packages plumage builds and runs with, only those that are missing, and
# says which. Needs root (or sudo) only when something is missing.
set -euo pipefail

packages=(
  cmake g++ make pkg-config python3
  libeigen3-dev libfftw3-dev libboost-dev libboost-filesystem-dev libyaml-cpp-dev
  libceres-dev libopenexr-dev libembree-dev catch2 libtbb-dev libcli11-dev
  libopenmpi-dev libpng-dev libstb-dev python3-matplotlib
  pybind11-dev python3-dev python3-numpy python3-pytest   # the Python package (python/)
  libflint-arb-dev libflint-dev   # Arb: rigorous reference for the BEM's Hankel functions (tests)
  clang libclang-rt-14-dev       # libFuzzer + ASan/UBSan for the fuzz harnesses (fuzz/, make fuzz)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "deps: all ${#packages[@]} required Debian packages are installed"
  exit 0
fi

echo "deps: installing missing Debian packages: ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null; then sudo_cmd=(sudo); else
    echo "deps: not root and no sudo; install these packages first: ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "deps: done"
