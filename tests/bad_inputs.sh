#!/usr/bin/env bash
# Every bad input gets a clear error (the file, the variable and the allowed range are
# named) and a non-zero exit, and leaves no result file behind.
#   bad_inputs.sh BIN_DIR WORK_DIR
set -uo pipefail
bin=$(readlink -f "$1"); work=$2
rm -rf "$work"; mkdir -p "$work" && cd "$work"
passed=0; failed=0

# case NAME EXPECTED_REGEX NAMELIST_TEXT
case_() {
  local name=$1 expect=$2 text=$3
  printf '%s\n' "$text" > "$name.nml"
  out=$("$bin/voussoir-run" "$name.nml" 2>&1); rc=$?
  if [[ $rc -ne 0 ]] && grep -Eq -- "$expect" <<<"$out" && grep -q "$name.nml" <<<"$out" \
     && [[ ! -e out.h5 && ! -e out.h5.part ]]; then
    passed=$((passed+1)); echo "PASS  $name"
  else
    failed=$((failed+1)); echo "FAIL  $name (exit $rc): $out"
  fi
}
o="&output file='out.h5' /"
case_ unknown_group     "unknown namelist group &geometry" "&geometry r = 1 /
$o"
case_ unknown_variable  "&arch.*thicknes"          "&arch thicknes = 0.1 /
$o"
case_ wrong_type        "&arch"                    "&arch n_voussoirs = 'many' /
$o"
case_ thick             "thickness_m = 0.6.*0 < thickness_m < r_ext_m" "&arch thickness_m = 0.6, r_ext_m = 0.5 /
$o"
case_ few_voussoirs     "n_voussoirs = 1 .*2 <= n_voussoirs <= 1000" "&arch n_voussoirs = 1 /
$o"
case_ many_voussoirs    "n_voussoirs = 100000 .*2 <= n_voussoirs <= 1000" "&arch n_voussoirs = 100000 /
$o"
case_ embrace_big       "embrace_deg = 190.*0 < embrace_deg <= 180" "&arch embrace_deg = 190 /
$o"
case_ embrace_zero      "embrace_deg = 0.*0 < embrace_deg <= 180" "&arch embrace_deg = 0 /
$o"
case_ density           "density_kg_m3 = -700.*density_kg_m3 > 0" "&arch density_kg_m3 = -700 /
$o"
case_ friction          "friction = -0.1.*friction >= 0" "&arch friction = -0.1 /
$o"
case_ joint_friction_neg "joint_friction\\(3\\) = -0.2.*joint_friction >= 0" "&arch joint_friction(3) = -0.2 /
$o"
case_ joint_friction_far "joint_friction\\(14\\) = 0.3.*joints are 0..n_voussoirs = 13" "&arch n_voussoirs = 13, joint_friction(14) = 0.3 /
$o"
case_ width             "width_m = -1.*width_m > 0" "&arch width_m = -1 /
$o"
case_ inset             "contact_inset_m = 0.05.*contact_inset_m < thickness_m/2" "&arch contact_inset_m = 0.05 /
$o"
case_ dt                "dt_s = 0.*0 < dt_s" "&solver dt_s = 0 /
$o"
case_ theta             "theta = 0.3.*0.5 <= theta <= 1" "&solver theta = 0.3 /
$o"
case_ tol               "tol = -1.*0 < tol < 1" "&solver tol = -1 /
$o"
case_ max_iter          "max_iter = 0 .*max_iter >= 1" "&solver max_iter = 0 /
$o"
case_ frequency         "frequency_hz = -1.*frequency_hz > 0" "&motion frequency_hz = -1 /
$o"
case_ amplitude         "amplitude_m = -0.01.*amplitude_m >= 0" "&motion amplitude_m = -0.01 /
$o"
case_ waveform          "waveform = 'square'" "&motion waveform = 'square' /
$o"
case_ record_missing    "record_file = .*no such file" "&motion waveform = 'record', record_file = 'nothere.csv' /
$o"
printf 't_s,accel_m_s2\n0.0,0.1\n0.01,0.2\n' > good_record.csv
case_ accel_missing     "record_file = .*no such file" "&motion waveform = 'accelerogram', record_file = 'nothere.AT2' /
$o"
case_ accel_empty       "record_file is empty.*accelerogram" "&motion waveform = 'accelerogram' /
$o"
case_ accel_scale       "record_scale = 0.*record_scale > 0" "&motion waveform = 'accelerogram', record_file = 'good_record.csv', record_scale = 0 /
$o"
case_ accel_scale_neg   "record_scale = -2.*record_scale > 0" "&motion waveform = 'accelerogram', record_file = 'good_record.csv', record_scale = -2 /
$o"
case_ accel_rest        "rest_s = -1.*rest_s >= 0" "&motion waveform = 'accelerogram', record_file = 'good_record.csv', rest_s = -1 /
$o"
case_ polygon_missing   "polygon_file = .*no such file" "&arch polygon_file = 'nothere.txt' /
$o"
case_ ramp_no_duration  "duration_s = 0.*duration_s > 0" "&motion waveform = 'ramp' /
$o"
case_ every             "every = 0 .*every >= 1" "&output file = 'out.h5', every = 0 /"
case_ restrained        "restrained_springings = 'middle'" "&arch restrained_springings = 'middle' /
$o"

# A missing input file.
out=$("$bin/voussoir-run" no_such_input.nml 2>&1); rc=$?
if [[ $rc -ne 0 ]] && grep -q "no_such_input.nml" <<<"$out"; then passed=$((passed+1)); echo "PASS  missing_input"
else failed=$((failed+1)); echo "FAIL  missing_input: $out"; fi

echo "$passed passed, $failed failed"
[[ $failed -eq 0 ]]
