"""How far the renderers hold at extreme ratios (issue 11, kind 3): prints
the tables of docs/lmm.md, docs/gl_shafts.md and docs/scene_export.md
("Precision").

  python3 -m validation.precision --build-dir build [--width 48]

The scene is the hard cases' base scene (validation/hard/cases.py: a spot
in fog over a floor, a black ball shadowing the shaft; the case of
/work/shared/cases/far_camera.json), at --width x 3/4 of it, with:

- the camera at 5 ... 5e7 units with the field of view that keeps the
  framing (a field of view below 1e-6 degrees is refused by the parser):
  each renderer against the reference at the same distance (256 samples;
  the reference's own line is its distance from the reference at 500
  units, where the perspective is already flat);
- every length times 1e-12 ... 1e12 (coefficients over it, intensities
  times its square): each renderer against its own image of the plain
  scene (the reference and lmm draw the same samples, so only rounding
  differs);
- the scene moved by 1e3 ... 1e9 along (1, -1, 1): likewise.

With --planet, instead: planet_test's scenes (issue 12 part 5; the eye
1 m above a 6360 km ground sphere, a spot 30 m up in 40 m of fog, a box
shading the shaft; the same over a flat ground quad 2e7 m across; the
planet from 30,000 km in a shell of Rayleigh fog), each renderer against
the reference (256 samples), and moved by 1e7 (1, -1, 1) and scaled by
1e-9 and 1e9 against its own plain image.

Relative RMS over the lit region (shafts_compare, lit 0.01); 'fail' where a
renderer exits with an error. Renderers (--renderers): lmm_tracer's
reference and lmm modes, gl_shafts, POV-Ray and Blender's Cycles (256
samples, minutes) through scene_export, where installed; cycles_unscaled is
Cycles with the export's --scale none (the scene's own units and position,
as every Blender export was before the exporter chose a frame).
"""

import argparse
import json
import math
import shutil
import subprocess
import tempfile
from pathlib import Path

from .hard.cases import base_scene, camera_at, moved, scaled

DISTANCES = [5.0, 50.0, 500.0, 5000.0, 5e4, 5e5, 5e6, 5e7]
SCALES = [1e-12, 1e-9, 1e-6, 1e-3, 1e3, 1e6, 1e9, 1e12]
OFFSETS = [1e3, 1e6, 1e7, 1e8, 1e9]


R_PLANET = 6360e3


def planet_ground(w, h, quad=False, sun=False):
    """gl_shafts/planet_test.c's ground scene; with quad, the ground a
    flat quad 2e7 m across at y = 0 instead of the sphere; with sun, a
    directional sun instead of the spot (its shadow map over a planet)."""
    ground = ({"type": "quad", "material": "ground", "corner": [-1e7, 0, 1e7],
               "u": [2e7, 0, 0], "v": [0, 0, -2e7]} if quad else
              {"type": "sphere", "material": "ground", "center": [0, -R_PLANET, 0],
               "radius": R_PLANET})
    lights = ([{"type": "directional", "direction": [0.3, -1, 0.2], "irradiance": [1, 1, 1]}]
              if sun else
              [{"type": "spot", "position": [0, 30, -60], "direction": [0, -1, 0],
                "intensity": [3000] * 3, "outer_angle_deg": 30,
                "inner_angle_deg": 20, "exponent": 1}])
    return {
        "format": "shafts-scene", "version": 1,
        "camera": {"position": [0, 1, 0], "look_at": [0, 3, -60], "fov_y_deg": 50,
                   "width": w, "height": h},
        "medium": {"sigma_s": [0.02] * 3, "sigma_a": [0.002] * 3,
                   "phase": {"type": "henyey_greenstein", "g": 0.3},
                   "bounds": {"min": [-100, -1, -200], "max": [100, 40, 5]}},
        "lights": lights,
        "materials": {"ground": {"diffuse": [0.3] * 3}, "box": {"diffuse": [0.5, 0.4, 0.3]}},
        "shapes": [ground, {"type": "box", "material": "box", "min": [-3, 12, -63],
                            "max": [3, 14, -57]}],
    }


def planet_space(w, h):
    """gl_shafts/planet_test.c's planet from 30,000 km."""
    top, dist = 6560e3, 3e7
    return {
        "format": "shafts-scene", "version": 1,
        "camera": {"position": [0, 0, dist], "look_at": [0, 0, 0],
                   "fov_y_deg": 2 * math.degrees(math.atan(1.3 * top / dist)),
                   "width": w, "height": h},
        "medium": {"sigma_s": [3e-8] * 3, "sigma_a": [0, 0, 0], "phase": {"type": "rayleigh"},
                   "bounds": {"min": [-top] * 3, "max": [top] * 3}},
        "lights": [{"type": "directional", "direction": [-0.8, 0, -0.6],
                    "irradiance": [1, 1, 1]}],
        "materials": {"ground": {"diffuse": [0.3] * 3}},
        "shapes": [{"type": "sphere", "material": "ground", "center": [0, 0, 0],
                    "radius": R_PLANET}],
    }


