"""A short scripted client for the stand-in server: the main job until the full agent exists.

It does what every real agent does first (``scene``, ``init``, ``beam``), then moves its joints
with speed commands for a few seconds and prints what the server tells it: game time, play
mode, its joint angles, the foot pressure and the ball as its camera sees it.
"""

from __future__ import annotations

import math

from agent.transport import TcpTransport
from world.effectors import EffectorMessage, write_effectors
from world.perception import Perception, parse_perception


def run_demo_client(host: str, port: int, cycles: int = 250, print_every: int = 25) -> int:
    """Play the scripted demo; returns the number of perceptions received."""
    transport = TcpTransport(host, port)
    try:
        transport.send(write_effectors(EffectorMessage(scene=("rsg/agent/nao/nao_hetero.rsg", 0))))
        transport.receive()
        transport.send(write_effectors(EffectorMessage(init=(1, "NaoDemo"), syn=True)))
        received = 0
        last_ball = "not seen yet"
        for cycle in range(cycles):
            perception = parse_perception(transport.receive())
            received += 1
            last_ball = _ball_text(perception) or last_ball
            action = EffectorMessage(joint_speeds=_wave(cycle), syn=True)
            if cycle == 2:
                action.beam = (-1.0, 0.0, 0.0)
            transport.send(write_effectors(action))
            if cycle % print_every == 0:
                print(_describe(perception, last_ball))
        return received
    finally:
        transport.close()


def _wave(cycle: int) -> dict[str, float]:
    """Wave both arms and bend the knees a little: speeds in rad/s."""
    phase = 2 * math.pi * cycle / 100
    arm = 2.0 * math.cos(phase)
    knee = 0.4 * math.cos(phase)
    return {
        "rae1": -arm,
        "lae1": -arm,
        "rae2": 0.0,
        "lae2": 0.0,
        "lle3": knee,
        "rle3": knee,
        "lle4": -2 * knee,
        "rle4": -2 * knee,
        "lle5": knee,
        "rle5": knee,
    }


def _ball_text(p: Perception) -> str | None:
    """The ball as the last image showed it, or None when this message has no image of it."""
    if p.vision is None:
        return None
    if p.vision.ball is None:
        return "not in view"
    b = p.vision.ball
    return f"{b.distance:.2f} m at {b.phi:+.1f} deg"


def _describe(p: Perception, ball: str) -> str:
    gs = p.game_state
    feet = ",".join(sorted(p.force_resistance)) or "none"
    return (
        f"t={p.time:6.2f}  {gs.play_mode:<13} shoulder={p.joints.get('raj1', 0):+7.2f} deg "
        f"knee={p.joints.get('rlj4', 0):+7.2f} deg  feet on ground: {feet:<5}  ball: {ball}"
    )
