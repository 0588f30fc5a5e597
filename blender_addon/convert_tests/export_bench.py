"""Times the Blender -> scene export (docs/blender.md, Mapping):

    blender -b --factory-startup --python export_bench.py [-- LEVELS...]

A UV sphere subdivided to about 0.1, 0.5 and 2 million triangles (the
Subdivision Surface modifier, evaluated by the depsgraph), a spot and a
volume box; prints the time of export_scene (depsgraph to arrays and JSON),
of its triangles per second, and of export_patch after moving the light
(what a viewport pays per change), best of three runs each."""
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy

import harness  # noqa: F401  (puts the package on sys.path)
import artist_scene as A
from shafts_blender.convert import export_patch, export_scene


def best(f, runs=3):
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t)
    return min(times), out


levels = [int(a) for a in harness.args()] or [2, 3, 4]
print("%10s %12s %14s %16s" % ("triangles", "export (s)", "Mtriangles/s", "patch (ms)"))
for level in levels:
    scene = A.spot_in_volume_box()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, location=(0, 0, 1))
    sphere = bpy.context.active_object
    mod = sphere.modifiers.new("Subdivision", "SUBSURF")
    mod.levels = mod.render_levels = level
    dg = bpy.context.evaluated_depsgraph_get()
    seconds, e = best(lambda: export_scene(dg))
    tris = sum(len(i) for _, i in e.meshes.values())
    spot = bpy.data.objects["Spot"]

    def patch():
        spot.location.x += 0.01
        d = bpy.context.evaluated_depsgraph_get()
        return export_patch(d, e)

    patch_seconds, p = best(patch)
    assert p is not None
    print("%10d %12.3f %14.2f %16.2f" % (tris, seconds, tris / seconds / 1e6,
                                         patch_seconds * 1e3))
sys.stdout.flush()
