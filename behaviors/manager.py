"""The behaviour manager: what strategy code calls to make the robot do things.

``Behavior.execute("get_up")`` runs one cycle of the named skill and says whether it has
finished. The manager keeps one instance of each skill per agent (created the first time it is
asked for), restarts a skill (``Skill.reset``) whenever it did not also run in the previous cycle,
and records how long the current and the previous behaviour have been running. Skills built of
other skills call :meth:`Behavior.execute_sub_behavior`, which keeps the same bookkeeping per
parent skill without touching the top-level behaviour.

One agent cycle::

    behavior.begin_cycle()                  # clears last cycle's joint commands
    done = behavior.execute("walk", target) # any number of skills may write commands
    send(behavior.effector_speeds())        # {effector: rad/s} for the server

Skills register themselves by being imported (see :mod:`behaviors.skill`); ``import behaviors``
imports the built-in ones.
"""

from __future__ import annotations

import contextlib
import inspect
import typing
from dataclasses import dataclass, field
from types import UnionType
from typing import TYPE_CHECKING, Any

from behaviors.joint_control import CYCLE_SECONDS, JointCommands
from behaviors.skill import Skill, SkillContext

if TYPE_CHECKING:
    from world.world_model import WorldModel


@dataclass(frozen=True, slots=True)
class BehaviorRun:
    """A stretch of cycles in which one skill ran without interruption."""

    name: str
    #: cycles the skill has run (each ``execute`` call counts one)
    cycles: int

    @property
    def seconds(self) -> float:
        """The run's length in server time (one cycle is 0.02 s)."""
        return self.cycles * CYCLE_SECONDS


@dataclass(slots=True)
class _Run:
    """The manager's mutable record of a run; ``last_cycle`` is when it last ran."""

    name: str
    cycles: int
    last_cycle: int

    def frozen(self) -> BehaviorRun:
        return BehaviorRun(self.name, self.cycles)


