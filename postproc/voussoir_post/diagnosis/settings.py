"""How the diagnosis simulates and judges: its settings, with the project's defaults."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

__all__ = ["DiagnosisSettings"]


@dataclass
class DiagnosisSettings:
    """How the diagnosis simulates; the defaults are the project's defaults."""

    bin_dir: Path
    n_ranks: int = 2
    dt_s: float = 1.0e-3
    amp_tol_fraction: float = 0.005  #: threshold search tolerance, fraction of the onset of rocking
    #: Step of the threshold search's upward scan: 5 %, as a laboratory ramps (the
    #: default of voussoir-sweep, 10 %, jumps narrow collapse bands more often).
    scan_step: float = 0.05
    inset_grid_m: tuple[float, ...] = (0.0005, 0.001, 0.002, 0.003, 0.004, 0.005, 0.006, 0.008, 0.010)
    friction_steps: tuple[float, ...] = (0.05, 0.10, 0.15, 0.20, 0.25)  #: below and above nominal
    min_friction: float = 0.15
    max_friction: float = 0.9
    thickness_factors: tuple[float, ...] = (0.76, 0.82, 0.88, 0.94, 1.06, 1.12)  #: geometry, nominal 1
    #: The coarser grids of each effect inside a pair of effects (bank.py).
    pair_inset_m: tuple[float, ...] = (0.001, 0.002, 0.004, 0.006, 0.008)
    pair_friction_steps: tuple[float, ...] = (-0.2, -0.15, -0.1, -0.05, 0.1)
    pair_thickness_factors: tuple[float, ...] = (0.82, 0.88, 0.94, 1.06)
    #: The play of base_restraint's brackets [m] the bank simulates, alone and in pairs
    #: (0: in contact; effects.py). LMGC90's truths have them 0 to 0.5 mm off.
    bracket_gaps_m: tuple[float, ...] = (0.0, 0.00025, 0.0005)
    #: Rounds of nodes added where a single effect's response is steep (bank.py).
    refine_rounds: int = 2
    #: Ceiling of every threshold search, in onsets of rocking (limit analysis) at the
    #: lowest frequency tested: data-independent.
    ceiling_factor: float = 6.0
    #: New frequencies [Hz] at which the rivals of an inconclusive verdict are simulated,
    #: to find the test that would separate them (next_test.py).
    probe_frequencies_hz: tuple[float, ...] = (0.75, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0)
    #: Whether the crown records of tests held near the threshold are weighed (crown.py) and
    #: such tests advised (next_test.py). Off by default: in the loop against LMGC90 they
    #: name none wrongly and raise P(truth) in 15 truths of 20, but name 11, and leave two
    #: whose collapse is not monotone in amplitude at 0.00 (docs/diagnosis.md).
    crown_records: bool = False
    #: Model samples drawn from the posterior for each specimen (posterior_samples_<id>.csv).
    posterior_samples: int = 200
    #: Where the simulation bank is cached (None: a folder `voussoir-bank` beside the output).
    bank_dir: Path | None = None
    figure_format: str = "png"  #: of report.md's figures: png, pdf or svg
    #: How far a specimen as built may lie from its stated ring thickness (relative standard
    #: deviation): 1.5 %, a mason's or joiner's tolerance on a ring of 25-40 mm; less for
    #: specimens measured after building, 0 for specimens made exactly (another code's).
    build_tolerance: float = 0.015
    log: object = print
