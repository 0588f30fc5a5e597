"""Bias or noise: what a renderer's remaining error on a scene is made of.

The validation renders every renderer at rising settings, so the run
already holds what tells bias from noise: how the error falls as the
setting rises. Monte Carlo noise has a variance inversely proportional to
the samples, so a renderer's relative RMS error at n samples is

    e(n)^2 = b^2 + c / n

with b the bias (what no number of samples removes) and c / n the noise's
share. Two settings n1 < n2 = r n1 of the same series give

    noise^2 = (e1^2 - e2^2) / (r - 1),   bias^2 = e2^2 - noise^2

(each clamped at 0), and the verdict at n2 is *noise* when noise >= bias,
*bias* otherwise. Where a light is in view, the errors are those away
from it (the report's second figure), whose noise is not heavy-tailed. A
deterministic renderer (gl_shafts without jitter, POV-Ray's media with
jitter 0, EEVEE) has no noise: its whole error is bias, which either still
falls with its setting (discretisation: more planes, intervals or samples
remove it) or has stopped falling (a floor: less than FLOOR_FALL of it
went at the last step). An error of exactly 0 is
*exact*. The reference's own noise (about a quarter of the self-check) is
part of every b; it is far below the errors classified here.

A row with bias names its cause from CAUSES, the known causes keyed by
renderer and scene feature, each backed by a measurement (docs/validation.md,
"Bias or noise"); where the scene has a twin (twins.py) the note adds the
renderer's verdict on the twin, which lacks the approximated features.
"""

import math

from .metrics import fmt_percent
from .scenes import light_mask
from .twins import has_phong

# A deterministic error that fell by less than this fraction at the last
# step of its setting has stopped falling: a floor.
FLOOR_FALL = 0.2
# A noise verdict whose bias is at least this also names the bias's cause.
NOTE_BIAS = 0.01
# A bias at most this many times the reference's own noise cannot be told
# from it.
REF_NOISE_FACTOR = 2.0


def _eevee_count(p):
    # Volumetric samples times TAA samples per froxel of tile x tile pixels.
    return p.get("samples", 1) * p.get("taa", 1) / float(p.get("tile", 1)) ** 2


# How each renderer's sweep converges: which runs form its series, the
# count a run's setting puts along it, whether its error is random, and
# the setting's name for the notes.
SERIES = {
    "lmm_tracer": (lambda p: p.get("mode") == "reference", lambda p: p["spp"], True, "spp"),
    "cycles": (lambda p: "samples" in p, lambda p: p["samples"], True, "spp"),
    "gl_shafts": (lambda p: p.get("xi") == "exact" and not p.get("jitter")
                  and "lattice" not in p, lambda p: p["planes"], False, "planes"),
    "povray": (lambda p: "intervals" in p, lambda p: p["intervals"] * p.get("samples", 1),
               False, "samples along a ray"),
    "eevee": (lambda p: "samples" in p, _eevee_count, False, "volumetric samples per pixel"),
    # The Blender add-on's engines: lmm_tracer's reference mode, and
    # gl_shafts at its defaults (one run, no series).
    "addon_tracer": (lambda p: "spp" in p, lambda p: p["spp"], True, "spp"),
    "addon_sweep": (lambda p: False, None, False, "planes"),
}


def features(data):
    """The features of a scene (its dict) that CAUSES are keyed by: medium,
    medium:TYPE, phase:TYPE (an atmosphere's Rayleigh and Mie phases), phong, reflect,
    transmit, shadows, several_lights, several_lights_in_medium, light_map,
    light_in_view."""
    out = set()
    medium = data.get("medium")
    if isinstance(medium, dict):
        out.add("medium")
        kind = medium.get("type", "homogeneous")
        out.add("medium:%s" % kind)
        if kind == "atmosphere":
            # Rayleigh's phase, and Mie's own (docs/scene-format.md).
            out.add("phase:rayleigh")
            out.add("phase:%s" % ((medium.get("mie") or {}).get("phase") or {}).get(
                "type", "isotropic"))
        else:
            out.add("phase:%s" % (medium.get("phase") or {}).get("type", "isotropic"))
    materials = [m for m in (data.get("materials") or {}).values() if isinstance(m, dict)]
    if any(has_phong(m) for m in materials):
        out.add("phong")
    for key in ("reflect", "transmit"):
        if any(any(float(c) > 0 for c in m.get(key, [0, 0, 0])) for m in materials):
            out.add(key)
    lights = data.get("lights") or []
    if data.get("shapes") and lights:
        out.add("shadows")
    if len(lights) > 1:
        out.add("several_lights")
        if "medium" in out:
            out.add("several_lights_in_medium")
    if any(isinstance(l, dict) and "light_map" in l for l in lights):
        out.add("light_map")
    try:
        if light_mask(data):
            out.add("light_in_view")
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        pass
    return out


