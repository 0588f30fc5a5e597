"""Our sky against Blender's Nishita sky texture (issue 12, part 4): prints
and writes the tables and figures of docs/sky.md.

  python3 -m validation.nishita --build-dir build [--out DIR]
      [--elevations 2,5,10,20,40,60] [--spp 4096] [--figure-spp 64]
      [--figures docs/img/sky] [--markdown FILE] [--json FILE] [--no-figures]

Blender 3.4's Sky Texture of type NISHITA (altitude 0, air, dust and ozone
at their defaults of 1, sun size 0.545 degrees) is rendered by Cycles
(validation/nishita_blender.py, `blender -b --factory-startup`) and our
reference (lmm_tracer --mode reference) renders the same sky: a scene in
kilometres with an `atmosphere` medium (R_g 6360, R_t 6420, the camera 1 m
above the ground) lit by a directional light with a 0.545 degree disk, in
two sets of constants:

- `bruneton`: the contract's reference values (Bruneton 2017, per km:
  Rayleigh [5.802, 13.558, 33.1]e-3 with H_R 8, Mie 3.996e-3 scattering and
  0.444e-3 absorption with H_M 1.2 and Cornette-Shanks g 0.8, ozone
  [0.650, 1.881, 0.085]e-3 in a 30 km tent around 25 km);
- `blender_rgb`: Blender's own constants (intern/sky/source/sky_nishita.cpp
  of Blender 3.4) taken at the three wavelengths Bruneton's RGB stands for
  (680, 550 and 440 nm): Rayleigh and ozone from its spectral tables, Mie
  2e-5 per metre with extinction 1.11 times it, H_M 1.2 km, Cornette-Shanks
  g 0.76. The difference between the two sets is the constants'; what is
  left between `blender_rgb` and Blender is its spectral model (21
  wavelengths through the CIE 1931 functions to XYZ, then to linear
  Rec.709), its quadrature and its texture's interpolation.

Units: Blender's sky is the spectral radiance (W m^-2 sr^-1 nm^-1, its
solar table) integrated against the CIE functions and turned into RGB,
without the photometric 683. Our sun's irradiance is the same quantity for
Blender's sun: measured from Blender's own disk with air, dust and ozone at
0 (radiance times its solid angle, the latter computed in single precision
as Blender does), so exposure and units cancel and the ratios below are
the models' alone.

Probes (one ray each, the middle pixel of a 5x5 image 1 degree wide, in
both renderers): the zenith; 5 degrees above the sun; the horizon (1 degree
up) towards the sun, at 90 degrees from it and opposite it; the sun's
centre (Blender's disk carries limb darkening, 1 at the centre). Each
probe's ratio ours / Blender per channel.

Where the build's lmm_tracer refuses the atmosphere (before issue 12's
atmosphere lands in the reference), our side is skipped with its message.
"""

import argparse
import json
import math
import shutil
import struct
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BLENDER_SCRIPT = ROOT / "validation" / "nishita_blender.py"
ELEVATIONS = [2, 5, 10, 20, 40, 60]
SUN_SIZE_DEG = 0.545  # Blender's default sun_size
EYE_HEIGHT_KM = 0.001

# (name, elevation, azimuth from the sun's) of each probe; "sun+5" and
# "sun" follow the sun's elevation.
PROBES = [("zenith", 90.0, 0.0), ("near_sun", "sun+5", 0.0),
          ("horizon_sun", 1.0, 0.0), ("horizon_side", 1.0, 90.0),
          ("horizon_anti", 1.0, 180.0), ("sun", "sun", 0.0)]

# The figures: a view towards the sun, pitched up 20 degrees, 60 high.
FIGURE = {"pitch": 20.0, "fov": 60.0, "width": 192, "height": 96}
FIGURE_ELEVATIONS = [2, 10, 40]

BRUNETON = {
    "rayleigh": {"sigma_s": [5.802e-3, 13.558e-3, 33.1e-3], "scale_height": 8.0},
    "mie": {"sigma_s": [3.996e-3] * 3, "sigma_a": [0.444e-3] * 3, "scale_height": 1.2,
            "phase": {"type": "cornette_shanks", "g": 0.8}},
    "ozone": {"sigma_a": [0.650e-3, 1.881e-3, 0.085e-3], "center_height": 25.0,
              "width": 30.0},
}

