#!/usr/bin/env bash
# The small IDA of docs/bridges.md ("The bridge under earthquakes"), not a test: the
# two-span bridge with fill of input/sweep_bridge_two_spans.nml (its &bridge group) under
# the first component of four far-field records of FEMA P695 (four events, the shortest
# pairs), scale_tol 10 %, on 2 MPI ranks; then voussoir-post fragility on it. Prints
# each search's row, the wall time of the IDA and of the fit, the fit's numbers, and
# leaves the files and figures in OUT (default results/bridge_ida/). N_RECORDS (1 to 4,
# default 4) plays the first records only (a quick look; one record: no fragility).
#   bash bench/bridge_ida.sh [BUILD_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$(readlink -f "${1:-$root/build}")
exe=$build/drivers/voussoir-sweep
post=${POST:-$root/.venv/bin/voussoir-post}
sets=$(readlink -f "${VOUSSOIR_RECORD_SETS:-$build/record_sets}")
out=$(readlink -f "${OUT:-$root/results/bridge_ida}")
n_records=${N_RECORDS:-4}
[[ -x $exe ]] || { echo "no $exe: build first (bash scripts/setup.sh)"; exit 1; }
[[ -f $sets/fema_p695_far_field/index.csv ]] || {
  echo "the far-field set is not exported in $sets: $post records --export (scripts/setup.sh does)"; exit 1; }
mkdir -p "$out"
cd "$out"
rm -f ida_bridge.h5 ida_bridge.csv
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

records=(P02_1_NORTHR_LOS000 P17_1_SUPERST_B-POE270 P09_1_KOCAELI_DZC180 P12_1_LANDERS_CLW-LN)
files=""
for r in "${records[@]:0:$n_records}"; do
  files+="${files:+, }'$sets/fema_p695_far_field/$r.AT2'"
done
{
  sed -n '/^&bridge/,/^\//p' "$root/input/sweep_bridge_two_spans.nml"
  cat <<NML
&motion lead_s = 0.5, rest_s = 2.0 /
&output file = 'ida_bridge.h5' /
&sweep mode = 'ida', record_files = $files,
  scale_tol = 0.1, scale_max = 20, progress_every_s = 60 /
NML
} > ida_bridge.nml

echo "== the IDA ($n_records records)"
/usr/bin/time -f "   wall %e s, CPU %U s user + %S s system (both ranks)" \
  mpirun --oversubscribe -np 2 "$exe" ida_bridge.nml 2>&1 | grep -E 'done|threshold scale|warning|wall'
if (( n_records < 2 )); then echo "files in $out (one record: no fragility)"; exit 0; fi
echo "== the fragility"
/usr/bin/time -f "   wall %e s" "$post" fragility ida_bridge.h5 --out "$out/" 2>&1 | \
  grep -E '^PGA: median|^PGV: median|^goodness|wall' | sed 's/^/   /'
echo "files in $out"
