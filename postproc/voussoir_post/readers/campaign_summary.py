"""The summary ``voussoir-diagnose check`` prints of a validated campaign: specimens with
their geometry, tests per specimen and frequency with the measured thresholds and
brackets, records, hinges and the warnings."""

from __future__ import annotations

import math

from ..tables import ReportTable, format_table
from .campaign import Campaign, measured_thresholds

__all__ = ["campaign_summary"]


def _mm(value_m: float | None) -> float | None:
    return None if value_m is None else 1e3 * value_m


def campaign_summary(campaign: Campaign) -> str:
    """A readable summary of a validated campaign: specimens with geometry, tests per
    specimen and frequency with the measured thresholds and brackets, records, hinges."""
    out = [f"Campaign '{campaign.name}' ({campaign.path}): valid",
           f"{len(campaign.specimens)} specimens, {len(campaign.tests)} tests, "
           f"{len(campaign.records)} records, {len(campaign.hinges)} hinge files", ""]

    out.append(format_table(ReportTable(
        ["specimen", "embrace_deg", "n_voussoirs", "r_ext_mm", "thickness_mm", "t/R_mean", "width_mm",
         "density_kg_m3", "friction", "tests"],
        [(s.specimen_id, s.embrace_deg, s.n_voussoirs, 1e3 * s.r_ext_m, 1e3 * s.thickness_m,
          s.thickness_ratio_mean, 1e3 * s.width_m, s.density_kg_m3, s.friction, len(campaign.tests_of(s.specimen_id)))
         for s in campaign.specimens.values()],
        title="Specimens")))
    out.append("")

    thresholds = measured_thresholds(campaign)
    rows = []
    for m in thresholds:
        tests = [campaign.tests[t] for t in m.test_ids]
        amps = ", ".join(f"{1e3 * t.amplitude_m:g}{'c' if t.collapsed else 's'}"
                         for t in sorted(tests, key=lambda t: t.amplitude_m))
        bracket = f"({_fmt_mm(m.low_m)}, {_fmt_mm(m.high_m)}]"
        rows.append((m.specimen_id, m.frequency_hz, len(tests), m.n_stand, m.n_collapse, amps,
                     _mm(m.threshold_m), bracket, m.threshold_accel_m_s2, m.non_monotonic))
    out.append(format_table(ReportTable(
        ["specimen", "frequency_hz", "tests", "stand", "collapse", "amplitudes_mm (s/c)", "threshold_mm",
         "bracket_mm", "threshold_accel_m_s2", "non_monotonic"],
        rows, title="Tests per specimen and frequency; measured threshold = midpoint of the bracket "
                    "(largest stand below, smallest collapse], or the smallest collapse when no "
                    "stand lies below ('-'); amplitudes: s = stand, c = collapse")))
    others = [t for t in campaign.tests.values() if t.frequency_hz is None or t.amplitude_m is None]
    if others:
        out.append("Tests without frequency and amplitude (not in a threshold pair): "
                   + ", ".join(f"{t.test_id} ({t.specimen_id}, {t.waveform}, {t.outcome})" for t in others))
    out.append("")

    if campaign.records:
        out.append(format_table(ReportTable(
            ["test", "specimen", "waveform", "samples", "dt_s", "duration_s", "peak_table_x_mm", "crown"],
            [(tid, campaign.tests[tid].specimen_id, campaign.tests[tid].waveform, r.t_s.size, r.dt_s,
              r.duration_s, 1e3 * float(abs(r.table_x_m).max()),
              "dx,dy" if r.crown_dx_m is not None and r.crown_dy_m is not None
              else ("dx" if r.crown_dx_m is not None else ("dy" if r.crown_dy_m is not None else "-")))
             for tid, r in campaign.records.items()],
            title="Records (records/<test_id>.csv)")))
    else:
        out.append("Records: none")
    out.append("")
    if campaign.hinges:
        out.append(format_table(ReportTable(
            ["test", "specimen", "hinges (t_s joint side)"],
            [(tid, campaign.tests[tid].specimen_id,
              "; ".join(f"{h.t_s:g} {h.joint}{h.side[0]}" for h in hs) or "-")
             for tid, hs in campaign.hinges.items()],
            title="Observed hinges (hinges/<test_id>.csv; i = intrados, e = extrados)")))
    else:
        out.append("Hinges: none")
    if campaign.warnings:
        out.append("")
        out.append("Warnings:")
        out.extend(f"  {w}" for w in campaign.warnings)
    return "\n".join(out)


def _fmt_mm(value_m: float) -> str:
    return "-" if value_m is None or math.isnan(value_m) else f"{1e3 * value_m:g}"
