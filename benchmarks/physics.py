"""Physics cost of the stand-in: cycle rates, where Bullet's step time goes, and what physics
changes WOULD buy (measured here, not adopted).

    .venv/bin/python benchmarks/physics.py                 # cycles_per_s[substeps=S,robots=N]
    .venv/bin/python benchmarks/physics.py --split         # Bullet's own timers, 22 robots
    .venv/bin/python benchmarks/physics.py --variants      # speed, stance, fidelity per variant
    .venv/bin/python benchmarks/physics.py --variant floor_iters5 --speed-only   # Bullet's floor
    .venv/bin/python benchmarks/physics.py --variant iters15 --pytest tests/test_walk.py -q
    .venv/bin/python benchmarks/physics.py --variant strike --contact   # ball bounce and roll
    .venv/bin/python benchmarks/physics.py --variant strike --run benchmarks/kick.py --impact
    .venv/bin/python benchmarks/physics.py --variant strike --kick-gaps 0.024 0.06 0.1
    .venv/bin/python benchmarks/physics.py --variant bounce --run benchmarks/kick.py --impact
    .venv/bin/python benchmarks/physics.py --variant strike_noself --run benchmarks/kick.py \
        --seeds 6 --strengths 0 1 --basic-trials 0

``cycles_per_s``: each cycle does what the server does per robot: new joint speeds, one world
step, sensor update, joint angles, gyro, accelerometer and foot pressure.

``--split`` records Bullet's internal profile timers (``STATE_LOGGING_PROFILE_TIMINGS``) for
22 standing robots and prints each phase's share of the step (the timers themselves slow the
step down, so only the shares mean something).

``--variants`` measures, per candidate physics change: the CPU time of one cycle of 22 standing
robots (``step_ms[...]``), whether an idle robot of type 0 and 4 still stands still after 4 s
(height and tilt), and the checks of ``tests/test_fidelity.py`` on the real-server recordings.
A variant is applied by patching the module constants that the world reads when it is built
(``sim.physics.SOLVER_ITERATIONS``, ``sim.session.BASE_SUBSTEPS``) or by setting an engine
parameter on every new world, so the committed physics stays as it is.

``strike`` (and ``rigid``, the same without the bounce) moves the soft-contact parameters from
the robot links to the ground (see :func:`_strike`): robot-ground contacts stay as tuned, the
foot-ball and robot-robot contacts become rigid, and the foot-ball contact bounces at 0.8 as on
the real server (``sim.contact_models``, ``contact: strike`` in ``config/server.yaml``).
``noself`` and ``strike_noself`` add the real server's rule that no two parts of one robot
touch (``self_collision: false``). ``--contact`` prints the ball's own figures under a variant
(bounce on the ground, roll distances); ``--run SCRIPT ARGS`` runs any benchmark script inside
the variant.
"""

from __future__ import annotations

import argparse
import collections
import contextlib
import dataclasses
import json
import math
import re
import runpy
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from pathlib import Path

import pybullet

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import sim.field
import sim.physics
import sim.robot
import sim.session
from sim.contact_models import (
    DEFAULT_CONTACT_MODEL,
    ContactPhysics,
    bounce_contact,
    soft_contact,
    strike_contact,
    with_self_collision,
)
from sim.field import Ball, build_field
from sim.physics import CYCLE_SECONDS, PhysicsWorld
from sim.robot import SimRobot
from world.field_geometry import BALL_RADIUS

TRACES = Path(__file__).resolve().parents[2] / "shared" / "reference" / "rcssserver3d-traces"


# --------------------------------------------------------------------------------------------
# plain cycle rates
# --------------------------------------------------------------------------------------------


