"""Twins of scenes: the same scene with what a peer renderer can only
approximate replaced by what every renderer represents exactly.

Cycles and EEVEE have one Henyey-Greenstein lobe for a phase function and a
Glossy shader for a highlight, so on a canonical scene with Nishita's hazy
phase or Phong highlights their error is mostly the exporter's substitution
(docs/scene_export.md), and their speed-against-error curves measure our
choice of phase, not their speed. A twin is generated from the scene (never
a hand copy, so it follows the scene when the scene changes):

- a Nishita phase (hazy, murky) becomes the Henyey-Greenstein lobe of the
  same mean cosine, the lobe scene_export gives Cycles and EEVEE (hazy: g =
  0.4, murky: g = 800/1411); Rayleigh, whose mean cosine is 0 and which the
  exporter writes as two lobes, becomes isotropic;
- a Phong highlight (a material with a specular colour that is not black)
  is dropped, leaving the Lambert material (its diffuse, reflect, transmit
  and emission stay).

Everything else (geometry, lights, medium coefficients, camera) is the
scene's. The twin's name is the scene's with `-hg` and/or `-lambert`.
"""

import copy
import json
from pathlib import Path

from .scenes import prepare_data

# A Nishita phase is 1 + k cos^(2n)(alpha/2) = 1 + k t^n with
# t = (1 + cos alpha) / 2 (docs/scene-format.md, "Phase functions").
NISHITA = {"nishita_hazy": (9.0, 8), "nishita_murky": (50.0, 32)}


def mean_cosine(phase):
    """The mean cosine of the phase angle, the integral of p cos alpha over
    the sphere, of a scene's phase object. For 1 + k t^n (mu = cos alpha,
    t = (1 + mu) / 2, dmu = 2 dt): the integral of the shape over mu in
    [-1, 1] is 2 + 2k / (n + 1), that of mu times it 2k (2 / (n + 2) -
    1 / (n + 1)); hazy: 1.6 / 4 = 0.4, murky: 800 / 1411."""
    kind = phase.get("type", "isotropic")
    if kind == "henyey_greenstein":
        return float(phase["g"])
    if kind in NISHITA:
        k, n = NISHITA[kind]
        return 2 * k * (2.0 / (n + 2) - 1.0 / (n + 1)) / (2 + 2 * k / (n + 1))
    if kind in ("isotropic", "rayleigh"):
        return 0.0
    raise ValueError("unknown phase function %r" % kind)


def twin_phase(phase):
    """The Henyey-Greenstein stand-in for a phase every peer cannot
    represent, as (phase, sentence); None for isotropic and HG phases."""
    kind = phase.get("type", "isotropic")
    if kind in ("isotropic", "henyey_greenstein"):
        return None
    g = mean_cosine(phase)
    if g == 0.0:
        return {"type": "isotropic"}, "%s phase as isotropic (its mean cosine is 0)" % kind
    return ({"type": "henyey_greenstein", "g": round(g, 6)},
            "%s phase as Henyey-Greenstein g = %.4g (the same mean cosine)" % (kind, g))


def has_phong(material):
    """Whether a material has a Phong highlight: a specular colour that is
    not black."""
    return any(float(c) > 0 for c in material.get("specular", [0, 0, 0]))


def make_twin(name, data):
    """The twin of the scene `data` called `name`: (twin name, twin data,
    list of sentences saying what changed), or None when the scene has
    nothing the twin would replace."""
    twin = copy.deepcopy(data)
    changes, suffix = [], ""
    medium = twin.get("medium")
    if isinstance(medium, dict) and isinstance(medium.get("phase"), dict):
        replaced = twin_phase(medium["phase"])
        if replaced:
            medium["phase"], sentence = replaced
            changes.append(sentence)
            suffix += "-hg"
    phong = sorted(n for n, m in (twin.get("materials") or {}).items()
                   if isinstance(m, dict) and has_phong(m))
    for n in phong:
        twin["materials"][n].pop("specular", None)
        twin["materials"][n].pop("shininess", None)
    if phong:
        changes.append("Phong highlights dropped (Lambert only): %s" % ", ".join(phong))
        suffix += "-lambert"
    if not changes:
        return None
    return name + suffix, twin, changes


def prepare_twin(source, cache_dir, scale=None):
    """Reads a scene file and prepares its twin (scenes.prepare_data):
    (PreparedScene, changes, the scene's own dict), or None when the scene
    has no twin or cannot be read (the scene's own run reports that)."""
    source = Path(source)
    try:
        data = json.loads(source.read_bytes())
    except (OSError, ValueError):
        return None
    made = make_twin(source.stem, data) if isinstance(data, dict) else None
    if made is None:
        return None
    name, twin, changes = made
    scene = prepare_data(name, twin, source.parent.resolve(), cache_dir, scale=scale,
                         source="%s, twin: %s" % (source, "; ".join(changes)))
    return scene, changes, data