# Blender 3.4, intern/sky/source/sky_nishita.cpp: its tables' values (per
# metre) at 680 nm and 440 nm, and at 540 and 560 nm, whose geometric
# (Rayleigh) and arithmetic (ozone) means stand for 550 nm.
_B_RAYLEIGH = {680: 5.29034598e-6, 540: 1.33028498e-5, 560: 1.15018478e-5,
               440: 3.01792901e-5}
_B_OZONE = {680: 7.3527551e-7, 540: 1.5479740e-6, 560: 2.0903865e-6,
            440: 7.3095688e-8}
_B_MIE = 2e-5  # scattering per metre; extinction 1.11 times it


def _blender_rgb():
    ray = [_B_RAYLEIGH[680], math.sqrt(_B_RAYLEIGH[540] * _B_RAYLEIGH[560]),
           _B_RAYLEIGH[440]]
    ozone = [_B_OZONE[680], 0.5 * (_B_OZONE[540] + _B_OZONE[560]), _B_OZONE[440]]
    km = 1e3
    return {
        "rayleigh": {"sigma_s": [v * km for v in ray], "scale_height": 8.0},
        "mie": {"sigma_s": [_B_MIE * km] * 3, "sigma_a": [0.11 * _B_MIE * km] * 3,
                "scale_height": 1.2, "phase": {"type": "cornette_shanks", "g": 0.76}},
        "ozone": {"sigma_a": [v * km for v in ozone], "center_height": 25.0,
                  "width": 30.0},
    }


CONSTANTS = {"bruneton": BRUNETON, "blender_rgb": _blender_rgb()}


def direction(elevation, azimuth):
    """Our frame (Y up, the sun towards -Z at azimuth 0): the unit vector at
    an elevation and an azimuth from the sun's, in degrees."""
    e, a = math.radians(elevation), math.radians(azimuth)
    return [math.sin(a) * math.cos(e), math.sin(e), -math.cos(a) * math.cos(e)]


def to_blender(d):
    """Our Y-up frame to Blender's Z-up one: the sun at Blender's +Y."""
    return [d[0], -d[2], d[1]]


def probe_direction(probe, sun_elevation):
    _, el, az = probe
    if el == "sun":
        el = sun_elevation
    elif el == "sun+5":
        el = sun_elevation + 5.0
    return direction(el, az)


def _f32(x):
    return struct.unpack("f", struct.pack("f", x))[0]


def blender_solid_angle(size_deg):
    """The sun's solid angle as Blender computes it, in single precision:
    2 pi (1 - cosf(size / 2)) (precompute_sun); 1 - cos loses about 5 of
    float's 7 digits for a 0.545 degree sun."""
    half = _f32(_f32(math.radians(size_deg)) / 2.0)
    return _f32(_f32(2.0 * math.pi) * _f32(1.0 - _f32(math.cos(half))))


def exact_solid_angle(size_deg):
    s = math.sin(math.radians(size_deg) / 4.0)
    return 4.0 * math.pi * s * s


def zenith_depths(constants):
    """Vertical optical depths from the ground to space (per channel):
    Rayleigh and Mie scattering sigma H (1 - exp(-60/H)), Mie's absorption
    likewise, ozone sigma_a w / 2 (the tent's area)."""
    def layer(sigma, h):
        return [s * h * (1.0 - math.exp(-60.0 / h)) for s in sigma]
    r, m, o = constants["rayleigh"], constants["mie"], constants["ozone"]
    return {"rayleigh": layer(r["sigma_s"], r["scale_height"]),
            "mie_scattering": layer(m["sigma_s"], m["scale_height"]),
            "mie_absorption": layer(m["sigma_a"], m["scale_height"]),
            "ozone": [s * o["width"] / 2.0 for s in o["sigma_a"]]}


