# EEVEE's volumetric settings for the validation sweep.
#
# scene_export's Blender script fixes EEVEE's volumetric quality at the
# settings measured best (2 px tiles, 256 slices, 32 shadow samples, TAA 64
# in final quality; docs/scene_export.md, EEVEE: 8 px tiles cost about 18
# points of mean_rel on a point light); the validation sweeps it for its
# speed-against-error curves, and scene_export/eevee_limits.py for the
# figures. Run this file before the exported script, in the same Blender
# process:
#
#   SHAFTS_EEVEE_SETTINGS='{"volumetric_tile_size": "8", "volumetric_samples": 32}' \
#     xvfb-run -a blender -b -P validation/blender_eevee.py -P DIR/NAME.py -- ...
#
# It registers a render_pre handler (persistent, so that the exported
# script's factory-settings reset keeps it) that sets the named attributes
# of scene.eevee just before rendering, after the exported script has set
# its own. Only attributes of scene.eevee can be set, and only from JSON
# numbers and strings: the environment variable is data, never code.
import json
import os
import sys

import bpy
from bpy.app.handlers import persistent

ALLOWED = {
    "volumetric_tile_size", "volumetric_samples", "volumetric_shadow_samples",
    "volumetric_sample_distribution", "taa_render_samples",
    "use_volumetric_shadows", "use_volumetric_lights",
}


def _settings():
    text = os.environ.get("SHAFTS_EEVEE_SETTINGS", "")
    if not text:
        return {}
    try:
        settings = json.loads(text)
    except ValueError as e:
        print("blender_eevee: SHAFTS_EEVEE_SETTINGS is not JSON: %s" % e, file=sys.stderr)
        sys.exit(2)
    if not isinstance(settings, dict) or not set(settings) <= ALLOWED:
        print("blender_eevee: SHAFTS_EEVEE_SETTINGS may only set %s"
              % ", ".join(sorted(ALLOWED)), file=sys.stderr)
        sys.exit(2)
    return settings


SETTINGS = _settings()


@persistent
def apply_settings(scene, *_):
    """Sets the requested EEVEE attributes on the scene about to render."""
    eevee = scene.eevee
    for key, value in SETTINGS.items():
        current = getattr(eevee, key)
        setattr(eevee, key, type(current)(value))
    print("blender_eevee: %s" % ", ".join(
        "%s=%s" % (k, getattr(eevee, k)) for k in sorted(SETTINGS)))


bpy.app.handlers.render_pre.append(apply_settings)
