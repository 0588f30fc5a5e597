"""The scene format's phase functions (docs/scene-format.md, "Phase
functions") and what Blender's engines make of them, for the import's
messages (importer.py).

Cycles and EEVEE have only Henyey-Greenstein lobes: scene_export's writer
gives Cycles a lobe or a mixture of lobes for a Nishita, Rayleigh or
Cornette-Shanks phase (the data's lobes), and EEVEE renders one lobe (it
averages the g of several). Our
engines (Shafts Tracer, Shafts Sweep) render the scene's phase itself.
`largest_error` says how far such lobes are from the phase: the largest
relative difference over every scattering angle, the figure a lighting
artist can weigh (docs/scene_export.md, "Feature by feature", gives what it
does to images).
"""
import math

import numpy as np

# The cosines of the scattering angle at which phases are compared: fine
# enough for the narrowest peak the format has (Nishita murky's cos^64 of
# the half angle, about 0.03 wide in the cosine).
MU = np.linspace(-1.0, 1.0, 40001)

NAMES = {"isotropic": "isotropic", "henyey_greenstein": "Henyey-Greenstein",
         "nishita_hazy": "Nishita hazy", "nishita_murky": "Nishita murky",
         "rayleigh": "Rayleigh", "cornette_shanks": "Cornette-Shanks"}

G_MAX = 0.999  # Cycles clamps a lobe's g to this (medium.G_MAX)


def hg(g, mu=MU):
    """Henyey-Greenstein, per steradian."""
    return (1.0 - g * g) / (4.0 * math.pi * (1.0 + g * g - 2.0 * g * mu) ** 1.5)


def _normalised(shape, mu):
    """shape(mu) divided by its integral over the sphere (2 pi times its
    integral over the cosine, by the trapezoid rule on MU)."""
    values = shape(MU)
    total = 2.0 * math.pi * float(np.sum(0.5 * (values[1:] + values[:-1]) * np.diff(MU)))
    return shape(mu) / total


def value(phase, mu=MU):
    """The format's phase `phase` (a phase object) at the cosines mu, per
    steradian (each integrates to 1 over the sphere)."""
    t, g = phase["type"], float(phase.get("g", 0.0))
    if t == "isotropic":
        return np.full_like(mu, 1.0 / (4.0 * math.pi))
    if t == "henyey_greenstein":
        return hg(g, mu)
    if t == "rayleigh":
        return 3.0 / (16.0 * math.pi) * (1.0 + mu * mu)
    if t == "cornette_shanks":
        return (3.0 * (1.0 - g * g) / (8.0 * math.pi * (2.0 + g * g))
                * (1.0 + mu * mu) / (1.0 + g * g - 2.0 * g * mu) ** 1.5)
    # Nishita et al. 1993: 1 + k cos^n(alpha / 2), cos^2(alpha / 2) = (1 + mu) / 2.
    k, half_power = {"nishita_hazy": (9.0, 8), "nishita_murky": (50.0, 32)}[t]
    return _normalised(lambda m: 1.0 + k * ((1.0 + m) / 2.0) ** half_power, mu)


def exact_in_cycles(phase):
    """Whether one Cycles lobe is this phase exactly."""
    t = phase["type"]
    return t == "isotropic" or (t == "henyey_greenstein"
                                and abs(float(phase.get("g", 0.0))) <= G_MAX)


def largest_error(phase, lobes):
    """The largest relative difference, over every scattering angle, of the
    mixture of lobes [(weight, g)] (weights summing to 1, g clamped as
    Cycles clamps it) from the phase."""
    mix = sum(w * hg(_clamped(g)) for w, g in lobes)
    return float(np.max(np.abs(mix / value(phase) - 1.0)))


def describe(phase):
    """The phase as a lighting artist reads it: "Cornette-Shanks (g = 0.8)"."""
    name = NAMES.get(phase["type"], phase["type"])
    return name + (" (g = %.4g)" % float(phase["g"]) if "g" in phase else "")


def _clamped(g):
    return min(max(g, -G_MAX), G_MAX)


def _lobes_text(lobes):
    if len(lobes) == 1:
        return "one Henyey-Greenstein lobe, g = %.4g" % _clamped(lobes[0][1])
    equal = max(w for w, _ in lobes) - min(w for w, _ in lobes) < 1e-9
    return "%s mixture of %d Henyey-Greenstein lobes, g = %s" % (
        "an equal-weight" if equal else "a", len(lobes),
        ", ".join("%.4g" % _clamped(g) for _, g in lobes))


def _percent(x):
    return ("%.1f%%" if x < 0.1 else "%.0f%%") % (100.0 * x)


def message(what, phase, cycles_lobes, atmosphere=False):
    """The import's sentence for a phase Cycles cannot hold: which engines
    render it exactly, and how far Cycles' lobes are from it."""
    eevee = ("EEVEE does not render a planet's atmosphere" if atmosphere
             else "EEVEE by one lobe (it averages the g of several)")
    return ("%s: the %s phase is exact in the Shafts Tracer and Shafts Sweep engines; "
            "Cycles approximates it by %s, up to %s off the phase at some scattering "
            "angles, and %s; what this does to images: docs/scene_export.md, "
            "\"Feature by feature\"."
            % (what, describe(phase), _lobes_text(cycles_lobes),
               _percent(largest_error(phase, cycles_lobes)), eevee))
