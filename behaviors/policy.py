"""A trained policy run with numpy alone: a small MLP loaded from an ``.npz`` file.

Why numpy: a playing agent must not import torch (``tests/test_imports.py``), and a policy
that runs in a match should be the very numbers that were trained. ``learning/export.py``
writes the actor of a stable-baselines3 PPO model into one ``.npz``: the layer weights, the
observation normalisation PPO trained behind (``VecNormalize``: mean, variance, epsilon,
clip), the action bounds, the names of the observation and action entries, the training
config as text and the git commit. :meth:`MlpPolicy.load` checks every shape and, where the
caller says what it feeds and expects, every name, and fails with a :class:`PolicyError`
that says what is wrong, so that a file trained for other inputs cannot silently act.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

#: Format version written into every file; bump it when the layout changes.
FORMAT_VERSION = 1
ACTIVATIONS = ("tanh", "relu")


class PolicyError(ValueError):
    """A policy file that cannot be used: missing entries, wrong shapes or names."""


@dataclass(frozen=True)
class MlpPolicy:
    """Deterministic actor: normalise, hidden layers with ``activation``, linear output,
    clip to [-1, 1] (the action space the policy was trained in), then scale by
    ``action_scale`` into the caller's units."""

    weights: tuple[np.ndarray, ...]
    biases: tuple[np.ndarray, ...]
    activation: str
    obs_mean: np.ndarray
    obs_var: np.ndarray
    obs_epsilon: float
    obs_clip: float
    action_scale: np.ndarray
    obs_names: tuple[str, ...]
    action_names: tuple[str, ...]
    config_text: str = ""
    git_commit: str = ""

    def __post_init__(self) -> None:
        _check_layers(self.weights, self.biases)
        if self.activation not in ACTIVATIONS:
            raise PolicyError(f"activation {self.activation!r} unknown; known: {ACTIVATIONS}")
        n_obs, n_act = self.weights[0].shape[1], self.weights[-1].shape[0]
        expected = {
            "obs_mean": (self.obs_mean, n_obs),
            "obs_var": (self.obs_var, n_obs),
            "action_scale": (self.action_scale, n_act),
        }
        for key, (array, size) in expected.items():
            if array.shape != (size,):
                raise PolicyError(f"{key} has shape {array.shape}, the layers need ({size},)")
        if len(self.obs_names) != n_obs:
            raise PolicyError(f"{len(self.obs_names)} observation names for {n_obs} inputs")
        if len(self.action_names) != n_act:
            raise PolicyError(f"{len(self.action_names)} action names for {n_act} outputs")
        if np.any(self.obs_var < 0) or self.obs_clip <= 0:
            raise PolicyError("obs_var must be >= 0 and obs_clip > 0")

    @property
    def n_obs(self) -> int:
        return int(self.weights[0].shape[1])

    @property
    def n_actions(self) -> int:
        return int(self.weights[-1].shape[0])

    def normalise(self, obs: np.ndarray) -> np.ndarray:
        """The observation as the network saw it in training (VecNormalize's formula)."""
        scaled = (obs - self.obs_mean) / np.sqrt(self.obs_var + self.obs_epsilon)
        return np.clip(scaled, -self.obs_clip, self.obs_clip)

    def raw_action(self, obs: Sequence[float] | np.ndarray) -> np.ndarray:
        """The action in the training space [-1, 1] for one observation."""
        x = np.asarray(obs, dtype=np.float64)
        if x.shape != (self.n_obs,):
            raise PolicyError(f"observation has shape {x.shape}, the policy takes ({self.n_obs},)")
        h = self.normalise(x)
        last = len(self.weights) - 1
        for i, (w, b) in enumerate(zip(self.weights, self.biases)):
            h = w @ h + b
            if i < last:
                h = np.tanh(h) if self.activation == "tanh" else np.maximum(h, 0.0)
        return np.clip(h, -1.0, 1.0)

    def act(self, obs: Sequence[float] | np.ndarray) -> np.ndarray:
        """The action in the caller's units (``raw_action`` times ``action_scale``)."""
        return self.raw_action(obs) * self.action_scale

    # ------------------------------------------------------------------ files
    def save(self, path: str | Path) -> None:
        """Write the policy to ``path`` (an ``.npz``; no pickled objects)."""
        arrays: dict[str, np.ndarray] = {
            "format_version": np.array(FORMAT_VERSION),
            "n_layers": np.array(len(self.weights)),
            "activation": np.array(self.activation),
            "obs_mean": self.obs_mean,
            "obs_var": self.obs_var,
            "obs_epsilon": np.array(self.obs_epsilon),
            "obs_clip": np.array(self.obs_clip),
            "action_scale": self.action_scale,
            "obs_names": np.array(self.obs_names),
            "action_names": np.array(self.action_names),
            "config_text": np.array(self.config_text),
            "git_commit": np.array(self.git_commit),
        }
        for i, (w, b) in enumerate(zip(self.weights, self.biases)):
            arrays[f"w{i}"] = w
            arrays[f"b{i}"] = b
        np.savez(Path(path), **arrays)

    @classmethod
    def load(
        cls,
        path: str | Path,
        obs_names: Sequence[str] | None = None,
        action_names: Sequence[str] | None = None,
    ) -> MlpPolicy:
        """Read a policy file; with ``obs_names``/``action_names`` also check that it was
        trained on exactly these inputs and outputs, in this order."""
        path = Path(path)
        try:
            with np.load(path, allow_pickle=False) as data:
                entries = {key: data[key] for key in data.files}
        except (OSError, ValueError) as error:
            raise PolicyError(f"{path}: not a readable policy file ({error})") from error
        policy = _from_entries(entries, str(path))
        _check_names(policy.obs_names, obs_names, f"{path}: observation")
        _check_names(policy.action_names, action_names, f"{path}: action")
        return policy


