#!/usr/bin/env bash
# Run one input file with the driver its name calls for, in a scratch folder, and check
# that it succeeds with the answer the driver promises and the reference answer its
# '! reference:' line names (tests/input_reference.py derives it independently).
#   run_input.sh INPUT.nml BIN_DIR WORK_DIR
set -euo pipefail
input=$(readlink -f "$1"); bin=$(readlink -f "$2"); work=$3; python=${4:-python3}
rm -rf "$work" && mkdir -p "$work" && cd "$work"
name=$(basename "$input" .nml)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
case "$name" in
  sweep_*)
    mpirun --oversubscribe -np 2 "$bin/voussoir-sweep" "$input" | tee output.txt ;;
  limit_*)
    "$bin/voussoir-limit" "$input" | tee output.txt
    "$bin/voussoir-limit" "$input" --json | python3 -c 'import json,sys; d=json.load(sys.stdin); assert "lambda_pos" in d' ;;
  bridge_*)  # a bridge is assessed by its limit analysis (docs/bridges.md)
    "$bin/voussoir-limit" "$input" | tee output.txt
    "$bin/voussoir-limit" "$input" --json | python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["assembly"] == "bridge" and d["load_factor"] > 0'
    if grep -q '^&motion' "$input"; then  # and shaken, where it gives a motion
      "$bin/voussoir-run" "$input" | tee run_output.txt
      first=$(head -n 1 run_output.txt | cut -d' ' -f1)
      [[ "$first" == "stood;" || "$first" == "collapsed" ]] || { echo "voussoir-run: first word '$first'"; exit 1; }
      result=$(sed -n 's/.*; result \(.*\)$/\1/p' run_output.txt | head -n 1)
      [[ -s "$result" ]] || { echo "no result file $result"; exit 1; }
    fi ;;
  *)
    "$bin/voussoir-run" "$input" | tee output.txt
    first=$(head -n 1 output.txt | cut -d' ' -f1)
    if [[ "$first" != "stood;" && "$first" != "collapsed" ]]; then
      echo "first word is '$first', not stood/collapsed"; exit 1
    fi
    if grep -Eq '(^|[ (=])\.[0-9]' output.txt; then  # '.018 mm' reads badly: '0.018 mm'
      echo "a number without its leading zero: $(grep -Eo '(^|[ (=])\.[0-9]+' output.txt | head -n 1)"; exit 1
    fi
    result=$(sed -n 's/.*; result \(.*\)$/\1/p' output.txt | head -n 1)
    [[ -s "$result" ]] || { echo "no result file $result"; exit 1; } ;;
esac
case "$name" in
  limit_*|bridge_*) ;;  # their numbers: tests/limit/check_limit.py
  *) "$python" "$(dirname "$0")/input_reference.py" "$input" "$bin" "$PWD" ;;
esac
