"""Self-localisation: where the robot stands on the field and which way it faces.

An extended Kalman filter over the pose (x, y, heading) in the TEAM frame (x towards the
opponent goal, y to the left; for the right team every field position is mirrored,
(x, y) -> (-x, -y)). Between images the heading follows the gyro's turn rate about the world's
vertical and the position follows the walk engine's odometry (:meth:`Localizer.add_odometry`),
while the uncertainty grows. Each image corrects the pose with

* flags and goal posts: range and bearing to a known point;
* field lines: every seen end point of a line (true end or where the view cut it) must lie on
  the field line it belongs to. Lines are matched to the field's by the current estimate, so
  they only refine a pose the filter already roughly has; they keep the pose good when one or
  no landmark is in view.

The update is an iterated EKF (Gauss-Newton on the prior plus the measurements): the bearings
to far landmarks make the problem non-linear enough that one linearisation loses accuracy.

The filter also notices when the robot was carried away (the trainer's ``move``, a beam): if the
landmarks disagree with the prediction far beyond the noise, it restarts from the landmarks
alone (two or more needed), or, with one landmark, it skips the image and widens its
uncertainty until an image with two comes.

Observations come in the robot's *ego* frame: origin at the torso centre, x forward and y to
the left along the ground (the torso's level frame, see ``world.kinematics.level_rotation``),
z up. Headings are degrees, counter-clockwise from the team frame's +x.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from world.field_geometry import FIELD_LINES, LANDMARKS

__all__ = [
    "Localizer",
    "LocalizerConfig",
    "Pose2D",
    "team_landmarks",
    "team_lines",
    "wrap_deg",
]

Array = NDArray[np.float64]


def wrap_deg(angle: float) -> float:
    """An angle in degrees wrapped to [-180, 180)."""
    return (angle + 180.0) % 360.0 - 180.0


def _wrap_rad(angle: float) -> float:
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def team_landmarks(side: str | None) -> dict[str, tuple[float, float, float]]:
    """Flag and goal-post positions in the team frame of ``side`` ('left', 'right'; None counts
    as left, the frame the world is written in)."""
    sign = -1.0 if side == "right" else 1.0
    return {name: (sign * x, sign * y, z) for name, (x, y, z) in LANDMARKS.items()}


def team_lines(side: str | None) -> Array:
    """Field line segments (lines, 2 ends, xy) in the team frame of ``side``."""
    sign = -1.0 if side == "right" else 1.0
    return sign * np.array(FIELD_LINES, dtype=float)[:, :, :2]


@dataclass(frozen=True, slots=True)
class Pose2D:
    """The robot's pose in the team frame with its uncertainty.

    ``sigma_xy`` is the root mean square of the position's two standard deviations (m),
    ``sigma_heading_deg`` the heading's; ``confidence`` (0..1) summarises both: about 0.9 when
    the robot knows its place to a few centimetres and a degree, 0.5 near 0.1 m and 3 degrees,
    towards 0 as it gets lost.
    """

    x: float
    y: float
    heading_deg: float
    confidence: float
    sigma_xy: float
    sigma_heading_deg: float


@dataclass(frozen=True)
class LocalizerConfig:
    """Noise model and gates. The defaults follow the server's vision noise (distance 0.1 %,
    angles about 0.15 deg, a fixed calibration offset of up to 5 mm per axis) plus the error
    of the torso's tilt estimate, and were checked on the stand-in server
    (``benchmarks/localization.py``)."""

    #: landmark range noise: base (m) plus a fraction of the range
    range_sigma_m: float = 0.01
    range_sigma_rel: float = 0.002
    #: landmark bearing noise: an angle plus a lateral offset (m) that matters up close
    bearing_sigma_deg: float = 0.25
    bearing_sigma_m: float = 0.01
    #: distance of a line end point from its field line: base (m) plus a fraction of the range
    line_sigma_m: float = 0.015
    line_sigma_rel: float = 0.004
    #: random walk of the position without odometry (m per sqrt(s)): unmodelled walking
    motion_sigma: float = 0.25
    #: random walk of the heading (deg per sqrt(s)): gyro error and unmodelled turns
    turn_sigma: float = 2.0
    #: odometry error: a fraction of the distance (and of the turn) reported
    odometry_sigma_rel: float = 0.25
    #: a landmark whose normalised innovation (chi-square, 2 dof) exceeds this means the robot
    #: was moved: restart from the landmarks
    kidnap_chi2: float = 40.0
    #: a line end point farther than this from every field line (m, plus 3 sigma of the pose
    #: uncertainty at its range) is not used
    line_gate_m: float = 0.35
    #: lines whose seen piece is longer than this must also point along their field line
    line_direction_min_length: float = 0.5
    line_direction_tolerance_deg: float = 15.0
    #: uncertainty after a restart from landmarks alone, before the update (m, deg)
    restart_sigma_m: float = 2.0
    restart_sigma_deg: float = 30.0
    #: widening when an image disagrees but cannot restart the filter (m, deg)
    doubt_sigma_m: float = 0.5
    doubt_sigma_deg: float = 10.0
    #: Gauss-Newton iterations per update from the prediction (a restart from landmarks
    #: alone takes more); the prediction is close, so one linearisation is enough
    iterations: int = 1


class Localizer:
    """The pose filter. Feed it :meth:`predict` every cycle, :meth:`update` with every image,
    :meth:`add_odometry` whenever the walk engine knows how far it moved.

    ``use_gyro_heading``: the heading follows the gyro (:meth:`predict`) and the turn passed to
    :meth:`add_odometry` only orients that step's translation; set it False where no gyro
    rates are fed, and the odometry's turn is applied instead. Either way, one turn is never
    counted twice.
    """

    def __init__(
        self,
        side: str | None = None,
        config: LocalizerConfig | None = None,
        use_gyro_heading: bool = True,
    ) -> None:
        self.config = config or LocalizerConfig()
        self.use_gyro_heading = use_gyro_heading
        self._state: Array | None = None  # x, y, heading (rad)
        self._cov = np.zeros((3, 3))
        self.last_update_time: float | None = None
        #: how many images corrected the pose, and how many restarted it
        self.updates = 0
        self.restarts = 0
        self.set_side(side)

    # ------------------------------------------------------------------ setup
    def set_side(self, side: str | None) -> None:
        """Use ``side``'s team frame. A pose already known is mirrored into the new frame."""
        if side not in (None, "left", "right"):
            raise ValueError(f"side must be 'left', 'right' or None, got {side!r}")
        old = getattr(self, "side", None)
        self.side = side
        self._landmarks = team_landmarks(side)
        lines = team_lines(side)
        self._line_start = lines[:, 0]
        direction = lines[:, 1] - lines[:, 0]
        self._line_length = np.linalg.norm(direction, axis=1)
        self._line_dir = direction / self._line_length[:, None]
        self._line_normal = np.stack([-self._line_dir[:, 1], self._line_dir[:, 0]], axis=1)
        # a point's offset from / position along each line is a product with this (2, 2 lines)
        # matrix minus the line start's own: one matrix product per image for all pieces
        self._line_frames = np.concatenate([self._line_normal, self._line_dir]).T
        self._line_frame_starts = np.einsum(
            "xl,lx->l", self._line_frames, np.concatenate([self._line_start, self._line_start])
        )
        if self._state is not None and (old == "right") != (side == "right"):
            x, y, h = self._state
            self._state = np.array([-x, -y, _wrap_rad(h + math.pi)])

    def set_pose(
        self, x: float, y: float, heading_deg: float, sigma_m: float = 0.1, sigma_deg: float = 5.0
    ) -> None:
        """Start from a known pose (e.g. where the agent beamed itself) in the team frame."""
        self._state = np.array([x, y, math.radians(wrap_deg(heading_deg))])
        self._cov = np.diag([sigma_m**2, sigma_m**2, math.radians(sigma_deg) ** 2])

    def forget(self) -> None:
        """Drop the pose: the next image with two landmarks starts afresh."""
        self._state = None

    # ------------------------------------------------------------------ outputs
    @property
    def pose(self) -> Pose2D | None:
        """The current estimate, or None before the first fix."""
        if self._state is None:
            return None
        x, y, h = self._state
        sigma_xy = math.sqrt(max(0.0, (self._cov[0, 0] + self._cov[1, 1]) / 2.0))
        sigma_deg = math.degrees(math.sqrt(max(0.0, self._cov[2, 2])))
        confidence = 1.0 / (1.0 + (sigma_xy / 0.1) ** 2 + (sigma_deg / 3.0) ** 2)
        return Pose2D(float(x), float(y), math.degrees(h), confidence, sigma_xy, sigma_deg)

    @property
    def covariance(self) -> Array:
        """3x3 covariance of (x m, y m, heading rad)."""
        return self._cov.copy()

    # ------------------------------------------------------------------ motion
    def predict(self, turn_rate_deg_s: float, dt: float) -> None:
        """One cycle of motion: turn by the gyro's rate about the vertical, grow uncertainty."""
        if self._state is None:
            return
        cfg = self.config
        if self.use_gyro_heading:
            self._state[2] = _wrap_rad(self._state[2] + math.radians(turn_rate_deg_s) * dt)
        self._cov[0, 0] += cfg.motion_sigma**2 * dt
        self._cov[1, 1] += cfg.motion_sigma**2 * dt
        self._cov[2, 2] += math.radians(cfg.turn_sigma) ** 2 * dt

    def add_odometry(self, dx: float, dy: float, dtheta_deg: float = 0.0) -> None:
        """The walk engine moved the torso ``dx`` forward and ``dy`` left (m, in the robot's
        frame at the start of the step) while turning ``dtheta_deg`` (counter-clockwise)."""
        if self._state is None:
            return
        x, y, h = self._state
        turn = math.radians(dtheta_deg)
        mid = h + turn / 2.0  # the step's translation happened while turning
        c, s = math.cos(mid), math.sin(mid)
        self._state[0] = x + c * dx - s * dy
        self._state[1] = y + s * dx + c * dy
        if not self.use_gyro_heading:
            self._state[2] = _wrap_rad(h + turn)
        jac = np.eye(3)
        jac[0, 2] = -s * dx - c * dy
        jac[1, 2] = c * dx - s * dy
        rel = self.config.odometry_sigma_rel
        step = math.hypot(dx, dy)
        noise = np.diag([(rel * step) ** 2, (rel * step) ** 2, (rel * turn) ** 2])
        self._cov = jac @ self._cov @ jac.T + noise

    # ------------------------------------------------------------------ vision
    def update(
        self,
        landmarks: Mapping[str, tuple[float, float]],
        lines: Array | None = None,
        time: float | None = None,
    ) -> bool:
        """Correct the pose with one image.

        ``landmarks``: flag/goal-post name -> (forward, left) position in the ego frame (m);
        ``lines``: (k, 2, 2) seen line pieces, both end points (forward, left) in the ego
        frame. Returns whether the image changed the pose.
        """
        points = [(name, p) for name, p in landmarks.items() if name in self._landmarks]
        field = np.array([self._landmarks[n][:2] for n, _ in points], dtype=float).reshape(-1, 2)
        seen = np.array([p for _, p in points], dtype=float).reshape(-1, 2)
        lines = np.zeros((0, 2, 2)) if lines is None else np.asarray(lines, dtype=float)

        prior, cov = self._state, self._cov
        if prior is not None:
            matched = self._match_lines(prior, cov, lines) if len(lines) else None
            if matched is None and not len(seen):
                return False
            state, new_cov, agrees = self._solve(prior, cov, field, seen, matched, check=True)
            if agrees:
                return self._accept(state, new_cov, time)
            # carried away, or lost: the prediction is worthless
            if len(seen) < 2:
                doubt_m = self.config.doubt_sigma_m
                doubt_rad = math.radians(self.config.doubt_sigma_deg)
                self._cov = cov + np.diag([doubt_m**2, doubt_m**2, doubt_rad**2])
                return False
            self.restarts += 1
        if len(seen) < 2:
            return False
        # a fresh start from the landmarks alone; lines join once that pose is close
        prior = _fit_points(field, seen, self._landmark_weights(seen))
        restart_m = self.config.restart_sigma_m
        restart_rad = math.radians(self.config.restart_sigma_deg)
        cov = np.diag([restart_m**2, restart_m**2, restart_rad**2])
        state, new_cov, _ = self._solve(prior, cov, field, seen, None, iterations=4)
        matched = self._match_lines(state, new_cov, lines) if len(lines) else None
        if matched is not None:
            state, new_cov, _ = self._solve(
                prior, cov, field, seen, matched, start=state, iterations=2
            )
        return self._accept(state, new_cov, time)

    def _accept(self, state: Array, cov: Array, time: float | None) -> bool:
        self._state, self._cov = state, cov
        self.updates += 1
        self.last_update_time = time
        return True

    def _landmark_weights(self, seen: Array) -> Array:
        ranges = np.hypot(seen[:, 0], seen[:, 1])
        range_sigma, bearing_sigma = self._landmark_sigmas(ranges)
        return 1.0 / (range_sigma**2 + (ranges * bearing_sigma) ** 2)

    def _landmark_sigmas(self, ranges: Array) -> tuple[Array, Array]:
        """Standard deviations of range (m) and bearing (rad) of landmarks at ``ranges``."""
        cfg = self.config
        range_sigma = cfg.range_sigma_m + cfg.range_sigma_rel * ranges
        bearing_sigma = math.radians(cfg.bearing_sigma_deg) + cfg.bearing_sigma_m / np.maximum(
            ranges, 0.1
        )
        return range_sigma, bearing_sigma

    def _match_lines(self, state: Array, cov: Array, lines: Array) -> tuple | None:
        """Assign each seen line piece to a field line; returns (end points (m, 2) in the ego
        frame, the field line index of each, their ranges) or None when nothing matches."""
        cfg = self.config
        c, s = math.cos(state[2]), math.sin(state[2])
        rot = np.array([[c, -s], [s, c]])
        ends = lines @ rot.T + state[:2]  # (k, 2 ends, 2) in the field
        n_lines = len(self._line_length)
        frames = ends @ self._line_frames - self._line_frame_starts  # (k, 2 ends, 2 lines)
        off, along = frames[..., :n_lines], frames[..., n_lines:]  # (k, 2 ends, lines) each
        ranges = np.hypot(lines[..., 0], lines[..., 1])  # (k, 2)
        pose_sigma = math.sqrt(max(cov[0, 0], cov[1, 1])) + ranges * math.sqrt(cov[2, 2])
        gate = cfg.line_gate_m + 3.0 * pose_sigma  # (k, 2)
        length = self._line_length[None, None]
        inside = (along > -gate[..., None]) & (along < length + gate[..., None])
        near = np.abs(off) < gate[..., None]
        ok = np.all(inside & near, axis=1)  # (k, lines)
        piece = ends[:, 1] - ends[:, 0]
        piece_length = np.hypot(piece[:, 0], piece[:, 1])
        long_enough = piece_length > cfg.line_direction_min_length
        unit = piece / np.maximum(piece_length, 1e-9)[:, None]
        cross = np.abs(
            unit[:, 0:1] * self._line_dir[None, :, 1] - unit[:, 1:2] * self._line_dir[None, :, 0]
        )
        aligned = cross < math.sin(math.radians(cfg.line_direction_tolerance_deg))
        ok &= aligned | ~long_enough[:, None]
        cost = np.where(ok, np.abs(off).max(axis=1), np.inf)
        best = np.argmin(cost, axis=1)
        found = np.isfinite(cost[np.arange(len(best)), best])
        if not found.any():
            return None
        # a short piece near two field lines (a corner) is ambiguous unless one is far better
        sorted_cost = np.sort(cost, axis=1)
        if sorted_cost.shape[1] > 1:
            clear = ~long_enough & np.isfinite(sorted_cost[:, 1])
            found &= ~clear | (sorted_cost[:, 1] > 3.0 * sorted_cost[:, 0] + 0.1)
        points = lines[found].reshape(-1, 2)
        which = np.repeat(best[found], 2)
        return points, which, ranges[found].reshape(-1)

    def _solve(
        self,
        prior: Array,
        cov: Array,
        field: Array,
        seen: Array,
        matched: tuple | None,
        start: Array | None = None,
        iterations: int | None = None,
        check: bool = False,
    ) -> tuple[Array, Array, bool]:
        """Iterated EKF update: the pose that best fits the prior and all measurements, its
        covariance, and (with ``check``, starting at the prior) whether every landmark agreed
        with the prior within the kidnap gate.

        Each measurement row ``h`` (a 3-vector) with weight ``w`` and residual ``r`` adds
        ``w h h^T`` to the information matrix and ``w h r`` to the right-hand side. There are a
        few dozen rows of three columns per image, so the sums are plain floats: numpy's
        per-call cost would be most of the work."""
        cov_rows = cov.tolist()
        prior_rows = _inverse3_rows(cov_rows)
        px, py, ph = prior.tolist()
        x, y, heading = (prior if start is None else start).tolist()
        landmarks = self._landmark_measurements(field, seen)
        lines = self._line_measurements(matched) if matched is not None else []
        agrees = True
        info = prior_rows
        for iteration in range(iterations or self.config.iterations):
            info = [row[:] for row in prior_rows]
            dx, dy, dh = px - x, py - y, _wrap_rad(ph - heading)
            rhs = [row[0] * dx + row[1] * dy + row[2] * dh for row in prior_rows]
            for fx, fy, measured_range, measured_bearing, range_var, bearing_var in landmarks:
                ex, ey = fx - x, fy - y
                r2 = ex * ex + ey * ey
                distance = math.sqrt(r2)
                bearing = _wrap_rad(math.atan2(ey, ex) - heading)
                range_row = (-ex / distance, -ey / distance, 0.0)
                bearing_row = (ey / r2, -ex / r2, -1.0)
                range_error = measured_range - distance
                bearing_error = _wrap_rad(measured_bearing - bearing)
                if check and iteration == 0 and agrees:
                    agrees = self._agrees(
                        range_row, bearing_row, range_error, bearing_error, cov_rows,
                        range_var, bearing_var,
                    )  # fmt: skip
                _accumulate(info, rhs, range_row, 1.0 / range_var, range_error)
                _accumulate(info, rhs, bearing_row, 1.0 / bearing_var, bearing_error)
            c, s = math.cos(heading), math.sin(heading)
            for qx, qy, nx, ny, offset, weight in lines:
                # the end point turned into the field: R(heading) q
                tx, ty = c * qx - s * qy, s * qx + c * qy
                row = (nx, ny, ny * tx - nx * ty)
                # signed distance of the end point from its field line, wanted: 0
                _accumulate(info, rhs, row, weight, offset - ((tx + x) * nx + (ty + y) * ny))
            step = _inverse3_rows(info)
            x += step[0][0] * rhs[0] + step[0][1] * rhs[1] + step[0][2] * rhs[2]
            y += step[1][0] * rhs[0] + step[1][1] * rhs[1] + step[1][2] * rhs[2]
            heading = _wrap_rad(
                heading + step[2][0] * rhs[0] + step[2][1] * rhs[1] + step[2][2] * rhs[2]
            )
        return np.array([x, y, heading]), np.array(_inverse3_rows(info)), agrees

    def _landmark_measurements(self, field: Array, seen: Array) -> list[tuple[float, ...]]:
        """Per landmark: field x, y, measured range, bearing, and their variances."""
        cfg = self.config
        bearing_base = math.radians(cfg.bearing_sigma_deg)
        out = []
        for (fx, fy), (ex, ey) in zip(field.tolist(), seen.tolist(), strict=True):
            distance = math.hypot(ex, ey)
            range_sigma = cfg.range_sigma_m + cfg.range_sigma_rel * distance
            bearing_sigma = bearing_base + cfg.bearing_sigma_m / max(distance, 0.1)
            out.append((fx, fy, distance, math.atan2(ey, ex), range_sigma**2, bearing_sigma**2))
        return out

    def _line_measurements(self, matched: tuple) -> list[tuple[float, ...]]:
        """Per matched line end point: its ego x, y, the field line's normal, the normal's
        offset of the line (start . normal), and the weight."""
        points, which, line_ranges = matched
        cfg = self.config
        normals = self._line_normal[which]
        offsets = np.einsum("mx,mx->m", self._line_start[which], normals)
        weights = (cfg.line_sigma_m + cfg.line_sigma_rel * line_ranges) ** -2
        return [
            (qx, qy, nx, ny, offset, weight)
            for (qx, qy), (nx, ny), offset, weight in zip(
                points.tolist(), normals.tolist(), offsets.tolist(), weights.tolist(), strict=True
            )
        ]

    def _agrees(
        self,
        range_row: tuple[float, float, float],
        bearing_row: tuple[float, float, float],
        range_error: float,
        bearing_error: float,
        cov: list[list[float]],
        range_var: float,
        bearing_var: float,
    ) -> bool:
        """Whether a landmark's innovation fits S = H P H^T + R within the kidnap gate."""
        (c00, c01, c02), (c10, c11, c12), (c20, c21, c22) = cov
        r0, r1, r2 = range_row
        b0, b1, b2 = bearing_row
        # P h for both rows
        pr0, pr1, pr2 = (
            c00 * r0 + c01 * r1 + c02 * r2,
            c10 * r0 + c11 * r1 + c12 * r2,
            c20 * r0 + c21 * r1 + c22 * r2,
        )
        pb0, pb1, pb2 = (
            c00 * b0 + c01 * b1 + c02 * b2,
            c10 * b0 + c11 * b1 + c12 * b2,
            c20 * b0 + c21 * b1 + c22 * b2,
        )
        a = r0 * pr0 + r1 * pr1 + r2 * pr2 + range_var
        b = r0 * pb0 + r1 * pb1 + r2 * pb2
        c = b0 * pr0 + b1 * pr1 + b2 * pr2
        d = b0 * pb0 + b1 * pb1 + b2 * pb2 + bearing_var
        i, j = range_error, bearing_error
        # i^T S^-1 i with the 2x2 inverse written out
        chi2 = (d * i * i - (b + c) * i * j + a * j * j) / (a * d - b * c)
        return chi2 < self.config.kidnap_chi2


