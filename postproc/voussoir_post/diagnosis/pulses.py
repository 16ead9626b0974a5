"""A pulse one way and the other: the record tests that part brackets on one side.

Brackets against one springing make an arch fall at a different table pulse one way than
the other; a free arch, or brackets on both sides, is mirror-symmetric and falls at the
same pulse both ways. An afd test, symmetric itself, hardly sees the difference. Measured
in LMGC90 on nine stored truths (bench/lmgc90/pulse.py, docs/diagnosis.md, "A pair of
pulses"): free arches keep the ratio of the two ways' thresholds within 0.99 to 1.05,
brackets with play move it to 0.79 to 0.85 (left) or 1.10 (right), and the diagnosis's
ratios of the truths' own models lie 0 to 5 % from LMGC90's (RATIO_SCALE).

**Reading.** A campaign's tests of waveform `record` of one specimen whose table records
(records/<test_id>.csv, `table_x_m`) are scaled copies of one shape, one way or the other,
are a *pulse pair*. Each record, less its first value, is fitted by least squares to the
group's shape (the mean of its records, each normalised to a peak |x| of 1 on its own
sign): the fitted factor is the test's scale [m of the shape's travel] and its sign the
way (+1: the shape's own way). Each way's rows bracket its threshold scale, as an afd
pair's do (largest stand below the smallest collapse). A pair enters the probabilities
when both ways have a collapse or a stand and one way's bracket is closed (a stand below
its collapse); its other tests are named as not read.

**Simulation** (`pulse_thresholds`): the shape, smoothed (zero-phase low-pass at
SMOOTH_HZ) and differentiated twice, is an accelerogram for the kernel's IDA sweep
(`&sweep mode = 'ida'`, `record_polarity = 'both'`), which finds each way's collapse
scale of each model. The models simulated are the nominal one and every model with
brackets on one side (alone, and with each value of the other effect's pair grid): the
others are mirror-symmetric, and their ratio is 1 (log ratio 0) by symmetry, not by
simulation; the nominal model's two ways check it.

**Likelihood** (`log_ratio_terms`): only the ratio of the two ways enters, not the level
(which the afd thresholds already weigh, through discrepancies a pulse would need of its
own). With the level log T+ = a uniform over the closed bracket B+ (in log) and log T- =
a + rho + e, e ~ N(0, RATIO_SCALE^2), rho the model's log ratio, the term is
P(log T- in B- | B+) = mean over a in B+ of [Phi((h- - a - rho)/s) - Phi((l- - a - rho)/s)],
in closed form with G(z) = z Phi(z) + phi(z), mixed with an outlier model (probability
OUTLIER_PROB: the ratio anywhere within a factor OUTLIER_FACTOR). A model's rho at a grid
point: 0 when mirror-symmetric; else that of its brackets (side and play), with the
other effect of a pair interpolated linearly between the simulated values of its pair
grid.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.signal import butter, sosfiltfilt
from scipy.stats import norm

from ..readers.campaign import Campaign, Specimen
from ..runner import code_hash
from .bank import key_variant, variant_key
from .effects import Variant, arch_group, nominal_value, restraint_parts
from .simulator import Simulator

__all__ = ["PulseRamp", "PulsePair", "read_pulse_pairs", "unit_pulse", "accelerogram", "one_sided",
           "pulse_variants", "pulse_thresholds", "log_ratio_terms", "grid_log_ratio", "pulse_log_likelihood",
           "RATIO_SCALE", "OUTLIER_PROB", "OUTLIER_FACTOR", "SHAPE_TOLERANCE", "PULSE_S", "SMOOTH_HZ",
           "table_demand", "reach_m", "add_pulse_banks", "PULSE_VERSION"]

#: The scale of the two codes' disagreement on the log ratio of the two ways' thresholds,
#: a normal law's sd, calibrated to coverage as the crown law is: LMGC90's ratios of nine
#: stored truths (bench/lmgc90/pulse.py; postproc/tests/data/lmgc90/pulse_thresholds.json)
#: against the ratio the diagnosis gives each truth's own model (1 when mirror-symmetric,
#: else the kernel's IDA both ways) differ by 0.0 to 5.0 % (RMS 2.9 %); their 90th
#: percentile, 5.0 %, over 1.645 is 0.030 (docs/diagnosis.md, "A pair of pulses").
RATIO_SCALE = 0.03
OUTLIER_PROB = 0.05
OUTLIER_FACTOR = 1.5  #: an outlier's ratio lies within this factor of the model's
#: Records of one pulse pair: RMS of the difference of two normalised shapes, relative to
#: their peak, at most this (a transducer's noise and a table's small distortions pass).
SHAPE_TOLERANCE = 0.05
#: The project's pulse (bench/lmgc90/pulse.py): a half-sine of table acceleration of
#: PULSE_S[0] s one way, a half-sine of PULSE_S[1] s the other way that brings the table to
#: rest, PULSE_S[2] s still; sampled every PULSE_DT.
PULSE_S = (0.15, 0.6, 1.5)
PULSE_DT = 1.0e-3
SMOOTH_HZ = 25.0  #: low-pass of a measured shape before it is differentiated
LEAD_S = 0.5  #: the arch at rest before the pulse (as the LMGC90 bench)
PULSE_VERSION = 1  #: part of the pulse bank's cache key


# ---------------------------------------------------------------- the pulse


def unit_pulse(dt: float = PULSE_DT) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t, table displacement, acceleration) of the pulse of unit travel [m]: the table
    from -0.5 to +0.5 m, at rest before and after."""
    tp, td, rest = PULSE_S
    t = np.arange(0.0, tp + td + rest + dt / 2, dt)
    acc = np.where(t < tp, np.sin(np.pi * t / tp), np.where(t < tp + td, -(tp / td) * np.sin(np.pi * (t - tp) / td),
                                                            0.0))
    # Exact integrals of the two half-sines: velocity, then displacement.
    w1, w2 = np.pi / tp, np.pi / td
    x1 = (np.minimum(t, tp) - np.sin(w1 * np.minimum(t, tp)) / w1) / w1
    vp, xp = 2.0 / w1, tp / w1  # at the end of the first half-sine
    s = np.clip(t - tp, 0.0, td)
    a2 = tp / td
    x = np.where(t < tp, x1, xp + vp * s - a2 * (s - np.sin(w2 * s) / w2) / w2)
    travel = xp + vp * td - a2 * td / w2
    return t, x / travel - 0.5, acc / travel


