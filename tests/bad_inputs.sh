#!/usr/bin/env bash
# Every bad input gets a clear error (the file, the variable and the allowed range are
# named) and a non-zero exit, and leaves no result file behind.
#   bad_inputs.sh BIN_DIR WORK_DIR
set -uo pipefail
bin=$(readlink -f "$1"); work=$2
rm -rf "$work"; mkdir -p "$work" && cd "$work"
passed=0; failed=0
# gfortran's own namelist messages: no refusal may quote one (issue 26).
compiler='Cannot match namelist object name|Integer overflow while reading item|Bad repeat count|Invalid string input|Equal sign must follow'

# case NAME EXPECTED_REGEX NAMELIST_TEXT   (the driver is $driver, voussoir-run unless set)
case_() {
  local name=$1 expect=$2 text=$3
  printf '%s\n' "$text" > "$name.nml"
  out=$("$bin/${driver:-voussoir-run}" "$name.nml" 2>&1); rc=$?
  if [[ $rc -ne 0 ]] && grep -Eq -- "$expect" <<<"$out" && grep -q "$name.nml" <<<"$out" \
     && ! grep -Eq -- "$compiler" <<<"$out" && [[ ! -e out.h5 && ! -e out.h5.part ]]; then
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
pad=$(printf '%*s' 1100 '')
case_ long_line         "&arch has no variable 'thicknes'" "&arch embrace_deg = 156,$pad thicknes = 0.1 /
$o"
case_ wrong_type        "&arch"                    "&arch n_voussoirs = 'many' /
$o"
# The namelist reader's own refusals (issue 26): the variable, what it expects, what it got.
case_ int_text_quoted   ":1: &arch n_voussoirs = 'abc' is not a whole number \(an integer from" "&arch n_voussoirs = 'abc' /
$o"
case_ int_text          ":1: &arch n_voussoirs = abc is not a whole number \(an integer from" "&arch n_voussoirs = abc /
$o"
case_ int_real          ":1: &arch n_voussoirs = 12.5 is not a whole number \(an integer from" "&arch n_voussoirs = 12.5 /
$o"
case_ int_overflow      ":1: &arch n_voussoirs = 99999999999 is not a whole number \(an integer from -2147483647 to 2147483647\)" "&arch n_voussoirs = 99999999999 /
$o"
case_ bad_logical       ":1: &solver allow_nonconvergence = maybe is not a logical \(.true. or .false.\)" "&solver allow_nonconvergence = maybe /
$o"
case_ open_string       ":1: &motion waveform: the text 'afd, frequency_hz = 1.0 / has no closing quote" "&motion waveform = 'afd, frequency_hz = 1.0 /
$o"
# &load (issue 25): a load outside every block (which load, where), a magnitude not
# finite or not positive, a point without a magnitude, a path without a live load, an
# axle beyond the assembly.
ld="&arch /
&limit minimum_thickness = .false. /"
case_ run_load_outside "&load point load 1 at \(x, y\) = \(5, 5\) m lies in no block" "&arch /
&load point_load_n(1) = 1000, point_load_x_m(1) = 5, point_load_y_m(1) = 5 /
$o"
# The steps at rest (&solver rest_capacity_m_s2, what a sweep's row input carries): not
# negative, and not under loads (the capacity is the arch's alone).
case_ rest_capacity_neg "&solver rest_capacity_m_s2 = -1 is outside the allowed range rest_capacity_m_s2 >= 0" "&solver rest_capacity_m_s2 = -1 /
$o"
case_ rest_capacity_load "&solver rest_capacity_m_s2 = 3 is outside the allowed range 0 with &load" "&arch /
&solver rest_capacity_m_s2 = 3 /
&load point_load_n(1) = 1000, point_load_x_m(1) = 0, point_load_y_m(1) = 0.5 /
$o"
# A live load on the support alone opens no mechanism (unbounded, said so).
printf 'block free\n-0.1 0\n0.1 0\n0.1 1\n-0.1 1\nblock driven\n-1 -0.2\n1 -0.2\n1 0\n-1 0\n' > load_block.txt
driver=voussoir-limit case_ load_on_support "unbounded\).*the live load acts on no free block \(only on the supports\)" "&arch polygon_file = 'load_block.txt', thickness_m = 0.2 /
&load point_load_n(1) = 100, point_load_x_m(1) = 0.5, point_load_y_m(1) = -0.1 /"
driver=voussoir-limit case_ load_outside "&load point load 1 at \(x, y\) = \(5, 5\) m lies in no block \(a point on a block or on its boundary, within 1e-9 m\)" "$ld
&load point_load_n(1) = 1000, point_load_x_m(1) = 5, point_load_y_m(1) = 5 /"
driver=voussoir-limit case_ load_inf "&load point_load_n\(1\) = Infinity is not a finite number" "$ld
&load point_load_n(1) = Inf /"
driver=voussoir-limit case_ load_nan "&load point_load_n\(1\) = NaN is not a finite number" "$ld
&load point_load_n(1) = NaN /"
driver=voussoir-limit case_ load_negative "&load point_load_n\(1\) = -5 is outside the allowed range 0 < point_load_n <= 1e12 N" "$ld
&load point_load_n(1) = -5 /"
driver=voussoir-limit case_ load_no_magnitude "&load point load 2 has a point, a direction, a kind, a patch or a case but no magnitude" "$ld
&load point_load_n(1) = 100, point_load_x_m(2) = 0.3 /"
driver=voussoir-limit case_ load_path_dead "&load path_points moves or repeats the live point loads, but no point load is live" "$ld
&load point_load_n(1) = 100, point_load_live(1) = .false., path_points = 5, path_x0_m = -0.3, path_x1_m = 0.3 /"
driver=voussoir-limit case_ load_path_one "&load path_points = 1 is outside the allowed range path_points = 0 \(no path\) or path_points >= 2" "$ld
&load point_load_n(1) = 100, path_points = 1 /"
driver=voussoir-limit case_ load_axle_off "&load live point load 1 \(axle 2\) at x = 3 m lies over no block" "$ld
&load point_load_n(1) = 100, axle_spacing_m(1) = 3 /"
driver=voussoir-limit case_ load_live_text "&load point_load_live\(1\) = 'x' is not a logical" "$ld
&load point_load_n(1) = 100, point_load_live = 'x' /"
# voussoir-sweep takes &load (issue 25): a load outside every block is refused before any run.
driver=voussoir-sweep case_ sweep_load_outside "sweep_load_outside.nml: &load point load 1 at \(x, y\) = \(5, 0\) m lies in no block" "&arch /
&motion waveform = 'afd', frequency_hz = 2, amplitude_m = 0.01 /
&sweep mode = 'threshold', frequencies_hz = 2 /
&load point_load_n(1) = 100, point_load_x_m(1) = 5 /
$o"
driver=voussoir-limit case_ limit_thickness_text ":2: &limit minimum_thickness = 'x' is not a logical \(.true. or .false.\)" "&arch /
&limit minimum_thickness = 'x' /"
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
# A voussoir a hundred times deeper than long is a sliver (issue 12: embrace_deg = 1e-6
# "collapsed" under its own weight).
case_ embrace_sliver    "embrace_deg = 1.00000E-006 is outside the allowed range 1.22 <= embrace_deg <= 180 for n_voussoirs = 13.*thickness_m/100" "&arch embrace_deg = 1e-6 /
$o"
case_ voussoirs_sliver  "n_voussoirs = 1000 is outside the allowed range 2 <= n_voussoirs <= 78 for embrace_deg = 180.*thickness_m/100" "&arch n_voussoirs = 1000, embrace_deg = 180, r_ext_m = 0.5, thickness_m = 0.4 /
$o"
case_ density           "density_kg_m3 = -700.*0 < density_kg_m3 <= 1e5" "&arch density_kg_m3 = -700 /
$o"
case_ friction          "friction = -0.1.*friction >= 0" "&arch friction = -0.1 /
$o"
case_ joint_friction_neg "joint_friction\\(3\\) = -0.2.*joint_friction >= 0" "&arch joint_friction(3) = -0.2 /
$o"
case_ joint_friction_far "joint_friction\\(14\\) = 0.3.*joints are 0..n_voussoirs = 13" "&arch n_voussoirs = 13, joint_friction(14) = 0.3 /
$o"
case_ width             "width_m = -1.*0 < width_m <= 1000 m" "&arch width_m = -1 /
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
case_ accel_lead        "&motion lead_s = -1 is outside the allowed range lead_s >= 0" "&motion waveform = 'accelerogram', record_file = 'good_record.csv', lead_s = -1 /
$o"
case_ lead_text         ":1: &motion lead_s = 'half' is not a number" "&motion lead_s = 'half' /
$o"
case_ lead_nan          "&motion lead_s = NaN is not a finite number" "&motion waveform = 'accelerogram', record_file = 'good_record.csv', lead_s = NaN /
$o"
case_ lead_huge         "steps.*limit of 1e8" "&motion waveform = 'accelerogram', record_file = 'good_record.csv', lead_s = 1e9 /
$o"
# The vertical component, the polarity and the unit of a record (issue 24).
case_ vertical_ratio_big "&motion vertical_ratio = 3 is outside the allowed range -2 <= vertical_ratio <= 2" "&motion waveform = 'accelerogram', record_file = 'good_record.csv', vertical_ratio = 3 /
$o"
case_ vertical_ratio_nan "&motion vertical_ratio = NaN is not a finite number" "&motion vertical_ratio = NaN /
$o"
case_ vertical_ratio_ramp "vertical_ratio = 0.5 .*waveform = 'ramp' has no vertical component" "&motion waveform = 'ramp', duration_s = 1, vertical_ratio = 0.5 /
$o"
case_ vertical_missing  "record_vertical_file = '.*nothere_v.csv': no such file" "&motion waveform = 'accelerogram', record_file = 'good_record.csv', record_vertical_file = 'nothere_v.csv' /
$o"
case_ vertical_and_ratio "record_vertical_file and vertical_ratio both give the vertical component" "&motion waveform = 'accelerogram', record_file = 'good_record.csv', record_vertical_file = 'good_record.csv', vertical_ratio = 0.5 /
$o"
case_ vertical_afd      "record_vertical_file is set but waveform = 'afd'" "&motion record_vertical_file = 'good_record.csv' /
$o"
printf 't_s,accel_m_s2\n0.0,0.1\n0.02,0.2\n' > other_step.csv
case_ vertical_steps    "record_vertical_file: .*other_step.csv has 2 samples 0.02 s apart, the horizontal record_file 2 samples 0.01 s apart" "&motion waveform = 'accelerogram', record_file = 'good_record.csv', record_vertical_file = 'other_step.csv' /
$o"
case_ polarity_two      "&motion record_polarity = 2 is outside the allowed range record_polarity = 1 or -1" "&motion waveform = 'accelerogram', record_file = 'good_record.csv', record_polarity = 2 /
$o"
case_ polarity_afd      "record_polarity = -1 .*waveform = 'afd' has no record to reverse" "&motion record_polarity = -1 /
$o"
printf 'EVENT_NAME: TEST\nEVENT_ID: X\nSAMPLING_INTERVAL_S: 0.01\nNDATA: 2\nUSER5:\n0.1\n0.2\n' > unitless.asc
case_ esm_unitless      "record_file: .*unitless.asc: the unit of the samples cannot be determined: .*no UNITS; state it in a header line such as 'UNITS: cm/s\^2'" "&motion waveform = 'accelerogram', record_file = 'unitless.asc' /
$o"
printf 'PEER NGA STRONG MOTION DATABASE RECORD\nTEST\nACCELERATION TIME SERIES\nNPTS=   2, DT=   .0100 SEC,\n 0.1 0.2\n' > unitless.AT2
case_ at2_unitless      "record_file: .*unitless.AT2:3: the line 'ACCELERATION TIME SERIES' names no units, so the unit of the samples cannot be determined: a PEER .AT2 record states it there, as 'ACCELERATION TIME SERIES IN UNITS OF G'" "&motion waveform = 'accelerogram', record_file = 'unitless.AT2' /
$o"
case_ esm_unitless_vertical "record_vertical_file: .*unitless.asc: the unit of the samples cannot be determined" "&motion waveform = 'accelerogram', record_file = 'good_record.csv', record_vertical_file = 'unitless.asc' /
$o"
case_ polygon_missing   "polygon_file = .*no such file" "&arch polygon_file = 'nothere.txt' /
$o"
case_ ramp_no_duration  "duration_s = 0.*duration_s > 0" "&motion waveform = 'ramp' /
$o"
case_ every             "every = 0 .*every >= 1" "&output file = 'out.h5', every = 0 /"
case_ restrained        "restrained_springings = 'middle'" "&arch restrained_springings = 'middle' /
$o"

# Non-finite and absurd values (issue 12): refused, never run to a NaN or a "stood".
case_ r_ext_inf         "&arch r_ext_m = Infinity is not a finite number" "&arch r_ext_m = Inf /
$o"
case_ r_ext_huge        "r_ext_m = 1.00000E\+300.*0 < r_ext_m <= 1000 m" "&arch r_ext_m = 1e300 /
$o"
case_ width_inf         "&arch width_m = Infinity is not a finite number" "&arch width_m = Inf /
$o"
case_ density_inf       "&arch density_kg_m3 = Infinity is not a finite number" "&arch density_kg_m3 = Inf /
$o"
case_ amplitude_inf     "&motion amplitude_m = Infinity is not a finite number" "&motion amplitude_m = Inf /
$o"
case_ table_gain_inf    "&motion table_gain = Infinity is not a finite number" "&motion table_gain = Inf /
$o"
case_ frequency_inf     "&motion frequency_hz = Infinity is not a finite number" "&motion frequency_hz = Inf /
$o"
case_ alert_inf         "&solver alert_m = Infinity is not a finite number" "&solver alert_m = Inf /
$o"
case_ stop_nan          "&output stop_after_collapse_s = NaN is not a finite number" "&output file = 'out.h5', stop_after_collapse_s = NaN /"
# Absurd values refused up front with their range (issue 26), not in the solver.
case_ ring_thin         "&arch thickness_m = 1.00000E-009 is outside the allowed range r_ext_m/1000 = 5.080E-4 m <= thickness_m < r_ext_m = 0.508" "&arch thickness_m = 1e-9 /
$o"
case_ amplitude_huge    "&motion amplitude_m = 1.00000E\+300 is outside the allowed range 0 <= amplitude_m <= 1000 g/\(table_gain \(2 pi frequency_hz\)\^2\) = 159 m" "&motion amplitude_m = 1e300 /
$o"
printf 't_s,table_x_m\n0,0\n0.01,1e300\n0.02,0\n0.03,0\n' > record_far.csv
printf 't_s,table_x_m\n0,0\n0.01,1\n0.02,0\n0.03,0\n0.04,0\n' > record_jerk.csv
printf 't_s,accel_m_s2\n0,0\n0.01,1e300\n0.02,0\n' > accel_huge.csv
case_ record_far        "record_file = '.*record_far.csv': its table_x_m \(peak .* m from the first sample\) is outside the allowed range \|table_x_m\| <= 1000 m" "&motion waveform = 'record', record_file = 'record_far.csv' /
$o"
case_ record_jerk       "record_file = '.*record_jerk.csv': its table acceleration \(peak 20000 m/s2\) is outside the allowed range \|acceleration\| <= 1000 g" "&motion waveform = 'record', record_file = 'record_jerk.csv', record_cutoff_hz = 0 /
$o"
case_ accel_huge        "record_file = '.*accel_huge.csv': its table acceleration \(peak 1.000E\+300 m/s2\) is outside the allowed range \|acceleration\| <= 1000 g" "&motion waveform = 'accelerogram', record_file = 'accel_huge.csv' /
$o"
case_ accel_scale_huge  "its table acceleration \(peak .* m/s2\) is outside the allowed range \|acceleration\| <= 1000 g.*record_scale" "&motion waveform = 'accelerogram', record_file = 'good_record.csv', record_scale = 1e6 /
$o"
case_ frequency_high    "frequency_hz = 1000000 .*frequency_hz <= 1/\(20 dt_s\) = 50" "&motion frequency_hz = 1e6 /
$o"
case_ dt_vs_frequency   "frequency_hz = 1.25 .*1/\(20 dt_s\) = 0.5" "&motion frequency_hz = 1.25 /
&solver dt_s = 0.1 /
$o"
case_ duration_huge     "1.00E\+12 steps.*duration_s.*dt_s.*limit of 1e8" "&motion duration_s = 1e9 /
$o"
case_ rest_huge         "steps.*limit of 1e8" "&motion rest_s = 1e9 /
$o"
case_ n_attack_huge     "steps.*limit of 1e8" "&motion n_attack = 2000000000 /
$o"
case_ dt_tiny           "steps.*dt_s = 1.000E-300.*limit of 1e8" "&solver dt_s = 1e-300 /
$o"
case_ every_memory      "GB of samples in memory.*every" "&arch n_voussoirs = 1000 /
&motion duration_s = 90 /
&solver dt_s = 1e-6 /
&output file = 'out.h5', every = 1 /"
case_ repeated_group    ":2: namelist group &arch appears a second time \(first at line 1\)" "&arch n_voussoirs = 13 /
&arch n_voussoirs = 9 /
$o"
# Namelist layouts (issue 34): every group is read wherever it stands on a line, as
# gfortran reads it, or the file is refused with its line; no group is ever ignored.
# The five bad values that a second group on a line once hid, refused again.
case_ line_dt           "&solver dt_s = 0 is outside the allowed range 0 < dt_s" "&arch friction = 0.5 / &solver dt_s = 0 / $o"
case_ line_theta        "&solver theta = 0.2 is outside the allowed range 0.5 <= theta <= 1" "&arch friction = 0.5 / &solver theta = 0.2 / $o"
case_ line_waveform     "&motion waveform = 'square' is not one of" "&arch friction=0.3 / &motion waveform='square' / &output file='out.h5' /"
case_ line_record       "record_file = .*nothere.csv.*no such file" "&arch friction = 0.5 / &motion waveform = 'record', record_file = 'nothere.csv' / $o"
case_ line_amplitude    ":1: &motion amplitude_m = 'big' is not a number" "&arch friction = 0.5 / &motion amplitude_m = 'big' / $o"
# Several groups on a line: one not closed before the next begins.
case_ line_unclosed     ":1: group &motion begins before &arch is closed: end &arch with /" "&arch friction = 0.5 &motion amplitude_m = 0.01 / $o"
# A group over many lines whose '/' is missing: the next group, lines later, is not swallowed.
case_ lines_unclosed    ":3: group &output begins before &motion is closed" "&motion amplitude_m = 0.01,
  frequency_hz = 1.5
$o"
# A group written without its '&' (gfortran would skip it, and run on defaults).
case_ group_no_ampersand ":1: 'solver dt_s = 0 /' stands outside every namelist group" "solver dt_s = 0 /
$o"
case_ group_bad_name    ":1: '&solver\\(dt_s = 0 /' is not the start of a namelist group" "&solver(dt_s = 0 /
$o"
# Comments: a '/' in a comment closes nothing; a comment without '!' is refused.
case_ comment_slash     ":2: group &output begins before &solver is closed" "&solver dt_s = 2e-3 ! the end /
$o"
case_ comment_hash      ":1: '# the arch of the tests' stands outside every namelist group" "# the arch of the tests
$o"
# &end misspelt is another group, begun before this one is closed.
case_ end_misspelt      ":1: group &edn begins before &solver is closed" "&solver dt_s = 2e-3 &edn
$o"
case_ end_stray_text    ":1: 'dt_s = 2e-3 /' stands outside every namelist group" "&solver &end dt_s = 2e-3 /
$o"
# Repeated commas: a null value is one more value, refused for a single-valued variable.
case_ commas_scalar     ":1: &solver dt_s takes one value; it is given 2" "&solver dt_s = 1e-3,, theta = 0.6 /
$o"
case_ commas_list       ":1: &arch joint_friction has 257 values; at most 256" "&arch joint_friction = 256*0.3,, /
$o"
# Strings with slashes: unquoted, the '/' ends the group and the rest stands outside it;
# a string is closed on its own line.
case_ slash_unquoted    ":1: 'run.h5 /' stands outside every namelist group" "&output file = out/run.h5 /"
case_ slash_open_string ":1: &output file: the text 'out/ has no closing quote" "&output file = 'out/
run.h5' /"
# An input that is not a readable file: a folder is refused by every driver.
mkdir -p input_folder
for d in voussoir-run voussoir-limit voussoir-sweep; do
  out=$("$bin/$d" input_folder 2>&1); rc=$?
  if [[ $rc -eq 1 ]] && grep -q "^$d: error: input_folder: is a folder, not an input file" <<<"$out" \
     && [[ ! -e voussoir_run.h5 ]]; then
    passed=$((passed+1)); echo "PASS  $d input_folder"
  else failed=$((failed+1)); echo "FAIL  $d input_folder (exit $rc): $out"; fi
done

# Plausibility against the assembly's own scale (issue 34): millimetres given as metres
# pass every range but make another arch or another motion; refused with a hint.
case_ mm_amplitude      "&motion amplitude_m = 46 m is larger than the arch's span \\(0.994 m; allowed: amplitude_m <= 0.994 m\\): did you mean millimetres \\(amplitude_m = 0.046 m\\)\\?" "&motion amplitude_m = 46 /
$o"
case_ mm_arch           "&arch r_ext_m = 508 m and embrace_deg = 156 make an arch 993.8 m wide, wider than any masonry arch .*did you mean millimetres \\(r_ext_m = 0.508 m, thickness_m = 0.071 m\\)\\?" "&arch r_ext_m = 508, thickness_m = 71, width_m = 145 /
$o"
case_ mm_radius         "make an arch 993.8 m wide.*did you mean millimetres \\(r_ext_m = 0.508 m\\)\\?" "&arch r_ext_m = 508 /
$o"
driver=voussoir-limit case_ mm_radius_limit "make an arch 993.8 m wide.*did you mean millimetres \\(r_ext_m = 0.508 m\\)\\?" "&arch r_ext_m = 508 /"
case_ mm_thickness      "&arch thickness_m = 12 m is thicker than any masonry arch ring \\(allowed: at most 10 m\\): did you mean millimetres \\(thickness_m = 0.012 m\\)\\?" "&arch r_ext_m = 20, thickness_m = 12 /
$o"
case_ mm_wall_amplitude "&motion amplitude_m = 0.5 m is larger than the wall's length \\(0.4 m" "&wall courses = 2, blocks_per_course = 2 / &motion amplitude_m = 0.5 /
$o"
case_ amplitude_over_span "&motion amplitude_m = 0.9 m is larger than the arch's span \\(0.6 m; allowed: amplitude_m <= 0.6 m\\)\$" "&arch r_ext_m = 0.3, embrace_deg = 180 / &motion amplitude_m = 0.9, frequency_hz = 0.5 /
$o"
# A grid sweep's amplitudes against every parameter set's arch, before any run.
driver=voussoir-sweep case_ sweep_mm_amplitudes "&sweep amplitudes_m\\(2\\) = 46 m is larger than the arch's span \\(0.994 m; allowed: amplitudes_m <= 0.994 m\\): did you mean millimetres \\(0.046 m\\)\\?" "&sweep mode = 'grid', frequencies_hz = 1.25, amplitudes_m = 0.02, 46 /
$o"
driver=voussoir-sweep case_ sweep_amplitude_set "&sweep amplitudes_m\\(2\\) = 0.9 m is larger than the arch's span of parameter set 0 \\(thickness_m = 0.071\\) \\(0.6 m" "&sweep mode = 'grid', frequencies_hz = 1.25, amplitudes_m = 0.02, 0.9, thickness_list_m = 0.071, 0.08 /
&arch r_ext_m = 0.3, embrace_deg = 180 /
$o"
# Where a real case could need it, a warning and the run goes on: a table acceleration
# beyond 10 g (a small block at a high frequency), a barrel over 100 m wide.
warned() {
  local name=$1 expect=$2 text=$3
  printf '%s\n' "$text" > "$name.nml"
  out=$("$bin/${driver:-voussoir-run}" "$name.nml" 2>&1); rc=$?
  if [[ $rc -eq 0 ]] && grep -Eq -- "^${driver:-voussoir-run}: warning: $name.nml: $expect" <<<"$out"; then
    passed=$((passed+1)); echo "PASS  $name"
  else failed=$((failed+1)); echo "FAIL  $name (exit $rc): $out"; fi
  rm -f warned.h5
}
warned warn_accel "&motion amplitude_m = 0.3 m at frequency_hz = 4 commands a full-cycle table acceleration A \\(2 pi f\\)\\^2 of 19.3 g, beyond any shaking table or earthquake \\(10 g\\)" "&motion amplitude_m = 0.3, frequency_hz = 4 /
&output file = 'warned.h5' /"
driver=voussoir-limit warned warn_width "&arch width_m = 145 m is the out-of-plane width of the blocks \\(more than 100 m\\): did you mean millimetres \\(width_m = 0.145 m\\)\\?" "&arch width_m = 145 /"

# A sweep's plan (issue 26): its cost is printed before the first run, and a plan beyond
# &sweep max_runs is refused with its count. 256 frequencies x 256 amplitudes = 65,536 jobs.
freqs=$(for k in $(seq 0 255); do printf '%s, ' "$(awk "BEGIN{printf \"%.2f\", 1 + 0.01*$k}")"; done)
amps=$(for k in $(seq 1 256); do printf '%s, ' "$(awk "BEGIN{printf \"%.3f\", 0.001*$k}")"; done)
grid="&sweep mode = 'grid', frequencies_hz = ${freqs%, }, amplitudes_m = ${amps%, }"
driver=voussoir-sweep case_ sweep_over_cap "the sweep would take 65536 runs \(65536 jobs\): more than &sweep max_runs = 65535; split the sweep or raise max_runs" "$grid, max_runs = 65535 /
$o"
driver=voussoir-sweep case_ sweep_progress "&sweep progress_every_s = -1 is outside the allowed range progress_every_s >= 0 \(0: no progress lines\)" "&sweep frequencies_hz = 1, progress_every_s = -1 /
$o"
# Under the cap the same plan starts, its estimate first; stopped once it is printed.
mkdir -p grid_cost && printf '%s /\n&output file = '"'out.h5'"' /\n' "$grid" > grid_cost/grid_cost.nml
(cd grid_cost && exec "$bin/voussoir-sweep" grid_cost.nml > log.txt 2>&1) & pid=$!
for _ in $(seq 300); do grep -q "estimate:" grid_cost/log.txt 2>/dev/null && break; sleep 0.1; done
kill "$pid" 2>/dev/null; wait "$pid" 2>/dev/null
if grep -Eq "^voussoir-sweep: estimate: 65536 jobs, 65536 runs, [0-9]+ s simulated, roughly [0-9.]+ [a-z]+ of wall time" grid_cost/log.txt; then
  passed=$((passed+1)); echo "PASS  sweep_cost_printed"
else failed=$((failed+1)); echo "FAIL  sweep_cost_printed: $(cat grid_cost/log.txt)"; fi
rm -rf grid_cost

# Polygon files that cannot be an assembly.
printf 'block free\n0 0\n1 0\n1 1\n0 1\n' > all_free.txt
printf 'block driven\n0 0\n1 0\n1 1\n0 1\n' > all_driven.txt
printf 'block free\n0 0\n1 0\n1 1\n0 1\nblock driven\n-1 -0.5\n2 -0.5\n2 0.01\n-1 0.01\n' > overlap.txt
# Polygons that cannot be blocks (issue 12: a NaN vertex ran and "stood").
table='block driven\n-1 -0.2\n1 -0.2\n1 0\n-1 0\n'
printf "block free\n-0.1 0\n0.1 0\nnan 1\n-0.1 1\n$table" > vertex_nan.txt
printf "block free\n-0.1 0\n0.1 0\n0.1 Inf\n-0.1 1\n$table" > vertex_inf.txt
printf "block free\n-1e200 0\n1e200 0\n1e200 1\n-1e200 1\n$table" > vertex_far.txt
printf "block free\n0 0.1\n0.1 0.1\n0.2 0.1\n$table" > flat.txt
printf "# a pentagram\nblock free\n0.2 0.1\n0.0191 0.1588\n0.1309 0.0049\n0.1309 0.1951\n0.0191 0.0412\n$table" > star.txt
printf "block free\n0 0\n1e-9 0\n1e-9 1e-9\n0 1e-9\n$table" > speck.txt
case_ polygon_nan       "vertex_nan.txt:4: vertex x = NaN is not a finite number" "&arch polygon_file = 'vertex_nan.txt' /
$o"
case_ polygon_inf       "vertex_inf.txt:4: vertex y = Infinity is not a finite number" "&arch polygon_file = 'vertex_inf.txt' /
$o"
case_ polygon_far       "vertex_far.txt:2: vertex x = -1.00000E\+200 m is outside the allowed range -1000 m <= x <= 1000 m" "&arch polygon_file = 'vertex_far.txt' /
$o"
case_ polygon_flat      "flat.txt:1: block 1 has zero area" "&arch polygon_file = 'flat.txt' /
$o"
case_ polygon_star      "star.txt:2: block 1 is not a convex polygon" "&arch polygon_file = 'star.txt' /
$o"
case_ polygon_speck     "speck.txt:1: block 1 is 1.00E-9 m wide at its narrowest: the allowed range is width >= 1e-4 m" "&arch polygon_file = 'speck.txt' /
$o"
case_ wall_speck        "&wall block_width_m = 1.00000E-009 is outside the allowed range 1e-4 m <= block_width_m <= 100 m" "&wall courses = 3, blocks_per_course = 3, block_width_m = 1e-9 /
$o"
case_ wall_wrong_type   "&wall.*The variables of &wall are: courses, blocks_per_course \(integer\)" "&wall courses = 'x' /
$o"
case_ polygon_no_driven "all_free.txt: no block is driven" "&arch polygon_file = 'all_free.txt' /
$o"
case_ polygon_no_free   "all_driven.txt: every block is driven" "&arch polygon_file = 'all_driven.txt' /
$o"
case_ polygon_overlap   "overlap.txt: blocks 1 and 2 overlap by 0.01 m" "&arch polygon_file = 'overlap.txt' /
$o"
# voussoir-limit reads the polygon file as voussoir-run does: overlapping blocks refused (issue 25).
driver=voussoir-limit case_ limit_polygon_overlap "overlap.txt: blocks 1 and 2 overlap by 0.01 m" "&arch polygon_file = 'overlap.txt' /"

# &sweep mode = 'msa' (issue 24): the levels stated, each > 0 and finite, increasing;
# the variables of the other modes refused (voussoir-sweep on one rank, no mpirun).
printf 't_s,accel_m_s2\n0.00,0.0\n0.01,1.0\n0.02,-0.5\n0.03,0.0\n' > msa_record.csv
msa="&arch /
&output file = 'out.h5' /"
driver=voussoir-sweep case_ msa_no_levels "&sweep msa_levels_g is not set: mode = 'msa' needs at least one intensity level \(the PGA in g" "$msa
&sweep mode = 'msa', record_files = 'msa_record.csv' /"
driver=voussoir-sweep case_ msa_level_zero "&sweep msa_levels_g\(2\) = 0 is outside the allowed range 0 < msa_levels_g <= 100 g" "$msa
&sweep mode = 'msa', record_files = 'msa_record.csv', msa_levels_g = 0.2, 0 /"
driver=voussoir-sweep case_ msa_level_nan "&sweep msa_levels_g\(1\) = NaN is outside the allowed range 0 < msa_levels_g <= 100 g \(finite\)" "$msa
&sweep mode = 'msa', record_files = 'msa_record.csv', msa_levels_g = NaN /"
driver=voussoir-sweep case_ msa_level_order "&sweep msa_levels_g\(3\) = 0.3 g is not above msa_levels_g\(2\) = 0.4 g: the levels must be strictly increasing" "$msa
&sweep mode = 'msa', record_files = 'msa_record.csv', msa_levels_g = 0.2, 0.4, 0.3 /"
driver=voussoir-sweep case_ msa_level_text ":3: &sweep msa_levels_g\(1\) = 'high' is not a number" "$msa
&sweep mode = 'msa', record_files = 'msa_record.csv', msa_levels_g = 'high' /"
driver=voussoir-sweep case_ msa_no_records "&sweep record_files is not set: mode = 'msa' needs at least one record" "$msa
&sweep mode = 'msa', msa_levels_g = 0.2 /"
driver=voussoir-sweep case_ msa_dt_check "&sweep dt_check_rows = 3 belongs to mode = 'ida'" "$msa
&sweep mode = 'msa', record_files = 'msa_record.csv', msa_levels_g = 0.2, dt_check_rows = 3 /"
driver=voussoir-sweep case_ msa_levels_in_ida "&sweep msa_levels_g is set but mode = 'ida' searches the scale of each record: remove it, or use mode = 'msa'" "$msa
&sweep mode = 'ida', record_files = 'msa_record.csv', msa_levels_g = 0.2 /"
driver=voussoir-sweep case_ msa_unknown_mode "&sweep mode = 'stripes' is not one of 'threshold', 'grid', 'ida', 'msa'" "$msa
&sweep mode = 'stripes' /"

# The output named where it cannot be written: refused before the run, nothing left.
case_ output_is_input   "&output file = 'output_is_input.nml' is the input file itself" "&output file = 'output_is_input.nml' /"
case_ output_no_folder  "&output file = 'no_folder/out.h5': the folder 'no_folder' does not exist" "&output file = 'no_folder/out.h5' /"
mkdir -p a_folder
case_ output_is_folder  "&output file = 'a_folder' is a folder" "&output file = 'a_folder' /"
[[ -z $(ls a_folder) && ! -e no_folder && $(head -c 1 output_is_input.nml) == "&" ]] \
  && { passed=$((passed+1)); echo "PASS  output_left_alone"; } || { failed=$((failed+1)); echo "FAIL  output_left_alone"; }

# The command line: --help and --version answer and exit 0; a stray argument is refused.
for d in voussoir-run voussoir-limit; do
  h=$("$bin/$d" --help 2>&1); rc1=$?
  v=$("$bin/$d" --version 2>&1); rc2=$?
  "$bin/$d" a.nml b.nml >/dev/null 2>&1; rc3=$?
  if [[ $rc1 -eq 0 && $h == usage:* && $rc2 -eq 0 && $v == "$d (voussoir "* && $rc3 -eq 2 ]]; then
    passed=$((passed+1)); echo "PASS  $d command line"
  else failed=$((failed+1)); echo "FAIL  $d command line: $rc1 $rc2 $rc3 $h $v"; fi
done

# &bridge (issue 37): what the values alone refuse, each naming the file, the group, the
# variable, its value, the allowed range and why; with voussoir-limit and voussoir-run.
br="shape = 'segmental', span_m(1) = 10, rise_m(1) = 2.5, ring_thickness_m = 0.45, n_voussoirs = 16"
driver=voussoir-limit case_ bridge_segmental_rise "&bridge rise_m\(1\) = 6 is outside the allowed range 0 < rise_m\(1\) <= span_m/2 = 5 m for a segmental arch" "&bridge shape = 'segmental', span_m(1) = 10, rise_m(1) = 6 /"
case_ bridge_segmental_rise_run "&bridge rise_m\(1\) = 6 is outside the allowed range 0 < rise_m\(1\) <= span_m/2 = 5 m" "&bridge shape = 'segmental', span_m(1) = 10, rise_m(1) = 6 /
$o"
driver=voussoir-limit case_ bridge_ring_too_thick "&bridge ring_thickness_m = 3 is outside the allowed range 0 < ring_thickness_m <= span_m\(1\)/4 = 2.5 m: a ring deeper than a quarter of its span" "&bridge shape = 'segmental', span_m(1) = 10, rise_m(1) = 2.5, ring_thickness_m = 3 /"
driver=voussoir-limit case_ bridge_skewback "&bridge abutment_width_m = 0.2 is outside the allowed range abutment_width_m > 0.36 m, the horizontal reach of span 1's springing joint .*would not carry the extrados end of its arch" "&bridge $br, abutment_width_m = 0.2 /"
driver=voussoir-limit case_ bridge_pier_too_narrow "&bridge pier_width_m = 0.5 is outside the allowed range pier_width_m >= 0.72 m: spans 1 and 2 do not meet pier 1 side by side" "&bridge $br, span_m(2) = 10, rise_m(2) = 2.5, pier_width_m = 0.5 /"
driver=voussoir-limit case_ bridge_semicircle_rise "&bridge rise_m\(1\) = 4 is outside the allowed range rise_m\(1\) = span_m/2 = 5 m for a semicircular arch" "&bridge shape = 'semicircular', span_m(1) = 10, rise_m(1) = 4 /"
driver=voussoir-limit case_ bridge_pointed_low "&bridge rise_m\(1\) = 4 is outside the allowed range rise_m\(1\) >= span_m/2 = 5 m for a pointed arch" "&bridge shape = 'pointed', span_m(1) = 10, rise_m(1) = 4 /"
driver=voussoir-limit case_ bridge_pointed_odd "&bridge n_voussoirs = 15 is outside the allowed range an even n_voussoirs for a pointed arch" "&bridge shape = 'pointed', span_m(1) = 10, rise_m(1) = 6, n_voussoirs = 15 /"
driver=voussoir-limit case_ bridge_three_centred_flat "&bridge rise_m\(1\) = 1 is outside the allowed range 1.33975 m < rise_m\(1\) < span_m/2 = 5 m for a three-centred arch" "&bridge shape = 'three-centred', span_m(1) = 10, rise_m(1) = 1 /"
driver=voussoir-limit case_ bridge_rise_without_span "&bridge rise_m\(2\) = 2 is outside the allowed range none: there are 1 spans" "&bridge $br, rise_m(2) = 2 /"
driver=voussoir-limit case_ bridge_no_span "&bridge gives no span: set span_m\(1\) > 0" "&bridge shape = 'segmental' /"
driver=voussoir-limit case_ bridge_gap_in_spans "&bridge span_m\(2\) is unset but span_m\(3\) = 10 is set" "&bridge $br, span_m(3) = 10 /"
driver=voussoir-limit case_ bridge_and_arch "&bridge and &arch both describe the assembly" "&arch friction = 0.5 /
&bridge $br /"
driver=voussoir-limit case_ bridge_shape_unknown "&bridge shape = 'gothic' is not one of 'segmental', 'semicircular', 'elliptical', 'three-centred', 'pointed', 'parabolic'" "&bridge shape = 'gothic', span_m(1) = 10, rise_m(1) = 2 /"
driver=voussoir-limit case_ bridge_density "&bridge pier_density_kg_m3 = 0 is outside the allowed range 0 < pier_density_kg_m3 <= 1e5" "&bridge $br, pier_density_kg_m3 = 0 /"
# Multi-ring arches: the number of rings, the friction between them, and that friction
# without a second ring.
driver=voussoir-limit case_ bridge_rings_too_many "&bridge n_rings = 7 is outside the allowed range 1 <= n_rings <= 6 \(1: a single ring" "&bridge $br, n_rings = 7 /"
case_ bridge_rings_none_run "&bridge n_rings = 0 is outside the allowed range 1 <= n_rings <= 6" "&bridge $br, n_rings = 0 /
$o"
driver=voussoir-limit case_ bridge_ring_joint_friction_negative "&bridge ring_joint_friction = -0.1 is outside the allowed range ring_joint_friction >= 0" "&bridge $br, n_rings = 2, ring_joint_friction = -0.1 /"
driver=voussoir-limit case_ bridge_ring_joint_friction_one_ring "&bridge ring_joint_friction = 0.3 is outside the allowed range none with n_rings = 1: a single ring has no ring-to-ring joints" "&bridge $br, ring_joint_friction = 0.3 /"

# The fill of &bridge (issue 37): below the extrados, a dispersion angle out of range or
# without a fill, a fill without a live load, a slanting live load.
fl="$br, fill_density_kg_m3 = 2000, fill_level_m = 3.45"
driver=voussoir-limit case_ bridge_fill_below_extrados "&bridge fill_level_m = 2.9 is outside the allowed range fill_level_m >= 2.95 m, the extrados of span 1's crown .*a fill surface below the extrados would cut the ring" "&bridge $br, fill_density_kg_m3 = 2000, fill_level_m = 2.9 /
&load point_load_n(1) = 1000, point_load_x_m(1) = 5 /"
driver=voussoir-limit case_ bridge_dispersion_90 "&bridge dispersion_angle_deg = 90 is outside the allowed range 0 <= dispersion_angle_deg < 90" "&bridge $fl, dispersion_angle_deg = 90 /"
driver=voussoir-limit case_ bridge_dispersion_without_fill "&bridge dispersion_angle_deg = 30 is outside the allowed range 0 without a fill" "&bridge $br, dispersion_angle_deg = 30 /"
driver=voussoir-limit case_ bridge_fill_without_live_load "&bridge fill_density_kg_m3 > 0 needs a live point load in &load" "&bridge $fl /"
driver=voussoir-limit case_ bridge_fill_slanting_load "&load point_load_dir_deg\(1\) = -80: with a fill the live loads stand on its surface" "&bridge $fl /
&load point_load_n(1) = 1000, point_load_x_m(1) = 5, point_load_dir_deg(1) = -80 /"
driver=voussoir-limit case_ bridge_spread_beyond_ends "&load live point load 1 at x = 0.5 m spreads through the fill beyond the ends of the bridge" "&bridge $fl, abutment_width_m = 0.5, dispersion_angle_deg = 80 /
&load point_load_n(1) = 1000, point_load_x_m(1) = 0.5 /"

driver=voussoir-limit case_ bridge_passive_without_phi "&bridge passive_mobilisation = 0.3 is outside the allowed range 0 without fill_friction_deg > 0" "&bridge $fl, passive_mobilisation = 0.3 /"
driver=voussoir-limit case_ bridge_passive_above_1 "&bridge passive_mobilisation = 1.5 is outside the allowed range 0 <= passive_mobilisation <= 1" "&bridge $fl, fill_friction_deg = 35, passive_mobilisation = 1.5 /"
driver=voussoir-limit case_ bridge_phi_without_fill "&bridge fill_friction_deg = 35 is outside the allowed range 0 without a fill" "&bridge $br, fill_friction_deg = 35 /"
driver=voussoir-limit case_ bridge_dispersion_negative "&bridge dispersion_angle_deg = -5 is outside the allowed range 0 <= dispersion_angle_deg < 90" "&bridge $fl, dispersion_angle_deg = -5 /"
# Boussinesq's dispersion (&bridge dispersion = 'boussinesq'): not beside an angle, not
# without a fill or with particles, not with a fill flush with a crown; an unknown rule.
bs="dispersion = 'boussinesq'"
driver=voussoir-limit case_ bridge_boussinesq_with_angle "&bridge dispersion_angle_deg = 30 is outside the allowed range 0 with dispersion = 'boussinesq'" "&bridge $fl, $bs, dispersion_angle_deg = 30 /"
driver=voussoir-limit case_ bridge_boussinesq_without_fill "&bridge fill_density_kg_m3 = 0 is outside the allowed range > 0 with dispersion = 'boussinesq'" "&bridge $br, $bs /"
driver=voussoir-limit case_ bridge_boussinesq_particles "&bridge dispersion = 'boussinesq' is outside the allowed range 'angle' with fill_model = 'particles'" "&bridge $fl, $bs, fill_model = 'particles', fill_particle_size_m = 0.25 /"
driver=voussoir-limit case_ bridge_boussinesq_flush "&bridge fill_level_m = 2.95 is outside the allowed range fill_level_m > 2.95 m with dispersion = 'boussinesq'" "&bridge $br, fill_density_kg_m3 = 2000, fill_level_m = 2.95, $bs /
&load point_load_n(1) = 1000, point_load_x_m(1) = 5 /"
driver=voussoir-limit case_ bridge_dispersion_unknown "&bridge dispersion = 'elastic' is not one of 'angle', 'boussinesq'" "&bridge $fl, dispersion = 'elastic' /"
# The parts' compressive strengths (issue 37).
driver=voussoir-limit case_ bridge_strength_both "&limit compressive_strength_pa gives every interface one strength, and &bridge gives its parts their own" "&bridge $fl, ring_compressive_strength_pa = 5e6 /
&limit compressive_strength_pa = 5e6 /
&load point_load_n(1) = 1000, point_load_x_m(1) = 5 /"
driver=voussoir-limit case_ bridge_strength_negative "&bridge ring_compressive_strength_pa = -1 is outside the allowed range 0 <= ring_compressive_strength_pa <= 1e10 Pa" "&bridge $br, ring_compressive_strength_pa = -1 /"
driver=voussoir-limit case_ bridge_strength_pier_one_span "&bridge pier_compressive_strength_pa = 2000000 is outside the allowed range 0 with one span" "&bridge $br, pier_compressive_strength_pa = 2e6 /"
driver=voussoir-limit case_ bridge_strength_backing_none "&bridge backing_compressive_strength_pa = 2000000 is outside the allowed range 0 without backing" "&bridge $br, backing_compressive_strength_pa = 2e6 /"
# Masonry backing (issue 37).
driver=voussoir-limit case_ bridge_backing_below_springing "&bridge backing_level_m = 0.1 is outside the allowed range backing_level_m > 0.[0-9]* m, the extrados end of the highest springing joint" "&bridge $fl, backing_level_m = 0.1 /"
driver=voussoir-limit case_ bridge_backing_over_crown "&bridge backing_level_m = 3 is outside the allowed range backing_level_m < 2.95 m, the lowest crown's extrados" "&bridge $fl, backing_level_m = 3.0 /"
driver=voussoir-limit case_ bridge_backing_course_alone "&bridge backing_course_m = 0.3 is outside the allowed range 0 without backing" "&bridge $fl, backing_course_m = 0.3 /"
driver=voussoir-limit case_ bridge_backing_negative "&bridge backing_level_m = -1 is outside the allowed range 0 <= backing_level_m <= 300 m" "&bridge $fl, backing_level_m = -1 /"
driver=voussoir-limit case_ bridge_backing_particles "&bridge backing_level_m = 1.5 is outside the allowed range 0 with fill_model = 'particles'" "&bridge $fl, fill_model = 'particles', fill_particle_size_m = 0.5, backing_level_m = 1.5 /"
# The fill as particles (issue 37, item 2(b)).
pt="$fl, fill_model = 'particles'"
driver=voussoir-limit case_ bridge_particles_no_size "&bridge fill_particle_size_m = 0 is outside the allowed range 0 < fill_particle_size_m <= 10 m with fill_model = 'particles'" "&bridge $pt /"
driver=voussoir-limit case_ bridge_particles_unknown_model "&bridge.*fill_model.*sand" "&bridge $fl, fill_model = 'sand', fill_particle_size_m = 0.25 /"
driver=voussoir-limit case_ bridge_particles_without_fill "&bridge fill_density_kg_m3 = 0 is outside the allowed range > 0 with fill_model = 'particles'" "&bridge $br, fill_model = 'particles', fill_particle_size_m = 0.25 /"
driver=voussoir-limit case_ bridge_particles_size_with_columns "&bridge fill_particle_size_m = 0.25 is outside the allowed range 0 with fill_model = 'columns'" "&bridge $fl, fill_particle_size_m = 0.25 /"
driver=voussoir-limit case_ bridge_particles_too_small "&bridge fill_particle_size_m = 0.01 is outside the allowed range fill_particle_size_m >= 0.0455 m: the fill would be cut into about 414000 particles" "&bridge $pt, fill_particle_size_m = 0.01 /"
driver=voussoir-limit case_ bridge_particles_thin_cover "&bridge fill_level_m = 3.1 is outside the allowed range fill_level_m >= 3.2 m with particles: at least half a particle" "&bridge $br, fill_density_kg_m3 = 2000, fill_level_m = 3.1, fill_model = 'particles', fill_particle_size_m = 0.5 /"
driver=voussoir-limit case_ bridge_particles_dispersion "&bridge dispersion_angle_deg = 30 is outside the allowed range 0 with fill_model = 'particles'" "&bridge $pt, fill_particle_size_m = 0.25, dispersion_angle_deg = 30 /"
driver=voussoir-limit case_ bridge_particles_rankine "&bridge fill_friction_deg = 35 is outside the allowed range 0 with fill_model = 'particles'" "&bridge $pt, fill_particle_size_m = 0.25, fill_friction_deg = 35 /"
driver=voussoir-limit case_ bridge_particles_negative_friction "&bridge fill_particle_friction = -0.1 is outside" "&bridge $pt, fill_particle_size_m = 0.25, fill_particle_friction = -0.1 /"

# Vehicles (&vehicle, issue 37) and live loads off a bridge's deck (from x = -1 to 11 m
# here: abutments 1 m wide behind a 10 m span): each names the variable and its value.
pa="path_x0_m = 1, path_x1_m = 9, path_points = 5"
driver=voussoir-limit case_ bridge_vehicle_off_deck_start "&load path_x0_m = -0.5 is outside the allowed range path_x0_m >= -0.4 m: there the vehicle \(2 axles over 1.2 m\) reaches back to x = -1.1 m, off the deck \(the bridge runs from x = -1 to 11 m" "&bridge $br /
&load path_x0_m = -0.5, path_x1_m = 9, path_points = 5 /
&vehicle name = 'lm1_tandem_lane1', effective_width_m = 3 /"
driver=voussoir-limit case_ bridge_vehicle_off_deck_end "&load path_x1_m = 10.8 is outside the allowed range path_x1_m <= 9 m: there the vehicle \(3 axles over 4 m\) reaches to x = 12.8 m, off the deck" "&bridge $br /
&load path_x0_m = 3, path_x1_m = 10.8, path_points = 5 /
&vehicle axle_load_kn = 50, 100, 50, axle_spacing_m = 2, 2 /"
driver=voussoir-limit case_ bridge_load_path_off_deck "&load path_x0_m = -2 is outside the allowed range path_x0_m >= -1 m: there the live load reaches back to x = -2 m, off the deck" "&bridge $br /
&load point_load_n(1) = 1000, $pa, path_x0_m = -2 /"
driver=voussoir-limit case_ bridge_axles_off_deck "&load live point loads with axle_spacing_m stand from x = 10 to 11.5 m, off the deck \(the bridge runs from x = -1 to 11 m\)" "&bridge $br /
&load point_load_n(1) = 1000, point_load_x_m(1) = 10, axle_spacing_m(1) = 1.5 /"
case_ bridge_vehicle_standing_off_deck "&vehicle first_axle_x_m = 10.5 is outside the allowed range -1 m <= first_axle_x_m <= 9.8 m: its axles stand from x = 10.5 to 11.7 m, off the deck" "&bridge $br /
&load $pa /
&vehicle name = 'lm1_tandem_lane1', first_axle_x_m = 10.5 /
$o"
driver=voussoir-limit case_ vehicle_unknown_name "&vehicle name = 'lorry' is not a named vehicle \('lm1_tandem_lane1'\) and gives no axles" "&bridge $br /
&load $pa /
&vehicle name = 'lorry' /"
driver=voussoir-limit case_ vehicle_spacings "&vehicle gives 3 axles \(axle_load_kn\) and 1 spacings \(axle_spacing_m\): give 2" "&bridge $br /
&load $pa /
&vehicle axle_load_kn = 50, 100, 50, axle_spacing_m = 2 /"
driver=voussoir-limit case_ vehicle_named_with_other_axles "&vehicle name = 'lm1_tandem_lane1' is a named vehicle with its own axles" "&bridge $br /
&load $pa /
&vehicle name = 'lm1_tandem_lane1', axle_load_kn = 100, 100, axle_spacing_m = 1.2 /"
driver=voussoir-limit case_ vehicle_and_live_load "&vehicle and a live point load of &load: the vehicle is the live load" "&bridge $br /
&load point_load_n(1) = 1000, $pa /
&vehicle axle_load_kn = 100 /"
driver=voussoir-limit case_ vehicle_without_path "&vehicle needs a &load path to move it over" "&bridge $br /
&vehicle axle_load_kn = 100 /"
driver=voussoir-limit case_ vehicle_narrow_effective_width "&vehicle effective_width_m = 0.5 is outside the allowed range 0 \(the whole axle on the strip\) or effective_width_m >= width_m = 1 m" "&bridge $br /
&load $pa /
&vehicle axle_load_kn = 100, effective_width_m = 0.5 /"
driver=voussoir-limit case_ vehicle_axle_load_zero_kn "&vehicle axle_load_kn\(1\) = -5 is outside the allowed range 0 < axle_load_kn <= 1e5 kN" "&bridge $br /
&load $pa /
&vehicle axle_load_kn = -5 /"

# Patches, load cases and partial factors (&load point_load_patch_m, point_load_case,
# &load_cases; issue 37, item 3): each names the variable and its value.
driver=voussoir-limit case_ patch_negative "&load point_load_patch_m\(1\) = -0.3 is outside the allowed range 0 <= point_load_patch_m <= 100 m" "&bridge $br /
&load point_load_n(1) = 1000, point_load_patch_m(1) = -0.3, $pa /"
driver=voussoir-limit case_ patch_off_deck "&load path_x0_m = -0.8 is outside the allowed range path_x0_m >= -0.7 m: there the live load reaches back to x = -1.1 m, off the deck" "&bridge $br /
&load point_load_n(1) = 1000, point_load_patch_m(1) = 0.6, path_x0_m = -0.8, path_x1_m = 9, path_points = 5 /"
driver=voussoir-limit case_ patch_dead "&load point_load_patch_m\(1\) = 0.3 is outside the allowed range point_load_patch_m = 0 for a dead load" "&bridge $br /
&load point_load_n(1) = 1000, point_load_live(1) = .false., point_load_x_m(1) = 5, point_load_y_m(1) = 2.9, point_load_patch_m(1) = 0.3 /"
driver=voussoir-limit case_ load_case_gamma_q_zero "&load_cases gamma_q\(1\) = 0 is outside the allowed range 0 < gamma_q <= 10" "&bridge $br /
&load point_load_n(1) = 1000, $pa /
&load_cases name(1) = 'axle', gamma_q(1) = 0 /"
driver=voussoir-limit case_ load_case_gamma_g_negative "&load_cases gamma_g\(1\) = -1 is outside the allowed range 0 < gamma_g <= 10" "&bridge $br /
&load point_load_n(1) = 1000, $pa /
&load_cases name(1) = 'axle', gamma_g(1) = -1 /"
driver=voussoir-limit case_ load_case_without_loads "&load_cases case 2 'tandem' has no live load: give it a live point load of &load with point_load_case\(j\) = 2" "&bridge $br /
&load point_load_n(1) = 1000, point_load_case(1) = 1, $pa /
&load_cases name(1) = 'axle', name(2) = 'tandem' /"
driver=voussoir-limit case_ load_case_beyond "&load point_load_case\(1\) = 3: &load_cases has cases 1..2" "&bridge $br /
&load point_load_n(1) = 1000, point_load_case(1) = 3, $pa /
&load_cases name(1) = 'axle', name(2) = 'tandem' /"
driver=voussoir-limit case_ load_case_without_cases "&load point_load_case\(1\) = 1 names a load case, but the file has no &load_cases" "&bridge $br /
&load point_load_n(1) = 1000, point_load_case(1) = 1, $pa /"
driver=voussoir-limit case_ load_case_unnamed "&load_cases gives a factor of case 1 but no name\\(1\\)" "&bridge $br /
&load point_load_n(1) = 1000, $pa /
&load_cases gamma_q(1) = 1.5 /"

# An unknown option is named, then the usage; exit 2 (issue 26).
for d in voussoir-run voussoir-limit voussoir-sweep; do
  out=$("$bin/$d" --foo x.nml 2>&1); rc=$?
  if [[ $rc -eq 2 ]] && grep -q "^$d: unknown option '--foo'\$" <<<"$out" && grep -q "^usage: " <<<"$out"; then
    passed=$((passed+1)); echo "PASS  $d unknown option"
  else failed=$((failed+1)); echo "FAIL  $d unknown option (exit $rc): $out"; fi
done

# A missing input file.
out=$("$bin/voussoir-run" no_such_input.nml 2>&1); rc=$?
if [[ $rc -ne 0 ]] && grep -q "no_such_input.nml" <<<"$out"; then passed=$((passed+1)); echo "PASS  missing_input"
else failed=$((failed+1)); echo "FAIL  missing_input: $out"; fi

echo "$passed passed, $failed failed"
[[ $failed -eq 0 ]]
