"""The restricted vision perceptor (``See``): what a robot's head camera reports.

Pure geometry on world poses the simulator supplies; numpy only, no pybullet, so it can be tested
and reused without a physics world. The behaviour follows rcssserver3d 0.7.2's
RestrictedVisionPerceptor with the nao settings (view cones 120 x 120 deg, the sense axis follows
the head, noise on, lines on); ``tests/test_vision.py`` checks it against recorded messages.

How the real perceptor works, and so how this one does:

* Every object position is taken relative to the camera (the head body's centre) in world
  coordinates, a fixed per-robot calibration offset (uniform +-0.005 m per axis, drawn once) is
  added, and the result is rotated into the camera frame (native frame: x right, y forward = the
  view axis, z up).
* phi (horizontal, + = left) = atan2(y, x) - 90 deg; theta (vertical, + = up) =
  atan2(z, hypot(x, y)). Objects closer than 0.1 m (the robot's own head) or with |phi| or
  |theta| above half the view cone are dropped, before noise; so noisy values may read 60.1.
* The reported distance of an object (flag, goal post, ball, body part) is the TRUE distance:
  the real server measures it before adding the calibration offset. Line end points measure it
  after. Then per observation: distance += N(0, 0.0965) * distance / 100, phi += N(0, 0.1480)
  deg, theta += N(0, 0.1225) deg. Note the sigma order: the server's source gives 0.1480 to the
  horizontal angle, and a standing robot's recorded readings agree (tests/test_vision.py).
* Field lines whose end points are not both visible are clipped: first against the plane 0.1 m
  in front of the camera, then, projected onto that image plane, against the rectangle of the
  view cone; the new end points are the first two crossings in the order top, bottom, left,
  right edge, so a line crossing the whole view is reported left end first whatever its
  direction on the field. A line keeps its place in the message only if both ends end up seen.
* Every robot is seen by the same rules, itself included: the own head is closer than 0.1 m and
  the own feet lie below the cone in any normal posture, so a robot sees its own lower arms only
  (as the traces show); a robot pitching its head far down would see its own feet, as on the
  real server. Robots without a team name (before ``init``) are not reported.
* Occlusion is NOT modelled, on purpose: the real server's occlusion test is disabled
  (everything in the cone is seen, through robots and goal posts).

Message order: flags and goal posts in the scene order G1L G2L G2R G1R F1L F2L F1R F2R, the ball,
then players (the real server orders robots by an internal node address; we report the robot
itself first, then ``others`` in the order given), then the lines in ``FIELD_LINES`` order.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from world.field_geometry import FIELD_LINES, LANDMARKS
from world.perception import Polar, SeenPlayer, Vision

#: Flags and goal posts in the order the real server lists them (its scene graph order).
LANDMARK_ORDER: tuple[str, ...] = ("G1L", "G2L", "G2R", "G1R", "F1L", "F2L", "F1R", "F2R")
#: Body parts a robot carries an ObjectState on, in the order the server reports them.
PLAYER_PARTS: tuple[str, ...] = ("head", "rlowerarm", "llowerarm", "rfoot", "lfoot")

#: Objects at most this far from the camera (after the calibration offset) are not seen.
MIN_DISTANCE = 0.1
#: Distance of the image plane used for clipping lines (m).
FOCAL_LENGTH = 0.1
#: Half-width of the uniform per-axis calibration offset (m).
CALIBRATION_ERROR = 0.005
#: Distance noise: sigma in percent of the distance.
DISTANCE_SIGMA_PERCENT = 0.0965
#: Horizontal angle (phi) noise sigma, degrees.
HORIZONTAL_SIGMA_DEG = 0.1480
#: Vertical angle (theta) noise sigma, degrees.
VERTICAL_SIGMA_DEG = 0.1225

Vec3 = tuple[float, float, float]

_LANDMARK_POINTS = np.array([LANDMARKS[name] for name in LANDMARK_ORDER], dtype=float)
_LINE_POINTS = np.array(FIELD_LINES, dtype=float)  # (lines, 2 ends, xyz)


@dataclass(frozen=True, slots=True)
class VisibleRobot:
    """A robot as vision sees it: team name, uniform number and the world positions of the body
    parts that carry an ObjectState (``head``, ``rlowerarm``, ``llowerarm``, ``rfoot``,
    ``lfoot``; missing parts are simply not seen)."""

    team: str
    unum: int
    parts: Mapping[str, Vec3]
    #: the parts present, in ``PLAYER_PARTS`` order, and their positions as one (n, 3) array:
    #: built once, as every viewer of this cycle stacks the same rows
    part_names: tuple[str, ...] = field(init=False, repr=False, compare=False)
    points: NDArray[np.float64] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        names = tuple(part for part in PLAYER_PARTS if part in self.parts)
        points = np.asarray([self.parts[part] for part in names], dtype=float).reshape(-1, 3)
        object.__setattr__(self, "part_names", names)
        object.__setattr__(self, "points", points)


class VisionSensor:
    """One robot's RestrictedVisionPerceptor.

    ``rng`` drives the calibration offset (drawn here, once, as the real server does when the
    robot is created) and the per-observation noise; the same seed and the same inputs give the
    same readings. With ``add_noise`` False the readings are exact. ``view_angle_deg`` and
    ``view_angle_v_deg`` are the full horizontal and vertical view cones.
    """

    def __init__(
        self,
        rng: np.random.Generator,
        add_noise: bool = True,
        view_angle_deg: float = 120.0,
        view_angle_v_deg: float = 120.0,
        sense_lines: bool = True,
    ) -> None:
        if not (0.0 < view_angle_deg < 180.0 and 0.0 < view_angle_v_deg < 180.0):
            raise ValueError("view cones must lie strictly between 0 and 180 degrees")
        self._rng = rng
        self.add_noise = add_noise
        self.half_h_deg = view_angle_deg / 2.0
        self.half_v_deg = view_angle_v_deg / 2.0
        self.sense_lines = sense_lines
        self._calibration = rng.uniform(-CALIBRATION_ERROR, CALIBRATION_ERROR, size=3)
        self._edges = view_edges(self.half_h_deg, self.half_v_deg)

    @property
    def calibration_offset(self) -> NDArray[np.float64]:
        """The fixed world-frame offset added to every relative position (when noise is on)."""
        return self._calibration.copy()

    def see(
        self,
        camera: ArrayLike,
        ball: Vec3 | None,
        others: Sequence[VisibleRobot],
        own: VisibleRobot | None,
    ) -> Vision:
        """One ``See`` reading from the camera pose ``camera`` (4x4 world transform of the head:
        columns are the world images of native x = right, y = forward, z = up; translation = the
        head centre). ``ball`` is the ball centre or None when there is no ball."""
        pose = np.asarray(camera, dtype=float)
        if pose.shape != (4, 4):
            raise ValueError(f"camera must be a 4x4 transform, got shape {pose.shape}")
        rotation, position = pose[:3, :3], pose[:3, 3]
        offset = self._calibration if self.add_noise else np.zeros(3)

        robots = [r for r in ([own] if own is not None else []) + list(others) if r.team]
        points, owners, parts = self._object_points(ball, robots)
        polars = self._see_objects(points, rotation, position, offset)

        vision = Vision()
        n_landmarks = len(LANDMARK_ORDER)
        for name, polar in zip(LANDMARK_ORDER, polars[:n_landmarks], strict=True):
            if polar is not None:
                vision.landmarks[name] = polar
        index = n_landmarks
        if ball is not None:
            vision.ball = polars[index]
            index += 1
        seen: dict[int, SeenPlayer] = {}
        for owner, part, polar in zip(owners, parts, polars[index:], strict=True):
            if polar is None:
                continue
            player = seen.get(owner)
            if player is None:  # (not setdefault: that would build a SeenPlayer per part)
                robot = robots[owner]
                player = seen[owner] = SeenPlayer(team=robot.team, unum=robot.unum)
            player.parts[part] = polar
        vision.players = [seen[k] for k in sorted(seen)]
        if self.sense_lines:
            vision.lines = self._see_lines(rotation, position, offset)
        return vision

    # --- objects -----------------------------------------------------------------------------

    @staticmethod
    def _object_points(
        ball: Vec3 | None, robots: Sequence[VisibleRobot]
    ) -> tuple[NDArray[np.float64], list[int], list[str]]:
        """All point objects in message order: landmarks, ball, then robot parts; for the parts
        also which robot (index into ``robots``) and which part each row is."""
        blocks = [_LANDMARK_POINTS]
        if ball is not None:
            blocks.append(np.asarray(ball, dtype=float).reshape(1, 3))
        owners: list[int] = []
        parts: list[str] = []
        for i, robot in enumerate(robots):
            blocks.append(robot.points)
            owners.extend([i] * len(robot.part_names))
            parts.extend(robot.part_names)
        return np.vstack(blocks), owners, parts

    def _see_objects(
        self,
        points: NDArray[np.float64],
        rotation: NDArray[np.float64],
        position: NDArray[np.float64],
        offset: NDArray[np.float64],
    ) -> list[Polar | None]:
        """Polar (or None when unseen) for each world point, noise included."""
        true_rel = points - position
        rel = true_rel + offset
        local = rel @ rotation  # row-wise R^T v: camera-frame coordinates
        phi, theta = _angles(local)
        distance = np.sqrt(np.einsum("ij,ij->i", true_rel, true_rel))
        far = np.einsum("ij,ij->i", rel, rel) > MIN_DISTANCE**2
        seen = far & self._in_cone(phi, theta)
        distance, phi, theta = self._noisy(distance, phi, theta)
        # tolist(): Python floats at once, not one numpy scalar per element
        return [
            Polar(d, p, t) if s else None
            for d, p, t, s in zip(
                distance.tolist(), phi.tolist(), theta.tolist(), seen.tolist(), strict=True
            )
        ]

    def _in_cone(self, phi: NDArray[np.float64], theta: NDArray[np.float64]) -> NDArray[np.bool_]:
        return (np.abs(phi) <= self.half_h_deg) & (np.abs(theta) <= self.half_v_deg)

    def _noisy(
        self, distance: NDArray[np.float64], phi: NDArray[np.float64], theta: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """Per-observation Gaussian noise (one draw per value, seen or not), if noise is on."""
        if not self.add_noise:
            return distance, phi, theta
        draws = self._rng.standard_normal((3, *distance.shape))
        return (
            distance + draws[0] * DISTANCE_SIGMA_PERCENT * distance / 100.0,
            phi + draws[1] * HORIZONTAL_SIGMA_DEG,
            theta + draws[2] * VERTICAL_SIGMA_DEG,
        )

    # --- lines -------------------------------------------------------------------------------

    def _see_lines(
        self,
        rotation: NDArray[np.float64],
        position: NDArray[np.float64],
        offset: NDArray[np.float64],
    ) -> list[tuple[Polar, Polar]]:
        """The field lines clipped to the view, as (begin, end) polars in ``FIELD_LINES`` order."""
        local = (_LINE_POINTS - position + offset) @ rotation
        begin, end, keep = clip_segments(
            local[:, 0], local[:, 1], self.half_h_deg, self.half_v_deg, self._edges
        )
        ends = np.stack([begin[keep], end[keep]], axis=1)  # (kept, 2, 3)
        phi, theta = _angles(ends)
        distance = np.sqrt(np.einsum("ijk,ijk->ij", ends, ends))
        distance, phi, theta = self._noisy(distance, phi, theta)
        return [
            (Polar(d[0], p[0], t[0]), Polar(d[1], p[1], t[1]))
            for d, p, t in zip(distance.tolist(), phi.tolist(), theta.tolist(), strict=True)
        ]


def _angles(local: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(phi, theta) in degrees of camera-frame points (last axis xyz): phi measured from the view
    axis, + to the left, wrapped to [-180, 180); theta the elevation, + up."""
    x, y, z = local[..., 0], local[..., 1], local[..., 2]
    phi = np.degrees(np.arctan2(y, x)) - 90.0
    phi = (phi + 180.0) % 360.0 - 180.0
    theta = np.degrees(np.arctan2(z, np.hypot(x, y)))
    return phi, theta


