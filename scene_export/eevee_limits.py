#!/usr/bin/env python3
"""EEVEE's own limits, measured: what remains once the export is right.

  python3 -m scene_export.eevee_limits [--build BUILD] [--work DIR] [--quick]
      [--exporter SCENE_EXPORT] [--part limits|surfaces|all]

(from the source directory, /usr/bin/python3 or any Python with the
validation package's needs.)

Renders test scenes with lmm_tracer (reference, 1024 in-scattering
samples) and with EEVEE through `scene_export --to blender` at the export's
final settings (TAA 64, 256 slices, 2 px tiles, 32 shadow samples) and at
variants of one setting each (validation/blender_eevee.py sets them), and
prints per rendering:

- mean_rel, scale and rel_rms over the lit region (validation/shafts_compare);
- the lit pixels split into "edge" pixels, which a one-pixel blur of the
  reference (the mean of the 3x3 neighbourhood) changes by more than
  EDGE_CHANGE (a light's peak, a cone's or a shadow's edge: where EEVEE's
  froxels blur), and "smooth" pixels: the
  smooth pixels' scale (sum of EEVEE / sum of reference) is EEVEE's uniform
  deficit, and the edge pixels' share of the summed relative error is what
  the froxel blur costs;
- for each reference, the luminance loss of one pass through an R11G11B10F
  texture (EEVEE 3.4 keeps the froxels' scattering and extinction, and the
  scattered light, in GPU_R11F_G11F_B10F: 6-bit mantissas for red and
  green, 5 for blue), modelled as Mesa's truncating conversion of every
  pixel (util/format_r11g11b10f.h, f32_to_uf11: mantissa >> 17).

The second part (--part surfaces) measures the light-side transmittance
on surfaces (issue 14, finding 3) on the two scenes the issue quotes:
the canonical teapot_spot (80x60) and the hard cases' base scene (64x48),
each rendered by EEVEE at the final settings with the export as it is and
with the surfaces' transmittance taken out (the exported script's one
`transmittance_setup` call replaced by None: the export before that fix,
all else equal), and the base scene also at the validation's settings
(the hard cases' and sweeps' points, validation/renderers.py). It prints
mean_rel, scale and rel_rms over the lit region and, where a light is in
view, the same away from the lights (validation.scenes.light_mask: a
square of 5% of the image height blacked out in both images).

--quick renders only the final settings (no variants). --exporter renders
another build's export (an older commit's, for the figures before a
change); the data of exports before issue 14 has no EEVEE notes. Takes about 10 min
on 2 busy cores (EEVEE at TAA 64 runs 1-2 min a rendering on llvmpipe).
docs/scene_export.md (EEVEE) quotes its output.
"""
import json
import os
import shutil
import struct
import subprocess
import sys

from scene_export import eevee_test
from validation.hard.cases import base_scene
from validation.metrics import mask_image
from validation.scenes import light_mask, localise

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(HERE)
OVERRIDE = os.path.join(SOURCE, "validation", "blender_eevee.py")
EDGE_CHANGE = 0.02
LUMA = (0.2126, 0.7152, 0.0722)

FINAL = {"taa_render_samples": 64}
VARIANTS = [
    ("final (TAA 64, tile 2)", {}),
    ("TAA 16", {"taa_render_samples": 16}),
    ("tile 4", {"volumetric_tile_size": "4"}),
    ("tile 8", {"volumetric_tile_size": "8"}),
    ("128 shadow samples", {"volumetric_shadow_samples": 128}),
]
SCENES = [("eevee_point_hg", True), ("eevee_spot", False), ("eevee_gobo", False),
          ("sun_window", False)]
# The surface part: (label, export as it is or without the surfaces'
# transmittance, EEVEE settings over FINAL). The validation's points are
# validation/renderers.py's Eevee sweep and hard-case settings.
SURFACE_SETTINGS = [
    ("final", True, {}),
    ("final, no surface transmittance", False, {}),
]
VALIDATION_SETTINGS = [
    ("tile 8, 32 slices, 16 shadow samples, TAA 1", True,
     {"volumetric_tile_size": "8", "volumetric_samples": 32,
      "volumetric_shadow_samples": 16, "taa_render_samples": 1}),
    ("tile 2, 128 slices, 64 shadow samples, TAA 8", True,
     {"volumetric_tile_size": "2", "volumetric_samples": 128,
      "volumetric_shadow_samples": 64, "taa_render_samples": 8}),
    ("TAA 16 (the peers' and the draft setting)", True, {"taa_render_samples": 16}),
]
TRANSMITTANCE_CALL = "transmittance = transmittance_setup(data, engine)"


