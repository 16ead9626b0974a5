"""A Gaussian-process emulator of the bank: a model's log threshold between its simulated nodes.

The bank simulates each model at a few values of its parameters (the nodes). Between
them the diagnosis needs a prediction and an honest statement of how well it is known:

- the mean follows the simulator: at a node it is what the bank simulated there (the
  mean of the node's search and its replicas), to within the simulator's own spread,
  which is the GP's nugget (the replicas' pooled variance over the node's number of
  searches). So every effect's curve passes through the nominal model at its nominal
  value, and a steep response is followed, not smoothed away;
- where the nodes do not lie on any smooth curve to within that spread (a pair near a
  change of mechanism, where one node stands 28 % above its neighbours), a roughness is
  added to the nugget, chosen with the kernel by the marginal likelihood (0 where the
  nodes are smooth): the mean then passes among such nodes, not through each;
- between nodes the GP's own variance says how much the emulator does not know; it
  vanishes at the nodes (but for the roughness: a threshold at an unsimulated value
  varies about the curve as the nodes do) and enters the likelihood as the emulator's
  error (likelihood.py), never as simulator noise;
- the lack of fit is measured apart: the leave-one-node-out residuals, standardised by
  their predictive spread (about 1 when the emulator is as good as it says), reported.

Kernel: Matern 5/2 on parameters scaled to [0, 1], plus a linear trend fitted first by
least squares. Its length scales, amplitude and roughness are chosen by the largest
marginal likelihood on a fixed grid (deterministic, no optimiser start to depend on),
once per set of nodes (kept: the same nodes are emulated at other points many times).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import cho_factor, cho_solve

__all__ = ["Emulation", "emulate", "LENGTH_SCALES", "AMPLITUDES"]

#: Length scales tried, in units of the parameter's range.
LENGTH_SCALES = (0.04, 0.07, 0.12, 0.2, 0.35, 0.6, 1.0, 2.0)
#: Amplitudes tried, as multiples of the residual standard deviation about the trend.
AMPLITUDES = (0.3, 1.0, 3.0)
AMPLITUDE_FLOOR = 0.003  #: smallest GP amplitude [log units], for nodes lying on a line
#: Roughness tried [log units]: a variation of the threshold from node to node that no
#: smooth curve follows, beyond the replicas' spread (a window of one node at a pair whose
#: response to the parameter is chaotic). Chosen with the kernel by the marginal
#: likelihood; 0 where the nodes lie on a smooth curve to within the replicas.
ROUGHNESS = (0.0, 0.01, 0.02, 0.04, 0.08, 0.16)


@dataclass
class Emulation:
    """The emulator's prediction at the points asked for."""

    mean: np.ndarray  #: predicted log threshold
    var: np.ndarray  #: the emulator's variance of it (0 at a node without noise)
    loo_z: np.ndarray  #: standardised leave-one-node-out residuals of the nodes
    length_scales: tuple[float, ...]
    amplitude: float
    roughness: float = 0.0  #: the node-to-node variation beyond the replicas [log units]


def _matern52(a: np.ndarray, b: np.ndarray, scales: np.ndarray) -> np.ndarray:
    d = (a[:, None, :] - b[None, :, :]) / scales[None, None, :]
    r = np.sqrt(np.sum(d * d, axis=2)) * math.sqrt(5.0)
    return (1.0 + r + r * r / 3.0) * np.exp(-r)


def _trend(x: np.ndarray) -> np.ndarray:
    return np.hstack([np.ones((x.shape[0], 1)), x])


#: The kernel chosen for each set of nodes (keyed by the nodes' bytes): the same nodes are
#: emulated at other points many times (each model's grid, the effects' sizes, the folds).
_CHOSEN: dict[bytes, tuple] = {}


def _choose(x: np.ndarray, r: np.ndarray, noise: np.ndarray) -> tuple:
    """(length scales, amplitude^2, roughness) of the largest marginal likelihood (the
    first of equals, in the order of the grids)."""
    key = x.tobytes() + b"|" + r.tobytes() + b"|" + noise.tobytes()
    if key in _CHOSEN:
        return _CHOSEN[key]
    n, d = x.shape
    base = max(AMPLITUDE_FLOOR, float(np.sqrt(np.mean(r * r))))
    combos, mats = [], []
    for scales in itertools.product(LENGTH_SCALES, repeat=d):
        k0 = _matern52(x, x, np.array(scales))
        for a, rough in itertools.product(AMPLITUDES, ROUGHNESS if n > d + 3 else (0.0,)):
            amp2 = (a * base) ** 2
            combos.append((scales, amp2, rough))
            mats.append(amp2 * k0 + np.diag(noise + rough * rough))
    try:  # every candidate at once (small matrices: one batched factorisation)
        low = np.linalg.cholesky(np.array(mats))
        ok = np.ones(len(mats), bool)
    except np.linalg.LinAlgError:  # one is not positive definite: factor them one by one
        low = np.zeros((len(mats), n, n))
        ok = np.zeros(len(mats), bool)
        for k, m in enumerate(mats):
            try:
                low[k] = np.linalg.cholesky(m)
                ok[k] = True
            except np.linalg.LinAlgError:
                pass
    low = low[ok]
    z = np.linalg.solve(low, np.broadcast_to(r, (low.shape[0], n))[..., None])[..., 0]  # L z = r
    logml = -0.5 * np.sum(z * z, axis=1) - np.sum(np.log(np.diagonal(low, axis1=1, axis2=2)), axis=1)
    best = [c for c, good in zip(combos, ok) if good][int(np.argmax(logml))]
    if len(_CHOSEN) > 20000:
        _CHOSEN.clear()
    _CHOSEN[key] = best
    return _CHOSEN[key]


def emulate(x: np.ndarray, y: np.ndarray, noise_var: np.ndarray, points: np.ndarray) -> Emulation:
    """Emulate y(x) from the nodes x (n, d) scaled to [0, 1], their log thresholds y (n,)
    and noise variances (n,), at `points` (m, d)."""
    x = np.asarray(x, float).reshape(len(y), -1)
    points = np.asarray(points, float).reshape(-1, x.shape[1])
    y = np.asarray(y, float)
    noise = np.maximum(np.asarray(noise_var, float), 1e-10)
    n, d = x.shape
    h = _trend(x)
    n_trend = h.shape[1] if n > h.shape[1] + 1 else 1
    h = h[:, :n_trend]
    beta, *_ = np.linalg.lstsq(h, y, rcond=None)
    r = y - h @ beta
    scales, amp2, rough = _choose(x, r, noise)
    c = cho_factor(amp2 * _matern52(x, x, np.array(scales)) + np.diag(noise + rough * rough), lower=True)
    alpha = cho_solve(c, r)
    ks = amp2 * _matern52(points, x, np.array(scales))
    mean = _trend(points)[:, :n_trend] @ beta + ks @ alpha
    v = cho_solve(c, ks.T)
    # A threshold at an unsimulated value varies about the smooth curve as the nodes do.
    var = np.maximum(amp2 - np.sum(ks * v.T, axis=1), 0.0) + rough * rough
    # Leave one node out, in closed form: residual alpha_i / [K^-1]_ii, variance 1 / [K^-1]_ii.
    kinv = cho_solve(c, np.eye(n))
    loo_z = alpha / np.sqrt(np.diag(kinv))
    return Emulation(mean, var, loo_z, tuple(scales), math.sqrt(amp2), rough)