def slant_density(elevation, scale_height, r_ground=6360.0, top=60.0, n=20000):
    """The integral of exp(-h / H) along the ray from the ground at an
    elevation (degrees) to `top` km up (Simpson's rule): the air mass of a
    layer times H."""
    s = math.sin(math.radians(elevation))
    t_end = -r_ground * s + math.sqrt((r_ground * s) ** 2 + top * (2 * r_ground + top))
    h = t_end / n
    acc = 0.0
    for i in range(n + 1):
        t = i * h
        alt = math.sqrt(r_ground * r_ground + t * t + 2 * r_ground * t * s) - r_ground
        acc += (1 if i in (0, n) else 4 if i % 2 else 2) * math.exp(-alt / scale_height)
    return acc * h / 3.0


def sun_mie_table(elevations=(2, 5, 10)):
    """The sun's Mie transmittance through each set's aerosols at low
    elevations, and Blender's over ours."""
    lines = ["| sun elevation | Mie transmittance, Bruneton 2017 | Blender 3.4 | Blender / ours |",
             "|---|---|---|---|"]
    for e in elevations:
        t = []
        for c in (BRUNETON, CONSTANTS["blender_rgb"]):
            m = c["mie"]
            t.append(math.exp(-(m["sigma_s"][0] + m["sigma_a"][0])
                              * slant_density(e, m["scale_height"])))
        lines.append("| %g | %.3f | %.3f | %.3f |" % (e, t[0], t[1], t[1] / t[0]))
    return "\n".join(lines) + "\n"


def _ray_length(elevation, r_ground=6360.0, top=60.0):
    s = math.sin(math.radians(elevation))
    return -r_ground * s + math.sqrt((r_ground * s) ** 2 + top * (2 * r_ground + top))


def midpoint_bias_table(elevations=(1.0, 90.0)):
    """Blender's view-ray quadrature (32 midpoint steps to the top of the
    atmosphere) adds a step's whole optical depth before it scatters at
    the step's middle, so each sample is dimmed by exp(-sigma_t d / 2) too
    much, d the step; near the ground, with Blender's constants in RGB,
    that factor's inverse is what ours / Blender would be if the first
    step gave all the light (an upper bound of the bias)."""
    c = CONSTANTS["blender_rgb"]
    sig = [r + ms + ma for r, ms, ma in zip(c["rayleigh"]["sigma_s"], c["mie"]["sigma_s"],
                                            c["mie"]["sigma_a"])]
    lines = ["| view elevation | step (km) | exp(sigma_t step / 2) at the ground, R / G / B |",
             "|---|---|---|"]
    for e in elevations:
        step = _ray_length(e) / 32.0
        lines.append("| %g | %.2f | %s |" % (e, step, " / ".join(
            "%.2f" % math.exp(v * step / 2.0) for v in sig)))
    return "\n".join(lines) + "\n"


def sun_ozone_table(elevations=(2, 5, 10, 20, 40, 60)):
    """Blender's sun disk leaves ozone out of its transmittance; ours keeps
    it. The ozone transmittance along the sun's path (Bruneton's ozone,
    Simpson's rule over the tent) is then what ours / Blender should be on
    the disk with Blender's constants."""
    o = CONSTANTS["blender_rgb"]["ozone"]
    lines = ["| sun elevation | ozone transmittance to the sun, R / G / B |", "|---|---|"]
    for e in elevations:
        s = math.sin(math.radians(e))
        t_end, n, acc = _ray_length(e), 20000, 0.0
        h = t_end / n
        for i in range(n + 1):
            t = i * h
            alt = math.sqrt(6360.0 ** 2 + t * t + 2 * 6360.0 * t * s) - 6360.0
            tent = max(0.0, 1.0 - abs(alt - o["center_height"]) / (o["width"] / 2.0))
            acc += (1 if i in (0, n) else 4 if i % 2 else 2) * tent
        area = acc * h / 3.0
        lines.append("| %g | %s |" % (e, " / ".join("%.3f" % math.exp(-a * area)
                                                      for a in o["sigma_a"])))
    return "\n".join(lines) + "\n"


def depth_table():
    lines = ["| vertical optical depth (R / G / B) | Bruneton 2017 | Blender 3.4 at 680/550/440 nm |",
             "|---|---|---|"]
    a, b = zenith_depths(BRUNETON), zenith_depths(CONSTANTS["blender_rgb"])
    for k in a:
        lines.append("| %s | %s | %s |" % (k.replace("_", " "),
                                           " / ".join("%.4f" % v for v in a[k]),
                                           " / ".join("%.4f" % v for v in b[k])))
    return "\n".join(lines) + "\n"