def luminance(path):
    """(width, height, luminance rows, RGB rows) of an image, top row first,
    read through `oiiotool --dumpdata` (nine decimals)."""
    text = eevee_test.run(["oiiotool", "--dumpdata", path])
    lines = text.splitlines()
    w, h = (int(x) for x in lines[0].split(":")[1].split(",")[0].split("x"))
    rows = [[0.0] * (3 * w) for _ in range(h)]
    for line in lines[1:]:
        if "Pixel (" not in line:
            continue
        pos, values = line.split(":", 1)
        x, y = (int(v) for v in pos.split("(")[1].rstrip(")").split(","))
        rows[y][3 * x:3 * x + 3] = [float(v) for v in values.split()[:3]]
    return w, h, [[sum(LUMA[c] * r[3 * i + c] for c in range(3)) for i in range(w)]
                  for r in rows], rows


def truncate(x, bits):
    """x rounded toward zero to `bits` mantissa bits (float32 in between)."""
    if x <= 0:
        return 0.0
    u = struct.unpack("<I", struct.pack("<f", x))[0]
    return struct.unpack("<f", struct.pack("<I", u & ~((1 << (23 - bits)) - 1)))[0]


def split(ref_y, img_y, w, h):
    """Smooth and edge statistics over the lit region."""
    peak = max(max(r) for r in ref_y)
    stats = {"smooth": [0, 0.0, 0.0, 0.0], "edge": [0, 0.0, 0.0, 0.0]}
    for j in range(h):
        for i in range(w):
            ry = ref_y[j][i]
            if ry <= 0.01 * peak:
                continue
            near = [ref_y[y][x] for y in range(max(j - 1, 0), min(j + 2, h))
                    for x in range(max(i - 1, 0), min(i + 2, w))]
            blurred = sum(near) / len(near)
            kind = "edge" if abs(blurred - ry) > EDGE_CHANGE * ry else "smooth"
            s = stats[kind]
            s[0] += 1
            s[1] += abs(img_y[j][i] - ry) / ry
            s[2] += img_y[j][i]
            s[3] += ry
    return stats


def r11g11b10_loss(rows, w, h, ref_y):
    peak = max(max(r) for r in ref_y)
    before = after = 0.0
    bits = (6, 6, 5)
    for j in range(h):
        for i in range(w):
            if ref_y[j][i] <= 0.01 * peak:
                continue
            for c in range(3):
                v = rows[j][3 * i + c]
                before += LUMA[c] * v
                after += LUMA[c] * truncate(v, bits[c])
    return 1.0 - after / before


