"""Two elementary skills: ``zero`` (every joint to 0 degrees) and ``hold`` (stay as you are).

They are small enough to test the manager with, and useful in their own right: ``zero`` is the
model's reference pose (arms forward, legs straight) and ``hold`` freezes a robot between
motions without letting it sag (speed 0 alone lets loaded joints drift).
"""

from __future__ import annotations

from behaviors.skill import Skill, SkillContext

#: A joint closer than this to its target (degrees) counts as there.
REACHED_DEG = 1.0


def _reached(current: dict[str, float], targets: dict[str, float], tolerance: float) -> bool:
    return all(abs(current.get(name, 0.0) - value) <= tolerance for name, value in targets.items())


class Zero(Skill):
    """All joints to 0 degrees; finished once every joint is within ``REACHED_DEG`` of it."""

    name = "zero"

    def step(self, context: SkillContext) -> bool:
        targets = dict.fromkeys(context.commands.joint_names, 0.0)
        context.commands.set_targets(targets)
        return _reached(context.world.robot.joints_deg, targets, REACHED_DEG)


class Hold(Skill):
    """Keep the joint angles the robot had when the skill started.

    It holds the angles captured at the start, not each cycle's current ones (which would let a
    loaded joint creep); finished once every joint is within ``REACHED_DEG`` of them."""

    name = "hold"

    def __init__(self) -> None:
        self._pose: dict[str, float] | None = None

    def reset(self) -> None:
        self._pose = None

    def step(self, context: SkillContext) -> bool:
        current = context.world.robot.joints_deg
        if self._pose is None:
            self._pose = {name: current.get(name, 0.0) for name in context.commands.joint_names}
        context.commands.set_targets(self._pose)
        # compare with the targets as clipped to the joint ranges, which the joints can reach
        targets = context.commands.targets()
        held = {name: targets[name] for name in self._pose}
        return _reached(current, held, REACHED_DEG)
