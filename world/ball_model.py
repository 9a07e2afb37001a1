"""The ball as the agent knows it: where it is, how fast it rolls, where it will stop.

A Kalman filter over (x, y, vx, vy) in the team frame. Its motion model is the server's ball:
once rolling it slows exponentially (velocity decays with a time constant of about 0.94 s, no
constant friction; ``nao-model-facts.md``, "ball rolling"), so a rolling ball travels ``v tau``
more before it rests. Kicks and bounces break that model; an observation far outside the
filter's expectation restarts the velocity from the last two observations instead of letting
the filter catch up slowly.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["ROLLING_TIME_CONSTANT", "BallConfig", "BallModel"]

#: The server's rolling ball loses speed as exp(-t / ROLLING_TIME_CONSTANT).
ROLLING_TIME_CONSTANT = 0.94

Array = NDArray[np.float64]


@dataclass(frozen=True)
class BallConfig:
    """Noise model of the ball filter."""

    #: observation noise: base (m) plus a fraction of the distance (vision noise, tilt error
    #: and the robot's own pose uncertainty, which :meth:`BallModel.observe` adds on top)
    sigma_m: float = 0.015
    sigma_rel: float = 0.006
    #: unmodelled acceleration (m/s^2) as white noise: sliding before rolling, small bumps
    acceleration_sigma: float = 1.5
    #: innovation (chi-square, 2 dof) beyond which the ball was kicked or moved: restart
    restart_chi2: float = 30.0
    #: velocity uncertainty (m/s) right after a restart
    restart_speed_sigma: float = 2.0
    #: below this speed (m/s) the ball counts as lying still
    still_speed: float = 0.05


class BallModel:
    """Ball filter. :meth:`predict` every cycle, :meth:`observe` whenever vision sees it.

    Positions are in the team frame (m), velocities in m/s. ``relative`` (the last seen
    position relative to the torso, native axes: x right, y forward, z up) is kept as the
    world model hands it over.
    """

    def __init__(self, config: BallConfig | None = None, tau: float = ROLLING_TIME_CONSTANT):
        self.config = config or BallConfig()
        self.tau = tau
        self._state: Array | None = None
        self._cov = np.zeros((4, 4))
        self._state_time = 0.0
        self._last_seen: float | None = None
        self._last_seen_position: Array | None = None
        self.time = 0.0
        #: last seen position relative to the torso (native axes), None before the first sight
        self.relative: Array | None = None
        #: height of the last seen ball centre above the ground (m)
        self.height = 0.0

    # ------------------------------------------------------------------ outputs
    @property
    def known(self) -> bool:
        return self._state is not None

    @property
    def position(self) -> tuple[float, float] | None:
        """Estimated position now, team frame (m)."""
        self._catch_up()
        if self._state is None:
            return None
        return (float(self._state[0]), float(self._state[1]))

    @property
    def velocity(self) -> tuple[float, float]:
        """Estimated velocity, team frame (m/s); zero before the first sight."""
        self._catch_up()
        if self._state is None:
            return (0.0, 0.0)
        return (float(self._state[2]), float(self._state[3]))

    @property
    def speed(self) -> float:
        return math.hypot(*self.velocity)

    @property
    def position_sigma(self) -> float:
        """RMS standard deviation of the position estimate (m); inf before the first sight."""
        self._catch_up()
        if self._state is None:
            return math.inf
        return math.sqrt((self._cov[0, 0] + self._cov[1, 1]) / 2.0)

    @property
    def time_since_seen(self) -> float:
        """Seconds since vision last reported the ball (inf if never)."""
        return math.inf if self._last_seen is None else self.time - self._last_seen

    @property
    def last_seen_time(self) -> float | None:
        return self._last_seen

    def predicted_stop(self) -> tuple[float, float] | None:
        """Where the ball comes to rest if nothing touches it (team frame): it rolls on for
        ``v tau`` along its velocity. None before the first sight."""
        self._catch_up()
        if self._state is None:
            return None
        x, y, vx, vy = self._state
        if math.hypot(vx, vy) < self.config.still_speed:
            return (float(x), float(y))
        return (float(x + vx * self.tau), float(y + vy * self.tau))

    def predicted_position(self, seconds: float) -> tuple[float, float] | None:
        """Where the rolling ball will be ``seconds`` from now (team frame)."""
        self._catch_up()
        if self._state is None:
            return None
        x, y, vx, vy = self._state
        travel = self.tau * (1.0 - math.exp(-max(0.0, seconds) / self.tau))
        return (float(x + vx * travel), float(y + vy * travel))

    # ------------------------------------------------------------------ filter
    def reset(self) -> None:
        """Forget the ball."""
        self._state = None
        self._last_seen = None
        self._last_seen_position = None
        self.relative = None

    def predict(self, time: float) -> None:
        """Roll the estimate on to ``time`` (s). Cheap: the filter catches up when it is next
        read or corrected, so cycles without an image cost nothing here."""
        self.time = max(self.time, time)

    def _catch_up(self) -> None:
        """Advance the filter from its own time to :attr:`time`."""
        dt = self.time - self._state_time
        self._state_time = self.time
        if self._state is None or dt <= 0.0:
            return
        decay = math.exp(-dt / self.tau)
        travel = self.tau * (1.0 - decay)
        x, y, vx, vy = self._state
        self._state = np.array([x + travel * vx, y + travel * vy, decay * vx, decay * vy])
        # covariance: the same transition on both axes, which never mix, plus white
        # acceleration noise integrated over dt (the standard constant-velocity model)
        f = np.array(
            [[1.0, 0.0, travel, 0.0], [0.0, 1.0, 0.0, travel], [0.0, 0.0, decay, 0.0],
             [0.0, 0.0, 0.0, decay]]
        )  # fmt: skip
        q = self.config.acceleration_sigma**2
        a, b, c = q * dt**3 / 3.0, q * dt**2 / 2.0, q * dt
        noise = np.array([[a, 0.0, b, 0.0], [0.0, a, 0.0, b], [b, 0.0, c, 0.0], [0.0, b, 0.0, c]])
        self._cov = f @ self._cov @ f.T + noise

    def observe(
        self,
        position: tuple[float, float],
        distance: float,
        time: float,
        pose_sigma: float = 0.0,
    ) -> None:
        """Take one sighting at ``position`` (team frame), seen from ``distance`` m away, while
        the robot's own position is uncertain by ``pose_sigma`` m."""
        self.predict(time)
        self._catch_up()
        z = np.asarray(position, dtype=float)
        sigma = self.config.sigma_m + self.config.sigma_rel * distance
        noise = sigma**2 + pose_sigma**2
        previous_seen, previous_position = self._last_seen, self._last_seen_position
        self._last_seen, self._last_seen_position = time, z
        if self._state is None:
            self._restart(z, noise, None, None, time)
            return
        # the innovation covariance is 2x2: its inverse written out costs far less than
        # np.linalg's fixed overhead
        (a, b), (c, d) = self._cov[:2, :2].tolist()
        a, d = a + noise, d + noise
        det = a * d - b * c
        h_inverse = np.array([[d / det, -b / det], [-c / det, a / det]])
        innovation = z - self._state[:2]
        chi2 = float(innovation @ h_inverse @ innovation)
        if chi2 > self.config.restart_chi2:
            self._restart(z, noise, previous_position, previous_seen, time)
            return
        gain = self._cov[:, :2] @ h_inverse
        self._state = self._state + gain @ innovation
        self._cov = self._cov - gain @ self._cov[:2, :]

    def _restart(
        self,
        z: Array,
        noise: float,
        previous: Array | None,
        previous_time: float | None,
        time: float,
    ) -> None:
        """Start over at ``z``; the velocity from the previous sighting if it is recent."""
        velocity = np.zeros(2)
        speed_var = self.config.restart_speed_sigma**2
        if previous is not None and previous_time is not None and 0.0 < time - previous_time < 0.2:
            dt = time - previous_time
            velocity = (z - previous) / dt
            speed_var = 2.0 * noise / dt**2
        self._state = np.array([z[0], z[1], velocity[0], velocity[1]])
        self._state_time = time
        self._cov = np.diag([noise, noise, speed_var, speed_var])