class Behavior:
    """One agent's skills, their lifetimes and this cycle's joint commands."""

    def __init__(self, world: WorldModel, robot_type: int = 0) -> None:
        self.world = world
        self.robot_type = robot_type
        self.commands = JointCommands(robot_type)
        self._context = SkillContext(world, self.commands, self)
        self._skills: dict[str, Skill] = {}
        self._signatures: dict[str, _Signature] = {}
        self._cycle = 0
        self._current: _Run | None = None
        self._previous: BehaviorRun | None = None
        #: names of the skills running right now, outermost first (the call stack of skills)
        self._running: list[str] = []
        #: parent skill name -> the run of the sub-skill it called last
        self._sub_runs: dict[str, _Run] = {}

    # ------------------------------------------------------------------ the agent loop
    def begin_cycle(self) -> None:
        """Start a new cycle: clear the joint commands the last one wrote."""
        self._cycle += 1
        self.commands.clear()

    def effector_speeds(self) -> dict[str, float]:
        """Effector name -> rad/s for this cycle, from the commands and the current joints."""
        return self.commands.effector_speeds(self.world.robot.joints_deg)

    # ------------------------------------------------------------------ running skills
    def execute(self, name: str, *args: Any) -> bool:
        """Run one cycle of skill ``name`` with ``args``; True once it has finished.

        The skill restarts (``reset``) unless it was also the top-level behaviour in the previous
        cycle. Raises KeyError for an unknown name and TypeError/ValueError for arguments the
        skill does not take; the messages list every skill and its signature.
        """
        if self._running:
            raise RuntimeError(
                f"skill {self._running[-1]!r} called execute({name!r}); skills run other skills "
                "with execute_sub_behavior, which leaves the top-level behaviour alone"
            )
        skill = self._prepare(name, args)
        run = self._current
        if run is None or not self._continues(run, name):
            if run is not None:
                self._previous = run.frozen()
            run = self._current = _Run(name, 0, self._cycle)
            self._restart(name)
        run.cycles += 1
        run.last_cycle = self._cycle
        return self._step(name, skill, args)

    def execute_sub_behavior(self, name: str, *args: Any) -> bool:
        """From inside a skill: run one cycle of skill ``name`` as part of the calling skill.

        The sub-skill restarts when its parent called a different sub-skill (or none) in the
        previous cycle, or when the parent itself restarted. The top-level ``current`` and
        ``previous`` behaviours are not changed.
        """
        if not self._running:
            raise RuntimeError(
                f"execute_sub_behavior({name!r}) called outside a skill; strategy code calls "
                "execute"
            )
        if name in self._running:
            raise RuntimeError(f"skill {name!r} would run itself: {' -> '.join(self._running)}")
        skill = self._prepare(name, args)
        parent = self._running[-1]
        run = self._sub_runs.get(parent)
        if run is None or not self._continues(run, name):
            run = self._sub_runs[parent] = _Run(name, 0, self._cycle)
            self._restart(name)
        run.cycles += 1
        run.last_cycle = self._cycle
        return self._step(name, skill, args)

    def skill(self, name: str) -> Skill:
        """This agent's instance of skill ``name`` (created on first use)."""
        instance = self._skills.get(name)
        if instance is None:
            cls = Skill.registry.get(name)
            if cls is None:
                raise KeyError(f"no skill {name!r}; registered skills:\n{describe_skills()}")
            instance = self._skills[name] = cls()
        return instance

    @property
    def skill_names(self) -> tuple[str, ...]:
        """Every registered skill name, sorted (what ``execute`` accepts)."""
        return tuple(sorted(Skill.registry))

    # ------------------------------------------------------------------ what ran
    @property
    def current(self) -> BehaviorRun | None:
        """The top-level behaviour of the latest ``execute`` and how long it has run."""
        return self._current.frozen() if self._current is not None else None

    @property
    def previous(self) -> BehaviorRun | None:
        """The top-level behaviour before the current one, with its full length."""
        return self._previous

    @property
    def running(self) -> tuple[str, ...]:
        """The skills stepping at this moment, outermost first (``("basic_kick", "walk")``
        while ``basic_kick`` runs ``walk`` as a sub-behaviour; empty between steps). Why: a
        skill may behave differently when another skill drives it (the walk's
        ``inside_skills`` settings)."""
        return tuple(self._running)

    @property
    def cycle(self) -> int:
        """How many cycles :meth:`begin_cycle` has started."""
        return self._cycle

    # ------------------------------------------------------------------ internals
    def _continues(self, run: _Run, name: str) -> bool:
        """Whether ``name`` carries on ``run``: the same skill, and it ran last or this cycle."""
        return run.name == name and run.last_cycle >= self._cycle - 1

    def _restart(self, name: str) -> None:
        self._skills[name].reset()
        self._sub_runs.pop(name, None)  # a restarted parent restarts its sub-skills too

    def _prepare(self, name: str, args: tuple[Any, ...]) -> Skill:
        instance = self.skill(name)
        signature = self._signatures.get(name)
        if signature is None:
            signature = self._signatures[name] = _Signature.of(type(instance))
        signature.check(name, args)
        try:
            instance.validate(*args)
        except ValueError as exc:
            raise ValueError(f"{signature.text(name)}: {exc}\n{describe_skills()}") from exc
        return instance

    def _step(self, name: str, skill: Skill, args: tuple[Any, ...]) -> bool:
        self._running.append(name)
        try:
            finished = skill.step(self._context, *args)
        finally:
            self._running.pop()
        if not isinstance(finished, bool):
            raise TypeError(
                f"skill {name!r} returned {finished!r} from step(); it must return True when "
                "finished and False otherwise"
            )
        return finished