def table_demand(t: np.ndarray, x: np.ndarray) -> tuple[float, float, float]:
    """(largest |x| about the record's centre, largest |velocity|, largest |acceleration|)
    of a unit record, after SMOOTH_HZ smoothing: what a scale multiplies, for the table's
    limits."""
    _, vel, acc = _derivatives(t, x)
    centre = 0.5 * (float(np.max(x)) + float(np.min(x)))
    return float(np.max(np.abs(x - centre))), float(np.max(np.abs(vel))), float(np.max(np.abs(acc)))


def reach_m(table, demand: tuple[float, float, float] | None = None) -> float:
    """The largest travel [m] of a pulse within the table's limits (stroke about the
    record's centre, peak velocity, peak acceleration); `demand`: table_demand of its unit
    record (default: the project's pulse)."""
    half, vmax, amax = demand or table_demand(*unit_pulse()[:2])
    return min(table.stroke_m / half, table.max_velocity_m_s / vmax, table.max_accel_m_s2 / amax)


def _derivatives(t: np.ndarray, x: np.ndarray):
    dt = float(np.mean(np.diff(t)))
    smooth = x
    if 1.0 / dt > 2.5 * SMOOTH_HZ:
        smooth = sosfiltfilt(butter(4, SMOOTH_HZ, fs=1.0 / dt, output="sos"), x - x[0]) + x[0]
    vel = np.gradient(smooth, dt)
    return smooth, vel, np.gradient(vel, dt)


