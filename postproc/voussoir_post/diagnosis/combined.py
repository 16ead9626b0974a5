"""Two effects acting together (`combined` of shared/MEASURED_DATA.md).

A pair's threshold is first *screened*: in logarithms the two effects are taken to add,
T(v1, v2) = T1(v1) T2(v2) / T0 (each Ti simulated alone, T0 the nominal model). That is
exact when one of them is a table gain (it divides any model's threshold) and an
approximation otherwise: two effects that lower the threshold by the same mechanism
overlap (sub-additive). So each pair is simulated once per specimen, each effect at its
own fit alone (the *calibration* point), and the departure from additivity there is
interpolated bilinearly towards zero at either nominal value. A pair whose screened
held-out fit
beats each of its members by strong evidence is *promising*: it is then simulated on a
small grid about its fitted values (both effects in the same &arch group), and the
simulated departure from the additive rule, ln(T / T_additive), interpolated over that
grid, corrects every prediction of the pair. Where either effect sits at its nominal
value the pair is that effect alone: the correction is zero there by construction.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from .actuator import TableEvidence
from .effects import COMBINED, Effect, Variant
from .settings import DiagnosisSettings

__all__ = ["CombinedEffect", "pair_variant", "all_pairs", "screen_pairs"]


def pair_variant(parts: list[tuple]) -> Variant:
    """The Variant of a list of (effect id, value) parts (none: the nominal model)."""
    if not parts:
        return Variant()
    if len(parts) == 1:
        return Variant(*parts[0])
    return Variant(COMBINED, tuple(parts))


class CombinedEffect(Effect):
    """Two effects of the catalogue at once; a value is the pair (value1, value2)."""

    def __init__(self, first: Effect, second: Effect, settings: DiagnosisSettings, table: TableEvidence):
        # The exact one (a table gain) second: the other then carries the simulations;
        # else one with a &sweep list first (its values share a sweep).
        if (first.exact_in_combination and not second.exact_in_combination) or (
                first.sweep_list is None and second.sweep_list is not None and not first.exact_in_combination):
            first, second = second, first
        self.members = (first, second)
        self.id = f"{first.id}+{second.id}"
        self.settings = settings
        self.table = table
        self._cache: dict = {}
        self._calibrated: dict = {}  #: specimen -> [the calibration values simulated]

    @property
    def member_ids(self) -> tuple[str, str]:
        return (self.members[0].id, self.members[1].id)

    # ---- values and predictions

    def candidate_values(self, pairs, settings):
        a, b = (m.pair_values(pairs, settings, self.table) for m in self.members)
        return [(x, y) for x in a for y in b]

    def fixed_value(self, table):
        return None

    def _simulated_grid(self, pair):
        """Axes and ln-corrections of the pair's simulated combinations, or None."""
        ids = self.member_ids
        points = {}
        for v, t in pair.simulated.items():
            if v.effect == COMBINED and tuple(e for e, _ in v.value) == ids and math.isfinite(t):
                points[tuple(x for _, x in v.value)] = t
        if not points:
            return None
        axes = [sorted({k[i] for k in points}, key=self._sort_key(i)) for i in (0, 1)]
        for i in (0, 1):  # the nominal value anchors each axis (correction 0 there)
            nominal = self.members[i].nominal(pair.spec)
            if nominal is not None and nominal not in axes[i]:
                axes[i] = sorted(axes[i] + [nominal], key=self._sort_key(i))
        corr = np.full((len(axes[0]), len(axes[1])), math.nan)
        for i in (0, 1):
            nominal = self.members[i].nominal(pair.spec)
            if nominal is not None:
                corr[(axes[0].index(nominal), slice(None)) if i == 0 else (slice(None), axes[1].index(nominal))] = 0.0
        for (x, y), t in points.items():
            corr[axes[0].index(x), axes[1].index(y)] = math.log(t / self._additive(pair, (x, y)))
        # A combination not simulated takes the value of the nearest one that was.
        known = np.argwhere(np.isfinite(corr))
        for i, j in np.argwhere(~np.isfinite(corr)):
            k = min(known, key=lambda ij: abs(ij[0] - i) + abs(ij[1] - j))
            corr[i, j] = corr[k[0], k[1]]
        return axes, corr

    def _sort_key(self, i):
        return (lambda v: v) if self.members[i].change_scale is None else float

    @staticmethod
    def _weights(axis: list, value) -> list[tuple[int, float]]:
        """Linear interpolation weights on one axis (clamped; exact match if categorical)."""
        if isinstance(value, str):
            return [(axis.index(value), 1.0)] if value in axis else []
        x = np.array(axis, float)
        v = float(value)
        if v <= x[0]:
            return [(0, 1.0)]
        if v >= x[-1]:
            return [(len(x) - 1, 1.0)]
        k = int(np.searchsorted(x, v)) - 1
        w = (v - x[k]) / (x[k + 1] - x[k])
        return [(k, 1.0 - w), (k + 1, w)]

    def _additive(self, pair, value) -> float:
        t0 = pair.simulated[Variant()]
        p1, p2 = (m.predict(pair, v) for m, v in zip(self.members, value))
        return p1 * p2 / t0

    def correction(self, pair, value) -> float:
        grid = self._simulated_grid(pair)
        if grid is None:
            return 0.0
        axes, corr = grid
        wa, wb = self._weights(axes[0], value[0]), self._weights(axes[1], value[1])
        if not wa or not wb:
            return 0.0
        return float(sum(u * w * corr[i, j] for i, u in wa for j, w in wb))

    def predict(self, pair, value):
        key = (id(pair), len(pair.simulated), value)
        if key not in self._cache:
            t = self._additive(pair, value)
            self._cache[key] = t * math.exp(self.correction(pair, value)) if math.isfinite(t) else math.nan
        return self._cache[key]

    def choose(self, close, pairs):
        """The smallest change from nominal, the two changes weighed by their scales."""
        spec = pairs[0].spec

        def change(value):
            total = 0.0
            for m, v in zip(self.members, value):
                nominal = m.nominal(spec)
                if m.change_scale is None or nominal is None:
                    total += 0.0 if v == "none" else 1.0
                else:
                    total += abs(float(v) - float(nominal)) / m.change_scale
            return total
        return min(close, key=change)

    def interval(self, value, fold_values, near, table):
        lows, highs = [], []
        for i, m in enumerate(self.members):
            lo, hi = m.interval(value[i], [f[i] for f in fold_values], [n[i] for n in near], table)
            lows.append(lo)
            highs.append(hi)
        return tuple(lows), tuple(highs)

    # ---- simulation of a promising pair

    def calibration(self, spec, values: tuple) -> list[Variant]:
        """The one combination simulated for the screen: each member at its own fit
        alone (none when one of them is exact or sits at its nominal value)."""
        if any(m.exact_in_combination for m in self.members):
            return []
        if any(m.nominal(spec) is not None and float(v) == float(m.nominal(spec))
               for m, v in zip(self.members, values)):
            return []
        if any(m.change_scale is None and not m.simulated_values(spec, self.settings) for m in self.members):
            return []  # a categorical effect that does not apply to this specimen
        self._calibrated.setdefault(spec.specimen_id, []).append(tuple(values))
        return [Variant(COMBINED, ((self.members[0].id, values[0]), (self.members[1].id, values[1])))]

    def variants_to_simulate(self, spec, fits: list[tuple]) -> list[Variant]:
        """The combinations simulated for one specimen: on each non-exact member's own
        simulated grid, the values that bracket every fit (at most three), without the
        nominal ones (a pair at a member's nominal value is the other member alone)."""
        if any(m.exact_in_combination for m in self.members):
            return []
        axes = []
        for i, m in enumerate(self.members):
            grid = m.simulated_values(spec, self.settings)
            vals = [f[i] for f in fits]
            if m.change_scale is None:
                axes.append(sorted({v for v in vals if v in grid}))
                continue
            lo, hi = min(float(v) for v in vals), max(float(v) for v in vals)
            below = [g for g in grid if g <= lo] or grid[:1]
            above = [g for g in grid if g >= hi] or grid[-1:]
            axis = [g for g in grid if below[-1] <= g <= above[0]]
            if len(axis) > 3:
                mid = float(np.median([float(v) for v in vals]))
                axis = [axis[0], min(axis[1:-1], key=lambda g: abs(g - mid)), axis[-1]]
            axes.append(axis)
        # The screen's calibration values join the grid, so that it stays complete.
        for v in self._calibrated.get(spec.specimen_id, ()):
            for i in (0, 1):
                if v[i] not in axes[i]:
                    axes[i] = sorted(axes[i] + [v[i]], key=self._sort_key(i))
        nominal = [m.nominal(spec) for m in self.members]
        return [Variant(COMBINED, ((self.members[0].id, x), (self.members[1].id, y)))
                for x in axes[0] for y in axes[1]
                if (nominal[0] is None or x != nominal[0]) and (nominal[1] is None or y != nominal[1])]

    def model(self, value, table):
        parts, motion = [], {}
        for m, v in zip(self.members, value):
            variant, extra = m.model(v, table)
            parts += list(variant.parts())
            motion.update(extra)
        return pair_variant(parts), motion

    # ---- words

    def _member_results(self, c):
        return [SimpleNamespace(effect=m.id, value=c.value[i], low=c.low[i], high=c.high[i])
                for i, m in enumerate(self.members)]

    def parameters(self, c, table):
        out = {}
        for m, part in zip(self.members, self._member_results(c)):
            out.update(m.parameters(part, table))
        return out

    def label(self, value):
        return " + ".join(m.label(v) for m, v in zip(self.members, value))

    def value_text(self, c):
        return "; ".join(m.value_text(part) for m, part in zip(self.members, self._member_results(c)))

    def sentence(self, c, table):
        a, b = (m.sentence(part, table) for m, part in zip(self.members, self._member_results(c)))
        return f"{a}, and {b}"


