#!/usr/bin/env python3
"""libshafts.so from Python through the shafts module
(blender_addon/shafts_blender/shafts.py), as the Blender add-on uses it: a
scene parsed from text, rendered by gl_shafts in-process (twice, on one
renderer), written as EXR, and compared with the gl_shafts CLI's image of
the same scene, which it must equal bit for bit; and a bad scene's error
read back with its file, line, column and key.

    python_api_test.py LIBSHAFTS GL_SHAFTS SHAFTS_COMPARE SOURCE_DIR
"""
import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

failures = []


def check(cond, what):
    print("%s: %s" % ("ok" if cond else "FAIL", what))
    if not cond:
        failures.append(what)


def main():
    libpath, gl_shafts, compare, source = sys.argv[1:5]
    sys.path.insert(0, str(Path(source) / "blender_addon" / "shafts_blender"))
    import shafts
    shafts.load_library(libpath)
    scenes = Path(source).resolve() / "scenes"
    data = json.loads((scenes / "teapot_spot.json").read_text())
    data["camera"]["width"], data["camera"]["height"] = 80, 60

    scene = shafts.Scene.from_json(json.dumps(data), name="inline.json", base_dir=scenes)
    check(scene.image_size == (80, 60), "image_size: %s" % (scene.image_size,))
    with shafts.SweepRenderer(scene) as renderer:
        first, stats = renderer.draw()
        second, _ = renderer.draw()
    check(first.shape == (60, 80, 3) and first.dtype == np.float32, "an (h, w, 3) float32 image")
    check(np.array_equal(first, second), "a renderer draws the same frame twice")
    check(bool(np.all(np.isfinite(first)) and first.min() >= 0 and first.max() > 0),
          "finite, non-negative, not black")
    check(stats["width"] == 80 and stats["planes"] > 0, "stats: %d planes" % stats["planes"])

    with tempfile.TemporaryDirectory() as tmp:
        mine, cli = Path(tmp) / "api.exr", Path(tmp) / "cli.exr"
        shafts.write_image(mine, first)
        scene_file = Path(tmp) / "scene.json"
        scene_file.write_text(json.dumps(data))
        # Relative asset paths resolve against the scene file's directory.
        for asset in (scenes / "assets").iterdir():
            (Path(tmp) / "assets").mkdir(exist_ok=True)
            shutil.copyfile(asset, Path(tmp) / "assets" / asset.name)
        subprocess.run([gl_shafts, str(scene_file), "-o", str(cli), "-q"], check=True)
        r = subprocess.run([compare, str(cli), str(mine), "--max-rel-rms", "0"],
                           stdout=subprocess.PIPE, universal_newlines=True)
        check(r.returncode == 0, "the in-process image equals the CLI's bit for bit\n" + r.stdout)
    scene.close()

    bad = '{"format": "shafts-scene", "version": 1,\n "camera": {"fov_y_deg": "wide"}}'
    try:
        shafts.Scene.from_json(bad, name="bad.json")
        check(False, "a bad scene is refused")
    except shafts.ShaftsError as e:
        check(e.status == "scene" and e.file == "bad.json" and e.line == 2 and e.column > 0
              and e.key == "camera", "its error has a location: %s" % e)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