def load_checked_policy(
    path: str | Path,
    obs_names: Sequence[str],
    action_names: Sequence[str],
    action_scale: Sequence[float] | np.ndarray,
) -> MlpPolicy:
    """Load a policy file for a skill: it must take exactly ``obs_names``, give exactly
    ``action_names`` and scale its outputs by ``action_scale`` (the skill's offsets), or a
    :class:`PolicyError` says which does not match."""
    policy = MlpPolicy.load(path, obs_names, action_names)
    expected = np.asarray(action_scale, dtype=float)
    if not np.allclose(policy.action_scale, expected):
        raise PolicyError(
            f"{path}: action scale {policy.action_scale.tolist()} is not the skill's "
            f"{expected.tolist()}"
        )
    return policy


def _check_layers(weights: Sequence[np.ndarray], biases: Sequence[np.ndarray]) -> None:
    """Consecutive layers must chain: w_i is (out_i, in_i), b_i is (out_i,), in_i = out_{i-1}."""
    if not weights or len(weights) != len(biases):
        raise PolicyError(f"{len(weights)} weight matrices and {len(biases)} bias vectors")
    for i, (w, b) in enumerate(zip(weights, biases)):
        if w.ndim != 2 or b.shape != (w.shape[0],):
            raise PolicyError(f"layer {i}: weights {w.shape} and bias {b.shape} do not match")
        if i and w.shape[1] != weights[i - 1].shape[0]:
            given = weights[i - 1].shape[0]
            raise PolicyError(f"layer {i} takes {w.shape[1]} inputs, layer {i - 1} gives {given}")


def _check_names(found: tuple[str, ...], wanted: Sequence[str] | None, what: str) -> None:
    if wanted is None or tuple(wanted) == found:
        return
    missing = [n for n in wanted if n not in found]
    extra = [n for n in found if n not in wanted]
    raise PolicyError(
        f"{what} names differ from what the caller uses: missing {missing}, unexpected {extra}"
        + ("" if missing or extra else " (same names, other order)")
    )


_REQUIRED = (
    "format_version", "n_layers", "activation", "obs_mean", "obs_var", "obs_epsilon",
    "obs_clip", "action_scale", "obs_names", "action_names",
)  # fmt: skip


def _from_entries(entries: dict[str, np.ndarray], where: str) -> MlpPolicy:
    missing = [key for key in _REQUIRED if key not in entries]
    if missing:
        raise PolicyError(f"{where}: missing entries {missing}")
    version = int(entries["format_version"])
    if version != FORMAT_VERSION:
        raise PolicyError(f"{where}: format version {version}, this code reads {FORMAT_VERSION}")
    n_layers = int(entries["n_layers"])
    layer_keys = [k for i in range(n_layers) for k in (f"w{i}", f"b{i}")]
    missing = [key for key in layer_keys if key not in entries]
    if missing:
        raise PolicyError(f"{where}: missing layer entries {missing}")
    try:
        return MlpPolicy(
            weights=tuple(entries[f"w{i}"].astype(np.float64) for i in range(n_layers)),
            biases=tuple(entries[f"b{i}"].astype(np.float64) for i in range(n_layers)),
            activation=str(entries["activation"]),
            obs_mean=entries["obs_mean"].astype(np.float64),
            obs_var=entries["obs_var"].astype(np.float64),
            obs_epsilon=float(entries["obs_epsilon"]),
            obs_clip=float(entries["obs_clip"]),
            action_scale=entries["action_scale"].astype(np.float64),
            obs_names=tuple(str(n) for n in entries["obs_names"]),
            action_names=tuple(str(n) for n in entries["action_names"]),
            config_text=str(entries.get("config_text", "")),
            git_commit=str(entries.get("git_commit", "")),
        )
    except PolicyError as error:
        raise PolicyError(f"{where}: {error}") from error
