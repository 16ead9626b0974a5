#!/usr/bin/env bash
# A full disk while a result is written: voussoir-run and voussoir-sweep must fail with a
# clear message (exit 1, no crash), leave no half-written file, and leave the previous
# result of the same name byte for byte as it was.
#   disk_full.sh BIN_DIR WORK_DIR
# The disk is a small tmpfs (mounting it needs root, as CI and the set-up have), filled
# up after a first, successful run.
set -uo pipefail
bin=$(readlink -f "$1"); work=$2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
failures=0
check() {  # check CONDITION-EXIT-CODE DESCRIPTION
  if [[ $1 -eq 0 ]]; then echo "PASS  $2"; else echo "FAIL  $2"; failures=$((failures + 1)); fi
}
umount "$work/disk" 2>/dev/null
rm -rf "$work" && mkdir -p "$work/disk"
if ! mount -t tmpfs -o size=1m tmpfs "$work/disk"; then
  echo "FAIL: cannot mount a small tmpfs at $work/disk (this test needs root)"; exit 1
fi
trap 'cd /; umount "$work/disk"' EXIT
cd "$work/disk"

fill_disk() {  # leave about $1 KiB free
  rm -f filler
  local free_kib
  free_kib=$(df -k --output=avail . | tail -n 1)
  dd if=/dev/zero of=filler bs=1K count=$((free_kib - $1)) status=none 2>/dev/null
}

# --- voussoir-run
cat > run.nml <<'NML'
&arch embrace_deg = 156, n_voussoirs = 13 /
&motion waveform = 'afd', frequency_hz = 1.25, amplitude_m = 0.02, rest_s = 0.5 /
&output file = 'run.h5' /
NML
"$bin/voussoir-run" run.nml > first.txt 2>&1
check $? "voussoir-run writes run.h5 on an empty disk"
before=$(md5sum run.h5 | cut -d' ' -f1)
fill_disk 32
"$bin/voussoir-run" run.nml > second.txt 2>&1
code=$?
cat second.txt
[[ $code -eq 1 ]]; check $? "voussoir-run on a full disk exits with 1 (got $code)"
grep -q "run.h5: not written" second.txt; check $? "the message names the file and says it was not written"
grep -q "left as it was" second.txt; check $? "the message says the earlier file is kept"
[[ "$(md5sum run.h5 | cut -d' ' -f1)" == "$before" ]]; check $? "the earlier run.h5 is byte for byte unchanged"
[[ ! -e run.h5.part ]]; check $? "no run.h5.part is left behind"
rm -f filler run.h5

# --- voussoir-sweep: a finished sweep is rewritten when rerun; the update fails
cat > sweep.nml <<'NML'
&arch embrace_deg = 156, n_voussoirs = 13 /
&motion waveform = 'afd', rest_s = 0.5 /
&output file = 'sweep.h5' /
&sweep mode = 'grid', frequencies_hz = 2.0, amplitudes_m = 0.005, 0.05 /
NML
mpirun --oversubscribe -np 2 "$bin/voussoir-sweep" sweep.nml > first.txt 2>&1
check $? "voussoir-sweep writes sweep.h5 and sweep.csv on an empty disk"
before_h5=$(md5sum sweep.h5 | cut -d' ' -f1)
before_csv=$(md5sum sweep.csv | cut -d' ' -f1)
fill_disk 4

mpirun --oversubscribe -np 2 "$bin/voussoir-sweep" sweep.nml > second.txt 2>&1
code=$?
cat second.txt
[[ $code -ne 0 && $code -lt 128 ]]; check $? "voussoir-sweep on a full disk fails without a crash (exit $code)"
grep -q "sweep.h5: not written" second.txt; check $? "the message names the sweep file and says it was not written"
[[ "$(md5sum sweep.h5 | cut -d' ' -f1)" == "$before_h5" ]]; check $? "the earlier sweep.h5 is byte for byte unchanged"
[[ "$(md5sum sweep.csv | cut -d' ' -f1)" == "$before_csv" ]]; check $? "the earlier sweep.csv is unchanged"
[[ ! -e sweep.h5.part && ! -e sweep.csv.part ]]; check $? "no .part file is left behind"

echo "$failures failure(s)"
[[ $failures -eq 0 ]]
