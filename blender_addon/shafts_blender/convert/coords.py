"""The one place where Blender's frame meets the scene format's.

Blender is right-handed with Z up; the scene format (docs/scene-format.md) is
right-handed with Y up. A Blender point (X, Y, Z) is the scene point
(X, Z, -Y): a rotation of -90 degrees about X, so nothing is mirrored. It is
the inverse of the rotation scene_export's Blender writer applies
(`to_blender` in scene_export/se_blender.c: scene (x, y, z) -> Blender
(x, -z, y)). Every module of this package converts through these functions.
"""
import numpy as np

# SCENE_FROM_BLENDER @ blender_vector = scene_vector (3x3, a rotation).
SCENE_FROM_BLENDER = np.array([[1.0, 0.0, 0.0],
                               [0.0, 0.0, 1.0],
                               [0.0, -1.0, 0.0]])
BLENDER_FROM_SCENE = SCENE_FROM_BLENDER.T

_S4 = np.eye(4)
_S4[:3, :3] = SCENE_FROM_BLENDER


def matrix_array(m):
    """A mathutils.Matrix (or nested sequence) as a float64 numpy array."""
    return np.array([list(row) for row in m], dtype=np.float64)


def vector(v):
    """A Blender direction or point (3 numbers) in the scene's frame, as a
    list of Python floats."""
    return [float(x) for x in SCENE_FROM_BLENDER @ np.asarray(v, dtype=np.float64)[:3]]


def points(a):
    """An (n, 3) array of Blender points in the scene's frame (float32)."""
    return (np.asarray(a, dtype=np.float64).reshape(-1, 3) @ SCENE_FROM_BLENDER.T).astype(np.float32)


def transform(m):
    """A Blender object-to-world 4x4 matrix as the scene's object-to-world
    matrix for geometry whose object-space points went through points():
    S M S^-1."""
    return _S4 @ matrix_array(m) @ _S4.T


def matrix_key(m):
    """A 4x4 matrix as the format's {"matrix": 16 numbers, row-major}."""
    m = np.asarray(m, dtype=np.float64)
    return {"matrix": [float(x) for x in m.reshape(16)]}