# The known causes of bias: (renderers, feature, short note[, the least
# bias the cause explains]). Each is backed by a measurement in
# docs/validation.md ("Bias or noise"). Every matching entry names a row's
# cause.
CAUSES = [
    # The add-on reads height fog and the atmosphere exactly from the
    # volume material's Shafts Medium properties, which scene_export's
    # Blender writer sets (docs/blender.md, "Height fog and the
    # atmosphere"), and a homogeneous medium's phase from the material's
    # shafts_phase record while the node graph holds the writer's lobes
    # (7c33a3a: Nishita hazy, murky and Rayleigh round trip at 0.0001 mean
    # relative, from 0.17, 0.34 and 0.22; convert.roundtrip), so the
    # add-on's engines have no phase cause left.
    (("cycles", "eevee"), "phase:nishita_hazy",
     "Nishita hazy phase exported as one HG lobe, g 0.4"),
    (("cycles", "eevee"), "phase:nishita_murky",
     "Nishita murky phase exported as one HG lobe, g 0.567"),
    (("cycles", "eevee"), "phase:rayleigh",
     "Rayleigh phase exported as two HG lobes"),
    (("cycles", "eevee", "addon_sweep", "addon_tracer"), "phong",
     "Phong highlights exported as Glossy"),
    (("eevee",), "several_lights_in_medium",
     "surfaces lit through the medium not attenuated (several lights)"),
    (("eevee",), "light_map", "light map without its colour (grey shadows)"),
    (("eevee",), "transmit", "glass by screen-space refraction"),
    (("eevee",), "medium", "EEVEE's froxel volumetrics"),
    (("gl_shafts", "addon_sweep"), "reflect",
     "reflecting and transmitting materials drawn opaque"),
    (("gl_shafts", "addon_sweep"), "transmit",
     "reflecting and transmitting materials drawn opaque"),
    (("gl_shafts", "addon_sweep"), "shadows", "shadow-map edges"),
    (("povray",), "transmit", "total internal reflection in the glass", 0.001),
    # The Cornette-Shanks phase is exported as Henyey-Greenstein lobes
    # fitted to it (scene_export/se_phase_fit.h): no mixture of lobes
    # follows its (1 + mu^2) factor exactly. POV-Ray renders the
    # atmosphere's scattering apart in frames, summed (it scatters with the
    # plain mean of its media's phases); validation.peers on sky_sunset at
    # 48x36: 0.87% mean relative, ratio 1.001 with the fitted lobe (1.63%,
    # 1.024 with the lobe of the mean cosine). Cycles' atmosphere was 5-10%
    # dark while rendered in one pass (Cycles 3.4 picks the colour channel
    # of its distance sampling from one number per path); the export
    # renders it once per channel with grey coefficients since 92f2aef
    # (validation.cycles_channels: the sky's top third 0.983-0.994 of the
    # reference), so that is no cause any more.
    (("povray", "cycles", "eevee"), "phase:cornette_shanks",
     "Cornette-Shanks phase exported as HG lobes fitted to it"),
    # What the atmosphere's exported lobes cost the image, measured apart on
    # the reference's Rayleigh and Mie light (validation.atmo_phase_bias,
    # 40x30): 2.5% relative RMS on sky_sunset, 0.5% on earth_from_space.
    # A larger bias the sweep's two points give Cycles there (7.5% and
    # 1.7% at 37178c5) is not resolved beyond that: at 24x18 two seeds
    # differ by more (validation.peers; docs/validation.md).
    # From space, at 512 spp, Cycles is 1.45% from the reference (mean
    # relative) against 1.37% between two seeds: about 1% per pixel beyond
    # the phases' 0.5%, unexplained (docs/validation.md).
    (("cycles",), "medium:atmosphere",
     "the phases' lobes cost 2.5% on the sunset and 0.5% from space "
     "(validation.atmo_phase_bias); the rest not explained (from space about "
     "1%; on the sunset not resolved under the noise)"),
    # gl_shafts' atmosphere: the optical depth from a table interpolated in
    # log tau (largest transmittance error 0.45%, gs_atmo_table_test) and
    # 3-point Gauss-Legendre per plane (docs/gl_shafts.md, "The atmosphere").
    (("gl_shafts", "addon_sweep"), "medium:atmosphere",
     "the optical-depth table's interpolation and the planes' quadrature"),
    (("cycles",), "transmit", "glass: Cycles' own refraction and caustics differ"),
]


