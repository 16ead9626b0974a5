#!/usr/bin/env bash
# The main job: the seed paper's 156-degree wooden arch shaken at 1.25 Hz with the
# amplitude that brought it down on the table (46 mm), and with the amplitude at which
# the paper's uncalibrated LMGC90 model fell (66 mm). Results go to results/.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
bash scripts/setup.sh
mkdir -p results
bin=build/drivers
for amplitude_mm in 46 66; do
  sed -e "s/amplitude_m = 0.046/amplitude_m = 0.0$amplitude_mm/" \
      -e "s/file = 'seed_156.h5'/file = 'results\/seed_156_A${amplitude_mm}mm.h5'/" \
      input/seed_156.nml > "results/seed_156_A${amplitude_mm}mm.nml"
  echo "[main] 156-degree arch, 1.25 Hz, A = $amplitude_mm mm:"
  "$bin/voussoir-run" "results/seed_156_A${amplitude_mm}mm.nml"
done
if [[ -x .venv/bin/voussoir-post ]]; then
  .venv/bin/voussoir-post history results/seed_156_A66mm.h5 >/dev/null || true
  .venv/bin/voussoir-post sequence results/seed_156_A66mm.h5 >/dev/null || true
fi
echo "[main] results in $root/results/"
