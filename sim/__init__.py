"""The PyBullet stand-in for SimSpark/rcssserver3d.

Robot model, field, referee, sessions, TCP server."""