def _visible_points(
    local: NDArray[np.float64], half_h_deg: float, half_v_deg: float
) -> NDArray[np.bool_]:
    """The server's visibility test for a line end point: far enough and inside the cone."""
    phi, theta = _angles(local)
    far = np.einsum("...i,...i->...", local, local) > MIN_DISTANCE**2
    return far & (np.abs(phi) <= half_h_deg) & (np.abs(theta) <= half_v_deg)


def clip_segments(
    begin: NDArray[np.float64],
    end: NDArray[np.float64],
    half_h_deg: float,
    half_v_deg: float,
    edges: ViewEdges | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """Clip camera-frame segments (``begin``, ``end``: (n, 3)) to the view as the real server
    does; returns the new end points and which segments are seen at all.

    Segments with both ends visible are kept unchanged. Others are cut at the plane
    y = FOCAL_LENGTH where they cross it, projected onto that plane and intersected with the
    edges of the view rectangle (top, bottom, left, right; at most the first two crossings
    count). Two crossings replace both ends (first crossing = begin); one crossing replaces the
    end that was not visible (the begin, if neither was). The crossing points are put back on
    the 3D segment, so their distance is a true distance. ``edges``: ``view_edges`` of the
    same half angles, precomputed (optional).
    """
    visible = _visible_points(np.stack([begin, end], axis=1), half_h_deg, half_v_deg)
    keep = visible[:, 0] & visible[:, 1]
    new_begin, new_end = begin.copy(), end.copy()
    rows = np.flatnonzero(~keep).tolist()
    if not rows:
        return new_begin, new_end, keep
    if edges is None:
        edges = view_edges(half_h_deg, half_v_deg)
    # Plain floats per clipped segment (a handful per image): the same IEEE operations as the
    # array formulas, without numpy's per-call cost on tiny arrays. The dot products with the
    # edge planes stay one matrix product, as Bullet-free numpy computes them.
    cut = [_cut_at_near_plane(begin[r].tolist(), end[r].tolist()) for r in rows]
    front = [k for k, (b, e) in enumerate(cut) if b[1] > 0.0 and e[1] > 0.0]
    hits: list[list[list[float]]] = [[] for _ in rows]
    if front:
        near_b = np.array([cut[k][0] for k in front])
        near_e = np.array([cut[k][1] for k in front])
        val_b, val_e = (near_b @ edges[2].T).tolist(), (near_e @ edges[2].T).tolist()
        lines = list(zip(edges[0].tolist(), edges[1].tolist(), strict=True))
        for k, vb, ve in zip(front, val_b, val_e, strict=True):
            hits[k] = _edge_crossings(*cut[k], vb, ve, lines)
    vis = visible[rows].tolist()
    for r, (vis_b, vis_e), crossings in zip(rows, vis, hits, strict=True):
        if len(crossings) >= 2:
            new_begin[r], new_end[r] = crossings[0], crossings[1]
        elif len(crossings) == 1 and not vis_b:
            new_begin[r] = crossings[0]
        elif len(crossings) == 1:
            new_end[r] = crossings[0]
        keep[r] = len(crossings) >= 2 or (len(crossings) == 1 and (vis_e or vis_b))
    return new_begin, new_end, keep


def _cut_at_near_plane(begin: list[float], end: list[float]) -> tuple[list[float], list[float]]:
    """Move the end behind y = FOCAL_LENGTH onto that plane, where exactly one end is behind."""
    b_y, e_y = begin[1], end[1]
    if (b_y < FOCAL_LENGTH) == (e_y < FOCAL_LENGTH):
        return begin, end
    factor = (FOCAL_LENGTH - e_y) / (b_y - e_y)
    on_plane = [e + (b - e) * factor for b, e in zip(begin, end, strict=True)]
    return (on_plane, end) if b_y < FOCAL_LENGTH else (begin, on_plane)


ViewEdges = tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]


