"""Issue 12's sky benchmark: the atmosphere scenes at 640x480 in every
renderer that draws them, timed in one run, with their errors against the
converged reference and both as ratios. docs/sky.md quotes its table.

  python3 -m validation.bench_sky [--build-dir build] [--out DIR]
      [--scenes sky_sunset,earth_from_space] [--width 640] [--height 480]
      [--ref-spp 256] [--spp 16] [--frames 5] [--cycles-samples 64]
      [--renderers gl_shafts,reference,blender_sky,pov,cycles]

Renderers (each skipped with its own message where it cannot draw the
scene, e.g. before the atmosphere lands in it):
- gl_shafts: gl_shafts_bench's best warm frame (--frames after a warm-up,
  the GL context and program builds counted apart), its image from the
  gl_shafts command line;
- reference: lmm_tracer --mode reference at --spp samples (wall time);
- blender_sky: Blender 3.4's Nishita sky texture (validation/nishita_blender.py,
  Cycles, one sample: the texture is deterministic) seen from the scene's
  camera in the planet's local frame (Z the local vertical at the eye, Y the
  sun's azimuth), its sun disk only where the scene's sun has one (of the
  same size), altitude from the eye's height (Blender's model is the
  Earth: lengths are scaled by 6360 km / ground_radius), scaled per
  channel by the scene's sun irradiance over Blender's own (measured from
  its disk, as validation/nishita.py does). Only from within Blender's 60 km
  altitude limit. Its "error" is the difference between two models of the
  sky (docs/sky.md, "Blender's Nishita sky"), not a renderer's error;
- pov, cycles: scene_export --to pov / blender (draft quality), POV-Ray and
  Blender's Cycles (--cycles-samples), wall time of the renderer alone.

The truth is the reference at --ref-spp samples (kept in
BUILD/bench_sky_refs by scene content, size and samples). Error: relative
RMS over the lit region (shafts_compare, lit 0.01). Ratios: time and error
over gl_shafts' (over the reference's when gl_shafts is skipped).
All work runs under nice -n 10.
"""

import argparse
import hashlib
import json
import math
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

from . import nishita
from .metrics import CompareFailed, compare
from .renderers import pov_frames
from .scenes import prepare_file

ROOT = Path(__file__).resolve().parent.parent
NICE = ["nice", "-n", "10"]
ALL = ["gl_shafts", "reference", "blender_sky", "pov", "cycles"]


class Skip(Exception):
    """A renderer cannot draw the scene: the message says why."""


def run(cmd, cwd=None, timeout=3600):
    t0 = time.perf_counter()
    proc = subprocess.run(NICE + [str(c) for c in cmd], cwd=cwd, capture_output=True,
                          text=True, timeout=timeout)
    return proc, time.perf_counter() - t0


def first_error(proc):
    """A tool's first error line, without the tool's name and the file's
    place: 'medium.type: gl_shafts renders homogeneous media only, ...'."""
    text = (proc.stderr or proc.stdout or "").strip().splitlines()
    lines = [l for l in text if "error" in l.lower()] or text
    if not lines:
        return "exit status %d" % proc.returncode
    return re.sub(r"^(\S+: error: )?(\S+:\d+:\d+: )?", "", lines[0])


# --- renderers ---------------------------------------------------------------


def truth(ctx, scene):
    key = hashlib.sha256(scene.path.read_bytes()).hexdigest()[:16]
    cache = ctx.build / "bench_sky_refs"
    cache.mkdir(parents=True, exist_ok=True)
    out = cache / ("%s_%s_%dx%d_%d.exr" % (scene.name, key, scene.width, scene.height,
                                            ctx.ref_spp))
    if not out.exists():
        proc, secs = run([ctx.build / "lmm_tracer" / "lmm_tracer", scene.path, "-o", out,
                          "-q", "--mode", "reference", "--spp", ctx.ref_spp])
        if proc.returncode != 0:
            raise Skip("the reference cannot render it: %s" % first_error(proc))
        print("bench_sky: %s: reference at %d samples in %.1f s (kept in %s)"
              % (scene.name, ctx.ref_spp, secs, cache))
    return out


def r_reference(ctx, scene, work):
    out = work / "reference.exr"
    proc, secs = run([ctx.build / "lmm_tracer" / "lmm_tracer", scene.path, "-o", out, "-q",
                      "--mode", "reference", "--spp", ctx.spp, "--seed", 7])
    if proc.returncode != 0:
        raise Skip(first_error(proc))
    return out, secs, "%d spp" % ctx.spp


