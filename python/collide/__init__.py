"""collide: collision detection and response for 3D games, from Python.

The module wraps the C++ library (docs/python.md): worlds, bodies, shapes, joints, queries, events
and scene files. Vectors are sequences of three numbers; rotations are quaternions (w, x, y, z);
the state of many bodies comes as NumPy arrays (World.positions, World.velocities, ...). Errors are
collide.Error (a ValueError) with the library's message.
"""
from ._collide import *  # noqa: F401,F403
from ._collide import Error, __version__  # noqa: F401