def all_pairs(singles: dict, settings: DiagnosisSettings, table: TableEvidence) -> list[CombinedEffect]:
    """Every pair of admissible single effects (two exact ones excepted)."""
    from itertools import combinations
    ids = [e for e, c in singles.items() if c.admissible]
    return [CombinedEffect(singles[a].eff, singles[b].eff, settings, table) for a, b in combinations(ids, 2)
            if not (singles[a].eff.exact_in_combination and singles[b].eff.exact_in_combination)]


def screen_pairs(pairs, singles: dict, combos: list[CombinedEffect], settings: DiagnosisSettings,
                 table: TableEvidence, max_pairs: int = 3) -> list[tuple[CombinedEffect, object]]:
    """The pairs screened by the additive rule (corrected by their calibration point):
    the promising ones (held-out likelihood beating each member alone by strong
    evidence), best first, at most `max_pairs`."""
    from .selection import clearly_better, evaluate_candidate, held_out_loss
    out = []
    for ce in combos:
        a, b = ce.member_ids
        screened = evaluate_candidate(pairs, ce, settings, table)
        loss = held_out_loss(screened, pairs)
        promising = all(clearly_better(loss, held_out_loss(singles[m], pairs)) for m in (a, b))
        settings.log(f"[diagnose] screen {ce.id}: held-out {100 * screened.cv_error:.1f} % at {ce.label(screened.value)}"
                     f" (-log likelihood {loss:.1f}; alone {held_out_loss(singles[a], pairs):.1f}, "
                     f"{held_out_loss(singles[b], pairs):.1f})" + (": promising" if promising else ""))
        if promising:
            out.append((loss, ce, screened))
    out.sort(key=lambda x: x[0])
    return [(ce, screened) for _, ce, screened in out[:max_pairs]]
