"""The reference answer of an input file, checked against what its run printed and wrote.

    input_reference.py INPUT.nml BIN_DIR RUN_DIR

Every input/ file (but the limit ones, whose numbers tests/limit/check_limit.py checks)
carries one line `! reference: RULE` naming an answer derived independently of the
dynamic code; this script verifies the rule's premise independently and then the run:

  below_capacity   the peak of the commanded afd table acceleration (the closed form of
                   docs/measured_data.md, differentiated numerically here) stays below
                   the static capacity lambda g of the limit analysis (voussoir-limit on
                   the same &arch): no mechanism can open, so the run must print `stood`.
  above_min_thickness  the ring is thicker than its minimum thickness (voussoir-limit's
                   exact discrete value) and the table is at rest: it must stand.
  ramp_capacity    a slow ramp of horizontal load collapses the arch once the load passes
                   lambda g, and before 1.15 lambda g (the fall after the onset).
  uplift           a block of half-width b and half-height h lifts off when the table
                   acceleration passes g b / h (DESIGN.md): the commanded peak (afd), or
                   record_scale times the peak of the accelerogram's samples (read here
                   from its CSV), exceeds it, and the block must have rotated by more
                   than 1 mrad.
  static_bound     a sweep: no threshold can lie below the static capacity, so the peak
                   commanded acceleration at every threshold amplitude is >= lambda g
                   (less 1 %, the search tolerance).
  lmgc90           a sweep of the seed arches: thresholds within 10 % of the seed paper's
                   LMGC90 (uncalibrated) column, for the arches whose geometry is known.
  none: WHY        no independent answer exists (the reason is stated); the run must only
                   succeed.
"""

from __future__ import annotations

import csv
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
PAPER = ROOT / "data" / "seed_2013" / "paper_dem_results.csv"
G = 9.81


def parse(text: str) -> dict:
    """{group: {name: value}} of a namelist (numbers and quoted strings; enough here)."""
    groups = {}
    for m in re.finditer(r"&(\w+)(.*?)\n\s*/", re.sub(r"!.*", "", text), re.S):
        values = {}
        for name, value in re.findall(r"(\w+)\s*=\s*('[^']*'|[^,=\n]+(?:,\s*[-+\d.eE]+)*)", m.group(2)):
            value = value.strip().rstrip(",")
            if value.startswith("'"):
                values[name.lower()] = value.strip("'")
            else:
                try:
                    nums = [float(v) for v in value.split(",") if v.strip()]
                except ValueError:  # a logical (.true.) or a word: kept as text
                    values[name.lower()] = value
                    continue
                values[name.lower()] = nums[0] if len(nums) == 1 else nums
        groups[m.group(1).lower()] = values
    return groups


def afd_peak_accel(f_hz: float, amp_m: float, n_attack=1, n_full=1, n_decay=1) -> float:
    """Peak |d2u/dt2| of the commanded afd displacement, on a fine grid."""
    T = 1.0 / f_hz
    ta, tf, td = n_attack * T, n_full * T, n_decay * T
    t = np.linspace(0.0, ta + tf + td, 200001)
    e = np.where(t < ta, np.sin(np.pi * t / (2 * ta)) ** 2,
                 np.where(t < ta + tf, 1.0, np.cos(np.pi * (t - ta - tf) / (2 * td)) ** 2))
    u = amp_m * e * np.sin(2 * np.pi * f_hz * t)
    a = np.gradient(np.gradient(u, t), t)
    return float(np.abs(a[2:-2]).max())


def limit_of(arch: dict, bin_dir: Path, work: Path) -> dict:
    nml = work / "reference_limit.nml"
    nml.write_text("&arch " + ", ".join(f"{k} = {v!r}" if isinstance(v, str) else f"{k} = {v}"
                                        for k, v in arch.items() if k in ("embrace_deg", "n_voussoirs", "r_ext_m",
                                                                          "thickness_m", "friction")) + " /\n")
    out = subprocess.run([str(bin_dir / "voussoir-limit"), str(nml), "--json"], capture_output=True, text=True,
                         check=True)
    return json.loads(out.stdout)


def arch_with_defaults(arch: dict) -> dict:
    full = {"embrace_deg": 156.0, "n_voussoirs": 13, "r_ext_m": 0.508, "thickness_m": 0.071, "friction": 0.5}
    full.update(arch)
    full["n_voussoirs"] = int(full["n_voussoirs"])
    return full