def world_with_robots(substeps: int, robots: int) -> tuple[PhysicsWorld, list[SimRobot]]:
    """A plain ground with ``robots`` robots of types 0-4 in turn, 2 m apart in two rows,
    dropped from 0.4 m: the scene every speed figure here (and ``scripts/physics``) times."""
    world = PhysicsWorld(substeps=substeps)
    plane = pybullet.createCollisionShape(pybullet.GEOM_PLANE, physicsClientId=world.client)
    pybullet.createMultiBody(0, plane, physicsClientId=world.client)
    team = []
    for k in range(robots):
        robot = SimRobot(world, k % 5)
        robot.place(-10.0 + 2.0 * (k % 11), -3.0 + 6.0 * (k // 11), 0.4, 0.0)
        team.append(robot)
    return world, team


def measure(substeps: int, robots: int, cycles: int) -> float:
    world, team = world_with_robots(substeps, robots)
    start = time.perf_counter()
    for c in range(cycles):
        s = math.sin(0.1 * c)
        for robot in team:
            robot.set_joint_speeds({"he1": s, "rae1": 2 * s, "lae1": -2 * s, "rle3": 0.3 * s})
        world.step_cycle()
        for robot in team:
            robot.update_sensors()
            robot.joint_angles_deg()
            robot.gyro_deg_s()
            robot.accelerometer()
            robot.force_resistance()
    elapsed = time.perf_counter() - start
    world.close()
    return cycles / elapsed


# --------------------------------------------------------------------------------------------
# where Bullet's step time goes
# --------------------------------------------------------------------------------------------

#: Bullet profile scopes worth reporting, in the order they nest.
SPLIT_SCOPES = (
    "internalSingleStepSimulation",
    "performDiscreteCollisionDetection",
    "updateAabbs",
    "calculateOverlappingPairs",
    "dispatchAllCollisionPairs",
    "solveConstraints",
    "solveGroupCacheFriendlySetup",
    "setupMultiBodyContactConstraint",
    "solveGroupCacheFriendlyIterations",
    "btMultiBody stepVelocities",
    "btMultiBody stepPositions",
)


def bullet_split(robots: int = 22, cycles: int = 30) -> dict[str, float]:
    """Share of the step (0..1) each Bullet scope takes, plus ``contacts_per_robot``."""
    world, _ = world_with_robots(2, robots)
    for _ in range(20):  # land and settle
        world.step_cycle()
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "timings.json"
        log = pybullet.startStateLogging(
            pybullet.STATE_LOGGING_PROFILE_TIMINGS, str(path), physicsClientId=world.client
        )
        for _ in range(cycles):
            world.step_cycle()
        pybullet.stopStateLogging(log, physicsClientId=world.client)
        contacts = len(pybullet.getContactPoints(physicsClientId=world.client))
        world.close()
        files = sorted(Path(folder).glob("timings.json*"))
        totals, counts = _scope_totals(json.loads(files[0].read_text()))
    step = totals["internalSingleStepSimulation"]
    iterations, residual = solver_analytics(robots)
    shares = {name: totals[name] / step for name in SPLIT_SCOPES if name in totals}
    steps = counts["internalSingleStepSimulation"]
    shares["contact_constraints_per_robot_step"] = (
        counts["setupMultiBodyContactConstraint"] / steps / robots
    )
    shares["contact_points_per_robot"] = contacts / robots
    shares["solver_iterations_used_mean"] = iterations
    shares["solver_remaining_residual_mean"] = residual
    return shares


def solver_analytics(robots: int = 22, steps: int = 20) -> tuple[float, float]:
    """Mean iterations the solver used per island and the residual it left
    (``reportSolverAnalytics``): all of them used means the step never converges early, so
    the iteration count sets the solver's cost."""
    world, team = world_with_robots(2, robots)
    for _ in range(20):
        world.step_cycle()
    pybullet.setPhysicsEngineParameter(reportSolverAnalytics=1, physicsClientId=world.client)
    islands = []
    for _ in range(steps):
        for robot in team:
            robot.before_cycle()
            robot.before_substep(0.0)
        islands.extend(pybullet.stepSimulation(physicsClientId=world.client) or [])
    world.close()
    n = max(1, len(islands))
    return (
        sum(i["numIterationsUsed"] for i in islands) / n,
        sum(i["remainingResidual"] for i in islands) / n,
    )


def _scope_totals(trace: dict | list) -> tuple[collections.Counter, collections.Counter]:
    """Total microseconds and count per scope name of a Chrome trace of begin/end events
    (Bullet appends a running number to each name; it is dropped)."""
    events = trace["traceEvents"] if isinstance(trace, dict) else trace
    totals: collections.Counter = collections.Counter()
    counts: collections.Counter = collections.Counter()
    stack = []
    for event in events:
        if event["ph"] == "B":
            stack.append(event)
        elif event["ph"] == "E" and stack:
            begin = stack.pop()
            name = re.sub(r"\d+$", "", begin["name"])
            totals[name] += event["ts"] - begin["ts"]
            counts[name] += 1
    return totals, counts


# --------------------------------------------------------------------------------------------
# physics variants (measured, not adopted)
# --------------------------------------------------------------------------------------------


def _engine_parameter(**params: float) -> Callable[[], contextlib.AbstractContextManager]:
    """A variant that sets Bullet engine parameters on every world built inside it."""

    @contextlib.contextmanager
    def apply() -> Iterator[None]:
        original = PhysicsWorld.__init__

        def init(self: PhysicsWorld, *args, **kwargs) -> None:
            original(self, *args, **kwargs)
            pybullet.setPhysicsEngineParameter(physicsClientId=self.client, **params)

        PhysicsWorld.__init__ = init
        try:
            yield
        finally:
            PhysicsWorld.__init__ = original

    return apply


def _constant(
    module: object, name: str, value: object
) -> Callable[[], contextlib.AbstractContextManager]:
    """A variant that changes a module constant the world reads when it is built."""

    @contextlib.contextmanager
    def apply() -> Iterator[None]:
        original = getattr(module, name)
        setattr(module, name, value)
        try:
            yield
        finally:
            setattr(module, name, original)

    return apply


def _contact(
    make: Callable[[ContactPhysics], ContactPhysics],
) -> Callable[[], contextlib.AbstractContextManager]:
    """A variant whose contacts are ``make(the soft contacts)`` (``sim.contact_models``), set
    as the module defaults that every world, robot, field and ball built inside it reads, and
    as what every session built inside it plays whatever contact model its config names.

    Why both: worlds built outside a session read the module defaults; a session builds its
    contacts from its model (the default ``bounce``) on top of those defaults, which would
    apply the bounces twice (the ball's restitution divided again: ball-ground above 1)."""

    @contextlib.contextmanager
    def apply() -> Iterator[None]:
        physics = make(soft_contact())

        def session_contacts(model: str = "", self_collision: bool = True) -> ContactPhysics:
            return with_self_collision(physics, self_collision)

        patches = [
            _constant(sim.robot, "DEFAULT_PHYSICS", physics.robot),
            _constant(sim.field, "DEFAULT_GROUND", physics.ground),
            _constant(sim.field, "DEFAULT_BALL", physics.ball),
            _constant(sim.field, "POST_RESTITUTION", physics.post_restitution),
            _constant(sim.session, "contact_physics", session_contacts),
        ]
        if physics.min_bounce_speed is not None:
            patches.append(_engine_parameter(restitutionVelocityThreshold=physics.min_bounce_speed))
        with contextlib.ExitStack() as stack:
            for patch in patches:
                stack.enter_context(patch())
            yield

    return apply


def _split_contact(base: ContactPhysics, robot_damping: float) -> ContactPhysics:
    """``base`` with the ground contact's spring split in two halves in series, one on the
    robot links and one on the ground, its damping put (nearly) all on the ground, and
    ``bounce``'s restitutions.

    Bullet combines two soft bodies' stiffnesses in series and adds their dampings, so a robot
    link (2k, d_r) on a ground (2k, d - d_r) touches it exactly as today's (k, d) link touches
    the rigid ground. What changes is every pair without the ground: a foot (2k, d_r) on the
    rigid ball is a stiff, lightly damped spring that bounces it (today: k with the full d,
    a heavily over-damped spring on 26 g that pushes it), and a robot's links touch each other
    (and other robots) with k and 2 d_r instead of k / 2 and 2 d.

    Measured in session 19 (not adopted; ``bounce`` is the model that came of it): the ball
    rolls and the fidelity checks are unchanged and a foot gives the ball about 2x its speed,
    but the get-up (``--run benchmarks/get_up.py --seed 0``) stands 0.18 with d_r = 4 and 0.60
    with d_r = 40 (0.91 today): the lightly damped, stiffer self-contacts (forearms on the
    thighs) throw it. Without self-collision (``split4_noself``) 0.76, as ``noself`` (0.81):
    the robot-ground contact is the same.
    """
    stiffness, damping = 2.0 * base.robot.contact_stiffness, base.robot.contact_damping
    physics = bounce_contact(base)
    return dataclasses.replace(
        physics,
        robot=dataclasses.replace(
            physics.robot, contact_stiffness=stiffness, contact_damping=robot_damping
        ),
        ground=dataclasses.replace(
            physics.ground,
            contact_stiffness=stiffness,
            contact_damping=damping - robot_damping,
        ),
    )


#: The striking bodies of ``strike_feet``.
FEET_AND_TOES = ("lfoot", "rfoot", "ltoe", "rtoe")


def _without_self_collision(physics: ContactPhysics) -> ContactPhysics:
    """No contacts between a robot's own parts, as on the real server."""
    return with_self_collision(physics, False)


def _strike_feet(physics: ContactPhysics) -> ContactPhysics:
    """Strike at the feet only: feet and toes rigid, every other link keeps its soft contacts
    (so a robot's other self-contacts stay as today; those links touch the soft ground with
    both springs in series, 500 N/m and 160 N s/m)."""
    strike = strike_contact(physics)
    robot = dataclasses.replace(strike.robot, soft_contacts=True, hard_bodies=FEET_AND_TOES)
    return dataclasses.replace(strike, robot=robot)


@contextlib.contextmanager
def _session_without_self_collision() -> Iterator[None]:
    """Sessions built inside ask for no self-collision whatever their ``SessionConfig`` says
    (benchmarks build their sessions with the default ``self_collision: true``, which would
    otherwise put the contacts back)."""
    original = sim.session.contact_physics

    def without(model: str = DEFAULT_CONTACT_MODEL, self_collision: bool = True) -> ContactPhysics:
        return original(model, False)

    sim.session.contact_physics = without
    try:
        yield
    finally:
        sim.session.contact_physics = original


def _strike(bounce: bool = True) -> Callable[[], contextlib.AbstractContextManager]:
    """The softness of the ground contact moved from the robots onto the ground
    (``sim.contact_models.strike_contact``; ``contact: strike`` in ``config/server.yaml``).

    Bullet makes a contact soft when EITHER body has soft-contact parameters (stiffness in
    series, damping summed), so the robots' 1000 N/m, 80 N s/m made the foot-ball contact a
    heavily over-damped spring on a 26 g ball: the foot pushes the ball instead of striking it.
    Robots without soft parameters on a ground with them keep the very same robot-ground
    contact while foot-ball and robot-robot become rigid. With ``bounce`` the foot-ball contact
    bounces at 0.8 like the real server's; without, the robot links keep restitution 0.

    Measured in session 4 (not adopted): the fidelity figures and ball rolls are unchanged, a
    driven foot box gives the ball 1.8x its speed instead of 1.0x, but the stand kick fell far
    more often (14 of 24 stand kicks against 2), because a robot's own links then touch each
    other rigidly. ``strike_noself`` adds the real server's rule that a robot's parts never
    touch each other (``self_collision: false``).
    """
    return _contact(lambda physics: strike_contact(physics, bounce))


def _together(
    *variants: Callable[[], contextlib.AbstractContextManager],
) -> Callable[[], contextlib.AbstractContextManager]:
    """A variant made of several variants applied at once."""

    @contextlib.contextmanager
    def apply() -> Iterator[None]:
        with contextlib.ExitStack() as stack:
            for variant in variants:
                stack.enter_context(variant())
            yield

    return apply


VARIANTS: dict[str, Callable[[], contextlib.AbstractContextManager]] = {
    "current": contextlib.nullcontext,
    "iters20": _constant(sim.physics, "SOLVER_ITERATIONS", 20),
    "iters15": _constant(sim.physics, "SOLVER_ITERATIONS", 15),
    # the count before session 27: one-leg stances topple (runs/kick_abort/); 100 is also
    # nearly left-right symmetric (benchmarks/symmetry.py), today's 60 not yet
    "iters30": _constant(sim.physics, "SOLVER_ITERATIONS", 30),
    "iters100": _constant(sim.physics, "SOLVER_ITERATIONS", 100),
    "substeps1": _constant(sim.session, "BASE_SUBSTEPS", 1),
    "dantzig": _engine_parameter(constraintSolverType=pybullet.CONSTRAINT_SOLVER_LCP_DANTZIG),
    "strike": _strike(bounce=True),
    "rigid": _strike(bounce=False),
    # the real server's rule: no contacts between a robot's own parts (disableInnerCollision)
    "noself": _together(
        _contact(lambda p: _without_self_collision(bounce_contact(p))),
        _session_without_self_collision,
    ),
    "strike_feet": _contact(_strike_feet),
    # the physics tuned before session 20 (the foot pushes the ball), and today's default
    "soft": _contact(lambda physics: physics),
    "bounce": _contact(bounce_contact),
    # robot-ground and robot-robot restitution 1e-4 instead of 0.01 (foot-ball still 0.8)
    "bounce_r001": _contact(lambda p: bounce_contact(p, 0.01)),
    "split4": _contact(lambda p: _split_contact(p, 4.0)),
    "split40": _contact(lambda p: _split_contact(p, 40.0)),
    "split4_noself": _together(
        _contact(lambda p: _without_self_collision(_split_contact(p, 4.0))),
        _session_without_self_collision,
    ),
    "strike_noself": _together(
        _contact(lambda p: _without_self_collision(strike_contact(p))),
        _session_without_self_collision,
    ),
    # Floors of Bullet's cost, not candidates: one 0.02 s step per cycle and 10 or 5 solver
    # iterations (robots sag and rock at these counts). What 22 robots cost here bounds any
    # server built on PyBullet on this machine, whatever its Python does.
    "floor_iters10": _together(
        _constant(sim.session, "BASE_SUBSTEPS", 1), _constant(sim.physics, "SOLVER_ITERATIONS", 10)
    ),
    "floor_iters5": _together(
        _constant(sim.session, "BASE_SUBSTEPS", 1), _constant(sim.physics, "SOLVER_ITERATIONS", 5)
    ),
    "residual": _engine_parameter(solverResidualThreshold=1e-3),
}


def step_ms(robots: int, cycles: int) -> float:
    """CPU milliseconds per cycle of ``robots`` idle standing robots (a session's base substep
    count; CPU time, so other processes on the machine disturb it less than wall time)."""
    world, _ = world_with_robots(sim.session.BASE_SUBSTEPS, robots)
    for _ in range(20):
        world.step_cycle()
    start = time.process_time()
    for _ in range(cycles):
        world.step_cycle()
    elapsed = time.process_time() - start
    world.close()
    return 1000.0 * elapsed / cycles


def idle_stance(robot_type: int, seconds: float = 4.0) -> tuple[float, float]:
    """Torso height drop (m) and largest tilt (deg) of an idle robot over ``seconds``."""
    world, (robot,) = world_with_robots(sim.session.BASE_SUBSTEPS, 1)
    robot.remove()
    robot = SimRobot(world, robot_type)
    robot.place(0.0, 0.0, 0.4, 0.0)
    for _ in range(50):
        world.step_cycle()
    start_height = robot.torso_position()[2]
    tilt = 0.0
    for _ in range(int(seconds / sim.physics.CYCLE_SECONDS)):
        world.step_cycle()
        tilt = max(tilt, math.degrees(math.acos(min(1.0, float(robot.torso_up()[2])))))
    drop = start_height - robot.torso_position()[2]
    world.close()
    return drop, tilt


def fidelity_checks() -> dict[str, bool]:
    """The assertions of tests/test_fidelity.py, evaluated (empty without the recordings)."""
    from sim.fidelity import load_recording, replay

    folder = TRACES / "fidelity"
    if not folder.exists():
        return {}

    def run(motion: str):
        return replay(
            load_recording(folder / f"{motion}.jsonl"), substeps=sim.session.BASE_SUBSTEPS
        )

    checks = {}
    c = run("stand_t0")
    checks["stand"] = bool(
        c.height_error.max() < 0.01
        and c.height_error.mean() < 0.003
        and abs(c.sim_force.mean() - c.real_force.mean()) < 2.0
        and c.sim_turn.max() < 3.0
    )
    for motion in ("crouch_t0", "crouch_t4"):
        c = run(motion)
        checks[motion] = bool(
            c.height_error.mean() < 0.01
            and c.height_error.max() < 0.02
            and abs(c.sim_height.min() - c.real_height.min()) < 0.01
            and c.sim_turn.max() < 5.0
        )
    c = run("fall_t0")
    checks["fall"] = bool(
        abs(c.sim_height[-1] - c.real_height[-1]) < 0.05
        and abs(c.sim_turn[-1] - c.real_turn[-1]) < 20.0
        and c.height_error.mean() < 0.02
    )
    c = run("swing_t0")  # an expected failure today: the real robot falls, ours stays up
    checks["swing_falls"] = bool(
        c.sim_height[-1] < 0.25 and abs(c.sim_turn[-1] - c.real_turn[-1]) < 35.0
    )
    return checks


def report_variant(name: str, cycles: int, checks: bool = True) -> None:
    with VARIANTS[name]():
        print(f"step_ms[{name},robots=1]: {step_ms(1, cycles):.2f}", flush=True)
        print(f"step_ms[{name},robots=22]: {step_ms(22, max(20, cycles // 10)):.2f}", flush=True)
        if not checks:
            return
        for robot_type in (0, 4):
            drop, tilt = idle_stance(robot_type)
            print(f"idle_height_drop_m[{name},type={robot_type}]: {drop:.4f}")
            print(f"idle_max_tilt_deg[{name},type={robot_type}]: {tilt:.2f}", flush=True)
        for check, passed in fidelity_checks().items():
            print(f"fidelity_{check}[{name}]: {int(passed)}", flush=True)


def ball_rebound(drop_height: float = 1.0) -> float:
    """Height of a dropped ball's first rebound over its drop height (centre above its rest
    height), on the field the current physics builds: e^2 for a restitution e, less what the
    contact's softness absorbs."""
    world = PhysicsWorld(substeps=sim.field.DEFAULT_SUBSTEPS)
    try:
        build_field(world)
        ball = Ball.create(world, (0.0, 0.0, BALL_RADIUS + drop_height))
        rising, peak = False, BALL_RADIUS
        for _ in range(round(3.0 / CYCLE_SECONDS)):
            world.step_cycle()
            vz = ball.velocity()[2]
            rising = rising or vz > 0.0
            if rising:
                peak = max(peak, ball.position()[2])
                if vz < 0.0:
                    break
    finally:
        world.close()
    return (peak - BALL_RADIUS) / drop_height


def report_contact(name: str) -> None:
    """The ball's figures under variant ``name``: rebound and rolls (real server: 2.71 m at
    4 m/s, 5.42 m at 8 m/s, nao-model-facts.md)."""
    from benchmarks.ball import roll

    with VARIANTS[name]():
        print(f"ball_rebound_ratio[{name},drop=1m]: {ball_rebound():.3f}", flush=True)
        for speed in (4.0, 8.0):
            distance, rest = roll(speed)
            print(f"ball_roll_distance_m[{name},v={speed:g}]: {distance:.3f}")
            print(f"ball_rest_time_s[{name},v={speed:g}]: {rest:.2f}", flush=True)


def report_kick_gaps(name: str, gaps: list[float], starts: int = 3) -> None:
    """The packaged stand kick at strength 1 with the ball ``gap`` m ahead of the toe instead of
    the calibrated ``ball_gap_m``: a later contact meets a faster foot, which matters once the
    foot strikes instead of pushing. Medians over ``starts`` starts (waits of
    ``benchmarks.kick.STAND_KICK_WAITS``) and both feet; falls counted."""
    from behaviors.kick import KICK_LEFT, default_kicks
    from benchmarks.kick import STAND_KICK_WAITS

    kicks = default_kicks()
    with VARIANTS[name]():
        for gap in gaps:
            motions = dict(kicks)
            for key, motion in kicks.items():
                if key.startswith(KICK_LEFT):
                    motions[key] = dataclasses.replace(motion, ball_gap_m=gap)
            results = [
                _impact_after_wait(
                    foot, seed, motions, STAND_KICK_WAITS[seed % len(STAND_KICK_WAITS)]
                )
                for seed in range(starts)
                for foot in ("left", "right")
            ]
            label = f"[{name},gap={gap:g}]"
            hit = [r for r in results if r.ball_speed_m_s > 0.0]
            print(f"kick_foot_speed_m_s{label}: {_median(r.foot_speed_m_s for r in hit):.2f}")
            print(f"kick_ball_speed_m_s{label}: {_median(r.ball_speed_m_s for r in hit):.2f}")
            print(f"kick_distance_m{label}: {_median(r.kick.distance_m for r in results):.2f}")
            print(f"kick_falls{label}: {sum(r.kick.fell for r in results)} of {len(results)}")
            print(f"kick_misses{label}: {len(results) - len(hit)}", flush=True)


def _impact_after_wait(foot: str, seed: int, motions: dict, wait: int) -> object:
    """``benchmarks.kick.measure_impact``, but started ``wait`` cycles after the placement as
    the stand-kick benchmark's starts are (measure_impact always starts one cycle after it)."""
    from benchmarks.kick import _ImpactRecorder, run_trial

    recorder = _ImpactRecorder(foot)
    kick = run_trial(foot, 1.0, seed, 0, 0.0, motions, recorder, wait_cycles=wait)
    return recorder.result(kick)


def _median(values) -> float:
    ordered = sorted(values)
    if not ordered:
        return math.nan
    mid = len(ordered) // 2
    return ordered[mid] if len(ordered) % 2 else 0.5 * (ordered[mid - 1] + ordered[mid])


def run_script(name: str, script: list[str]) -> None:
    """Run a benchmark script (path, then its arguments) inside variant ``name``."""
    path = Path(script[0]).resolve()
    sys.argv = [str(path), *script[1:]]
    sys.path.insert(0, str(path.parent))
    print(f"# variant: {name}", flush=True)
    with VARIANTS[name]():
        runpy.run_path(str(path), run_name="__main__")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cycles", type=int, default=500)
    parser.add_argument("--split", action="store_true", help="Bullet's step split, 22 robots")
    parser.add_argument("--variants", action="store_true", help="every variant in VARIANTS")
    parser.add_argument("--variant", choices=sorted(VARIANTS), help="one variant")
    parser.add_argument("--speed-only", action="store_true", help="variants: no stance/fidelity")
    parser.add_argument("--contact", action="store_true", help="ball rebound and rolls")
    parser.add_argument("--kick-gaps", type=float, nargs="+", help="stand kick, ball gaps (m)")
    parser.add_argument("--starts", type=int, default=3, help="--kick-gaps: starts per gap")
    parser.add_argument(
        "--pytest", nargs=argparse.REMAINDER, metavar="ARG", help="run pytest in --variant (last)"
    )
    parser.add_argument(
        "--run", nargs=argparse.REMAINDER, metavar="SCRIPT", help="a script in --variant (last)"
    )
    args = parser.parse_args()
    if args.run:
        run_script(args.variant or "current", args.run)
        return
    if args.contact:
        report_contact(args.variant or "current")
        return
    if args.kick_gaps:
        report_kick_gaps(args.variant or "current", args.kick_gaps, args.starts)
        return
    if args.pytest:
        import pytest

        with VARIANTS[args.variant or "current"]():
            raise SystemExit(pytest.main(args.pytest))
    if args.split:
        for name, value in bullet_split().items():
            print(f"bullet_split[{name}]: {value:.3f}")
        return
    if args.variants or args.variant:
        for name in [args.variant] if args.variant else list(VARIANTS):
            report_variant(name, args.cycles, checks=not args.speed_only)
        return
    for substeps in (1, 2, 4):
        for robots in (1, 22):
            cycles = args.cycles if robots == 1 else max(50, args.cycles // 10)
            rate = measure(substeps, robots, cycles)
            print(f"cycles_per_s[substeps={substeps},robots={robots}]: {rate:.1f}")


if __name__ == "__main__":
    main()
