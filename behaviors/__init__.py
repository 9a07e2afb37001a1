"""Skills and the behaviour manager. Runs with numpy only: no pybullet, no torch."""
