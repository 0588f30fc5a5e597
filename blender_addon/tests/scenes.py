"""The engines' test scenes, built by script as an artist builds them (watts,
spot size and blend, a volume cube, Diffuse BSDF surfaces), on the convert
tests' helpers (blender_addon/convert_tests/artist_scene.py). Each function
starts from an empty scene and returns it, 64x48 pixels."""
import sys
from pathlib import Path

import bpy

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "convert_tests"))
import artist_scene  # noqa: E402
from artist_scene import (add_object, camera, cube_mesh, diffuse_material,  # noqa: E402
                          light, plane_mesh, spot_in_volume_box, volume_material,
                          world_volume)


def reset():
    """An empty scene, the add-ons left enabled (read_factory_settings, which
    the convert tests use, would disable the installed add-on)."""
    bpy.ops.wm.read_homefile(use_empty=True)
    return bpy.context.scene


artist_scene.reset = reset
__all__ = ["spot_in_volume_box", "sun_through_window", "point_in_world_volume",
           "sun_in_height_fog", "SCENES"]


def sun_through_window():
    """A sun shining through a window in a wall into a volume box."""
    scene = reset()
    camera(scene, (6.5, -7.5, 2.5), (82, 0, 42), lens=30)
    light(scene, "Sun", "SUN", 4.0, (0, 5, 6), (-50, 0, 0), angle=0.0)
    floor = add_object(scene, "Floor", plane_mesh("Floor", 14.0))
    floor.data.materials.append(diffuse_material("Floor", (0.6, 0.6, 0.6)))
    wall = diffuse_material("Wall", (0.7, 0.7, 0.65))
    # The wall in the plane y = 0, 6 wide and 4 high, a 1.6 x 1.2 window.
    for name, (x0, x1, z0, z1) in {"Left": (-3, -0.8, 0, 4), "Right": (0.8, 3, 0, 4),
                                   "Sill": (-0.8, 0.8, 0, 1.6),
                                   "Lintel": (-0.8, 0.8, 2.8, 4)}.items():
        part = add_object(scene, name, cube_mesh(name, 1.0),
                          ((x0 + x1) / 2, 0.05, (z0 + z1) / 2), scale=(x1 - x0, 0.1, z1 - z0))
        part.data.materials.append(wall)
    fog = add_object(scene, "Fog", cube_mesh("Fog", 1.0), (0, -3, 2), scale=(6, 5.8, 4))
    fog.data.materials.append(volume_material("Fog", "scatter_absorption", density=0.08,
                                              anisotropy=0.5))
    return scene


def point_in_world_volume():
    """A point light over a floor and a sphere in a World volume."""
    scene = reset()
    camera(scene, (0, -7, 2.5), (80, 0, 0), lens=35)
    light(scene, "Point", "POINT", 1000.0, (0.5, 0, 3.5), shadow_soft_size=0.0)
    floor = add_object(scene, "Floor", plane_mesh("Floor", 12.0))
    floor.data.materials.append(diffuse_material("Floor", (0.5, 0.55, 0.6)))
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.7, location=(0, 0, 1.2), segments=24,
                                         ring_count=12)
    ball = bpy.context.active_object
    ball.data.materials.append(diffuse_material("Ball", (0.8, 0.6, 0.2)))
    world_volume(scene, 0.04, anisotropy=0.3)
    return scene


def sun_in_height_fog():
    """A sun over a floor in a box of height fog (base 0, H = 1 m,
    Henyey-Greenstein g = 0.3) set by the material's Shafts Medium
    properties, as an artist asks our engines for it; the Principled
    Volume is what Cycles would render (homogeneous)."""
    scene = reset()
    camera(scene, (0, -12, 2), (90, 0, 0), lens=35)
    light(scene, "Sun", "SUN", 3.0, (0, 0, 8), (60, 0, 30), angle=0.0)
    floor = add_object(scene, "Floor", plane_mesh("Floor", 20.0))
    floor.data.materials.append(diffuse_material("Floor", (0.5, 0.5, 0.5)))
    fog = add_object(scene, "Fog", cube_mesh("Fog", 1.0), (0, 0, 2), scale=(8, 8, 4))
    mat = volume_material("Fog", "principled", density=0.3, anisotropy=0.3)
    fog.data.materials.append(mat)
    m = mat.shafts_medium
    m.kind = 'HEIGHT_FOG'
    m.sigma_s, m.sigma_a = (0.3, 0.3, 0.3), (0.02, 0.02, 0.02)
    m.base_height, m.scale_height = 0.0, 1.0
    m.phase, m.phase_g = 'HENYEY_GREENSTEIN', 0.3
    return scene


SCENES = {"spot_box": spot_in_volume_box, "sun_window": sun_through_window,
          "point_world": point_in_world_volume}
