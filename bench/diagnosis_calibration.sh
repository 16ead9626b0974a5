#!/usr/bin/env bash
# Calibration of the diagnosis's probabilities on campaigns made by LMGC90
# (bench/diagnosis_calibration.py): the stored LMGC90 truths (bench/lmgc90/truths.sh
# makes more), replayed as laboratory campaigns with real laboratories' faults and
# diagnosed on the stored simulation bank; prints the rates and scores and writes
# OUT/calibration.json and OUT/diagnosis_reliability.png. Runs neither LMGC90 nor the kernel.
#   bash bench/diagnosis_calibration.sh [OUT=build/calibration] [--draws D] [--faults lab|ideal]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-$root/build/calibration}
py=python3; [[ -x "$root/.venv/bin/python" ]] && py="$root/.venv/bin/python"
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
"$py" "$root/bench/diagnosis_calibration.py" "$out" "${@:2}"
