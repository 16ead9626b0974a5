#!/usr/bin/env bash
# The diagnosis's replay bank (bench/diagnosis_replay.py): rebuild the simulation bank of
# the test arches with the executables of BIN_DIR and judge it against the stored one by
# the paired McNemar test over the replayed noise draws of every stored truth; --store
# replaces the stored bank (after a change of the kernel that the test judged).
#   bash bench/diagnosis_replay_bank.sh [BIN_DIR=build/drivers] [--store]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bin=${1:-$root/build/drivers}
py=python3; [[ -x "$root/.venv/bin/python" ]] && py="$root/.venv/bin/python"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$py" "$root/bench/diagnosis_replay.py" "$bin" "$work" "${@:2}"
