"""The test generator's own time step, checked against a finer one (issue 23, item 7).

    python bench/diagnosis_generator_dt.py BIN_DIR [SLUG ...]

For each stored outcome map (postproc/tests/data/replay/maps, made at dt 5e-4 s), remakes
the map at dt 2.5e-4 s and prints, per pair, the first collapse over the onset at both
steps and their relative difference: how much of what the replay tests call the truth is
the generator's discretisation.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "postproc"), str(ROOT / "postproc" / "tests")]

from independent_campaigns import Truth  # noqa: E402
from replay_maps import MAP_DIR, MAP_TRUTHS, first_collapse_ratio, load_map, outcome_map  # noqa: E402


def main() -> int:
    bin_dir = Path(sys.argv[1])
    slugs = sys.argv[2:] or ["nothing", "friction_0.43"]
    print(f"{'truth':28s} {'pair':16s} {'dt 5e-4':>8s} {'dt 2.5e-4':>10s} {'change':>8s}")
    for slug in slugs:
        stored = load_map(MAP_DIR / f"{slug}.json")
        t0 = time.time()
        fine = outcome_map(MAP_TRUTHS[slug] if slug in MAP_TRUTHS else Truth(), bin_dir, dt_s=2.5e-4,
                           log=lambda m: None)
        for a, b in zip(stored["pairs"], fine["pairs"]):
            ra, rb = first_collapse_ratio(a), first_collapse_ratio(b)
            print(f"{slug:28s} {a['specimen_id'] + ' ' + format(a['frequency_hz'], 'g') + ' Hz':16s} {ra:8.3f} "
                  f"{rb:10.3f} {100 * (rb - ra) / ra:+7.1f} %")
        print(f"  ({time.time() - t0:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