def r_gl_shafts(ctx, scene, work):
    out = work / "gl_shafts.exr"
    proc, _ = run([ctx.build / "gl_shafts" / "gl_shafts", scene.path, "-o", out, "-q"])
    if proc.returncode != 0:
        raise Skip(first_error(proc))
    proc, _ = run([ctx.build / "gl_shafts" / "gl_shafts_bench", "--ref-spp", 0,
                   "--frames", ctx.frames, scene.path])
    if proc.returncode != 0:
        raise Skip(first_error(proc))
    rows = [l for l in proc.stdout.splitlines() if l.startswith("|")]
    head = [c.strip() for c in rows[0].strip("|").split("|")]
    cells = [c.strip() for c in rows[2].strip("|").split("|")]
    col = next(i for i, h in enumerate(head) if h.startswith("ms/frame"))
    best = float(cells[col].split()[0])
    return out, best / 1000.0, "defaults, best of %d warm frames" % ctx.frames


def _export(ctx, scene, target, out):
    proc, _ = run([ctx.build / "scene_export" / "scene_export", scene.path, "--to", target,
                   "-o", out, "-p"])
    if proc.returncode != 0:
        raise Skip("scene_export: %s" % first_error(proc))


def r_pov(ctx, scene, work):
    if not shutil.which("povray"):
        raise Skip("povray is not installed")
    pov = work / "pov" / "scene.pov"
    _export(ctx, scene, "pov", pov)
    proc, secs = run(["povray", "scene.ini"], cwd=pov.parent)
    # An atmosphere with Mie comes in two frames whose sum is the image.
    out = pov_frames(pov.parent) if proc.returncode == 0 else None
    if out is None:
        raise Skip("povray: %s" % first_error(proc))
    return out, secs, "scene_export draft"


def r_cycles(ctx, scene, work):
    if not shutil.which("blender"):
        raise Skip("blender is not installed")
    py = work / "cycles" / "scene.py"
    _export(ctx, scene, "blender", py)
    out = py.parent / "out.exr"
    proc, secs = run(["blender", "-b", "-P", py, "--", "--engine", "cycles", "--out", out,
                      "--samples", ctx.cycles_samples, "--seed", 1], cwd=py.parent)
    if proc.returncode != 0 or not out.exists():
        raise Skip("blender: %s" % first_error(proc))
    return out, secs, "%d samples (wall, with start-up)" % ctx.cycles_samples


def _sub(a, b):
    return [x - y for x, y in zip(a, b)]


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def _unit(a):
    n = math.sqrt(_dot(a, a))
    return [x / n for x in a]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def blender_sky_view(data):
    """The Nishita view of a scene: (view dict, irradiance) or Skip."""
    m = data.get("medium", {})
    if m.get("type") != "atmosphere":
        raise Skip("the scene has no atmosphere")
    suns = [l for l in data.get("lights", []) if l.get("type") == "directional"]
    if len(suns) != 1:
        raise Skip("Blender's sky has one sun; the scene has %d directional lights"
                   % len(suns))
    cam = data["camera"]
    centre, rg = m["center"], float(m["ground_radius"])
    up = _unit(_sub(cam["position"], centre))
    altitude_m = (math.sqrt(_dot(_sub(cam["position"], centre),
                                 _sub(cam["position"], centre))) - rg) * 6360e3 / rg
    if altitude_m > 60000.0:
        raise Skip("Blender's sky texture renders from at most 60 km above the ground; "
                   "the eye is %.0f km up" % (altitude_m / 1e3))
    sun_from = _unit([-c for c in suns[0]["direction"]])
    elevation = math.degrees(math.asin(max(-1.0, min(1.0, _dot(sun_from, up)))))
    h = _sub(sun_from, [_dot(sun_from, up) * u for u in up])
    y_b = _unit(h) if _dot(h, h) > 1e-12 else _unit(_cross(up, [1.0, 0.0, 0.0]))
    x_b = _cross(y_b, up)
    look = _unit(_sub(cam["look_at"], cam["position"]))
    view = {"name": "sky", "elevation_deg": elevation,
            "dir": [_dot(look, x_b), _dot(look, y_b), _dot(look, up)],
            "fov_deg": cam["fov_y_deg"], "width": cam["width"], "height": cam["height"],
            "samples": 1, "altitude_m": max(0.0, altitude_m)}
    # Blender's disk only where the scene's sun has one, of the same size.
    diameter = float(suns[0].get("angular_diameter_deg", 0.0))
    view["sun_disc"] = diameter > 0
    if diameter > 0:
        view["sun_size_deg"] = diameter
    return view, suns[0]["irradiance"]


