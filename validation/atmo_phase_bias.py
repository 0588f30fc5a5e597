"""What the phases Cycles is given cost an atmosphere scene per pixel,
measured without Cycles: the reference renders the scene's parts apart,
and the exported lobes' error is applied to them.

  python3 -m validation.atmo_phase_bias [--build-dir DIR] [--scene FILE]
      [--width W] [--height H] [--spp N] [--work DIR] [--rayleigh-g G]

Under a directional sun the phase angle is the same at every point of a
camera ray, so in the reference's single scattering a pixel's radiance is
L = S_R p_R(mu) + S_M p_M(mu) + G (Rayleigh's and Mie's in-scattering,
the ground), mu the cosine between the sun's light and the way back to the
eye. A phase p' in place of p makes the pixel L + S p (p'/p - 1): exactly,
not to first order. The reference renders three variants of the scene
(the same extinction in all three): (a) the scene; (f) Mie's scattering
turned into absorption, so L_f = S_R p_R + G; (g) that with a black
ground, L_g = S_R p_R. Rayleigh's part is L_g and Mie's L_a - L_f; the
lobes are those of the Blender export's data (scene_export --to blender,
the atmosphere's `scatter` slices: part 0 Rayleigh, part 1 Mie, weight
to - from). Printed: the relative RMS over the lit pixels (the
reference's luminance above 1% of its largest, as shafts_compare's lit
region) of the luminance's change from Rayleigh's lobes, from Mie's,
and from both, and the ratio of the sums, over the whole image and over its top
third (the peers' sky rows). This is the bias the phases put into Cycles'
image; Cycles' noise and any bias of its own come on top. --rayleigh-g
judges another equal pair +-G for Rayleigh; --work keeps the renders, and
a second run there with the same scene and settings reuses them. The
figures of docs/scene_export.md, "What the phases cost the image", come
from this script.
"""

import argparse
import json
import math
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from .scenes import pixel_direction

ROOT = Path(__file__).resolve().parent.parent
LUMA = (0.2126, 0.7152, 0.0722)


def hg(g, mu):
    """The normalised Henyey-Greenstein phase."""
    d = 1.0 + g * g - 2.0 * g * mu
    return (1.0 - g * g) / (4.0 * math.pi * d * math.sqrt(d))


def rayleigh(mu):
    return 3.0 / (16.0 * math.pi) * (1.0 + mu * mu)


def cornette_shanks(g, mu):
    return (3.0 / (8.0 * math.pi) * (1.0 - g * g) / (2.0 + g * g) * (1.0 + mu * mu)
            / (1.0 + g * g - 2.0 * g * mu) ** 1.5)


def read_pixels(path):
    """{(x, y): (r, g, b)} of an image, through `oiiotool --dumpdata`."""
    out = subprocess.run(["oiiotool", "--dumpdata", str(path)], check=True,
                         stdout=subprocess.PIPE, text=True).stdout
    pixels = {}
    for m in re.finditer(r"Pixel \((\d+), (\d+)\): (\S+) (\S+) (\S+)", out):
        pixels[(int(m.group(1)), int(m.group(2)))] = tuple(float(v) for v in m.group(3, 4, 5))
    return pixels


def pixel_mu(camera, light_dir, w, h):
    """The cosine of the phase angle at each pixel's centre: between the
    light's direction of travel and the way back to the eye."""
    n = math.sqrt(sum(c * c for c in light_dir))
    ldir = [c / n for c in light_dir]
    mu = {}
    for y in range(h):
        for x in range(w):
            d = pixel_direction(camera, x + 0.5, y + 0.5, w, h)
            mu[(x, y)] = -sum(a * b for a, b in zip(ldir, d))
    return mu