def renderers(build, work):
    def lmm(mode):
        def render(scene, out):
            subprocess.run([str(build / "lmm_tracer" / "lmm_tracer"), str(scene), "-o", str(out),
                            "--mode", mode, "--spp", "64", "--seed", "1", "-q"],
                           check=True, capture_output=True)
        return render

    def gl(scene, out):
        subprocess.run([str(build / "gl_shafts" / "gl_shafts"), str(scene), "-o", str(out), "-q"],
                       check=True, capture_output=True)

    def pov(scene, out):
        pov_file = out.with_suffix(".pov")
        subprocess.run([str(build / "scene_export" / "scene_export"), str(scene), "--to", "pov",
                        "-o", str(pov_file)], check=True, capture_output=True)
        subprocess.run(["povray", pov_file.with_suffix(".ini").name], cwd=str(out.parent),
                       check=True, capture_output=True)
    def cycles_with(*options):
        def cycles(scene, out):
            py = out.with_suffix(".py")
            subprocess.run([str(build / "scene_export" / "scene_export"), str(scene), "--to",
                            "blender", "-o", str(py)] + list(options), check=True,
                           capture_output=True)
            subprocess.run(["blender", "-b", "-P", str(py), "--", "--engine", "cycles",
                            "--out", str(out), "--samples", "256"], check=True,
                           capture_output=True)
        return cycles
    out = [("reference", lmm("reference")), ("lmm", lmm("lmm")), ("gl_shafts", gl)]
    if shutil.which("povray"):
        out.append(("povray", pov))
    if shutil.which("blender"):
        out.append(("cycles", cycles_with()))
        out.append(("cycles_unscaled", cycles_with("--scale", "none")))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build-dir", default="build")
    ap.add_argument("--width", type=int, default=48)
    ap.add_argument("--planet", action="store_true",
                    help="the planet-scale table only (see above)")
    ap.add_argument("--renderers", default="reference,lmm,gl_shafts,povray",
                    help="comma-separated, of reference, lmm, gl_shafts, povray, cycles "
                         "(Blender's Cycles, 256 samples; slow) and cycles_unscaled (the "
                         "same, exported with --scale none: the scene's own units and "
                         "position)")
    args = ap.parse_args(argv)
    build = Path(args.build_dir).resolve()
    w, h = args.width, args.width * 3 // 4
    compare = build / "validation" / "shafts_compare"
    with tempfile.TemporaryDirectory(prefix="precision.") as tmp:
        work = Path(tmp)
        wanted = args.renderers.split(",")
        rs = [(n, fn) for n, fn in renderers(build, work) if n in wanted]
        count = [0]

        def render(name, scene, fn):
            count[0] += 1
            path = work / ("s%d.json" % count[0])
            path.write_text(json.dumps(scene))
            out = work / ("s%d.exr" % count[0])
            try:
                fn(path, out)
            except subprocess.CalledProcessError:
                return None
            return out

        def error(ref, img):
            if ref is None or img is None:
                return "fail"
            p = subprocess.run([str(compare), str(ref), str(img), "--json"],
                               capture_output=True, text=True)
            if p.returncode != 0:
                return "fail"
            e = json.loads(p.stdout)["rel_rms"]
            return "%.2g%%" % (100 * e) if e >= 1e-4 else "< 0.01%"

        def reference(scene):
            path = work / "ref.json"
            path.write_text(json.dumps(scene))
            out = work / ("ref%d.exr" % count[0])
            count[0] += 1
            try:
                subprocess.run([str(build / "lmm_tracer" / "lmm_tracer"), str(path), "-o",
                                str(out), "--spp", "256", "--seed", "7", "-q"],
                               check=True, capture_output=True)
            except subprocess.CalledProcessError:
                return None
            return out

        names = [n for n, _ in rs]
        if args.planet:
            print("Planet scale: against the reference (256 samples); moved by 1e7 (1, -1, 1) "
                  "and scaled, against the renderer's own plain image:\n")
            cols = ["reference", "moved 1e7", "scaled 1e-9", "scaled 1e9"]
            print("| scene | renderer | " + " | ".join(cols) + " |")
            print("|---" * (len(cols) + 2) + "|")
            scenes = [("eye 1 m above a 6360 km sphere", planet_ground(w, h)),
                      ("eye 1 m above a quad 2e7 m across", planet_ground(w, h, quad=True)),
                      ("the same under a directional sun", planet_ground(w, h, sun=True)),
                      ("the planet from 30,000 km", planet_space(w, h))]
            for title, scene in scenes:
                ref = reference(scene)
                for n, fn in rs:
                    own = render(n, scene, fn)
                    cells = [error(ref, own)]
                    cells.append(error(own, render(n, moved(scene, (1e7, -1e7, 1e7)), fn)))
                    for k in (1e-9, 1e9):
                        cells.append(error(own, render(n, scaled(scene, k), fn)))
                    print("| %s | %s | %s |" % (title, n, " | ".join(cells)))
            return 0
        print("Camera distance (the framing kept), against the reference there:\n")
        print("| distance | fov (degrees) | " + " | ".join(names) + " |")
        print("|---" * (len(names) + 2) + "|")
        ref500 = reference(camera_at(500.0)(w, h))
        for d in DISTANCES:
            scene = camera_at(d)(w, h)
            ref = reference(scene)
            cells = []
            for n, fn in rs:
                img = render(n, scene, fn)
                cells.append(error(ref500 if n == "reference" else ref,
                                   img if n != "reference" else ref))
            print("| %g | %.3g | %s |" % (d, scene["camera"]["fov_y_deg"], " | ".join(cells)))
        print("\nScale (every length times it), against the renderer's own plain image:\n")
        print("| scale | " + " | ".join(names) + " |")
        print("|---" * (len(names) + 1) + "|")
        plain = {n: render(n, base_scene(w, h), fn) for n, fn in rs}
        for k in SCALES:
            cells = [error(plain[n], render(n, scaled(base_scene(w, h), k), fn)) for n, fn in rs]
            print("| %g | %s |" % (k, " | ".join(cells)))
        print("\nPosition (moved by d (1, -1, 1)), against the renderer's own plain image:\n")
        print("| d | " + " | ".join(names) + " |")
        print("|---" * (len(names) + 1) + "|")
        for o in OFFSETS:
            cells = [error(plain[n], render(n, moved(base_scene(w, h), (o, -o, o)), fn))
                     for n, fn in rs]
            print("| %g | %s |" % (o, " | ".join(cells)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
