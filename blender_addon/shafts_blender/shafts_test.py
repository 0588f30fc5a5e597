#!/usr/bin/env python3
"""Tests of the shafts module (shafts.py) outside Blender, against the real
library: the version, located errors (scene, mesh arrays, patch, options),
meshes from arrays against the same mesh from its OBJ file, scene updates
with a live sweep renderer synced against a fresh one, the progress
callback, a cancel from another thread during a reference render (after
which the scene still renders), and the light meshes and Whitted modes.

    shafts_test.py LIBSHAFTS SOURCE_DIR VERSION
"""
import json
import sys
import threading
from pathlib import Path

import numpy as np

failures = []


def check(cond, what):
    print("%s: %s" % ("ok" if cond else "FAIL", what))
    if not cond:
        failures.append(what)


def raises(fn, **want):
    """Calls fn; returns the ShaftsError it raised if its fields are `want`."""
    try:
        fn()
    except shafts.ShaftsError as e:
        got = {k: getattr(e, k) for k in want}
        if got == want:
            return e
        print("  got %s: %s" % (got, e))
        return None
    print("  no error")
    return None


SCENE = {
    "format": "shafts-scene", "version": 1,
    "camera": {"position": [0, 2, 6], "look_at": [0, 0.7, 0], "fov_y_deg": 40,
               "width": 48, "height": 32},
    "medium": {"sigma_s": [0.1, 0.1, 0.1],
               "bounds": {"min": [-4, -1, -4], "max": [4, 4, 4]}},
    "lights": [{"type": "spot", "position": [0, 3.5, 0.5], "look_at": [0, 0, 0],
                "intensity": [40, 40, 40], "outer_angle_deg": 30}],
    "materials": {"white": {"diffuse": [0.8, 0.8, 0.8]}},
    "shapes": [{"type": "box", "material": "white", "min": [-3, -0.1, -3], "max": [3, 0, 3]},
               {"type": "mesh", "material": "white", "file": "teapot.obj",
                "transform": {"translate": [0, 0, 0], "scale": 0.4}}],
}


def read_obj(path):
    """The vertices and triangles of a triangulated OBJ file."""
    vs, fs = [], []
    for line in Path(path).read_text().splitlines():
        parts = line.split()
        if parts and parts[0] == "v":
            vs.append([float(x) for x in parts[1:4]])
        elif parts and parts[0] == "f":
            idx = [int(p.split("/")[0]) - 1 for p in parts[1:]]
            fs += [[idx[0], idx[i], idx[i + 1]] for i in range(1, len(idx) - 1)]
    return np.array(vs, np.float32), np.array(fs, np.int32)


def test_errors(assets):
    e = raises(lambda: shafts.Scene.from_json('{"format": "shafts-scene", "version": 1,\n'
                                              ' "camera": 3}', name="bad.json"),
               status="scene", file="bad.json", line=2, key="camera")
    check(e is not None and e.column == 12, "a bad scene: %s" % e)
    e = raises(lambda: shafts.Scene.load(assets / "missing.json"), status="io")
    check(e is not None, "a missing scene file: %s" % e)
    text = json.dumps(SCENE, indent=1).replace('"file": "teapot.obj"', '"data": "teapt"')
    pos, tri = read_obj(assets / "teapot.obj")
    e = raises(lambda: shafts.Scene.from_json(text, name="m.json", meshes={"teapot": (pos, tri)}),
               status="scene", key="shapes[1].data")
    check(e is not None and e.line > 1 and "did you mean 'teapot'" in e.message,
          "an unknown mesh name: %s" % e)
    bad = tri.copy()
    bad[5, 1] = len(pos)
    e = raises(lambda: shafts.Scene.from_json(text.replace("teapt", "teapot"), name="m.json",
                                              meshes={"teapot": (pos, bad)}),
               status="scene", key="shapes[1].data")
    check(e is not None and "triangle 5 refers to vertex %d" % len(pos) in e.message,
          "an index out of range: %s" % e)
    nan = pos.copy()
    nan[3, 2] = np.nan
    e = raises(lambda: shafts.Scene.from_json(text.replace("teapt", "teapot"), name="m.json",
                                              meshes={"teapot": (nan, tri)}),
               status="scene", key="shapes[1].data")
    check(e is not None and "non-finite position" in e.message, "a NaN position: %s" % e)
    with shafts.Scene.from_json(SCENE, base_dir=assets) as s:
        e = raises(lambda: s.update('{"camera": {"position": [0, 2, 6],\n "look_at": [0, 0, 0],'
                                    ' "fov_y_deg": 0, "width": 8, "height": 8}}', name="p.json"),
                   status="scene", file="p.json", line=2, key="camera.fov_y_deg")
        check(e is not None, "a bad patch: %s" % e)
        e = raises(lambda: s.update({"lights": []}), status="scene", key="lights")
        check(e is not None and "parse the scene again" in e.message, "a light removed: %s" % e)
        check(s.image_size == (48, 32), "a bad patch leaves the scene as it was")
        e = raises(lambda: shafts.SweepRenderer(s, options={"planes": -3}), status="arg",
                   key="planes")
        check(e is not None, "a bad sweep option: %s" % e)
        e = raises(lambda: shafts.SweepRenderer(s, options={"xi": "fast"}), status="arg", key="xi")
        check(e is not None and "lattice, exact" in e.message, "a bad choice: %s" % e)
        e = raises(lambda: shafts.render_lmm(s, scheme="bent"), status="arg", key="scheme")
        check(e is not None, "a bad tracer option: %s" % e)


