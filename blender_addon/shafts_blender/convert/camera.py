"""Blender's camera (or a 3D viewport's view) as the scene's pinhole camera.

The scene camera is a pinhole with a full vertical field of view `fov_y_deg`
and square pixels (docs/scene-format.md, camera). Blender's projection comes
from `Object.calc_matrix_camera`, which applies the sensor fit (AUTO,
HORIZONTAL, VERTICAL) and the pixel aspect: for a perspective projection P,
tan(fov_y / 2) = 1 / P[1][1] whatever the fit. The camera's frame is its
object matrix: it looks along -Z with +Y up (Blender's convention).

Exact: perspective cameras without shift, square pixels. Approximated with a
warning: lens shift (the format has no off-centre projection; a project key
would be needed, so the image is centred), non-square pixels, depth of field
(the scene's camera is a pinhole), orthographic and panoramic cameras (a
perspective camera of 40 degrees at the same place), a missing camera.
"""
import math

import numpy as np

from . import coords

DEFAULT_FOV_DEG = 40.0


def image_size(scene, size=None):
    """The image size in pixels: `size` (w, h) if given, else the render
    resolution scaled by its percentage (at least one pixel a side)."""
    if size is not None:
        return max(1, int(size[0])), max(1, int(size[1]))
    r = scene.render
    pct = r.resolution_percentage / 100.0
    return max(1, int(r.resolution_x * pct)), max(1, int(r.resolution_y * pct))


def _frame(cam_to_world):
    m = coords.matrix_array(cam_to_world)
    position = coords.vector(m[:3, 3])
    forward = coords.vector(-m[:3, 2])
    up = coords.vector(m[:3, 1])
    n = math.sqrt(sum(x * x for x in forward)) or 1.0
    look_at = [p + f / n for p, f in zip(position, forward)]
    return position, look_at, up


def _fov_from_projection(p, w, h, what, warnings):
    p = coords.matrix_array(p)
    if abs(p[3][3]) > 1e-12:  # orthographic
        warnings.add("%s is orthographic; it is rendered as a perspective camera of "
                     "%g degrees at the same place." % (what, DEFAULT_FOV_DEG))
        return DEFAULT_FOV_DEG
    if abs(p[0][2]) > 1e-9 or abs(p[1][2]) > 1e-9:
        warnings.add("%s has an off-centre projection (lens shift); the scene format has "
                     "no shift, so the image is centred on the camera's axis." % what)
    fov = math.degrees(2.0 * math.atan(1.0 / p[1][1]))
    if p[0][0] > 0 and abs(p[0][0] / p[1][1] - h / w) > 1e-4 * (h / w):
        warnings.add("%s has non-square pixels; the scene's pixels are square, with the "
                     "same vertical field of view." % what)
    return min(max(fov, 1e-3), 179.9)


def export_camera(depsgraph, scene, warnings, view=None, size=None):
    """The "camera" object of the scene format."""
    w, h = image_size(scene, size)
    if view is not None:
        view_matrix, projection = view
        position, look_at, up = _frame(np.linalg.inv(coords.matrix_array(view_matrix)))
        fov = _fov_from_projection(projection, w, h, "The viewport's view", warnings)
    elif scene.camera is None:
        warnings.add("The scene has no camera; a camera at (0, -10, 0) in Blender's "
                     "frame looking at the origin, Z up, is used.")
        position, look_at, up = coords.vector((0.0, -10.0, 0.0)), [0.0, 0.0, 0.0], [0.0, 1.0, 0.0]
        fov = DEFAULT_FOV_DEG
    else:
        obj = scene.camera.evaluated_get(depsgraph)
        what = "The camera '%s'" % obj.name
        position, look_at, up = _frame(obj.matrix_world)
        data = obj.data
        if obj.type != "CAMERA":
            warnings.add("%s is not a camera object; its frame is used with a field of "
                         "view of %g degrees." % (what, DEFAULT_FOV_DEG))
            fov = DEFAULT_FOV_DEG
        elif data.type == "PANO":
            warnings.add("%s is panoramic; it is rendered as a perspective camera of %g "
                         "degrees at the same place." % (what, DEFAULT_FOV_DEG))
            fov = DEFAULT_FOV_DEG
        else:
            r = scene.render
            projection = obj.calc_matrix_camera(depsgraph, x=w, y=h,
                                                scale_x=r.pixel_aspect_x,
                                                scale_y=r.pixel_aspect_y)
            fov = _fov_from_projection(projection, w, h, what, warnings)
            if r.pixel_aspect_x != r.pixel_aspect_y:
                warnings.add("%s renders with a pixel aspect of %g:%g; the scene's pixels "
                             "are square, with the same vertical field of view."
                             % (what, r.pixel_aspect_x, r.pixel_aspect_y))
            if data.dof.use_dof:
                warnings.add("%s has depth of field; the scene's camera is a pinhole, "
                              "so everything is in focus." % what)
    return {"position": position, "look_at": look_at, "up": up, "fov_y_deg": fov,
            "width": w, "height": h}
