"""The PyBullet stand-in for SimSpark/rcssserver3d: robot model, field, referee, sessions, server."""
