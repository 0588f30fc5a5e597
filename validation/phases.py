"""The scene format's phase functions for the validation scripts: the
add-on's own definitions (blender_addon/shafts_blender/convert/phase.py,
math and numpy only), loaded by their path, since the add-on's package
needs Blender. One Python definition of the phases in the project.

    hg(g, mu)            Henyey-Greenstein, per steradian
    value(phase, mu)     the format's phase object at the cosine(s) mu
"""
import importlib.util
from pathlib import Path

_PATH = (Path(__file__).resolve().parent.parent / "blender_addon" / "shafts_blender"
         / "convert" / "phase.py")
_spec = importlib.util.spec_from_file_location("shafts_convert_phase", _PATH)
_module = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_module)

hg = _module.hg


def value(phase, mu):
    """The phase `phase` (a dict as in a scene file) at the cosine mu of the
    scattering angle, per steradian: a float for a float mu, an array for
    an array."""
    v = _module.value(phase, mu)
    return float(v) if getattr(v, "ndim", 0) == 0 else v