def render_eevee(script, img, settings):
    """Renders the exported script with EEVEE at FINAL plus `settings`;
    returns the wall time in seconds (raises eevee_test.Failed)."""
    env = dict(os.environ, SHAFTS_EEVEE_SETTINGS=json.dumps(dict(FINAL, **settings)))
    p = subprocess.run(["/usr/bin/time", "-f", "%e", "xvfb-run", "-a", "-s",
                        "-screen 0 640x480x24", "blender", "-b", "-P", OVERRIDE,
                        "-P", script, "--", "--engine", "eevee", "--out", img],
                       env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    if p.returncode != 0:
        raise eevee_test.Failed("EEVEE failed on %s:\n%s" % (script, p.stdout.decode()[-2000:]))
    return float(p.stderr.decode().strip().splitlines()[-1])


def without_surface_transmittance(script, out_dir):
    """A copy of an exported script's directory whose script gives the
    surfaces no light-side transmittance (the export before issue 14's
    finding 3); returns the copy's script."""
    shutil.rmtree(out_dir, ignore_errors=True)
    shutil.copytree(os.path.dirname(script), out_dir)
    out = os.path.join(out_dir, os.path.basename(script))
    with open(out, encoding="utf-8") as f:
        text = f.read()
    if text.count(TRANSMITTANCE_CALL) != 1:
        raise eevee_test.Failed("%s: the transmittance call is not there once" % script)
    with open(out, "w", encoding="utf-8") as f:
        f.write(text.replace(TRANSMITTANCE_CALL, "transmittance = None"))
    return out


def surfaces(build, work, compare, exporter):
    """The surface part (see the module's comment)."""
    print("| scene | export and setting | mean_rel | scale | rel_rms "
          "| away from the lights: mean_rel, scale, rel_rms | s |")
    print("|---|---|---|---|---|---|---|")
    with open(os.path.join(SOURCE, "scenes", "teapot_spot.json"), encoding="utf-8") as f:
        teapot = json.load(f)
    teapot["camera"].update(width=80, height=60)
    cases = [("teapot_spot", teapot, SURFACE_SETTINGS),
             ("hard base", base_scene(64, 48), SURFACE_SETTINGS + VALIDATION_SETTINGS)]
    for name, data, settings in cases:
        d = os.path.join(work, name.replace(" ", "_"))
        shutil.rmtree(d, ignore_errors=True)
        os.makedirs(d)
        # The scene's files (the teapot's mesh) linked beside its copy.
        data = localise(data, os.path.join(SOURCE, "scenes"), d)
        scene = eevee_test.write_scene(os.path.join(d, "scene.json"), data)
        ref = os.path.join(d, "reference.exr")
        eevee_test.run([os.path.join(build, "lmm_tracer", "lmm_tracer"), scene, "-o", ref,
                        "--mode", "reference", "--spp", "1024", "--quiet"])
        script = os.path.join(d, "export", "scene.py")
        eevee_test.export(build, scene, script, exporter)
        plain = without_surface_transmittance(script, os.path.join(d, "export_plain"))
        rects = light_mask(data)
        ref_masked = mask_image(ref, rects, os.path.join(d, "reference_masked.exr"))
        for k, (label, transmittance, extra) in enumerate(settings):
            img = os.path.join(d, "eevee_%d.exr" % k)
            seconds = render_eevee(script if transmittance else plain, img, extra)
            r = json.loads(eevee_test.run([compare, ref, img, "--json"]))
            away = "(no light in view)"
            if rects:
                m = json.loads(eevee_test.run([compare, ref_masked, mask_image(
                    img, rects, os.path.join(d, "eevee_%d_masked.exr" % k)), "--json"]))
                away = "%.2f%%, %.4f, %.1f%%" % (100 * m["mean_rel"], m["scale"],
                                                 100 * m["rel_rms"])
            print("| %s | %s | %.2f%% | %.4f | %.1f%% | %s | %.0f |"
                  % (name, label, 100 * r["mean_rel"], r["scale"], 100 * r["rel_rms"],
                     away, seconds))
            sys.stdout.flush()


def main(argv):
    build = os.path.join(SOURCE, "build")
    work = None
    quick = False
    exporter = None
    part = "all"
    i = 0
    while i < len(argv):
        if argv[i] == "--build" and i + 1 < len(argv):
            build, i = argv[i + 1], i + 2
        elif argv[i] == "--work" and i + 1 < len(argv):
            work, i = argv[i + 1], i + 2
        elif argv[i] == "--exporter" and i + 1 < len(argv):
            exporter, i = os.path.abspath(argv[i + 1]), i + 2
        elif argv[i] == "--part" and i + 1 < len(argv) \
                and argv[i + 1] in ("limits", "surfaces", "all"):
            part, i = argv[i + 1], i + 2
        elif argv[i] == "--quick":
            quick, i = True, i + 1
        else:
            print(__doc__.split("\n\n")[1], file=sys.stderr)
            return 2
    build = os.path.abspath(build)
    work = os.path.abspath(work or os.path.join(build, "scene_export", "eevee_limits"))
    os.makedirs(work, exist_ok=True)
    compare = os.path.join(build, "validation", "shafts_compare")
    if part in ("surfaces", "all"):
        surfaces(build, os.path.join(work, "surfaces"), compare, exporter)
        print()
    if part == "surfaces":
        return 0
    print("| scene | setting | mean_rel | scale | rel_rms | smooth px | smooth scale "
          "| smooth mean_rel | edge px | edge mean_rel | edge share of error | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    models = []
    for name, sweep in SCENES:
        d = os.path.join(work, name)
        os.makedirs(d, exist_ok=True)
        scene = os.path.join(eevee_test.TESTDATA, name + ".json")
        ref = os.path.join(d, "reference.exr")
        eevee_test.run([os.path.join(build, "lmm_tracer", "lmm_tracer"), scene, "-o", ref,
                        "--mode", "reference", "--spp", "1024", "--quiet"])
        script = os.path.join(d, "export", "scene.py")
        eevee_test.export(build, scene, script, exporter)
        w, h, ref_y, ref_rows = luminance(ref)
        models.append((name, r11g11b10_loss(ref_rows, w, h, ref_y)))
        for label, settings in (VARIANTS if sweep and not quick else VARIANTS[:1]):
            img = os.path.join(d, "eevee_%s.exr" % label.split(" (")[0].replace(" ", "_"))
            seconds = render_eevee(script, img, settings)
            r = json.loads(eevee_test.run([compare, ref, img, "--json"]))
            _, _, img_y, _ = luminance(img)
            st = split(ref_y, img_y, w, h)
            sm, ed = st["smooth"], st["edge"]
            total = sm[1] + ed[1]
            print("| %s | %s | %.2f%% | %.4f | %.1f%% | %d | %.4f | %.2f%% | %d | %.1f%% | %.0f%% | %.0f |"
                  % (name, label, 100 * r["mean_rel"], r["scale"], 100 * r["rel_rms"],
                     sm[0], sm[2] / sm[3] if sm[3] else 0, 100 * sm[1] / max(sm[0], 1),
                     ed[0], 100 * ed[1] / max(ed[0], 1), 100 * ed[1] / total if total else 0,
                     seconds))
            sys.stdout.flush()
    print()
    print("R11G11B10F, one truncating pass over the reference's lit pixels "
          "(luminance lost):")
    for name, loss in models:
        print("  %s: %.2f%%" % (name, 100 * loss))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
