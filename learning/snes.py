"""Separable natural evolution strategy (SNES): a mean and a spread per parameter.

Why this one: the searches here (get-up frames, walk parameters) have 10-30 bounded parameters,
noisy scores and a few hundred generations at most; SNES needs no covariance matrix, moves
each parameter's spread on its own (parameters of very different scales need no hand
scaling beyond a start spread) and is a dozen lines (Schaul et al., "High dimensions and heavy
tails for natural evolution strategies", 2011).

Use: ``ask`` a generation of samples, score them, ``tell`` the scores (higher is better).
"""

from __future__ import annotations

import math

import numpy as np


def utilities(count: int) -> np.ndarray:
    """SNES's rank utilities, best first (they sum to zero)."""
    raw = np.maximum(0.0, math.log(count / 2 + 1) - np.log(np.arange(1, count + 1)))
    return raw / raw.sum() - 1.0 / count


def default_population(dimensions: int) -> int:
    """The usual population size 4 + 3 ln(n), rounded up to an even count (mirrored pairs)."""
    size = 4 + int(3 * math.log(dimensions))
    return size + size % 2


class SNES:
    """Mean and spread within ``low``..``high``; samples are clipped to the bounds and the
    update uses the clipped steps, so a parameter pressed against a bound stops moving out.

    Samples come in mirrored pairs (mean +- the same noise): the pair's score difference
    carries the gradient, the shared noise cancels (antithetic sampling)."""

    def __init__(
        self,
        mean: np.ndarray,
        spread: np.ndarray,
        low: np.ndarray,
        high: np.ndarray,
        population: int | None = None,
        seed: int = 0,
    ) -> None:
        self.mean = np.asarray(mean, dtype=float).copy()
        self.spread = np.asarray(spread, dtype=float).copy()
        self.low = np.asarray(low, dtype=float)
        self.high = np.asarray(high, dtype=float)
        n = len(self.mean)
        if not (len(self.spread) == len(self.low) == len(self.high) == n):
            raise ValueError("mean, spread, low and high must have the same length")
        if np.any(self.spread <= 0.0) or np.any(self.low >= self.high):
            raise ValueError("spreads must be positive and every low below its high")
        self.population = population or default_population(n)
        if self.population < 2 or self.population % 2:
            raise ValueError(f"population must be even and at least 2, got {self.population}")
        self.eta_mean = 1.0
        self.eta_spread = (3 + math.log(n)) / (5 * math.sqrt(n))
        self._rng = np.random.default_rng(seed)
        self._samples: np.ndarray | None = None

    def ask(self) -> np.ndarray:
        """A generation of samples, one per row."""
        half = self._rng.standard_normal((self.population // 2, len(self.mean)))
        noise = np.concatenate([half, -half])
        self._samples = np.clip(self.mean + self.spread * noise, self.low, self.high)
        return self._samples.copy()

    def tell(self, scores: np.ndarray) -> None:
        """Move the mean and the spreads towards the better samples of the last ``ask``."""
        if self._samples is None:
            raise RuntimeError("tell() without a generation from ask()")
        scores = np.asarray(scores, dtype=float)
        if scores.shape != (len(self._samples),):
            raise ValueError(f"need {len(self._samples)} scores, got shape {scores.shape}")
        order = np.argsort(-scores)
        u = utilities(len(order))
        steps = (self._samples - self.mean) / self.spread
        ranked = steps[order]
        self.mean = np.clip(
            self.mean + self.eta_mean * self.spread * (u @ ranked), self.low, self.high
        )
        self.spread = self.spread * np.exp(0.5 * self.eta_spread * (u @ (ranked**2 - 1.0)))
        self._samples = None
