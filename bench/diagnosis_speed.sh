#!/usr/bin/env bash
# Speed of the diagnosis (issue 6 goal: under 10 minutes on this 2-core machine) on a
# campaign of 4 arches x 3 frequencies with about 6 tests each, written by the
# simulator (voussoir_post.synthetic, with contact insets of 3 mm hidden in it).
# Prints the time of `voussoir-diagnose run` alone (the campaign is written first).
#   bash bench/diagnosis_speed.sh [NP=2]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
np=${1:-2}
py=python3; [[ -x "$root/.venv/bin/python" ]] && py="$root/.venv/bin/python"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$py" - "$root" "$work/campaign" <<'PY'
import sys
sys.path.insert(0, sys.argv[1] + "/postproc")
from voussoir_post.synthetic import SyntheticSpecimen, Truth, write_synthetic_campaign
specimens = (SyntheticSpecimen("B180", 180.0, 15, (0.8, 1.0, 1.25)),
             SyntheticSpecimen("B156", 156.0, 13, (1.0, 1.25, 2.0)),
             SyntheticSpecimen("B132", 132.0, 11, (1.25, 1.6, 2.5)),
             SyntheticSpecimen("B118", 118.0, 10, (2.0, 2.5, 3.0)))
n = write_synthetic_campaign(sys.argv[2], Truth(effect="contact_edges", inset_m=0.003), sys.argv[1] + "/build/drivers",
                             specimens=specimens, start_fraction=0.65, step_fraction=0.05, seed=11)
print(f"campaign: {len(specimens)} arches x 3 frequencies, {sum(n.values())} tests "
      f"({sum(n.values()) / len(n):.1f} per pair)")
PY
start=$(date +%s.%N)
"$py" -m voussoir_post.diagnose_cli run "$work/campaign" --out "$work/out" --np "$np" \
      --bin-dir "$root/build/drivers" | tail -n 1
end=$(date +%s.%N)
"$py" -c "print(f'diagnosis wall time on $np ranks: {$end - $start:.1f} s (goal 600 s)')"
