"""What an agent knows: the wire codec, typed perceptions and (later) the world model.

Nothing in this package imports pybullet or torch: both the server and a playing agent use it.
"""