# A bias with no cause of CAUSES: what remains for a renderer on surfaces
# it represents exactly, measured on lmm_table's Lambert twin (Cycles 0.21%
# at 64 and 256 spp, mean relative 0.04%: isolated pixels on edges, where
# the reference's pixel centre and Cycles' samples hit different surfaces,
# and faint facets of the cylinder, which Blender gets tessellated).
# POV-Ray writes half-float EXR: rounding to 11 significant bits is a
# relative RMS error of 2^-11 / sqrt(12) = 0.014% (lmm_table: 0.02%).
# The add-on's tracer engine renders the meshes Blender holds after the
# export: spheres and cylinders as flat-shaded facets, which the pixel
# centres it shares with the reference see at the facets' own normals and
# silhouettes. Measured on the full run at 8b517b4: its difference images
# on lmm_table-lambert (1.6%) and lmm_lens-lambert (3.2%) hold nothing but
# the cylinder's vertical facets and the sphere's latitude-longitude grid.
FALLBACK = {"cycles": "edge pixels and tessellated curved shapes",
            "eevee": "edge pixels and tessellated curved shapes",
            "addon_tracer": "Blender's tessellated spheres and cylinders (flat facets)",
            "povray": "half-float EXR output"}


def causes(renderer, feats, bias=1.0):
    """The notes of the known causes of a bias that apply to `renderer` on a
    scene with features `feats`, without repeats."""
    out = []
    for names, feature, note, *least in CAUSES:
        if (renderer in names and feature in feats and note not in out
                and bias >= (least[0] if least else 0)):
            out.append(note)
    return out


def split(e1, e2, r):
    """(bias, noise) at the larger setting, from the errors e1 at n and e2
    at r n of a Monte Carlo series (the module's rule)."""
    noise2 = max(0.0, (e1 * e1 - e2 * e2) / (r - 1.0))
    bias2 = max(0.0, e2 * e2 - noise2)
    return bias2 ** 0.5, min(noise2, e2 * e2) ** 0.5


def classify_runs(renderer, runs, metrics="metrics"):
    """The verdict on one renderer's runs (dicts with params and the figures
    under the key `metrics`): a dict with kind ("exact", "noise", "bias" or
    "unknown"), error, bias, noise, whether the error still falls with the
    setting, and the basis (the two settings compared); None when there is
    no series."""
    if renderer not in SERIES:
        return None
    member, count, random, axis = SERIES[renderer]
    measured = [r for r in runs if r.get(metrics) and r[metrics].get("rel_rms") is not None]
    pts = sorted((count(r["params"]), r[metrics]["rel_rms"]) for r in measured
                 if member(r["params"]))
    if not pts and not random:
        # No sweep (a scene without a medium): the renderer's one run, all
        # of whose error is bias.
        pts = sorted((0, r[metrics]["rel_rms"]) for r in measured)[:1]
    if not pts:
        return None
    n2, e2 = pts[-1]
    lower = [p for p in pts if p[0] < n2]
    out = {"kind": "unknown", "error": e2, "bias": None, "noise": None, "falls": None,
           "basis": "%s %g" % (axis, n2) if n2 else "one setting"}
    if e2 == 0:
        out.update(kind="exact", bias=0.0, noise=0.0)
        return out
    if not lower:
        if not random:
            out.update(kind="bias", bias=e2, noise=0.0)
        return out
    n1, e1 = lower[-1]
    out["basis"] = "%s %g to %g: %s to %s" % (axis, n1, n2, fmt_percent(e1), fmt_percent(e2))
    out["falls"] = e2 <= (1.0 - FLOOR_FALL) * e1
    if random:
        bias, noise = split(e1, e2, n2 / float(n1))
        out.update(kind="noise" if noise >= bias else "bias", bias=bias, noise=noise)
    else:
        out.update(kind="bias", bias=e2, noise=0.0)
    return out