def view_edges(half_h_deg: float, half_v_deg: float) -> ViewEdges:
    """The view rectangle on the image plane (y = FOCAL_LENGTH), edges in the server's order
    top, bottom, left, right: start points (4, 2) and directions (4, 2) in image (x, z), and the
    normals (4, 3) of the planes through the camera and each edge (X . normal == 0 on it)."""
    f = FOCAL_LENGTH
    rx = math.tan(math.radians(half_h_deg)) * f
    ry = math.tan(math.radians(half_v_deg)) * f
    starts = np.array([(-rx, ry), (-rx, -ry), (-rx, ry), (rx, ry)])
    directions = np.array([(2 * rx, 0.0), (2 * rx, 0.0), (0.0, -2 * ry), (0.0, -2 * ry)])
    normals = np.array([(0.0, -ry, f), (0.0, ry, f), (f, rx, 0.0), (f, -rx, 0.0)])
    return starts, directions, normals


def _edge_crossings(
    begin: list[float],
    end: list[float],
    val_b: list[float],
    val_e: list[float],
    edges: list[tuple[list[float], list[float]]],
) -> list[list[float]]:
    """The 3D points where a segment in front of the camera, projected onto the image plane,
    crosses the edges of the view rectangle, in the server's edge order (top, bottom, left,
    right). ``val_b``/``val_e``: the ends' dot products with each edge plane's normal;
    ``edges``: each edge's start and direction in image (x, z)."""
    f = FOCAL_LENGTH
    scale_b, scale_e = f / begin[1], f / end[1]
    bp0, bp1 = begin[0] * scale_b, begin[2] * scale_b
    d0, d1 = end[0] * scale_e - bp0, end[2] * scale_e - bp1
    crossings = []
    for ((s0, s1), (g0, g1)), vb, ve in zip(edges, val_b, val_e, strict=True):
        denom = d0 * g1 - d1 * g0
        if denom == 0.0 or vb == ve:
            continue
        w0, w1 = s0 - bp0, s1 - bp1
        along = (w0 * g1 - w1 * g0) / denom  # along the segment
        across = (w0 * d1 - w1 * d0) / denom  # along the edge
        if 0.0 <= along <= 1.0 and 0.0 <= across <= 1.0:
            t = vb / (vb - ve)
            crossings.append([b + (e - b) * t for b, e in zip(begin, end, strict=True)])
    return crossings