# --- Blender -------------------------------------------------------------


def blender_views(elevations, figures):
    views = [{"name": "calibration", "elevation_deg": 45.0,
              "dir": to_blender(direction(45.0, 0.0)), "fov_deg": 1.0,
              "width": 5, "height": 5, "air": 0.0, "dust": 0.0, "ozone": 0.0}]
    for e in elevations:
        for p in PROBES:
            views.append({"name": "e%g_%s" % (e, p[0]), "elevation_deg": e,
                          "dir": to_blender(probe_direction(p, e)), "fov_deg": 1.0,
                          "width": 5, "height": 5})
        if figures and e in FIGURE_ELEVATIONS:
            views.append({"name": "e%g_figure" % e, "elevation_deg": e,
                          "dir": to_blender(direction(FIGURE["pitch"], 0.0)),
                          "fov_deg": FIGURE["fov"], "width": FIGURE["width"],
                          "height": FIGURE["height"]})
    return views


def run_blender(views, out, blender="blender"):
    """Renders the views in one Blender process; returns its results."""
    out.mkdir(parents=True, exist_ok=True)
    job = out / "job.json"
    job.write_text(json.dumps({"out": str(out), "views": views}))
    cmd = ["nice", "-n", "10", blender, "-b", "--factory-startup", "-P",
           str(BLENDER_SCRIPT), "--", str(job)]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    results = out / "results.json"
    if proc.returncode != 0 or not results.exists():
        sys.stderr.write(proc.stdout[-2000:] + proc.stderr[-2000:])
        raise RuntimeError("blender failed (exit %d)" % proc.returncode)
    return json.loads(results.read_text())


# --- Ours ------------------------------------------------------------------


def sky_scene(sun_elevation, irradiance, constants, look, fov, width, height,
              spp, disk=True):
    """Our sky: the atmosphere in kilometres, the eye 1 m above the ground
    looking along `look`, the sun at `sun_elevation` (towards -Z)."""
    medium = {"type": "atmosphere", "center": [0.0, -6360.0, 0.0],
              "ground_radius": 6360.0, "top_radius": 6420.0}
    medium.update(json.loads(json.dumps(constants)))
    sun = direction(sun_elevation, 0.0)
    light = {"type": "directional", "direction": [-c for c in sun],
             "irradiance": list(irradiance)}
    if disk:
        light["angular_diameter_deg"] = SUN_SIZE_DEG
    up = [0.0, 1.0, 0.0] if abs(look[1]) < 0.999 else [0.0, 0.0, -1.0]
    eye = [0.0, EYE_HEIGHT_KM, 0.0]
    return {"format": "shafts-scene", "version": 1,
            "camera": {"position": eye, "look_at": [eye[i] + look[i] for i in range(3)],
                       "up": up, "fov_y_deg": fov, "width": width, "height": height},
            "medium": medium, "lights": [light], "render": {"spp": spp}}


def pixel(path, x, y):
    """The RGB of one pixel of an image, through oiiotool."""
    proc = subprocess.run(["oiiotool", str(path), "--cut", "1x1+%d+%d" % (x, y),
                           "--printstats"], capture_output=True, text=True, check=True)
    for line in proc.stdout.splitlines():
        if "Stats Avg:" in line:
            return [float(v) for v in line.split(":", 1)[1].split()[:3]]
    raise RuntimeError("oiiotool printed no statistics for %s" % path)


class Refused(Exception):
    """lmm_tracer refused the scene (its message)."""


def run_ours(build, scene, out, crop=None):
    """Renders a scene with the reference; returns the wall time."""
    path = out.with_suffix(".json")
    path.write_text(json.dumps(scene))
    cmd = ["nice", "-n", "10", str(build / "lmm_tracer" / "lmm_tracer"), str(path),
           "-o", str(out), "-q", "--mode", "reference"]
    if crop:
        cmd += ["--crop"] + [str(c) for c in crop]
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    seconds = time.perf_counter() - t0
    if proc.returncode != 0:
        raise Refused(proc.stderr.strip())
    return seconds