def reference_noise(entry, ref_spp, metrics="metrics"):
    """The reference's own noise on a scene entry: the error of lmm_tracer's
    reference-mode run with the most spp (another seed) carried to the
    reference's spp at the rate the sweep measures between its two largest
    spp, error proportional to spp^-p with p between 1/2 (plain Monte
    Carlo) and 1 (its stratified sampling reaches that); None without
    such runs."""
    pts = sorted((r["params"]["spp"], r[metrics]["rel_rms"]) for r in entry.get("runs", [])
                 if r["renderer"] == "lmm_tracer" and r["params"].get("mode") == "reference"
                 and r.get(metrics) and r[metrics].get("rel_rms"))
    if not pts or not ref_spp:
        return None
    n2, e2 = pts[-1]
    rate = 0.5
    if len(pts) > 1 and pts[-2][0] < n2:
        n1, e1 = pts[-2]
        rate = min(1.0, max(0.5, math.log(e1 / e2) / math.log(n2 / float(n1))))
    return e2 * (n2 / float(ref_spp)) ** rate


def classify(entry, data, twin=None, ref_spp=None):
    """Every renderer's verdict on a scene entry of the results (its runs),
    the scene's dict `data`, when it has one its twin's entry, and the
    reference's spp (for its noise); the verdicts with bias carry a note
    naming the cause."""
    feats = features(data)
    # With a light in view, the errors away from it: next to the light the
    # radiance is unbounded and Monte Carlo noise there is heavy-tailed (a
    # few fireflies), so it does not fall as 1/sqrt(n) over a sweep's few
    # sample counts and would pass for bias.
    metrics = ("metrics_masked" if any(r.get("metrics_masked") for r in entry.get("runs", []))
               else "metrics")
    ref_noise = reference_noise(entry, ref_spp, metrics)
    out = {}
    for renderer in dict.fromkeys(r["renderer"] for r in entry.get("runs", [])):
        v = classify_runs(renderer, [r for r in entry["runs"] if r["renderer"] == renderer],
                          metrics)
        if v is None:
            continue
        v["away_from_lights"] = metrics == "metrics_masked"
        if v["kind"] == "bias" or (v["bias"] or 0) >= NOTE_BIAS:
            known = causes(renderer, feats, v["bias"])
            if ref_noise is not None and v["bias"] <= REF_NOISE_FACTOR * ref_noise:
                # Too small to tell from the reference's own noise.
                known = ["the reference's own noise (%s)" % fmt_percent(ref_noise)]
            elif v["falls"] and not SERIES[renderer][2]:
                # A deterministic error still falling: the setting's
                # discretisation, which more of it removes.
                known = ["discretisation: falls with more %s" % SERIES[renderer][3]]
            if not known and renderer in FALLBACK and ("shadows" in feats
                                                        or renderer == "povray"):
                known = [FALLBACK[renderer]]
            v["note"] = "; ".join(known) if known else "cause not identified"
            tv = (twin or {}).get("verdicts", {}).get(renderer)
            if tv is not None:
                v["note"] += " (on the twin: %s)" % short(tv)
        out[renderer] = v
    return out


def short(v):
    """A verdict in a few words: "noise", "bias 19 %", "exact"."""
    if v is None:
        return ""
    if v["kind"] == "bias":
        return "bias %s" % fmt_percent(v["bias"])
    if v["kind"] == "noise":
        return "noise (bias %s)" % fmt_percent(v["bias"]) if v["bias"] else "noise"
    return v["kind"]


def text(v):
    """The verdict and, with bias, its cause: a table cell."""
    if v is None:
        return ""
    return short(v) + (": " + v["note"] if v.get("note") else "")