def accelerogram(t: np.ndarray, x: np.ndarray, path: Path) -> Path:
    """Write the CSV accelerogram (t_s, accel_m_s2) of a unit displacement record for the
    kernel's IDA sweep: smoothed, differentiated twice, the table at rest at both ends."""
    _, _, acc = _derivatives(t, x)
    acc[0] = acc[-1] = 0.0
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("t_s,accel_m_s2\n" + "".join(f"{a - t[0]:.5f},{b:.8e}\n" for a, b in zip(t, acc)))
    return path


# ---------------------------------------------------------------- reading a campaign


@dataclass(frozen=True)
class PulseRamp:
    """One way's bracket of a pulse pair, in scales [m of the shape's travel]."""

    polarity: int
    low: float  #: largest stand below `high` (0: none)
    high: float  #: smallest collapse (inf: every test stood)
    test_ids: tuple[str, ...] = ()

    @property
    def closed(self) -> bool:
        return self.low > 0 and math.isfinite(self.high)


@dataclass
class PulsePair:
    """The tests of one specimen driven by one shape, both ways."""

    specimen_id: str
    t_s: np.ndarray = field(repr=False)
    shape: np.ndarray = field(repr=False)  #: unit travel, its own way positive
    ramps: dict[int, PulseRamp] = field(default_factory=dict)  #: by polarity

    @property
    def key(self) -> str:
        """A digest of the shape (to 1e-4 of its travel) and its sampling."""
        text = json.dumps([round(float(self.t_s[1] - self.t_s[0]), 6), len(self.t_s),
                           [round(float(v), 4) for v in self.shape[::10]]])
        return hashlib.sha256(text.encode()).hexdigest()[:12]

    @property
    def bank_key(self) -> str:
        """Its key in Bank.pulses: the specimen and the shape."""
        return f"{self.specimen_id}:{self.key}"

    @property
    def usable(self) -> bool:
        """Both ways observed, one of them a closed bracket."""
        return len(self.ramps) == 2 and any(r.closed for r in self.ramps.values()) and all(
            r.low > 0 or math.isfinite(r.high) for r in self.ramps.values())


def _normalised(x: np.ndarray) -> np.ndarray:
    x = x - x[0]
    k = int(np.argmax(np.abs(x)))
    return x / x[k] if x[k] != 0 else x


def read_pulse_pairs(campaign: Campaign, specimens=None) -> list[PulsePair]:
    """The campaign's usable pulse pairs (module docstring) of the specimens given (default
    all)."""
    groups: list[tuple[str, np.ndarray, list]] = []  # (specimen, time, [(test, normalised, raw)])
    for tid, test in campaign.tests.items():
        rec = campaign.records.get(tid)
        if test.waveform != "record" or rec is None or (specimens is not None and test.specimen_id not in specimens):
            continue
        x = np.asarray(rec.table_x_m, float)
        if x.size < 8 or not np.any(x != x[0]):
            continue
        t = np.asarray(rec.t_s, float)
        u = _normalised(x)
        for sid, t0, members_ in groups:
            if sid != test.specimen_id or abs(t0[-1] - t[-1]) > 0.05 * t0[-1]:
                continue
            ref = members_[0][1]
            other = np.interp(t0, t, u)
            if float(np.sqrt(np.mean((other - ref) ** 2))) <= SHAPE_TOLERANCE:
                members_.append((test, other, np.interp(t0, t, x - x[0])))
                break
        else:
            groups.append((test.specimen_id, t, [(test, u, x - x[0])]))
    pairs = []
    for sid, t, members_ in groups:
        # The mean of the normalised records (its largest excursion +1), to unit travel,
        # about its centre; `ref` from its start, as each record less its first value.
        shape = np.mean([m[1] for m in members_], axis=0)
        shape = shape / (float(np.max(shape)) - float(np.min(shape)))
        shape = shape - 0.5 * (float(np.max(shape)) + float(np.min(shape)))
        ref = shape - shape[0]
        rows: dict[int, list] = {1: [], -1: []}
        for test, _, raw in members_:
            scale = float(raw @ ref / (ref @ ref))
            rows[1 if scale > 0 else -1].append((abs(scale), test))
        pair = PulsePair(sid, t, shape)
        for pol, rs in rows.items():
            if not rs:
                continue
            falls = [s for s, test in rs if test.collapsed]
            high = min(falls) if falls else math.inf
            stands = [s for s, test in rs if not test.collapsed and s < high]
            pair.ramps[pol] = PulseRamp(pol, max(stands) if stands else 0.0, high,
                                        tuple(test.test_id for _, test in sorted(rs, key=lambda r: r[0])))
        if pair.usable:
            pairs.append(pair)
    return pairs


