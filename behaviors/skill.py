"""The base of every behaviour: a :class:`Skill` runs one cycle at a time and says when it is done.

A skill subclass with a ``name`` registers itself when its module is imported, so a new
behaviour joins the manager (``behaviors.manager.Behavior``) without editing any central list.
Skills never talk to the server: they write joint targets or speeds into the cycle's
:class:`~behaviors.joint_control.JointCommands`, which the agent turns into effectors.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

from behaviors.joint_control import JointCommands

if TYPE_CHECKING:
    from world.world_model import WorldModel


@dataclass
class SkillContext:
    """What a skill sees and writes in one cycle."""

    #: everything the agent knows (perception-fed only)
    world: WorldModel
    #: this cycle's joint commands: write targets or speeds here
    commands: JointCommands
    #: the manager, for skills made of skills (``manager.execute_sub_behavior``)
    manager: Any


class Skill:
    """One behaviour. Subclasses set ``name`` and implement :meth:`step` (and :meth:`reset`).

    The manager creates one instance per skill and agent, calls :meth:`reset` whenever the skill
    starts again after another one ran, then :meth:`step` every cycle with the caller's
    arguments. ``step`` returns True once the skill has finished.
    """

    #: the name users pass to ``Behavior.execute``; empty for abstract helpers
    name: ClassVar[str] = ""
    #: name -> class of every concrete skill defined so far (filled at import time only)
    registry: ClassVar[dict[str, type[Skill]]] = {}

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if not cls.name:
            return
        existing = Skill.registry.get(cls.name)
        if existing is not None and existing is not cls:
            raise TypeError(
                f"skill name {cls.name!r} is taken by {existing.__module__}.{existing.__qualname__}"
            )
        Skill.registry[cls.name] = cls

    def reset(self) -> None:
        """Forget any progress: the next :meth:`step` starts the skill afresh."""

    def validate(self, *args: Any) -> None:
        """Raise ValueError for argument values ``step`` cannot use (a negative distance, an
        unknown pose name). The manager calls this before every step, after checking the
        number and types of the arguments against ``step``'s signature, and adds the skill's
        signature and the list of skills to the message."""

    def step(self, context: SkillContext, *args: Any) -> bool:
        """Run one cycle; True when finished. Extra parameters after ``context`` are the
        arguments of ``Behavior.execute(name, *args)``; annotate them so that the manager can
        check callers' types."""
        raise NotImplementedError
