#include "se_scale.h"

#include <math.h>
#include <stdio.h>

#include "se_geom.h"
#include "se_text.h"

/* POV-Ray: a camera 5000 units from a scene 3.5 across put the scene in
 * 0.4 units when the scale followed a sphere that held the camera: 71%
 * off, the sphere around the light covering it all. The scale follows the
 * content alone, however far the camera: keeping the camera within 1e6
 * units (against POV-Ray's MAX_DISTANCE of 1e7) shrank the hard cases'
 * base scene to 0.7 units at 1.4e6 radii, 59% off, while with the content
 * at 300 units POV-Ray renders it 0.13% from the reference with the camera
 * 5e9 units away (measured by validation/precision.py). */
se_frame se_scale_pov(const sh_scene *s, const se_options *opt, se_notes *notes) {
  sh_vec3 c;
  double r;
  se_content_sphere(s, &c, &r);
  if (opt->scale_mode == SE_SCALE_NONE) {
    if (r < 3.0)
      se_note(notes,
              "with --scale none the scene is %g units across, where POV-Ray's "
              "tolerances of 1e-3 units are no longer negligible.",
              2.0 * r);
    return se_frame_pov(1.0, sh_v3s(0.0));
  }
  double scale = pow(10.0, round(log10(300.0 / r)));
  /* An atmosphere: the air's thickness about 100 units (kilometres for
   * the Earth in km or m), so that an eye a metre above the ground stays
   * above POV-Ray's tolerances of 1e-3 units. */
  if (s->medium.present && s->medium.type == SH_MEDIUM_ATMOSPHERE)
    scale = pow(10.0, round(log10(100.0 / (s->medium.atmo.top_radius -
                                           s->medium.atmo.ground_radius))));
  if (opt->scale_mode == SE_SCALE_FIXED) {
    scale = opt->scale;
    if (r * scale < 3.0)
      se_note(notes,
              "with --scale %g the scene is %g units across, where POV-Ray's "
              "tolerances of 1e-3 units are no longer negligible.",
              scale, 2.0 * r * scale);
  }
  return se_frame_pov(scale, c);
}

/* Blender: measured by validation/precision.py on the hard cases' base
 * scene (3.5 units in radius) kept in its own units: Cycles was within
 * 0.01% of its plain image scaled by 1e-6 to 1e3, 0.04% 1e3 from the
 * origin, 0.6% with the camera 5e4 away, and failed beyond (black at
 * 1e-9, 120% at 1e6, 17% 1e6 from the origin, 3.8% with the camera 5e5
 * away). */
se_frame se_scale_blender(const sh_scene *s, const se_options *opt, se_notes *notes) {
  sh_vec3 c;
  double r;
  se_content_sphere(s, &c, &r);
  double cam = sh_length(sh_sub(s->camera.position, c));
  se_frame f = se_frame_blender(1.0, sh_v3s(0.0));
  if (opt->scale_mode != SE_SCALE_NONE) {
    if (opt->scale_mode == SE_SCALE_FIXED)
      f.scale = opt->scale;
    else if (r < 1e-2 || r > 1e2)
      f.scale = pow(10.0, -floor(log10(r)));
    sh_vec3 o = cam < r ? s->camera.position : c;
    if (sh_length(o) > 1e2 * r) f.origin = o;
  }
  double rs = r * f.scale, far = sh_length(sh_sub(c, f.origin)) * f.scale;
  /* Only a forced scale, or none, can leave the range. */
  if (rs < 1e-6 || rs > 1e5 || far > 1e5 * rs) {
    char given[40] = "none";
    if (opt->scale_mode == SE_SCALE_FIXED) snprintf(given, sizeof given, "%g", f.scale);
    se_note(notes,
            "with --scale %s the scene is %g units across and %g from Blender's "
            "origin: Cycles and EEVEE compute in single precision and hold about "
            "1e-6 to 1e5 units in radius and 1e5 radii from the origin; expect a "
            "wrong image.",
            given, 2.0 * rs, far);
  }
  if (cam > 3e4 * r)
    se_note(notes,
            "the camera is %g scene radii from the scene's content: Cycles and EEVEE "
            "compute in single precision and hold about 3e4 radii, whatever the "
            "scale and origin; expect a wrong image.",
            cam / r);
  return f;
}

char *se_scale_describe(const se_frame *f) {
  if (f->scale == 1.0 && f->origin.x == 0 && f->origin.y == 0 && f->origin.z == 0)
    return se_printf_alloc("the scene's own units and position");
  return se_printf_alloc("lengths multiplied by %g, the scene point (%.17g, %.17g, %.17g) "
                         "at the origin",
                         f->scale, f->origin.x, f->origin.y, f->origin.z);
}