def _accumulate(
    info: list[list[float]], rhs: list[float], row: tuple[float, float, float], w: float, r: float
) -> None:
    """Add one weighted measurement row: info += w h h^T, rhs += w h r."""
    h0, h1, h2 = row
    w0, w1, w2 = w * h0, w * h1, w * h2
    i0, i1, i2 = info
    i0[0] += w0 * h0
    i0[1] += w0 * h1
    i0[2] += w0 * h2
    i1[0] += w1 * h0
    i1[1] += w1 * h1
    i1[2] += w1 * h2
    i2[0] += w2 * h0
    i2[1] += w2 * h1
    i2[2] += w2 * h2
    rhs[0] += w0 * r
    rhs[1] += w1 * r
    rhs[2] += w2 * r


def _inverse3_rows(m: list[list[float]]) -> list[list[float]]:
    """The inverse of a 3x3 matrix (rows) by its adjugate: for the filter's small,
    well-conditioned information and covariance matrices this is several times cheaper than
    ``np.linalg.inv`` (whose fixed cost dominates at this size) and agrees with it to rounding."""
    (a, b, c), (d, e, f), (g, h, i) = m
    co_a, co_b, co_c = e * i - f * h, f * g - d * i, d * h - e * g
    det = a * co_a + b * co_b + c * co_c
    if det == 0.0:
        raise np.linalg.LinAlgError("singular 3x3 matrix")
    k = 1.0 / det
    return [
        [co_a * k, (c * h - b * i) * k, (b * f - c * e) * k],
        [co_b * k, (a * i - c * g) * k, (c * d - a * f) * k],
        [co_c * k, (b * g - a * h) * k, (a * e - b * d) * k],
    ]


def _fit_points(field: Array, seen: Array, weights: Array) -> Array:
    """The pose (x, y, heading rad) that maps ego points ``seen`` onto ``field`` best in the
    weighted least-squares sense (2D Procrustes: closed form, no starting guess needed)."""
    w = weights / weights.sum()
    field_mean = w @ field
    seen_mean = w @ seen
    f = field - field_mean
    p = seen - seen_mean
    cross = float(np.sum(w * (p[:, 0] * f[:, 1] - p[:, 1] * f[:, 0])))
    dot = float(np.sum(w * (p[:, 0] * f[:, 0] + p[:, 1] * f[:, 1])))
    heading = math.atan2(cross, dot)
    c, s = math.cos(heading), math.sin(heading)
    x = field_mean[0] - (c * seen_mean[0] - s * seen_mean[1])
    y = field_mean[1] - (s * seen_mean[0] + c * seen_mean[1])
    return np.array([x, y, heading])
