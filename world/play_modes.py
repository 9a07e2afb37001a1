"""Play mode names, in the order rcssserver3d 0.7.2 lists them (the monitor sends an index)."""

from __future__ import annotations

PLAY_MODES: tuple[str, ...] = (
    "BeforeKickOff",
    "KickOff_Left",
    "KickOff_Right",
    "PlayOn",
    "KickIn_Left",
    "KickIn_Right",
    "corner_kick_left",
    "corner_kick_right",
    "goal_kick_left",
    "goal_kick_right",
    "offside_left",
    "offside_right",
    "GameOver",
    "Goal_Left",
    "Goal_Right",
    "free_kick_left",
    "free_kick_right",
    "direct_free_kick_left",
    "direct_free_kick_right",
    "pass_left",
    "pass_right",
)


def play_mode_index(name: str) -> int:
    """Index of a play mode as the monitor protocol encodes it; ValueError lists the valid names."""
    try:
        return PLAY_MODES.index(name)
    except ValueError:
        raise ValueError(f"unknown play mode {name!r}; valid: {', '.join(PLAY_MODES)}") from None
