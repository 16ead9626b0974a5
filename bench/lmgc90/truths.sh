#!/usr/bin/env bash
# Calibration truths of the diagnosis made by LMGC90 (docs/lmgc90.md). A bench: never a
# dependency of the tests, which replay the stored JSONs.
#   bash bench/lmgc90/truths.sh LMGC90_BUILD_DIR [--truths N] [--seed S] [--out DIR] [--check]
# VOUSSOIR_PYTHON: the project's Python (default .venv/bin/python, else /work/main/.venv/bin/python).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
if [ $# -lt 1 ] || [ ! -d "$1/pylmgc90" ]; then
    echo "usage: $0 LMGC90_BUILD_DIR [--truths N] [--seed S] [--out DIR] [--check]" >&2
    echo "(LMGC90_BUILD_DIR must hold pylmgc90; see docs/lmgc90.md for the build)" >&2
    exit 2
fi
build="$1"; shift
py="${VOUSSOIR_PYTHON:-}"
if [ -z "$py" ]; then
    if [ -x "$root/.venv/bin/python" ]; then py="$root/.venv/bin/python"; else py=/work/main/.venv/bin/python; fi
fi
export PYTHONPATH="$root/postproc${PYTHONPATH:+:$PYTHONPATH}"
exec "$py" "$here/truths.py" --lmgc90-build "$build" "$@"