# ---------------------------------------------------------------- simulation


def one_sided(variant: Variant) -> str | None:
    """The base_restraint value of a variant with brackets on one side, else None."""
    for e, v in variant.parts():
        if e == "base_restraint" and restraint_parts(v)[0] in ("left", "right"):
            return str(v)
    return None


def pulse_variants(bank_keys) -> list[Variant]:
    """The models simulated for a pulse: the nominal one and every variant of the bank
    (keys) with brackets on one side."""
    return [Variant()] + [v for v in map(key_variant, sorted(bank_keys)) if one_sided(v)]


def pulse_thresholds(spec: Specimen, pair: PulsePair, variants: list[Variant], settings, cache: Path, work: Path
                     ) -> dict[str, tuple[float, float]]:
    """Each variant's collapse scale [m of the shape's travel] its own way and the other
    ((+, -); inf where the IDA's ceiling stood), by the kernel's IDA sweep, cached per
    specimen, shape and variant under the executables' hash."""
    code = code_hash(settings.bin_dir, ("voussoir-sweep",))
    out, todo = {}, []
    for v in variants:
        key = hashlib.sha256(json.dumps([PULSE_VERSION, code, settings.dt_s, pair.key, arch_group(spec, v)],
                                        sort_keys=True).encode()).hexdigest()[:16]
        path = Path(cache) / f"{spec.specimen_id}-pulse-{key}.json"
        if path.exists():
            d = json.loads(path.read_text())
            out[variant_key(v)] = (d["plus"], d["minus"])
        else:
            todo.append((v, path))
    if todo:
        sim = Simulator(settings, Path(work))
        record = accelerogram(pair.t_s, pair.shape, Path(work) / f"pulse_{pair.key}.csv")
        found = sim.record_thresholds(spec, record.resolve(), [v for v, _ in todo], lead_s=LEAD_S,
                                      rest_s=PULSE_S[2])
        for v, path in todo:
            plus, minus = found[v]
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(json.dumps({"specimen_id": spec.specimen_id, "variant": variant_key(v),
                                        "plus": plus, "minus": minus}) + "\n")
            out[variant_key(v)] = (plus, minus)
    return out


# ---------------------------------------------------------------- likelihood


def _g(z):
    """The integral of the standard normal cdf: z Phi(z) + phi(z)."""
    return z * norm.cdf(z) + norm.pdf(z)


