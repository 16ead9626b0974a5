"""The fits of bench/ida_dt_convergence.sh (not a test): for each case (a time step, or
the main job's with a tighter NLGS tolerance) the IDA files of its model samples
(``ida_dt_<tag>_<sample>.h5`` in --dir), the interval-censored lognormal of PGA over
their rows (the fragility's own fit, earthquake/fragility.py), its median and beta
with a 90 % band, and against the reference case (the smallest dt at the default
tolerance) the median ratio and the beta difference with a *paired* band: every
bootstrap resample draws the records (the rows of one record over the samples a
cluster; each record of the bench's subset is its own event) and refits every case on
the same drawn rows. Also the brackets that moved against the reference, the runs and
the summed search wall time of each case.

    python bench/ida_dt_convergence.py --dir DIR TAG=DT,TOL [TAG=DT,TOL ...]
"""

from __future__ import annotations

import argparse
import math
import os

import h5py
import numpy as np

from voussoir_post.earthquake.fragility import clustered_resamples, fit_intervals
from voussoir_post.earthquake.ida import read_ida
from voussoir_post.units import G_M_S2

SAMPLES = ("nominal", "posterior")


def load_case(folder: str, tag: str):
    """(low, high, record keys, fits per sample, runs, wall s, brackets) of a case's rows, in
    record then sample order."""
    low, high, keys, runs, wall, brackets = [], [], [], 0, 0.0, []
    for sample in SAMPLES:
        ida = read_ida(os.path.join(folder, f"ida_dt_{tag}_{sample}.h5"))
        lo, hi = ida.intensity_brackets("pga")
        order = np.argsort(ida.record, kind="stable")
        for k in order.tolist():
            low.append(lo[k])
            high.append(hi[k])
            keys.append((ida.record[k], sample))
            brackets.append((float(ida.scale_stood[k]), float(ida.scale_threshold[k]), bool(ida.censored[k])))
        with h5py.File(os.path.join(folder, f"ida_dt_{tag}_{sample}.h5"), "r") as f:
            runs += int(np.sum(f["results/n_runs"][()]))
            wall += float(np.sum(f["results/wall_time_s"][()]))
    return np.array(low), np.array(high), keys, runs, wall, brackets


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dir", required=True)
    parser.add_argument("--bootstrap", type=int, default=1000)
    parser.add_argument("--index", help="the record set's index.csv: each record's event, so that a resample "
                                        "draws the events, then their records (as the fragility's band)")
    parser.add_argument("cases", nargs="+", metavar="TAG=DT,TOL")
    args = parser.parse_args()
    cases = []
    for text in args.cases:
        tag, values = text.split("=")
        dt, tol = (float(v) for v in values.split(","))
        cases.append((tag, dt, tol))
    data = {tag: load_case(args.dir, tag) for tag, _, _ in cases}
    keys = data[cases[0][0]][2]
    for tag, _, _ in cases:
        if data[tag][2] != keys:
            raise SystemExit(f"case {tag}: not the same rows (record, sample) as {cases[0][0]}")
    used = np.all([np.isfinite(data[tag][0]) for tag, _, _ in cases], axis=0)
    default_tol = [c for c in cases if c[2] == max(c2[2] for c2 in cases)]
    ref = min(default_tol, key=lambda c: c[1])[0]
    tags = [tag for tag, _, _ in cases]
    lows = {t: data[t][0][used] for t in tags}
    highs = {t: data[t][1][used] for t in tags}
    fits = {t: fit_intervals(lows[t], highs[t]) for t in tags}
    clusters = [k[0] for k, u in zip(keys, used) if u]
    events = None
    if args.index:
        import csv
        with open(args.index, newline="") as f:
            event_of = {row["file"]: row["event"] for row in csv.DictReader(line for line in f
                                                                            if not line.startswith("#"))}
        events = [event_of[os.path.basename(c)] for c in clusters]

    def statistic(pick):
        out = []
        for t in tags:
            f = fit_intervals(lows[t][pick], highs[t][pick], tol=1e-9)
            out += [math.log(f.median), f.beta]
        return out

    values, n_clusters = clustered_resamples(statistic, int(used.sum()), clusters, events, args.bootstrap, 20261129)
    values = np.array(values)
    i_ref = tags.index(ref)
    print(f"{int(used.sum())} rows ({len(set(clusters))} records x {len(SAMPLES)} model samples; "
          f"{int((~used).sum())} left out: a failed search with no stand in some case); bands: 90 %, "
          f"{len(values)} paired bootstrap resamples of the {n_clusters} {'events, then their records' if events else 'records'}; "
          f"reference: {ref}")
    print(f"{'case':>20s} {'dt_s':>8s} {'tol':>7s} {'median PGA g':>13s} {'90 % band':>16s} {'ratio to ref':>12s} "
          f"{'paired band':>16s} {'beta':>7s} {'90 % band':>15s} {'beta - ref':>10s} {'paired band':>17s} "
          f"{'moved':>6s} {'runs':>5s} {'search s':>9s}")
    for k, (tag, dt, tol) in enumerate(cases):
        fit = fits[tag]
        ln_med, beta = values[:, 2 * k], values[:, 2 * k + 1]
        m_band = np.exp(np.percentile(ln_med, [5, 95])) / G_M_S2
        b_band = np.percentile(beta, [5, 95])
        r_band = np.exp(np.percentile(ln_med - values[:, 2 * i_ref], [5, 95]))
        d_band = np.percentile(beta - values[:, 2 * i_ref + 1], [5, 95])
        ratio = fit.median / fits[ref].median
        moved = sum(1 for a, b in zip(data[tag][5], data[ref][5])
                    if not (a[2] == b[2] and all(math.isclose(x, y, rel_tol=1e-9) for x, y in zip(a[:2], b[:2]))))
        print(f"{tag:>20s} {dt:8.2g} {tol:7.0e} {fit.median / G_M_S2:13.4f} {m_band[0]:7.4f} - {m_band[1]:6.4f} "
              f"{ratio:12.4f} {r_band[0]:7.4f} - {r_band[1]:6.4f} {fit.beta:7.4f} {b_band[0]:6.4f} - {b_band[1]:6.4f} "
              f"{fit.beta - fits[ref].beta:+10.4f} {d_band[0]:+7.4f} - {d_band[1]:+7.4f} {moved:6d} "
              f"{data[tag][3]:5d} {data[tag][4]:9.1f}")
    for k, (tag, dt, tol) in enumerate(cases):
        same_dt = [j for j, c in enumerate(cases) if c[1] == dt and c[2] > tol]
        if not same_dt:
            continue
        j = same_dt[0]
        r_band = np.exp(np.percentile(values[:, 2 * k] - values[:, 2 * j], [5, 95]))
        d_band = np.percentile(values[:, 2 * k + 1] - values[:, 2 * j + 1], [5, 95])
        print(f"tolerance: {tag} against {tags[j]} (the same dt): median x {fits[tag].median / fits[tags[j]].median:.4f} "
              f"(paired band {r_band[0]:.4f} - {r_band[1]:.4f}), beta {fits[tag].beta - fits[tags[j]].beta:+.4f} "
              f"({d_band[0]:+.4f} - {d_band[1]:+.4f})")
    print("per model sample (median PGA g, beta):")
    for tag in tags:
        parts = []
        for sample in SAMPLES:
            rows = np.array([k[1] == sample for k in keys]) & used
            f = fit_intervals(data[tag][0][rows], data[tag][1][rows])
            parts.append(f"{sample} {f.median / G_M_S2:.4f}, {f.beta:.4f}")
        print(f"{tag:>20s}  " + "; ".join(parts))


if __name__ == "__main__":
    main()
