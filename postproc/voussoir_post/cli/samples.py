"""``voussoir-post samples POSTERIOR.csv --n 30``: the diagnosis's posterior samples stratified
by the rival models (:mod:`voussoir_post.diagnosis.strata`), written as a samples file that
``&sweep model_samples_file`` of an IDA reads and that ``voussoir-post fragility`` reads back
for the mixture of the models."""

from __future__ import annotations

import os

from ..errors import DONE

__all__ = ["add_samples_parser", "cmd_samples"]


def cmd_samples(args) -> int:
    from ..diagnosis.strata import stratify_file

    diagnosis = args.diagnosis or os.path.join(os.path.dirname(os.path.abspath(args.samples)), "diagnosis.json")
    out = args.out or os.path.splitext(args.samples)[0] + f"_stratified{args.n}.csv"
    if os.path.isdir(out):
        out = os.path.join(out, os.path.splitext(os.path.basename(args.samples))[0] + f"_stratified{args.n}.csv")
    strata = stratify_file(args.samples, diagnosis, args.n, out, args.min_probability)
    counts = strata.counts()
    print(f"{args.n} samples over {len(counts)} models of posterior probability >= {args.min_probability:g} "
          f"({diagnosis}):")
    for m, k in counts.items():
        print(f"  {m}: probability {strata.probabilities[m]:.4g}, share {strata.shares[m]:.4f} -> {k} sample"
              f"{'s' if k != 1 else ''} (weight {strata.shares[m] / k:.4g} each; exact share x n = "
              f"{strata.shares[m] * args.n:.2f})")
    left = 1.0 - sum(strata.probabilities.values())
    print(f"  left out: models of probability below {args.min_probability:g}, {left:.3g} of the posterior together")
    print(f"wrote {out}")
    return DONE


def add_samples_parser(sub) -> None:
    p = sub.add_parser("samples", help="the diagnosis's posterior samples stratified by the rival models, for the "
                                       "calibrated IDA (&sweep model_samples_file) and its mixture fragility",
                       description="Write N rows of a posterior samples file (voussoir-diagnose's "
                                   "posterior_samples_<specimen>.csv): each model of posterior probability at least "
                                   "--min-probability gets a share of the N by its probability (at least one), "
                                   "its first rows in the file; each stratum's probability and weight in comment "
                                   "lines (docs/earthquakes.md, 'The calibrated fragility: a mixture of the models').")
    p.add_argument("samples", metavar="POSTERIOR.csv", help="the diagnosis's posterior samples of one specimen")
    p.add_argument("--n", type=int, default=30, help="samples to write (default 30)")
    p.add_argument("--diagnosis", metavar="DIAGNOSIS.json",
                   help="the diagnosis whose 'probabilities' weigh the models (default: diagnosis.json beside "
                        "the samples)")
    p.add_argument("--min-probability", type=float, default=0.01, metavar="P",
                   help="models below this posterior probability get no sample (default 0.01)")
    p.add_argument("--out", help="the stratified file, or a folder (default: <samples stem>_stratified<N>.csv "
                                 "beside the samples)")
    p.set_defaults(func=cmd_samples)
