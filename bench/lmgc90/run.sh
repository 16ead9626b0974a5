#!/usr/bin/env bash
# Side-by-side bench against LMGC90 (issue 26): the same cases in both codes on this
# machine, timed in alternation. Not part of the test suite: LMGC90 is not a dependency.
# docs/lmgc90.md says how to build LMGC90 here, what differs between the two models, and
# gives the table measured on this machine.
#
#   bash bench/lmgc90/run.sh LMGC90_BUILD_DIR [N=5] [CASES...]
#
# LMGC90_BUILD_DIR: the LMGC90 3.0.0rc1 build folder (the one holding pylmgc90/).
# N: rounds; each round runs each code once on each case (report: best and median).
# CASES (default: arch156_46 arch156_70 arch180_30 wall10):
#   arch156_<A in mm>  the seed paper's 156-degree arch (input/seed_156.nml) at 1.25 Hz
#   arch180_30         the 180-degree arch of bench/kernel_speed.sh (bench/arch_180_1hz.nml)
#   wall<N>            the running-bond wall N x N of bench/walls.sh
# Environment: LMGC90_PYTHON (default /usr/bin/python3: the Python pylmgc90 was built
# for), VOUSSOIR_BIN_DIR (default build/drivers), VOUSSOIR_PYTHON (default .venv/bin/python
# or python3: the Python with h5py that reads Voussoir's result files), BENCH_JSON (also write the table there).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
usage="usage: bash bench/lmgc90/run.sh LMGC90_BUILD_DIR [N=5] [CASES...]"
(($# >= 1)) || { echo "run.sh: no LMGC90 build folder given. $usage
This bench needs an LMGC90 build (docs/lmgc90.md says how to make one); without one
there is nothing to compare and nothing is run." >&2; exit 2; }
lmgc=$(cd "$1" 2>/dev/null && pwd) || { echo "run.sh: no folder '$1'. $usage" >&2; exit 2; }
shift
n=${1:-5}; (($#)) && shift
[[ "$n" =~ ^[1-9][0-9]*$ ]] || { echo "run.sh: N (rounds) must be a positive whole number, not '$n'" >&2; exit 2; }
cases=("$@"); ((${#cases[@]})) || cases=(arch156_46 arch156_70 arch180_30 wall10)
lpy=${LMGC90_PYTHON:-/usr/bin/python3}
[[ -d "$lmgc/pylmgc90" ]] || { echo "run.sh: $lmgc has no pylmgc90/ (is it the LMGC90 build folder? docs/lmgc90.md)" >&2; exit 2; }
PYTHONPATH="$lmgc" "$lpy" -c 'from pylmgc90 import chipy, pre' >/dev/null 2>&1 || {
  echo "run.sh: $lpy cannot import pylmgc90 from $lmgc (set LMGC90_PYTHON to the Python it was built for; it needs numpy)" >&2; exit 2; }
exe="${VOUSSOIR_BIN_DIR:-$root/build/drivers}/voussoir-run"
[[ -x "$exe" ]] || { echo "run.sh: no $exe (build Voussoir first: README, or set VOUSSOIR_BIN_DIR)" >&2; exit 2; }
py=python3; [[ -x "$root/.venv/bin/python" ]] && py="$root/.venv/bin/python"; py=${VOUSSOIR_PYTHON:-$py}
"$py" -c 'import h5py, numpy' 2>/dev/null || { echo "run.sh: $py has no h5py/numpy (set VOUSSOIR_PYTHON to the project's Python: README)" >&2; exit 2; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
echo "$(date -u '+%Y-%m-%d %H:%M UTC') on $(hostname): $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "Voussoir: $("$exe" --version 2>/dev/null | head -1 || echo "$exe") (git $(git -C "$root" describe --always --dirty 2>/dev/null || echo '?'))"
echo "LMGC90:   $lmgc ($(PYTHONPATH="$lmgc" "$lpy" -c 'import pylmgc90, os; print(os.path.dirname(pylmgc90.__file__))' 2>/dev/null | tail -1))"
"$py" "$root/bench/lmgc90/bench.py" --voussoir "$exe" --lmgc90-python "$lpy" --lmgc90-build "$lmgc" \
  --work "$work" --repeats "$n" ${BENCH_JSON:+--json "$BENCH_JSON"} "${cases[@]}"
