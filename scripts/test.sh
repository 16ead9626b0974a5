#!/usr/bin/env bash
# Build and run the whole test suite: the Fortran CTest programs, the runs of every
# input file, the MPI sweep tests, and the Python tests (pytest).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
bash scripts/setup.sh
echo "[test] ctest"
(cd build && ctest --output-on-failure -j 2)
if [[ -d postproc/tests ]]; then
  echo "[test] pytest"
  VOUSSOIR_BIN_DIR="$root/build/drivers" .venv/bin/python -m pytest -q postproc/tests
fi