def log_ratio_terms(pair: PulsePair, rho: np.ndarray, scale: float = RATIO_SCALE) -> np.ndarray:
    """log P(the other way's bracket | the closed way's bracket, log ratio rho) for each rho
    (module docstring), the outlier model mixed in."""
    rho = np.asarray(rho, float)
    plus, minus = pair.ramps[1], pair.ramps[-1]
    if not plus.closed:  # condition on the way that is closed: the ratio's sign turns
        plus, minus, rho = minus, plus, -rho
    la, ha = math.log(plus.low), math.log(plus.high)
    lb = math.log(minus.low) if minus.low > 0 else -math.inf
    hb = math.log(minus.high) if math.isfinite(minus.high) else math.inf
    w = ha - la

    def part(c):  # mean over a in (la, ha) of Phi((c - a - rho) / s)
        if c == math.inf:
            return np.ones_like(rho)
        if c == -math.inf:
            return np.zeros_like(rho)
        return scale / w * (_g((c - rho - la) / scale) - _g((c - rho - ha) / scale))

    normal = np.clip(part(hb) - part(lb), 0.0, None)
    # Outlier: the log ratio uniform within log(OUTLIER_FACTOR) of rho; the other way's
    # level then uniform over the convolution: P = overlap of B- with (a + rho +- h), a in B+.
    h = math.log(OUTLIER_FACTOR)
    lo_b, hi_b = max(lb, la - h - 1.0), min(hb, ha + h + 1.0)
    xs = np.linspace(0.0, 1.0, 41)
    a = la + w * xs
    lo = a[None, :] + rho[..., None] - h
    hi = a[None, :] + rho[..., None] + h
    overlap = np.clip(np.minimum(hi, hi_b) - np.maximum(lo, lo_b), 0.0, None) / (2 * h)
    outlier = np.trapezoid(overlap, xs, axis=-1)
    return np.log(np.maximum((1 - OUTLIER_PROB) * normal + OUTLIER_PROB * outlier, 1e-300))


def grid_log_ratio(grid, ratios: dict[str, tuple[float, float]], spec: Specimen) -> np.ndarray:
    """Each grid point's predicted log ratio (the -x scale over the +x scale, log): 0 for a
    mirror-symmetric model; else that of its brackets, the other effect of a pair
    interpolated linearly between its simulated values (module docstring)."""
    rho = np.zeros(grid.n)
    if "base_restraint" not in grid.names:
        return rho
    table: dict[str, dict[str | None, list]] = {}  # restraint -> other effect -> [(value, log ratio)]
    for key, (p, m) in ratios.items():
        v = key_variant(key)
        side = one_sided(v)
        if side is None or not (math.isfinite(p) and math.isfinite(m) and p > 0 and m > 0):
            continue
        others = [(e, x) for e, x in v.parts() if e != "base_restraint"]
        e, x = others[0] if others else (None, None)
        table.setdefault(side, {}).setdefault(e, []).append((x, math.log(m / p)))
    values = grid.values[grid.names.index("base_restraint")]
    other = [n for n in grid.names if n not in ("base_restraint", "table_motion")]
    for i, r in enumerate(values):
        if restraint_parts(r)[0] not in ("left", "right") or str(r) not in table:
            continue
        alone = table[str(r)].get(None)
        if alone is None:
            continue
        if not other:
            rho[i] = alone[0][1]
            continue
        e = other[0]
        x = float(grid.values[grid.names.index(e)][i])
        nodes = sorted([(nominal_value(e, spec), alone[0][1])] + [(float(a), b) for a, b in table[str(r)].get(e, [])])
        rho[i] = float(np.interp(x, [a for a, _ in nodes], [b for _, b in nodes]))
    return rho


def pulse_log_likelihood(grid, pairs: list[PulsePair], ratios: dict[str, dict], specimens: dict) -> np.ndarray:
    """The pulse pairs' log likelihood at every grid point of a model (0 without pairs)."""
    total = np.zeros(grid.n)
    for pp in pairs:
        r = ratios.get(pp.bank_key)
        if r is None:
            continue
        rho = grid_log_ratio(grid, r, specimens[pp.specimen_id])
        uniq, inv = np.unique(rho, return_inverse=True)
        total += log_ratio_terms(pp, uniq)[inv]
    return total


def add_pulse_banks(bank, obs, settings, cache: Path, work: Path) -> int:
    """Simulate (or read from `cache`) every pulse pair's thresholds into bank.pulses;
    returns the number of variants simulated or read."""
    n = 0
    for pp in obs.pulse_pairs:
        spec = obs.specimens[pp.specimen_id]
        variants = pulse_variants(bank.specimens[pp.specimen_id].thresholds)
        bank.pulses[pp.bank_key] = pulse_thresholds(spec, pp, variants, settings, cache,
                                                    Path(work) / f"pulse-{pp.specimen_id}")
        n += len(variants)
    return n
