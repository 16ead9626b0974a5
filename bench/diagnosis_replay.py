"""The replay bank of the diagnosis's tests, and the paired check of a change of it.

    python bench/diagnosis_replay.py BIN_DIR OUT_DIR [--store]

Builds the simulation bank of the test arches (postproc/tests/independent_campaigns.py
ARCHES, all their frequencies) with the executables of BIN_DIR into OUT_DIR, then replays
the campaigns of every stored LMGC90 truth (postproc/tests/data/lmgc90, as the tests do)
on the stored bank and on the new one, and prints, per truth and in all, how often each
is right (truth in the 90 % set, and no wrong cause named), the exact McNemar test of the
paired draws (a change of the kernel's last bits is judged better or no worse, not "the
same seed passes") and whether the tests' judgement (test_diagnosis_lmgc90.judge) still
holds on the new bank. With --store the new bank replaces the stored one only when the
judgement holds and it is no worse.
"""

from __future__ import annotations

import shutil
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "postproc"), str(ROOT / "postproc" / "tests")]

from voussoir_post.diagnosis.bank import Bank, build_bank, load_banks  # noqa: E402
from voussoir_post.diagnosis.rates import mcnemar  # noqa: E402
from voussoir_post.diagnosis.settings import DiagnosisSettings  # noqa: E402

from independent_campaigns import ARCHES  # noqa: E402
from lmgc90_campaigns import stored_truths  # noqa: E402
from test_diagnosis_lmgc90 import DRAWS, judge, outcomes  # noqa: E402

DATA = ROOT / "postproc" / "tests" / "data" / "replay"


def arches_bank(bin_dir: Path, out: Path) -> Bank:
    specs = {a.specimen_id: a.specimen() for a in ARCHES}
    freqs = {a.specimen_id: list(a.frequencies_hz) for a in ARCHES}
    settings = DiagnosisSettings(bin_dir=bin_dir, n_ranks=2, log=print)
    return build_bank(specs, freqs, {k: (1, 1, 1) for k in specs}, settings, out, out / "work")


def stored() -> Bank:
    return load_banks(DATA / "bank")


def right(o: dict) -> bool:
    return not o["wrong_named"] and (o["in_set"] if o["truth"] != "outside" else not o["named"])


def main() -> int:
    bin_dir, out = Path(sys.argv[1]), Path(sys.argv[2])
    t0 = time.time()
    new = arches_bank(bin_dir, out)
    print(f"bank: {new.searches} threshold searches in {time.time() - t0:.0f} s")
    before_all, after_all, new_outcomes = [], [], []
    print(f"{'truth':44s} {'stored':>8s} {'new':>8s} {'better':>7s} {'worse':>6s} {'p':>6s}")
    for truth in stored_truths():
        old_o, new_o = outcomes(stored(), [truth]), outcomes(new, [truth])
        a, b = [right(o) for o in old_o], [right(o) for o in new_o]
        m = mcnemar(a, b)
        print(f"{truth['slug']:44s} {sum(a):5d}/{len(a)} {sum(b):5d}/{len(b)} {m['better']:7d} {m['worse']:6d} "
              f"{m['p_value']:6.3f}")
        before_all += a
        after_all += b
        new_outcomes += new_o
    m = mcnemar(before_all, after_all)
    worse = m["worse"] > m["better"] and m["p_value"] < 0.05
    print(f"{'all':44s} {sum(before_all):5d}/{len(before_all)} {sum(after_all):5d}/{len(after_all)} "
          f"{m['better']:7d} {m['worse']:6d} {m['p_value']:6.3f}  -> the new bank is "
          f"{'worse' if worse else 'better or no worse'} ({DRAWS} campaigns a truth)")
    failed = judge(new_outcomes)
    print("the tests' judgement on the new bank: " + ("holds" if not failed else "FAILS: " + "; ".join(failed)))
    if "--store" in sys.argv:
        if failed or worse:
            print("not stored: the new bank fails the judgement or is worse")
            return 1
        (DATA / "bank").mkdir(parents=True, exist_ok=True)
        for old in (DATA / "bank").glob("*.json"):
            old.unlink()
        for f in out.glob("*.json"):
            shutil.copy(f, DATA / "bank" / (f.name.split("-")[0] + ".json"))
        print(f"stored in {DATA / 'bank'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