def main() -> int:
    nml_path, bin_dir, run_dir = Path(sys.argv[1]), Path(sys.argv[2]), Path(sys.argv[3])
    text = nml_path.read_text()
    m = re.search(r"^! reference: (\S+)(.*)$", text, re.M)
    if not m:
        print(f"FAIL: {nml_path} has no '! reference: RULE' line (see tests/input_reference.py)")
        return 1
    rule = m.group(1).rstrip(":")
    g = parse(text)
    arch = arch_with_defaults(g.get("arch", {}))
    motion = g.get("motion", {})
    printed = (run_dir / "output.txt").read_text() if (run_dir / "output.txt").exists() else ""
    first = printed.split()[0] if printed.split() else ""
    checks: list[tuple[bool, str]] = []

    if rule == "none":
        print(f"reference: none{m.group(2)}")
        return 0
    if rule == "below_capacity":
        peak = afd_peak_accel(motion["frequency_hz"], motion["amplitude_m"], int(motion.get("n_attack", 1)),
                              int(motion.get("n_full", 1)), int(motion.get("n_decay", 1)))
        lam = limit_of(arch, bin_dir, run_dir)
        cap = min(lam["lambda_pos"], lam["lambda_neg"]) * G
        checks.append((peak < cap, f"premise: peak table acceleration {peak:.3f} m/s2 < lambda g = {cap:.3f} m/s2"))
        checks.append((first == "stood;", f"the run stood (printed '{first}')"))
    elif rule == "above_min_thickness":
        lam = limit_of(arch, bin_dir, run_dir)
        ratio = arch["thickness_m"] / arch["r_ext_m"]
        checks.append((ratio > lam["min_thickness_ratio_ext"] and float(motion.get("amplitude_m", 0)) == 0.0,
                       f"premise: t/R_ext = {ratio:.4f} > minimum {lam['min_thickness_ratio_ext']:.4f}, table at rest"))
        checks.append((first == "stood;", f"the run stood (printed '{first}')"))
    elif rule == "ramp_capacity":
        lam = limit_of(arch, bin_dir, run_dir)
        cap = lam["lambda_pos"] * G
        mt = re.search(r"collapsed at ([\d.]+) s", printed)
        load = motion["ramp_rate_m_s3"] * float(mt.group(1)) if mt else math.nan
        checks.append((mt is not None, "the ramp collapsed the arch"))
        checks.append((cap <= load <= 1.15 * cap,
                       f"load at collapse {load:.3f} m/s2 within [lambda g, 1.15 lambda g] = [{cap:.3f}, {1.15 * cap:.3f}]"))
    elif rule == "uplift":
        blocks = (nml_path.parent / g["arch"]["polygon_file"]).read_text()
        free = re.search(r"block free\n((?:\s*[-\d.]+\s+[-\d.]+\n)+)", blocks).group(1).split()
        xy = np.array(free, float).reshape(-1, 2)
        b, h = (xy[:, 0].max() - xy[:, 0].min()) / 2, (xy[:, 1].max() - xy[:, 1].min()) / 2
        if motion.get("waveform") == "accelerogram":
            rows = csv.DictReader(line for line in open(nml_path.parent / motion["record_file"])
                                  if not line.startswith("#"))
            peak = float(motion.get("record_scale", 1.0)) * max(abs(float(r["accel_m_s2"])) for r in rows)
        else:
            peak = afd_peak_accel(motion["frequency_hz"], motion["amplitude_m"])
        result = re.search(r"result (\S+)", printed).group(1)
        with h5py.File(run_dir / result, "r") as f:
            rotation = float(np.abs(f["bodies/position"][:, 0, 2]).max())
        checks.append((peak > G * b / h, f"premise: peak {peak:.3f} m/s2 > g b/h = {G * b / h:.3f} m/s2"))
        checks.append((rotation > 1e-3, f"the block rocked: peak rotation {rotation:.4f} rad > 1 mrad"))
    elif rule in ("static_bound", "lmgc90"):
        out = g["output"]["file"]
        rows = list(csv.DictReader(line for line in open(run_dir / out.replace(".h5", ".csv"))
                                   if not line.startswith("#")))
        sweep = g["sweep"]
        embr = np.atleast_1d(sweep.get("embrace_list_deg", [arch["embrace_deg"]]))
        nv = np.atleast_1d(sweep.get("n_voussoirs_list", [arch["n_voussoirs"]]))
        for r in rows:
            s = int(r["param_set"])
            set_arch = dict(arch, embrace_deg=float(embr[min(s, embr.size - 1)]),
                            n_voussoirs=int(nv[min(s, nv.size - 1)]))
            f_hz, thr = float(r["frequency_hz"]), float(r["threshold_m"])
            if rule == "static_bound":
                cap = limit_of(set_arch, bin_dir, run_dir)["lambda_pos"] * G
                acc = afd_peak_accel(f_hz, thr, int(motion.get("n_attack", 1)), int(motion.get("n_full", 1)),
                                     int(motion.get("n_decay", 1)))
                checks.append((acc >= 0.99 * cap, f"set {s}, {f_hz:g} Hz: threshold {1e3 * thr:.1f} mm "
                                                  f"(peak {acc:.2f} m/s2) >= lambda g = {cap:.2f} m/s2"))
            else:
                sid = f"A{int(round(set_arch['embrace_deg']))}"
                paper = {row["specimen_id"]: row for row in csv.DictReader(
                    line for line in open(PAPER) if not line.startswith("#")) if row["model"] == "uncalibrated"}
                known = m.group(2).split()
                if sid not in known:
                    continue
                ref = float(paper[sid]["amplitude_m"])
                checks.append((abs(thr - ref) <= 0.10 * ref, f"{sid}, {f_hz:g} Hz: threshold {1e3 * thr:.1f} mm "
                                                             f"within 10 % of LMGC90's {1e3 * ref:.0f} mm"))
    else:
        print(f"FAIL: unknown reference rule '{rule}'")
        return 1
    for good, what in checks:
        print(("PASS  " if good else "FAIL  ") + what)
    return 0 if checks and all(c[0] for c in checks) else 1


if __name__ == "__main__":
    sys.exit(main())
