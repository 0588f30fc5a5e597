#include "se_scale.h"

#include <math.h>
#include <stdio.h>

#include "sh_camera.h"

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
/* The axis (0, 1, 2) along which unit vector v lies exactly, its sign in
 * *sign; -1 if v is not exactly along an axis. */
static int exact_axis(sh_vec3 v, double *sign) {
  int axis = -1;
  for (int k = 0; k < 3; k++) {
    double x = sh_vget(v, k);
    if (x == 1.0 || x == -1.0) {
      axis = k;
      *sign = x;
    } else if (x != 0.0) {
      return -1;
    }
  }
  return axis;
}

/* Blender's axes for a far camera whose right, up and back vectors lie
 * exactly along scene axes: Blender's X, Y, Z are the camera's right, up
 * and back, a proper rotation (the camera's is right-handed), so the
 * camera's matrix is the identity. Blender keeps a camera's rotation in
 * single precision (up to about 6e-8 radians off the rotation that turns
 * its -Z to the scene's forward): from 1.4e5 scene radii the image was
 * 3.8% off the reference, 56% at 1.4e6 radii; an identity rotation is
 * exact (0.47% at 5 to 1.4e7 radii, validation/precision.py). Returns 0 and leaves f as it is otherwise. */
static int camera_axes(const sh_scene *s, se_frame *f) {
  sh_camera_frame cf;
  sh_camera_frame_init(&s->camera, &cf);
  sh_vec3 v[3] = {cf.right, cf.up, sh_neg(cf.forward)};
  int axis[3];
  double sign[3];
  for (int i = 0; i < 3; i++)
    if ((axis[i] = exact_axis(v[i], &sign[i])) < 0) return 0;
  for (int i = 0; i < 3; i++) {
    f->axis[i] = axis[i];
    f->sign[i] = sign[i];
  }
  return 1;
}

se_frame se_scale_blender(const sh_scene *s, const se_options *opt, se_notes *notes) {
  sh_vec3 c;
  double r;
  se_content_sphere(s, &c, &r);
  double cam = sh_length(sh_sub(s->camera.position, c));
  se_frame f = se_frame_blender(1.0, sh_v3s(0.0));
  if (opt->scale_mode != SE_SCALE_NONE) {
    if (opt->scale_mode == SE_SCALE_FIXED)
      f.scale = opt->scale;
    else if (s->medium.present && s->medium.type == SH_MEDIUM_ATMOSPHERE)
      /* An atmosphere: the air's thickness 10 to 100 units (kilometres for
       * the Earth), as for POV-Ray: Blender's clip start is at least 1e-6
       * units, and the content rule (10^4 km a unit for the Earth) made that
       * 10 m, clipping the ground away below an eye 1 m up. */
      f.scale = pow(10.0, -floor(log10((s->medium.atmo.top_radius -
                                        s->medium.atmo.ground_radius) / 10.0)));
    else if (r < 1e-2 || r > 1e2)
      f.scale = pow(10.0, -floor(log10(r)));
    sh_vec3 o = cam < r ? s->camera.position : c;
    if (sh_length(o) > 1e2 * r) f.origin = o;
  }
  /* A far camera along the scene's axes turned to Blender's: where the
   * medium is a box (height fog's and the atmosphere's nodes take Blender's
   * Z as the scene's up). */
  int aligned = opt->scale_mode != SE_SCALE_NONE && cam > 1e3 * r &&
                (!s->medium.present || s->medium.type == SH_MEDIUM_HOMOGENEOUS) &&
                camera_axes(s, &f);
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
  if (cam > 3e4 * r && !aligned)
    se_note(notes,
            "the camera is %g scene radii from the scene's content: Blender keeps its "
            "rotation in single precision, which holds about 3e4 radii (a camera "
            "looking along a scene axis, with its up along another, is exact in a "
            "medium box or none); expect a wrong image.",
            cam / r);
  return f;
}

static int same_axes(const se_frame *a, const se_frame *b) {
  for (int i = 0; i < 3; i++)
    if (a->axis[i] != b->axis[i] || a->sign[i] != b->sign[i]) return 0;
  return 1;
}

char *se_scale_describe(const se_frame *f) {
  static const char *const names[3] = {"x", "y", "z"};
  char axes[80] = "";
  const se_frame blender = se_frame_blender(1.0, sh_v3s(0.0));
  const se_frame pov = se_frame_pov(1.0, sh_v3s(0.0));
  if (!same_axes(f, &blender) && !same_axes(f, &pov))
    snprintf(axes, sizeof axes, "; the target's axes are the scene's %s%s, %s%s, %s%s",
             f->sign[0] < 0 ? "-" : "+", names[f->axis[0]], f->sign[1] < 0 ? "-" : "+",
             names[f->axis[1]], f->sign[2] < 0 ? "-" : "+", names[f->axis[2]]);
  if (f->scale == 1.0 && f->origin.x == 0 && f->origin.y == 0 && f->origin.z == 0 && !*axes)
    return se_printf_alloc("the scene's own units and position");
  return se_printf_alloc("lengths multiplied by %g, the scene point (%.17g, %.17g, %.17g) "
                         "at the origin%s",
                         f->scale, f->origin.x, f->origin.y, f->origin.z, axes);
}
