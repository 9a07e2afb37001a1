"""Skills and the behaviour manager. Runs with numpy only: no pybullet, no torch.

Importing this package imports the built-in skill modules listed in
:data:`BUILTIN_SKILL_MODULES`, so every built-in skill is registered and
``Behavior.execute(name)`` finds it. A user's skills register by being imported.
"""

from __future__ import annotations

import importlib

from behaviors.joint_control import DEFAULT_GAIN, JointCommands
from behaviors.manager import Behavior, BehaviorRun, describe_skills
from behaviors.mirror import (
    MIRROR_TABLE,
    MirrorEntry,
    ObservationLayout,
    Segment,
    mirror_accelerometer,
    mirror_action,
    mirror_direction_deg,
    mirror_effector_speeds,
    mirror_field_point,
    mirror_gyro,
    mirror_joint_angles,
    mirror_keyframes,
    mirror_observation,
    mirror_vector_native,
)
from behaviors.skill import Skill, SkillContext

#: Modules whose skills every agent has; add a module here when it defines built-in skills.
BUILTIN_SKILL_MODULES: tuple[str, ...] = (
    "behaviors.basic",
    "behaviors.poses",
    "behaviors.keyframes",
    "behaviors.get_up",
    "behaviors.walk",
    "behaviors.kick",
    "behaviors.basic_kick",
    "behaviors.dribble",
    "behaviors.learned_walk",
)

for _module in BUILTIN_SKILL_MODULES:
    importlib.import_module(_module)

__all__ = [
    "BUILTIN_SKILL_MODULES",
    "DEFAULT_GAIN",
    "MIRROR_TABLE",
    "Behavior",
    "BehaviorRun",
    "JointCommands",
    "MirrorEntry",
    "ObservationLayout",
    "Segment",
    "Skill",
    "SkillContext",
    "describe_skills",
    "mirror_accelerometer",
    "mirror_action",
    "mirror_direction_deg",
    "mirror_effector_speeds",
    "mirror_field_point",
    "mirror_gyro",
    "mirror_joint_angles",
    "mirror_keyframes",
    "mirror_observation",
    "mirror_vector_native",
]