# --- Report -----------------------------------------------------------------


def ratios(ours, theirs):
    return [o / t if t > 0 else float("nan") for o, t in zip(ours, theirs)]


def _fmt(r):
    return " / ".join("%.2f" % v for v in r)


def markdown(res):
    lines = ["| sun elevation | probe | Blender RGB | ours / Blender (Bruneton 2017) |"
             " ours / Blender (Blender's constants in RGB) |",
             "|---|---|---|---|---|"]
    for e in res["elevations"]:
        for p in PROBES:
            key = "e%g_%s" % (e, p[0])
            b = res["blender"][key]
            cells = []
            for c in CONSTANTS:
                o = res["ours"].get(c, {}).get(key)
                cells.append(_fmt(ratios(o, b)) if o else "n/a")
            lines.append("| %g | %s | %s | %s | %s |" % (
                e, p[0], " / ".join("%.4g" % v for v in b), cells[0], cells[1]))
    return "\n".join(lines) + "\n"


def svg_plot(res, path, constants="bruneton"):
    """Ratio ours / Blender against the sun's elevation, one panel per
    probe, red, green and blue lines; log ratio axis 1/8 to 8."""
    probes = [p[0] for p in PROBES]
    w, h, pw, ph = 900, 250, 130, 170
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" '
           'font-family="sans-serif" font-size="11">' % (w, h),
           '<rect width="100%" height="100%" fill="white"/>',
           '<text x="10" y="16">ours (%s) / Blender Nishita, per channel, against '
           'the sun\'s elevation (degrees); log axis</text>' % constants]
    lo, hi = math.log(1 / 8.0), math.log(8.0)
    els = res["elevations"]
    x_of = lambda i, k: 40 + k * (pw + 15) + pw * (math.log(els[i]) - math.log(els[0])) / \
        max(1e-9, math.log(els[-1]) - math.log(els[0]))
    y_of = lambda r: 30 + ph * (hi - min(hi, max(lo, math.log(r)))) / (hi - lo)
    for k, name in enumerate(probes):
        x0 = 40 + k * (pw + 15)
        out.append('<rect x="%d" y="30" width="%d" height="%d" fill="none" stroke="#999"/>'
                   % (x0, pw, ph))
        out.append('<text x="%d" y="%d">%s</text>' % (x0 + 4, 30 + ph + 28, name))
        for r in (0.25, 0.5, 1, 2, 4):
            y = y_of(r)
            out.append('<line x1="%d" x2="%d" y1="%.1f" y2="%.1f" stroke="%s"/>'
                       % (x0, x0 + pw, y, y, "#666" if r == 1 else "#ddd"))
            if k == 0:
                out.append('<text x="4" y="%.1f">%g</text>' % (y + 4, r))
        for i, e in enumerate(els):
            out.append('<text x="%.1f" y="%d" text-anchor="middle">%g</text>'
                       % (x_of(i, k), 30 + ph + 13, e))
        for ch, colour in enumerate(("#d62728", "#2ca02c", "#1f77b4")):
            pts = []
            for i, e in enumerate(els):
                key = "e%g_%s" % (e, name)
                o = res["ours"].get(constants, {}).get(key)
                b = res["blender"].get(key)
                if o and b and b[ch] > 0 and o[ch] > 0:
                    pts.append("%.1f,%.1f" % (x_of(i, k), y_of(o[ch] / b[ch])))
            if pts:
                out.append('<polyline fill="none" stroke="%s" stroke-width="1.5" '
                           'points="%s"/>' % (colour, " ".join(pts)))
    out.append("</svg>")
    path.write_text("\n".join(out) + "\n")


def to_png(exr, png, scale):
    subprocess.run(["oiiotool", str(exr), "--ch", "R,G,B", "--mulc", repr(scale),
                    "--colorconvert", "linear", "sRGB", "-d", "uint8", "-o", str(png)],
                   check=True, capture_output=True)


def parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build-dir", default=str(ROOT / "build"))
    ap.add_argument("--out", default="/tmp/shafts-nishita")
    ap.add_argument("--elevations", default=",".join("%g" % e for e in ELEVATIONS))
    ap.add_argument("--spp", type=int, default=4096, help="our probes' samples")
    ap.add_argument("--figure-spp", type=int, default=64)
    ap.add_argument("--figures", default=str(ROOT / "docs" / "img" / "sky"))
    ap.add_argument("--no-figures", action="store_true")
    ap.add_argument("--markdown")
    ap.add_argument("--json")
    ap.add_argument("--blender", default="blender")
    return ap.parse_args(argv)


def main(argv=None):
    args = parse(argv)
    build, out = Path(args.build_dir), Path(args.out)
    elevations = [float(e) for e in args.elevations.split(",")]
    figures = not args.no_figures
    if not shutil.which(args.blender):
        print("nishita: blender is not installed (tools/bootstrap.sh installs it)")
        return 1
    print("nishita: Blender's Nishita sky (%d renders)..." % len(blender_views(elevations, figures)))
    bres = run_blender(blender_views(elevations, figures), out / "blender", args.blender)
    cal = bres["views"]["calibration"]["rgb"]
    irradiance = [v * blender_solid_angle(SUN_SIZE_DEG) for v in cal]
    print("nishita: Blender %s; its sun's irradiance in its RGB: %s"
          % (bres["blender"], ", ".join("%.4g" % v for v in irradiance)))
    res = {"elevations": elevations, "irradiance": irradiance,
           "blender_version": bres["blender"],
           "blender": {k: v["rgb"] for k, v in bres["views"].items()},
           "ours": {}, "ours_seconds": {}, "refused": None}
    for c, consts in CONSTANTS.items():
        res["ours"][c] = {}
        for e in elevations:
            for p in PROBES:
                key = "e%g_%s" % (e, p[0])
                scene = sky_scene(e, irradiance, consts, probe_direction(p, e), 1.0, 5, 5,
                                  args.spp)
                img = out / "ours" / c / (key + ".exr")
                img.parent.mkdir(parents=True, exist_ok=True)
                try:
                    res["ours_seconds"]["%s_%s" % (c, key)] = run_ours(build, scene, img,
                                                                       (2, 2, 3, 3))
                except Refused as err:
                    res["refused"] = str(err)
                    break
                res["ours"][c][key] = pixel(img, 0, 0)
                print("nishita: %s %s: ours %s, Blender %s, ratio %s" % (
                    c, key, _fmt(res["ours"][c][key]), _fmt(res["blender"][key]),
                    _fmt(ratios(res["ours"][c][key], res["blender"][key]))))
            if res["refused"]:
                break
        if res["refused"]:
            print("nishita: our reference is skipped: %s" % res["refused"])
            break
    table = (depth_table() + "\n" + sun_mie_table() + "\n" + midpoint_bias_table() + "\n"
             + sun_ozone_table() + "\n" + markdown(res))
    print(table)
    if args.markdown:
        Path(args.markdown).write_text(table)
    if args.json:
        Path(args.json).write_text(json.dumps(res, indent=1))
    if figures:
        fig = Path(args.figures)
        fig.mkdir(parents=True, exist_ok=True)
        if not res["refused"]:
            svg_plot(res, fig / "nishita_ratio_bruneton.svg", "bruneton")
            svg_plot(res, fig / "nishita_ratio_blender_rgb.svg", "blender_rgb")
        for e in elevations:
            if e not in FIGURE_ELEVATIONS:
                continue
            name = "e%g_figure" % e
            # One exposure for both images: the horizon beside the sun at 2.
            scale = 0.5 / max(1e-9, max(res["blender"]["e%g_horizon_side" % e]))
            to_png(out / "blender" / (name + ".exr"), fig / ("nishita_blender_e%g.png" % e),
                   scale)
            if res["refused"]:
                continue
            scene = sky_scene(e, irradiance, BRUNETON, direction(FIGURE["pitch"], 0.0),
                              FIGURE["fov"], FIGURE["width"], FIGURE["height"],
                              args.figure_spp)
            img = out / "ours" / (name + ".exr")
            run_ours(build, scene, img)
            to_png(img, fig / ("nishita_ours_e%g.png" % e), scale)
        print("nishita: figures in %s" % fig)
    return 0


if __name__ == "__main__":
    sys.exit(main())
