"""Stage 1 of the diagnosis: what a campaign observed, reduced to what the inference uses.

Each (specimen, frequency) pair with a collapse gives a *bracket*: the collapse threshold
(in commanded amplitude) lies in (low_m, high_m], low_m the largest `stand` amplitude
below the smallest `collapse` amplitude high_m (0 when no stand row lies below); a pair
whose tests all stood is a lower bound (high_m infinite: the threshold lies above its
largest stand). The
table's own evidence enters as one measured gain per test (records fitted as
gain x command(t - delay), or measured / commanded peak acceleration).

Observations are plain data: they can be read from a campaign folder
(`from_campaign`) or written by a replay of stored simulations (the tests and the
calibration bench), and the later stages cannot tell the difference.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..readers.campaign import Campaign, Specimen, measured_thresholds
from .actuator import TableEvidence, table_evidence

__all__ = ["PairObservation", "Observations", "from_campaign", "cycles_of"]


@dataclass(frozen=True)
class PairObservation:
    """The bracket of one (specimen, frequency) pair and its tests' measured gains."""

    specimen_id: str
    frequency_hz: float
    low_m: float  #: largest stand amplitude below high_m (0: none below)
    high_m: float  #: smallest collapse amplitude (inf: every test stood)
    gains: tuple[float, ...] = ()  #: measured table gain of each test of the pair (may be empty)
    test_ids: tuple[str, ...] = ()

    @property
    def threshold_m(self) -> float:
        """The measured threshold of docs/measured_data.md (midpoint of the bracket; inf
        for a pair whose tests all stood)."""
        return 0.5 * (self.low_m + self.high_m) if self.low_m > 0 else self.high_m

    @property
    def closed(self) -> bool:
        """Both ends known: a stand below the smallest collapse."""
        return self.low_m > 0 and math.isfinite(self.high_m)

    @property
    def collapsed(self) -> bool:
        """Some test of the pair fell (else the pair is a lower bound)."""
        return math.isfinite(self.high_m)


@dataclass
class Observations:
    """Everything the inference reads from a campaign."""

    name: str
    specimens: dict[str, Specimen]  #: every specimen with a pair (certain set-up or apart)
    pairs: list[PairObservation]
    cycles: dict[str, tuple[int, int, int]]  #: afd cycles (attack, full, decay) of each specimen
    gain_source: str = "none"  #: 'records', 'peak_accel' or 'none'
    delay_s: float = 0.0  #: mean delay of the records (reported, not inferred)
    delay_se_s: float = math.nan
    apart: list[PairObservation] = field(default_factory=list)  #: specimens with setup_certain = 0
    #: The table transducer's calibration (relative standard deviation; table.csv).
    gain_bias_sd: float = 0.01
    #: How far the specimens as built may lie from their stated ring thickness (relative
    #: standard deviation; DiagnosisSettings.build_tolerance, models.tolerance_spread).
    build_tolerance: float = 0.015
    #: Whether the campaign reports any `stand` row (None: read from the pairs' brackets).
    stand_rows: bool | None = None
    #: Tests the diagnosis does not read: driven by a record without an afd frequency and
    #: amplitude (an earthquake, a pulse), so in no (specimen, frequency) pair.
    unread: tuple[str, ...] = ()
    #: Record tests read as pulses one way and the other (pulses.py), of certain specimens.
    pulse_pairs: list = field(default_factory=list)

    @property
    def stands_unreported(self) -> bool:
        """True when the campaign reports collapses only: its pairs are then read as the
        first collapses of ramps whose stands went unreported (likelihood.bracket_terms);
        where it reports stands elsewhere, a pair with none fell at its first test."""
        if self.stand_rows is not None:
            return not self.stand_rows
        return all(p.low_m <= 0 for p in self.pairs + self.apart)

    def of(self, specimen_id: str) -> list[PairObservation]:
        return [p for p in self.pairs if p.specimen_id == specimen_id]

    def frequencies(self, specimen_id: str) -> list[float]:
        return sorted({p.frequency_hz for p in self.pairs + self.apart if p.specimen_id == specimen_id})


def cycles_of(campaign: Campaign, test_id: str) -> tuple[int, int, int]:
    t = campaign.tests[test_id]
    return (t.n_attack, t.n_full, t.n_decay)


def from_campaign(campaign: Campaign) -> tuple[Observations, TableEvidence]:
    """The observations of a campaign read from its folder, and its table evidence."""
    table = table_evidence(campaign)
    gain_of = {tid: g for tid, g, _, _ in table.per_test}  # from the records, else from the peaks
    pairs, apart, cycles = [], [], {}
    for m in measured_thresholds(campaign):
        low = m.low_m if math.isfinite(m.low_m) else 0.0
        if not m.has_collapse and not low > 0:
            continue
        # A pair whose tests all stood says that its threshold lies above the largest stand.
        high = float(m.high_m) if m.has_collapse else math.inf
        obs = PairObservation(m.specimen_id, float(m.frequency_hz), float(low), high,
                              tuple(float(gain_of[t]) for t in m.test_ids if t in gain_of), tuple(m.test_ids))
        (pairs if campaign.specimens[m.specimen_id].setup_certain else apart).append(obs)
        cycles.setdefault(m.specimen_id, cycles_of(campaign, m.test_ids[0]))
    specimens = {sid: s for sid, s in campaign.specimens.items() if any(p.specimen_id == sid for p in pairs + apart)}
    stand_rows = any(not t.collapsed for t in campaign.tests.values() if t.waveform == "afd")
    from .pulses import read_pulse_pairs  # pulses.py reads the bank's keys, which reads PairObservation
    certain = {sid for sid in specimens if any(p.specimen_id == sid for p in pairs)}
    pulse_pairs = read_pulse_pairs(campaign, certain)
    pulsed = {tid for pp in pulse_pairs for r in pp.ramps.values() for tid in r.test_ids}
    unread = tuple(t.test_id for t in campaign.tests.values()
                   if (t.frequency_hz is None or t.amplitude_m is None) and t.test_id not in pulsed)
    return (Observations(campaign.name, specimens, pairs, cycles, table.source, table.delay_s, table.delay_se,
                         apart, campaign.table.displacement_gain_sd, stand_rows=stand_rows, unread=unread,
                         pulse_pairs=pulse_pairs), table)