def test_meshes(assets):
    pos, tri = read_obj(assets / "teapot.obj")
    text = json.dumps(SCENE).replace('"file": "teapot.obj"', '"data": "teapot"')
    with shafts.Scene.from_json(SCENE, base_dir=assets) as from_file, \
            shafts.Scene.from_json(text, meshes={"teapot": (pos, tri)}) as from_arrays:
        a, _ = shafts.render_reference(from_file, spp=2, threads=2)
        b, _ = shafts.render_reference(from_arrays, spp=2, threads=2)
        diff = float(np.abs(a - b).max() / max(a.max(), 1e-30))
        check(diff < 1e-5, "the teapot from arrays renders as from its OBJ (%.2g)" % diff)
        c, _ = shafts.SweepRenderer(from_file).draw()
        d, _ = shafts.SweepRenderer(from_arrays).draw()
        diff = float(np.abs(c - d).max() / max(c.max(), 1e-30))
        check(diff < 1e-5, "and with the sweep (%.2g)" % diff)


def test_update(assets):
    moved = json.loads(json.dumps(SCENE))
    moved["camera"]["position"] = [1, 2.5, 6]
    moved["lights"][0]["intensity"] = [60, 50, 40]
    patch = {"camera": moved["camera"], "lights": moved["lights"],
             "transforms": [None, {"translate": [0.3, 0, 0], "scale": 0.4}]}
    moved["shapes"][1]["transform"] = patch["transforms"][1]
    with shafts.Scene.from_json(SCENE, base_dir=assets) as s, \
            shafts.Scene.from_json(moved, base_dir=assets) as fresh:
        live = shafts.SweepRenderer(s, live=True)
        before, _ = live.draw()
        changed = s.update(patch)
        check(changed == shafts.CHANGED_CAMERA | shafts.CHANGED_LIGHTS | shafts.CHANGED_SHAPES,
              "update returns the changed bits (%d)" % changed)
        check(s.update({"camera": moved["camera"]}) == 0, "an unchanged camera changes nothing")
        if hasattr(shafts.load_library(), "gs_renderer_sync"):
            live.sync(changed)
            after, stats = live.draw()
            want, _ = shafts.SweepRenderer(fresh, live=True).draw()
            check(not np.array_equal(before, after), "the synced frame shows the change")
            check(np.array_equal(after, want),
                  "a synced live renderer draws what a fresh one draws")
            check(stats.get("programs_compiled") == 0, "no program compiled after the sync (%s)"
                  % stats.get("programs_compiled"))
        else:
            print("skip: this library has no gs_renderer_sync")
        live.close()


def test_progress_and_cancel(assets):
    big = json.loads(json.dumps(SCENE))
    big["camera"]["width"], big["camera"]["height"] = 160, 120
    with shafts.Scene.from_json(big, base_dir=assets) as s:
        calls = []
        rgb, stats = shafts.render_reference(s, spp=1, threads=2,
                                             progress=lambda d, t: calls.append((d, t)))
        tiles = 10 * 8
        check(len(calls) == tiles and max(calls) == (tiles, tiles),
              "progress is called once per tile up to (%d, %d): %d calls" % (tiles, tiles, len(calls)))
        check(rgb.shape == (120, 160, 3) and stats["camera_rays"] == 160 * 120, "the stats")

        cancel = shafts.CancelFlag()
        started = threading.Event()
        outcome = {}

        def work():
            try:
                outcome["result"] = shafts.render_reference(
                    s, spp=4096, threads=2, cancel=cancel, progress=lambda d, t: started.set())
            except shafts.ShaftsError as e:
                outcome["error"] = e

        t = threading.Thread(target=work)
        t.start()
        check(started.wait(60), "the render started")
        cancel.set()
        t.join(120)
        e = outcome.get("error")
        check(not t.is_alive() and e is not None and e.status == "cancelled",
              "a cancel from another thread stops the render: %s" % (e or outcome.keys()))
        rgb, _ = shafts.render_reference(s, spp=1, threads=2)
        check(float(rgb.max()) > 0, "the scene renders again after a cancel")


def test_modes(assets):
    with shafts.Scene.from_json(SCENE, base_dir=assets) as s:
        rgb, stats = shafts.render_lmm(s, mesh_step=0.1, radius=3, spp=1)
        check(stats["mode"] == "lmm" and stats["mesh_step"] == 0.1 and stats["kl"] == 3
              and stats["shaded_points"] > 0, "lmm mode with its stats")
        rgb, stats = shafts.render_lmm(s, mode="whitted", area_radius=0.05, area_samples=4, spp=1)
        check(stats["mode"] == "whitted" and "mesh_step" not in stats and rgb.max() > 0,
              "whitted with sphere lights")


def main():
    global shafts
    libpath, source, version = sys.argv[1:4]
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import shafts as module
    shafts = module
    shafts.load_library(libpath)
    check(shafts.version() == version, "version %s" % shafts.version())
    assets = Path(source).resolve() / "scenes" / "assets"
    test_errors(assets)
    test_meshes(assets)
    test_update(assets)
    test_progress_and_cancel(assets)
    test_modes(assets)
    print("%d failed" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
