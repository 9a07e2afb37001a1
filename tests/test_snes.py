"""The separable natural evolution strategy used by the parameter searches."""

from __future__ import annotations

import numpy as np
import pytest

from learning.snes import SNES, default_population, utilities


def test_utilities_rank_the_best_highest_and_sum_to_zero():
    u = utilities(12)
    assert u.sum() == pytest.approx(0.0)
    assert np.all(np.diff(u) <= 0.0) and u[0] > 0.0 > u[-1]


def test_samples_come_in_mirrored_pairs_within_the_bounds():
    es = SNES(np.zeros(3), np.ones(3), -np.full(3, 0.5), np.full(3, 0.5), population=6, seed=1)
    samples = es.ask()
    assert samples.shape == (6, 3)
    assert np.all(samples >= -0.5) and np.all(samples <= 0.5)
    unclipped = np.abs(samples[:3]) < 0.5
    assert np.allclose(samples[:3][unclipped], -samples[3:][unclipped])


def test_it_climbs_a_bounded_quadratic_to_its_optimum():
    """Maximise -(x - target)^2 with one target coordinate outside the bounds: the mean goes
    to the target, and to the bound where the target lies beyond it."""
    target = np.array([0.3, -2.0, 5.0])
    low, high = np.array([-1.0, -3.0, 0.0]), np.array([1.0, 3.0, 4.0])
    es = SNES(np.zeros(3), np.array([0.3, 0.5, 0.5]), low, high, seed=0)
    for _ in range(150):
        samples = es.ask()
        es.tell(-np.sum((samples - target) ** 2, axis=1))
    assert es.mean == pytest.approx(np.array([0.3, -2.0, 4.0]), abs=0.05)
    assert np.all(es.spread[:2] < 0.1)


def test_misuse_is_refused():
    with pytest.raises(ValueError):
        SNES(np.zeros(2), np.ones(2), np.zeros(2), np.ones(2), population=3)
    with pytest.raises(ValueError):
        SNES(np.zeros(2), np.array([1.0, 0.0]), -np.ones(2), np.ones(2))
    es = SNES(np.zeros(2), np.ones(2), -np.ones(2), np.ones(2))
    with pytest.raises(RuntimeError):
        es.tell(np.zeros(es.population))
    es.ask()
    with pytest.raises(ValueError):
        es.tell(np.zeros(es.population + 1))
    assert default_population(18) % 2 == 0 and default_population(18) >= 12
