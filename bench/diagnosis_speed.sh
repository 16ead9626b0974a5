#!/usr/bin/env bash
# Speed of the diagnosis on a campaign of 4 arches x 3 frequencies, written by the
# independent test generator (postproc/tests/independent_campaigns.py) with two causes
# hidden in it (4 mm chamfers and friction 0.42). Prints the time of `voussoir-diagnose
# run` alone (the campaign is written first; the simulation bank is made from nothing,
# about 141 threshold searches per specimen and frequency), then the time of a second
# run on the same campaign, whose bank is cached.
#   bash bench/diagnosis_speed.sh [NP=2]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
np=${1:-2}
py=python3; [[ -x "$root/.venv/bin/python" ]] && py="$root/.venv/bin/python"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$py" - "$root" "$work/campaign" <<'PY'
import sys
from pathlib import Path
sys.path.insert(0, sys.argv[1] + "/postproc/tests")
from independent_campaigns import Arch, Truth, write_campaign
arches = (Arch("B180", 180.0, 15, (0.8, 1.0, 1.25)),
          Arch("B156", 156.0, 13, (1.0, 1.25, 2.0)),
          Arch("B132", 132.0, 11, (1.25, 1.6, 2.5)),
          Arch("B118", 118.0, 10, (2.0, 2.5, 3.0)))
n = write_campaign(Path(sys.argv[2]), Truth(chamfer_m=0.004, friction=0.42), Path(sys.argv[1]) / "build/drivers",
                   arches=arches, seed=5)
print(f"campaign: {len(arches)} arches x 3 frequencies, {sum(n.values())} tests "
      f"({sum(n.values()) / len(n):.1f} per pair)")
PY
start=$(date +%s.%N)
"$py" -m voussoir_post.cli.diagnose run "$work/campaign" --out "$work/out" --np "$np" \
      --bin-dir "$root/build/drivers" | tail -n 1
end=$(date +%s.%N)
grep -o "simulation bank of .* s\." "$work/out/report.md"
"$py" -c "print(f'diagnosis wall time on $np ranks, bank made: {$end - $start:.1f} s')"
start=$(date +%s.%N)
"$py" -m voussoir_post.cli.diagnose run "$work/campaign" --out "$work/again" --np "$np" \
      --bin-dir "$root/build/drivers" | tail -n 1
end=$(date +%s.%N)
"$py" -c "print(f'diagnosis wall time on $np ranks, bank cached: {$end - $start:.1f} s')"
