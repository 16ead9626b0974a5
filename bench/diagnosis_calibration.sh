#!/usr/bin/env bash
# Calibration of the diagnosis's probabilities (bench/diagnosis_calibration.py): truths
# drawn from a prior over the catalogue and outside it, made by the independent
# generator, diagnosed in noise draws on the stored simulation bank; prints the rates
# and writes OUT/calibration.json and OUT/diagnosis_reliability.png. The outcome maps are
# kept in OUT/maps, so a rerun with the same OUT and seed simulates nothing new.
#   bash bench/diagnosis_calibration.sh [OUT=build/calibration] [--truths N] [--draws D] [--seed S]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-$root/build/calibration}
py=python3; [[ -x "$root/.venv/bin/python" ]] && py="$root/.venv/bin/python"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$py" "$root/bench/diagnosis_calibration.py" "$root/build/drivers" "$out" "${@:2}"