def lobes(exporter, scene, work):
    """{part: [(g, weight)]} of the Blender export's atmosphere."""
    out = work / "export.py"
    subprocess.run([str(exporter), str(scene), "--to", "blender", "-o", str(out)], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    data = json.loads((work / "export.blender.json").read_text())
    parts = {}
    for s in data["medium"]["atmosphere"]["scatter"]:
        parts.setdefault(s["part"], []).append((s["anisotropy"], s["to"] - s["from"]))
    return parts


def render(tracer, data, name, work, args):
    """Renders a variant into work (kept there: a second run in the same
    --work with the same scene and settings reads the image again)."""
    path, img = work / (name + ".json"), work / (name + ".exr")
    text = json.dumps({"scene": data, "size": [args.width, args.height], "spp": args.spp})
    if img.exists() and path.exists() and path.read_text() == text:
        return read_pixels(img)
    scene = work / (name + ".scene.json")
    scene.write_text(json.dumps(data))
    subprocess.run(["nice", "-n", "10", str(tracer), str(scene), "-o", str(img), "-q",
                    "--width", str(args.width), "--height", str(args.height),
                    "--spp", str(args.spp)], check=True)
    path.write_text(text)
    return read_pixels(img)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build-dir", default=str(ROOT / "build"))
    ap.add_argument("--scene", default=str(ROOT / "scenes" / "sky_sunset.json"))
    ap.add_argument("--width", type=int, default=40)
    ap.add_argument("--height", type=int, default=30)
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--work", help="keep the renders here (default: a temporary directory)")
    ap.add_argument("--rayleigh-g", type=float,
                    help="judge the equal pair +-G for Rayleigh instead of the export's")
    args = ap.parse_args(argv)
    build = Path(args.build_dir)
    scene = json.loads(Path(args.scene).read_text())
    medium = scene["medium"]
    if medium.get("type") != "atmosphere" or len(scene.get("lights", [])) != 1 \
            or scene["lights"][0]["type"] != "directional":
        sys.exit("atmo_phase_bias: needs an atmosphere and one directional light")
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(args.work or tmp)
        work.mkdir(parents=True, exist_ok=True)
        parts = lobes(build / "scene_export" / "scene_export", Path(args.scene), work)
        if args.rayleigh_g is not None:
            parts[0] = [(args.rayleigh_g, 0.5), (-args.rayleigh_g, 0.5)]
        mie = medium.get("mie")
        variant_f = json.loads(json.dumps(scene))
        if mie:
            m = variant_f["medium"]["mie"]
            m["sigma_a"] = [a + s for a, s in zip(m.get("sigma_a", [0, 0, 0]), m["sigma_s"])]
            m["sigma_s"] = [0.0, 0.0, 0.0]
        variant_g = json.loads(json.dumps(variant_f))
        variant_g["medium"]["ground_albedo"] = [0.0, 0.0, 0.0]
        tracer = build / "lmm_tracer" / "lmm_tracer"
        la = render(tracer, scene, "a", work, args)
        lf = render(tracer, variant_f, "f", work, args) if mie else la
        lg = render(tracer, variant_g, "g", work, args)
    print("Rayleigh's lobes (g, weight): %s; Mie's: %s" % (
        ", ".join("(%.6g, %.6g)" % l for l in parts.get(0, [])),
        ", ".join("(%.6g, %.6g)" % l for l in parts.get(1, []))))
    mu = pixel_mu(scene["camera"], scene["lights"][0]["direction"], args.width, args.height)
    mie_phase = (mie or {}).get("phase", {"type": "isotropic"})

    def mie_p(c):
        t = mie_phase["type"]
        if t == "cornette_shanks":
            return cornette_shanks(mie_phase["g"], c)
        if t == "henyey_greenstein":
            return hg(mie_phase["g"], c)
        if t == "isotropic":
            return 1.0 / (4.0 * math.pi)
        sys.exit("atmo_phase_bias: Mie phase %s not handled" % t)

    def mix(part, c):
        return sum(w * hg(g, c) for g, w in parts.get(part, []))

    lum = {k: sum(LUMA[i] * v[i] for i in range(3)) for k, v in la.items()}
    lit = max(lum.values()) * 0.01
    top = args.height / 3.0
    print("| change from | region | relative RMS | ratio of sums |")
    print("|---|---|---|---|")
    for what in ("Rayleigh's lobes", "Mie's lobes", "both"):
        for region in ("lit", "top third"):
            sq = n = 0
            s_ref = s_new = 0.0
            for k, c in mu.items():
                if lum[k] <= lit or (region == "top third" and k[1] >= top):
                    continue
                er = mix(0, c) / rayleigh(c) - 1.0
                em = mix(1, c) / mie_p(c) - 1.0 if mie else 0.0
                d = ref = 0.0
                for i in range(3):
                    ray, mpart = lg[k][i], la[k][i] - lf[k][i]
                    d += LUMA[i] * ((ray * er if what != "Mie's lobes" else 0.0) +
                                    (mpart * em if what != "Rayleigh's lobes" else 0.0))
                    ref += LUMA[i] * la[k][i]
                sq += (d / ref) ** 2
                n += 1
                s_ref += ref
                s_new += ref + d
            print("| %s | %s | %.4f | %.4f |" % (what, region, math.sqrt(sq / max(n, 1)),
                                                   s_new / s_ref))


if __name__ == "__main__":
    main()