# --------------------------------------------------------------------------------------------
# Argument checking and the skill list
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Signature:
    """The arguments a skill's ``step`` takes after the context, with their annotated types
    where those can be resolved (unresolvable annotations are not checked)."""

    signature: inspect.Signature
    types: dict[str, Any]
    #: whether an annotation checks values (``Literal``), so types alone cannot be cached
    value_sensitive: bool = False
    #: argument type tuples already accepted: a skill runs every cycle with the same kinds of
    #: arguments, and binding the signature each time cost 0.1-0.2 ms of a 1 ms think budget
    _accepted: set[tuple[type, ...]] = field(default_factory=set, compare=False, repr=False)

    @classmethod
    def of(cls, skill_class: type[Skill]) -> _Signature:
        signature = _step_signature(skill_class)
        types = {
            p.name: p.annotation
            for p in signature.parameters.values()
            if p.annotation is not inspect.Parameter.empty and not isinstance(p.annotation, str)
        }
        return cls(signature, types, any(map(_checks_values, types.values())))

    def text(self, name: str) -> str:
        return f"{name}{_signature_text(self.signature)}"

    def check(self, name: str, args: tuple[Any, ...]) -> None:
        key = tuple(map(type, args))
        if key in self._accepted:
            return
        self._check(name, args)
        if not self.value_sensitive:
            self._accepted.add(key)

    def _check(self, name: str, args: tuple[Any, ...]) -> None:
        try:
            bound = self.signature.bind(*args)
        except TypeError as exc:
            raise TypeError(
                f"bad arguments {args!r} for skill {self.text(name)}: {exc}\n"
                f"registered skills:\n{describe_skills()}"
            ) from None
        for param, value in bound.arguments.items():
            expected = self.types.get(param)
            kind = self.signature.parameters[param].kind
            values = value if kind is inspect.Parameter.VAR_POSITIONAL else (value,)
            for item in values:
                if expected is not None and not _matches(item, expected):
                    raise TypeError(
                        f"skill {self.text(name)}: argument {param!r} must be "
                        f"{_type_name(expected)}, got {item!r}\nregistered skills:\n"
                        f"{describe_skills()}"
                    )


def _checks_values(expected: Any) -> bool:
    """Whether :func:`_matches` looks at values for ``expected`` (a ``Literal`` anywhere in it)."""
    if typing.get_origin(expected) is typing.Literal:
        return True
    return any(_checks_values(arg) for arg in typing.get_args(expected))


def _matches(value: Any, expected: Any) -> bool:
    """A shallow isinstance check that understands unions, ``float`` accepting ints, and
    generic aliases (only their outer type is checked); ``Any`` and the like pass."""
    if expected is Any or expected is object:
        return True
    if expected is None or expected is type(None):
        return value is None
    origin = typing.get_origin(expected)
    if origin is typing.Union or origin is UnionType:
        return any(_matches(value, option) for option in typing.get_args(expected))
    if origin is typing.Literal:
        return value in typing.get_args(expected)
    if origin is not None:
        expected = origin
    if not isinstance(expected, type):
        return True
    if expected in (int, float) and isinstance(value, bool):
        return False
    if expected is float:
        return isinstance(value, int | float)
    return isinstance(value, expected)


def _type_name(expected: Any) -> str:
    return getattr(expected, "__name__", None) or str(expected)


def _step_signature(skill_class: type[Skill]) -> inspect.Signature:
    """``step``'s parameters after ``self`` and ``context``, with annotations evaluated where
    possible (as ``inspect.signature(eval_str=True)`` would, but one parameter at a time, so that
    one annotation naming a type imported only for type checking does not lose all the others).
    An annotation that cannot be evaluated stays a string and is not checked."""
    step = skill_class.step
    raw = list(inspect.signature(step).parameters.values())[2:]
    namespace = getattr(inspect.unwrap(step), "__globals__", {})
    params = []
    for param in raw:
        annotation = param.annotation
        if isinstance(annotation, str):
            # evaluate the skill's own annotation text; one that fails is simply not checked
            with contextlib.suppress(Exception):
                annotation = eval(annotation, namespace)
        params.append(param.replace(annotation=annotation))
    return inspect.Signature(params)


def _signature_text(signature: inspect.Signature) -> str:
    """``(distance: float, label: str | None = None)``: annotations as written in code."""
    parts = []
    for param in signature.parameters.values():
        text = param.name
        if param.kind is inspect.Parameter.VAR_POSITIONAL:
            text = "*" + text
        if param.annotation is not inspect.Parameter.empty:
            annotation = param.annotation
            if not isinstance(annotation, str):
                annotation = inspect.formatannotation(annotation)
            text += f": {annotation}"
        if param.default is not inspect.Parameter.empty:
            text += f" = {param.default!r}"
        parts.append(text)
    return "(" + ", ".join(parts) + ")"


def describe_skills() -> str:
    """One line per registered skill: its call signature and the first line of its docstring."""
    lines = []
    for name in sorted(Skill.registry):
        cls = Skill.registry[name]
        doc = (inspect.getdoc(cls) or "").split("\n", 1)[0]
        lines.append(f"  {name}{_signature_text(_step_signature(cls))}  {doc}".rstrip())
    return "\n".join(lines)
