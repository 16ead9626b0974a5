#!/usr/bin/env bash
# Build and run the whole test suite: the Fortran CTest programs, the runs of every
# input file, the MPI sweep tests, and the Python tests (pytest). No test may be
# skipped or left unrun: either counts as a failure.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
bash scripts/setup.sh
echo "[test] ctest"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
(cd build && ctest --output-on-failure -j 2) 2>&1 | tee "$log"
if grep -Eq '\*\*\*Skipped|Not Run|Disabled' "$log"; then
  echo "[test] FAIL: some CTest tests were skipped or not run (every test must run)"
  exit 1
fi
echo "[test] pytest"
VOUSSOIR_BIN_DIR="$root/build/drivers" .venv/bin/python -m pytest -q postproc/tests
