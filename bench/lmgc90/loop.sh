#!/usr/bin/env bash
# The laboratory loop against LMGC90 (issue 35 item 4; docs/diagnosis.md, "The loop
# against LMGC90"). A bench: never a dependency of the tests. Resumable: run it again
# with the same --out to go on.
#   bash bench/lmgc90/loop.sh LMGC90_BUILD_DIR --out DIR [--truths N] [--designs advised,ramps,recorded,naive] [--np N]
#   bash bench/lmgc90/loop.sh --summary --out DIR
# VOUSSOIR_PYTHON: the project's Python (default .venv/bin/python, else /work/main/.venv/bin/python);
# VOUSSOIR_BIN_DIR: the executables (default build/drivers).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
py="${VOUSSOIR_PYTHON:-}"
if [ -z "$py" ]; then
    if [ -x "$root/.venv/bin/python" ]; then py="$root/.venv/bin/python"; else py=/work/main/.venv/bin/python; fi
fi
export PYTHONPATH="$root/postproc${PYTHONPATH:+:$PYTHONPATH}"
export OPENBLAS_NUM_THREADS="${OPENBLAS_NUM_THREADS:-1}" OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
if [ "${1:-}" = "--summary" ]; then
    exec "$py" "$here/loop.py" "$@"
fi
if [ $# -lt 1 ] || [ ! -d "$1/pylmgc90" ]; then
    echo "usage: $0 LMGC90_BUILD_DIR --out DIR [--truths N] [--designs advised,ramps,recorded,naive] [--np N]" >&2
    echo "       $0 --summary --out DIR" >&2
    echo "(LMGC90_BUILD_DIR must hold pylmgc90; see docs/lmgc90.md for the build)" >&2
    exit 2
fi
build="$1"; shift
exec "$py" "$here/loop.py" --lmgc90-build "$build" "$@"
