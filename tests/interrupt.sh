#!/usr/bin/env bash
# Ctrl-C or SIGTERM during a long voussoir-run: the run ends at the next step, writes
# what it computed (whole, marked interrupted), says so, and exits 128 + the signal.
#   interrupt.sh BIN_DIR WORK_DIR PYTHON
set -uo pipefail
bin=$(readlink -f "$1"); work=$2; py=$3
rm -rf "$work"; mkdir -p "$work" && cd "$work"
failed=0
for sig in TERM INT; do
  printf "&motion waveform = 'afd', frequency_hz = 1.0, amplitude_m = 0.005, duration_s = 3000 /\n&output file = 'long_$sig.h5' /\n" > long_$sig.nml
  "$bin/voussoir-run" long_$sig.nml > out_$sig.txt 2>&1 &
  pid=$!
  sleep 1.5
  kill -$sig $pid
  wait $pid; rc=$?
  want=$((128 + $(kill -l $sig)))
  if [[ $rc -ne $want ]] || ! grep -q "^interrupted at t = .* by signal $(kill -l $sig): the result holds the run" out_$sig.txt \
     || [[ -e long_$sig.h5.part ]]; then
    echo "FAIL  SIG$sig: exit $rc (want $want): $(cat out_$sig.txt)"; failed=1; continue
  fi
  # The file is whole, readable by the postprocessor, and its record stops where the run did.
  if "$py" - long_$sig.h5 "$(kill -l $sig)" <<'PY'
import sys
from voussoir_post.readers.results import read_run
r = read_run(sys.argv[1])
ok = r.interrupted_by_signal == int(sys.argv[2]) and 0 < r.time_s[-1] < 3000 and r.n_steps == len(r.step_time_s)
ok = ok and abs(r.time_s[-1] - r.step_time_s[-1]) < 1e-9 and not r.collapsed
print(f"interrupted by {r.interrupted_by_signal} at t = {r.time_s[-1]:.3f} s, {r.n_steps} steps")
sys.exit(0 if ok else 1)
PY
  then echo "PASS  SIG$sig"; else echo "FAIL  SIG$sig: the file"; failed=1; fi
done
exit $failed