def r_blender_sky(ctx, scene, work):
    if not shutil.which("blender"):
        raise Skip("blender is not installed")
    view, irradiance = blender_sky_view(scene.data)
    cal = nishita.blender_views([], False)[0]
    res = nishita.run_blender([cal, view], work / "blender_sky")
    own = [v * nishita.blender_solid_angle(nishita.SUN_SIZE_DEG)
           for v in res["views"]["calibration"]["rgb"]]
    gain = [e / o for e, o in zip(irradiance, own)]
    out = work / "blender_sky.exr"
    subprocess.run(["oiiotool", str(work / "blender_sky" / "sky.exr"), "--ch", "R,G,B",
                    "--mulc", ",".join(repr(g) for g in gain), "-o", str(out)],
                   check=True, capture_output=True)
    return out, res["views"]["sky"]["seconds"], \
        "Nishita texture, sun %.1f deg, 1 sample (render call, with its precomputation)" \
        % view["elevation_deg"]


RENDERERS = {"gl_shafts": r_gl_shafts, "reference": r_reference,
             "blender_sky": r_blender_sky, "pov": r_pov, "cycles": r_cycles}


# --- the run -----------------------------------------------------------------


def bench_scene(ctx, name):
    src = Path(name) if name.endswith(".json") else ROOT / "scenes" / (name + ".json")
    name = src.stem
    if not src.exists():
        print("bench_sky: %s: skipped: %s is not in this tree yet" % (name, src))
        return None
    data = json.loads(src.read_text())
    scene = prepare_file(src, ctx.out / "scenes", ctx.width / float(data["camera"]["width"]))
    if scene.height != ctx.height:
        print("bench_sky: %s: the scene's aspect gives %dx%d" % (name, scene.width,
                                                                scene.height))
    work = ctx.out / name
    work.mkdir(parents=True, exist_ok=True)
    try:
        ref = truth(ctx, scene)
    except Skip as e:
        print("bench_sky: %s: skipped: %s" % (name, e))
        return None
    rows = []
    for r in ctx.renderers:
        try:
            img, secs, setting = RENDERERS[r](ctx, scene, work)
            err = compare(ctx.build / "validation" / "shafts_compare", ref, img)["rel_rms"]
            rows.append((r, setting, secs, err))
        except (Skip, CompareFailed) as e:
            rows.append((r, "skipped: %s" % e, None, None))
    return name, scene, rows


def table(name, scene, rows):
    base = next((r for r in rows if r[0] == "gl_shafts" and r[2]), None) or \
        next((r for r in rows if r[0] == "reference" and r[2]), None)
    out = ["%s at %dx%d (ratios over %s)" % (name, scene.width, scene.height,
                                             base[0] if base else "nothing"),
           "", "| renderer | setting | time (s) | time ratio | error (rel. RMS) | error ratio |",
           "|---|---|---|---|---|---|"]
    for r, setting, secs, err in rows:
        if secs is None:
            out.append("| %s | %s | | | | |" % (r, setting))
            continue
        tr = "%.3g" % (secs / base[2]) if base else ""
        er = "%.3g" % (err / base[3]) if base and base[3] else ""
        out.append("| %s | %s | %.4g | %s | %.3g%% | %s |" % (r, setting, secs, tr,
                                                            100 * err, er))
    return "\n".join(out) + "\n"


def parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build-dir", default=str(ROOT / "build"))
    ap.add_argument("--out", default="/tmp/shafts-bench-sky")
    ap.add_argument("--scenes", default="sky_sunset,earth_from_space")
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=480)
    ap.add_argument("--ref-spp", type=int, default=256)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--frames", type=int, default=5)
    ap.add_argument("--cycles-samples", type=int, default=64)
    ap.add_argument("--renderers", default=",".join(ALL))
    ap.add_argument("--markdown")
    args = ap.parse_args(argv)
    args.renderers = [r for r in args.renderers.split(",") if r]
    bad = [r for r in args.renderers if r not in RENDERERS]
    if bad:
        ap.error("unknown renderer '%s'; expected one of: %s" % (bad[0], ", ".join(ALL)))
    args.build, args.out = Path(args.build_dir), Path(args.out)
    return args


def main(argv=None):
    ctx = parse(argv)
    ctx.out.mkdir(parents=True, exist_ok=True)
    text = []
    for name in [s for s in ctx.scenes.split(",") if s]:
        got = bench_scene(ctx, name)
        if got:
            text.append(table(*got))
    report = "\n".join(text) or "bench_sky: no scene could be benchmarked\n"
    print(report)
    if ctx.markdown:
        Path(ctx.markdown).write_text(report)
    return 0


if __name__ == "__main__":
    sys.exit(main())
