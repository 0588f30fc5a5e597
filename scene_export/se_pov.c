#include "se_pov.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "se_geom.h"
#include "se_frame.h"
#include "se_pov_terms.h"
#include "se_scale.h"
#include "se_text.h"
#include "sh_medium.h"
#include "sh_tessellate.h"

/* The state of one export. */
typedef struct pov {
  const sh_scene *scene;
  const se_options *opt;
  se_notes *notes;
  se_buf *b;
  double scale;     /* POV-Ray units per scene unit */
  se_frame frame;   /* the coordinate and unit mapping (se_frame.h) */
  double pov_radius; /* the bounding sphere's radius in POV-Ray units */
  sh_vec3 center;   /* the bounding sphere, in scene units */
  double radius;
  const char *name; /* the output's base name (plain), for the light maps */
  /* The image as the sum of frames (single scattering is linear in the
   * scattering; se_pov.h): an atmosphere with Mie scattering has frame 1
   * for Rayleigh's light and the surfaces' and one frame per Mie lobe; a
   * medium whose phase is a weighted mixture of lobes (Cornette-Shanks)
   * one frame per lobe, the surfaces' light in frame 1. split is
   * nframes > 1; frames after the first hold scattered light only. */
  int split, nframes;
  int nlobes;                          /* the scattering phase's lobes ... */
  se_phase_pov lobes[SE_POV_MAX_LOBES]; /* (the medium's, or Mie's) */
  double lobe_w[SE_POV_MAX_LOBES];     /* and their weights */
} pov;

/* The sign the summing step gives frame f (1-based): the lobes of a
 * signed fit (se_pov_terms.h) with a negative weight are rendered with
 * |w| and subtracted; frame 1 and the other frames are added. */
static int frame_sign(const pov *p, int f) {
  int lobe = p->scene->medium.type == SH_MEDIUM_ATMOSPHERE ? f - 2 : f - 1;
  return f > 1 && lobe >= 0 && lobe < p->nlobes && p->lobe_w[lobe] < 0.0 ? -1 : 1;
}

/* Numbers: 10 significant digits, enough for half-float output. */
static void num(se_buf *b, double v) { se_buf_printf(b, "%.10g", v == 0 ? 0.0 : v); }

/* "x, y, z": a vector's components, without the brackets. */
static void components(se_buf *b, sh_vec3 v) {
  num(b, v.x);
  se_buf_puts(b, ", ");
  num(b, v.y);
  se_buf_puts(b, ", ");
  num(b, v.z);
}

/* "<x, y, z>" after `prefix`. */
static void vector(se_buf *b, const char *prefix, sh_vec3 v) {
  se_buf_printf(b, "%s<", prefix);
  components(b, v);
  se_buf_puts(b, ">");
}

/* A scene-space point and direction in POV-Ray's frame (se_frame.h). */
static void point(pov *p, sh_vec3 v) {
  vector(p->b, "", se_frame_point(&p->frame, v));
}
static void direction(pov *p, sh_vec3 v) {
  vector(p->b, "", se_frame_dir(&p->frame, v));
}
static void colour(se_buf *b, sh_vec3 c) { vector(b, "rgb ", c); }

/* POV-Ray's `matrix` for object-to-world m followed by the scale and the
 * z flip: its rows are the images of x, y, z and the translation, as POV-Ray
 * applies matrices to row vectors. */
static void matrix(pov *p, const sh_mat4 *m) {
  se_buf_puts(p->b, "matrix <");
  for (int col = 0; col < 4; col++)
    for (int row = 0; row < 3; row++) {
      num(p->b, se_frame_matrix(&p->frame, m, row, col));
      if (col < 3 || row < 2) se_buf_puts(p->b, ", ");
    }
  se_buf_puts(p->b, ">");
}

/* The matrix of a card: the unit square of the xy plane to the card, for
 * POV-Ray's image_map, which covers that square. */
static void card_matrix(pov *p, const se_card *c) {
  sh_mat4 m = sh_mat4_identity();
  sh_vec3 cols[4] = {c->ex, c->ey, c->normal, c->origin};
  for (int k = 0; k < 4; k++) {
    m.m[0][k] = cols[k].x;
    m.m[1][k] = cols[k].y;
    m.m[2][k] = cols[k].z;
  }
  matrix(p, &m);
}

static int is_grey(sh_vec3 c) { return c.x == c.y && c.y == c.z; }

/* The summing step's arguments after `oiiotool`: the frames, each after
 * the first added or subtracted by its sign, into NAME.exr. */
static void oiiotool_args(const pov *p, se_buf *b, const char *name) {
  for (int f = 1; f <= p->nframes; f++)
    se_buf_printf(b, " %s%d.exr%s", name, f,
                  f == 1 ? "" : frame_sign(p, f) < 0 ? " --sub" : " --add");
  se_buf_printf(b, " -o %s.exr", name);
}

/* The commands that make the image (se_output.render): POV-Ray in the
 * export's directory, then the summing step when there are frames. */
static void render_command(const pov *p, se_buf *b, const char *pov_path,
                           size_t dir_len, const char *name) {
  if (dir_len > 0) {
    char *dir = se_printf_alloc("%.*s", (int)(dir_len > 1 ? dir_len - 1 : dir_len), pov_path);
    if (!dir) {
      b->failed = 1;
      return;
    }
    se_buf_puts(b, "cd ");
    se_shell_word(b, dir);
    se_buf_puts(b, " && ");
    free(dir);
  }
  se_buf_printf(b, "povray %s.ini", name);
  if (p->split) {
    se_buf_puts(b, " && oiiotool");
    oiiotool_args(p, b, name);
  }
}

static void header(pov *p, const char *name) {
  const char *scene = se_base_name(p->scene->file ? p->scene->file : "scene");
  size_t fn = strlen(scene) + 2;
  char *file = malloc(fn);
  if (file) se_comment_text(scene, file, fn);
  se_buf *b = p->b;
  se_buf_printf(b, "// POV-Ray 3.7 scene exported by scene_export from %s.\n",
                file ? file : "the scene");
  free(file);
  if (p->split) {
    se_buf_printf(b, "// Render it with `povray %s.ini` in this directory: it writes frames\n"
                     "// %s1.exr to %s%d.exr (%s),\n"
                     "// whose signed sum (the .ini's Frame_Signs) is the image:\n// `oiiotool",
                  name, name, name, p->nframes,
                  p->scene->medium.type == SH_MEDIUM_ATMOSPHERE
                      ? "Rayleigh's light and the surfaces', then Mie's, a frame per lobe"
                      : "a frame per lobe of the phase, the surfaces' light in the first");
    oiiotool_args(p, b, name);
    se_buf_puts(b, "`.\n"
                     "// Linear radiance as half-float OpenEXR, one ray through each pixel "
                     "centre.\n");
  } else {
    se_buf_printf(b, "// Render it with `povray %s.ini` in this directory: it writes %s.exr,\n",
                  name, name);
    se_buf_puts(b, "// linear radiance as half-float OpenEXR, one ray through each pixel "
                   "centre.\n");
  }
  se_buf_puts(b, "// Coordinates: the scene's, moved so that ");
  components(b, p->frame.origin);
  se_buf_puts(b, " is at the origin,\n// with z negated (POV-Ray is left-handed) and ");
  se_buf_printf(b, "lengths multiplied by %g\n// (coefficients per unit length divided by it, "
                   "intensities multiplied by its\n// square): the frame scene_export %s, "
                   "where POV-Ray's fixed tolerances\n// of 1e-3 units are negligible%s.\n",
                p->scale,
                p->opt->scale_mode == SE_SCALE_AUTO ? "chose (--scale auto)" : "was given",
                p->opt->scale_mode == SE_SCALE_AUTO ? "" : " unless a note below says otherwise");
  se_notes_comment(p->notes, b, "// ");
  se_buf_puts(b, "\n#version 3.7;\n\n");
}

static int trace_levels(const pov *p) {
  /* POV-Ray counts each crossing of the medium's box as a trace level:
   * allow entering and leaving it on top of the scene's recursion. */
  return p->scene->render.max_depth + 1 + (p->scene->medium.present ? 2 : 0);
}

/* The sun's disks (docs/scene-format.md, "The sun's disk"): a sky_sphere
 * layer per directional light with a disk, its pigment evaluated at the
 * ray's direction on the unit sphere: the background plus irradiance /
 * Omega within the cone (the select's argument is the cosine to the
 * light's direction minus the cone's, in double precision), transparent
 * outside it so that the background shows, as POV-Ray layers sky_sphere
 * pigments over the background. Like the background, it is attenuated by
 * the media the ray crosses. */
static void sun_disks(pov *p) {
  const sh_scene *s = p->scene;
  se_buf *b = p->b;
  int any = 0;
  for (int i = 0; i < s->nlights; i++) {
    const sh_light *l = &s->lights[i];
    if (l->type != SH_LIGHT_DIRECTIONAL || !(l->disk_solid_angle > 0)) continue;
    if (!any++)
      se_buf_puts(b, "// The sun's disks: the background plus irradiance / solid angle in the\n"
                     "// cone around the direction each light comes from.\nsky_sphere {\n");
    sh_vec3 from = se_frame_dir(&p->frame, sh_neg(l->direction));
    se_buf_printf(b, "  // lights[%d]: angular diameter %.10g degrees\n", i,
                  l->angular_diameter_deg);
    se_buf_puts(b, "  pigment {\n    function { select(x * ");
    num(b, from.x);
    se_buf_puts(b, " + y * ");
    num(b, from.y);
    se_buf_puts(b, " + z * ");
    num(b, from.z);
    se_buf_printf(b, " - %.17g, 0, 1, 1) }\n", l->disk_cos_half);
    se_buf_puts(b, "    color_map { [0 rgbt <0, 0, 0, 1>] [1 ");
    colour(b, sh_madd(s->background, l->irradiance, 1.0 / l->disk_solid_angle));
    se_buf_puts(b, "] }\n  }\n");
  }
  if (any) se_buf_puts(b, "}\n\n");
}

static void globals(pov *p) {
  const sh_scene *s = p->scene;
  se_buf *b = p->b;
  se_buf_printf(b,
                "global_settings {\n  assumed_gamma 1.0\n  max_trace_level %d\n"
                "  adc_bailout 1e-10\n  ambient_light rgb <1, 1, 1>\n}\n\n",
                trace_levels(p));
  if (p->split)
    se_buf_puts(b, "// Frames after the first hold scattered light only: no background, no\n"
                   "// sun's disk, and no light reflected by surfaces (SE_Lit 0; mirrors and\n"
                   "// transmission stay).\n"
                   "#declare SE_Lit = (frame_number <= 1 ? 1 : 0);\n"
                   "#if (frame_number <= 1)\n");
  se_buf_puts(b, "background { ");
  colour(b, s->background);
  se_buf_puts(b, " }\n\n");
  sun_disks(p);
  if (p->split) se_buf_puts(b, "#end\n\n");
  double aspect = (double)s->camera.width / s->camera.height;
  double hfov = 2.0 * atan(tan(0.5 * s->camera.fov_y_deg * SH_PI / 180.0) * aspect) *
                180.0 / SH_PI;
  se_buf_puts(b, "// The pinhole camera; `angle` is POV-Ray's horizontal field of view.\n");
  se_buf_puts(b, "camera {\n  perspective\n  location ");
  point(p, s->camera.position);
  se_buf_printf(b, "\n  right x * %.17g\n  up y\n  sky ", aspect);
  direction(p, s->camera.up);
  se_buf_puts(b, "\n  angle ");
  num(b, hfov);
  se_buf_puts(b, "\n  look_at ");
  point(p, s->camera.look_at);
  se_buf_puts(b, "\n}\n\n");
}

/* The medium's box in scene units, enlarged by a hair. */
static void medium_box(const pov *p, sh_vec3 *lo, sh_vec3 *hi) {
  double eps = 1e-4 * p->radius;
  *lo = sh_sub(p->scene->medium.bmin, sh_v3s(eps));
  *hi = sh_add(p->scene->medium.bmax, sh_v3s(eps));
}

/* The surface of a helper object: unlit, of the given pigment; `hidden`
 * keeps camera and reflected rays from seeing it at all. The medium's box
 * must not be hidden: a ray enters its interior (and its media) only by
 * crossing its surface. */
static void helper_texture(se_buf *b, const char *pigment, int hidden) {
  se_buf_printf(b, "  pigment { %s }\n  finish { ambient 0 diffuse 0 emission 0 }\n"
                   "  hollow%s\n", pigment, hidden ? " no_image no_reflection" : "");
}

/* The pigment of light i's card: its map, written next to the .pov as
 * NAME_map<i>.exr, each texel filtering light by its colour. */
static void map_pigment(pov *p, int i) {
  char *file = se_printf_alloc("%s_map%d.exr", p->name, i);
  if (!file) {
    p->b->failed = 1;
    return;
  }
  se_buf_puts(p->b, "  pigment { image_map { exr ");
  se_pov_string(p->b, file);
  free(file);
  se_buf_puts(p->b, " interpolate 2 filter all 1 } }\n");
}

static void spot_or_point(pov *p, int i) {
  const sh_scene *s = p->scene;
  const sh_light *l = &s->lights[i];
  se_buf *b = p->b;
  double f = 1e-4 * p->pov_radius;     /* fade distance */
  double r = 1e-3 * p->pov_radius;     /* the sphere around a light in the medium */
  sh_vec3 lo, hi;
  int inside = 0;
  if (s->medium.present) {
    medium_box(p, &lo, &hi);
    inside = se_in_box(l->position, lo, hi);
  }
  sh_vec3 c = sh_scale(l->intensity, p->scale * p->scale / (2.0 * f * f));
  if (inside) {
    /* The medium's extinction at the light, per POV-Ray unit, over the
     * radius r of the sphere below (r is 1e-3 of the scene: the density
     * of a non-uniform medium hardly changes across it). */
    sh_vec3 st = se_frame_per_length(&p->frame, sh_medium_sigma_t_at(&s->medium, l->position));
    c = sh_mul(c, sh_vexp(sh_scale(st, -r)));
  }
  se_buf_printf(b, "// lights[%d]: %s light, 1/r^2 through fade_power 2 with fade_distance %g.\n",
                i, l->type == SH_LIGHT_SPOT ? "spot" : "point", f);
  se_buf_puts(b, "light_source {\n  ");
  point(p, l->position);
  se_buf_puts(b, "\n  color ");
  colour(b, c);
  if (l->type == SH_LIGHT_SPOT) {
    double outer = l->outer_deg, inner = l->inner_deg;
    if (outer > 90.0)
      se_note(p->notes,
              "lights[%d]: a spot cone of half-angle %g degrees reaches behind the "
              "light, where POV-Ray spotlights give no light; the cone is cut at "
              "90 degrees.",
              i, outer);
    /* POV-Ray takes a falloff of 90 degrees for none at all (measured: a
     * third of the light missing); 89.999 differs from 90 by 2e-5 in cos. */
    if (outer > 89.999) {
      outer = 89.999;
      inner = fmin(inner, outer);
    }
    se_buf_puts(b, "\n  spotlight\n  point_at ");
    point(p, sh_madd(l->position, l->direction, p->radius));
    se_buf_printf(b, "\n  radius %.17g\n  falloff %.17g\n  tightness %.17g", inner,
                  outer, l->exponent);
  }
  se_buf_puts(b, "\n  fade_distance ");
  num(b, f);
  se_buf_puts(b, "\n  fade_power 2\n  media_interaction on\n  media_attenuation on\n}\n");
  if (inside) {
    se_buf_puts(b, "// An invisible sphere around the light, so that shadow rays cross a surface\n"
                   "// just before reaching it and POV-Ray attenuates them by the medium all the way\n"
                   "// but for the radius, which the colour above makes up for.\n");
    se_buf_puts(b, "sphere {\n  ");
    point(p, l->position);
    se_buf_puts(b, ", ");
    num(b, r);
    se_buf_puts(b, "\n");
    helper_texture(b, "rgbt <1, 1, 1, 1>", 1);
    se_buf_puts(b, "}\n");
  }
  if (l->type == SH_LIGHT_SPOT && l->has_map) {
    se_card card = se_spot_card(l, 2e-3 * p->pov_radius / p->scale);
    se_buf_printf(b, "// The light map of lights[%d] as a filter card in front of the light.\n", i);
    se_buf_puts(b, "polygon {\n  5, <0, 0>, <1, 0>, <1, 1>, <0, 1>, <0, 0>\n");
    map_pigment(p, i);
    se_buf_puts(b, "  finish { ambient 0 diffuse 0 emission 0 }\n  hollow no_image no_reflection\n  ");
    card_matrix(p, &card);
    se_buf_puts(b, "\n}\n");
  }
  se_buf_puts(b, "\n");
}

static void directional(pov *p, int i) {
  const sh_light *l = &p->scene->lights[i];
  se_buf *b = p->b;
  double dist = 4.0 * p->radius;
  se_window w;
  if (l->has_map) {
    w = se_window_card(l, p->center, p->radius);
    dist = w.light_distance;
  }
  se_buf_printf(b, "// lights[%d]: directional light, a parallel light beyond the scene.\n", i);
  se_buf_puts(b, "light_source {\n  ");
  point(p, sh_madd(p->center, l->direction, -dist));
  se_buf_puts(b, "\n  color ");
  colour(b, l->irradiance);
  se_buf_puts(b, "\n  parallel\n  point_at ");
  point(p, p->center);
  se_buf_puts(b, "\n  media_interaction on\n  media_attenuation on\n}\n");
  if (l->has_map) {
    se_buf_printf(b, "// The window of lights[%d] as a filter card upstream of the scene, in an\n"
                     "// opaque wall that blocks the light outside the window.\n", i);
    se_buf_puts(b, "polygon {\n  5, <0, 0>, <1, 0>, <1, 1>, <0, 1>, <0, 0>\n");
    map_pigment(p, i);
    se_buf_puts(b, "  finish { ambient 0 diffuse 0 emission 0 }\n  hollow no_image no_reflection\n  ");
    card_matrix(p, &w.card);
    se_buf_puts(b, "\n}\npolygon {\n  10, ");
    double x0 = w.wall_lo_x, y0 = w.wall_lo_y, x1 = w.wall_hi_x, y1 = w.wall_hi_y;
    se_buf_printf(b, "<%.10g, %.10g>, <%.10g, %.10g>, <%.10g, %.10g>, <%.10g, %.10g>, <%.10g, %.10g>,\n",
                  x0, y0, x1, y0, x1, y1, x0, y1, x0, y0);
    se_buf_puts(b, "  <0, 0>, <1, 0>, <1, 1>, <0, 1>, <0, 0>\n");
    helper_texture(b, "rgb <0, 0, 0>", 1);
    se_buf_puts(b, "  ");
    card_matrix(p, &w.card);
    se_buf_puts(b, "\n}\n");
  }
  se_buf_puts(b, "\n");
}

static void material(pov *p, int i) {
  const sh_material *m = &p->scene->materials[i];
  se_buf *b = p->b;
  char name[80];
  se_comment_text(m->name, name, sizeof name);
  se_buf_printf(b, "// materials[%d]: %s\n", i, name);
  se_buf_printf(b, "#macro SE_Material%d()\n", i);
  sh_vec3 kt = m->transmit;
  int transparent = !sh_is_black(kt);
  /* The lit layer's pigment transmit T: POV-Ray 3.7 scales ambient,
   * emission and diffuse by the opacity 1 - filter - transmit, which the
   * colours below undo. A grey k_t < 1 is the lit layer's own transmit; any
   * other k_t is T = 0.5 here and a pure filter layer of colour k_t / T
   * underneath, so that the transmitted light is T * k_t / T = k_t. */
  double T = 0.0;
  int filter_layer = 0;
  if (transparent) {
    if (is_grey(kt) && kt.x < 1.0) T = kt.x;
    else {
      T = 0.5;
      filter_layer = 1;
    }
  }
  double att = 1.0 - T;
  if (filter_layer) {
    se_buf_puts(b, "  texture { pigment { rgbf <");
    num(b, kt.x / T);
    se_buf_puts(b, ", ");
    num(b, kt.y / T);
    se_buf_puts(b, ", ");
    num(b, kt.z / T);
    se_buf_puts(b, ", 1> } finish { ambient 0 diffuse 0 emission 0 } }\n");
  }
  /* Pigment: diffuse / pi (POV-Ray's diffuse has no 1/pi), divided by the
   * opacity. Ambient and emission are multiplied by the pigment, so a
   * channel with emission but no diffuse gets a pigment of 1e-6. */
  sh_vec3 pig = sh_scale(m->diffuse, SH_INV_PI / att);
  sh_vec3 emis = sh_v3s(0.0);
  for (int k = 0; k < 3; k++) {
    double e = sh_vget(m->emission, k);
    double *pc = k == 0 ? &pig.x : k == 1 ? &pig.y : &pig.z;
    double *ec = k == 0 ? &emis.x : k == 1 ? &emis.y : &emis.z;
    if (e > 0) {
      if (*pc <= 0) *pc = 1e-6;
      *ec = e / (*pc * att);
    }
  }
  se_buf_puts(b, "  texture {\n    pigment { rgbt <");
  components(b, pig);
  se_buf_puts(b, ", ");
  num(b, T);
  const char *lit = p->split ? "SE_Lit * " : "";
  const char *lit_rgb = p->split ? "rgb SE_Lit * " : "rgb ";
  se_buf_puts(b, "> }\n    finish {\n      ambient ");
  vector(b, lit_rgb, sh_scale(p->scene->ambient, SH_PI));
  se_buf_puts(b, "\n      emission ");
  vector(b, lit_rgb, emis);
  se_buf_printf(b, "\n      diffuse %s1 brilliance 1\n", lit);
  if (!sh_is_black(m->specular)) {
    double s = m->specular.x;
    if (!is_grey(m->specular)) {
      s = (m->specular.x + m->specular.y + m->specular.z) / 3.0;
      se_note(p->notes,
              "materials[%d] (%s): POV-Ray's phong highlight takes the light's "
              "colour only; the coloured specular is replaced by its grey mean %g.",
              i, name, s);
    }
    se_buf_printf(b, "      phong %s", lit);
    num(b, s);
    se_buf_puts(b, " phong_size ");
    num(b, m->shininess);
    se_buf_puts(b, "\n");
  }
  if (!sh_is_black(m->reflect)) {
    se_buf_puts(b, "      reflection { ");
    colour(b, m->reflect);
    se_buf_puts(b, " }\n");
  }
  se_buf_puts(b, "    }\n  }\n");
  if (transparent) {
    se_buf_puts(b, "  interior { ior ");
    num(b, m->ior);
    se_buf_puts(b, " }\n");
    if (m->ior != 1.0)
      se_note(p->notes,
              "materials[%d] (%s): at total internal reflection POV-Ray sends the "
              "whole ray along the mirror direction, where the reference weights "
              "it by transmit.",
              i, name);
  }
  se_buf_puts(b, "#end\n\n");
}

/* A mesh whose object-space positions are already (q - oo) * k (shape). */
static void mesh2(pov *p, const sh_mesh *m, double k) {
  se_buf *b = p->b;
  se_buf_printf(b, "mesh2 {\n  vertex_vectors { %d", m->nverts);
  for (int v = 0; v < m->nverts; v++) {
    const float *q = m->positions + 3 * v;
    se_buf_printf(b, ",\n    <%.9g, %.9g, %.9g>", q[0] * k, q[1] * k, q[2] * k);
  }
  se_buf_printf(b, "\n  }\n  face_indices { %d", m->ntris);
  for (int t = 0; t < m->ntris; t++) {
    const unsigned *q = m->indices + 3 * t;
    se_buf_printf(b, ",\n    <%u, %u, %u>", q[0], q[1], q[2]);
  }
  se_buf_puts(b, "\n  }\n");
}

/* The size of m's linear part: the geometric mean of its columns' lengths
 * (its scale factor for a uniform scale with any rotation), 1 if a column
 * has no length (the format refuses singular transforms). */
static double linear_size(const sh_mat4 *m) {
  double product = 1.0;
  for (int col = 0; col < 3; col++) {
    double len = sh_length(sh_v3(m->m[0][col], m->m[1][col], m->m[2][col]));
    if (!(len > 0) || !isfinite(len)) return 1.0;
    product *= cbrt(len);
  }
  return product;
}

static sh_status shape(pov *p, int i, sh_error *err) {
  const sh_shape *s = &p->scene->shapes[i];
  se_buf *b = p->b;
  static const char *names[] = {"mesh", "sphere", "box", "cylinder", "quad",
                                "heightfield"};
  se_buf_printf(b, "// shapes[%d]: %s\n", i, names[s->type]);
  /* The object space too is written moved and scaled, (q - oo) k with oo
   * the frame's origin in object space, and the matrix undoes it: POV-Ray's
   * tolerances apply in object space as well (a quad 4e-9 across written
   * as is and scaled by its matrix came out 14% off). k is the frame's
   * scale times the transform's own (linear_size), so that object space
   * has POV-Ray's units and the matrix's linear part, the transform's over
   * its size, is about 1 whatever the scale of the shape's transform (a
   * teapot given at scale 1e-12 was written 1e14 units large under a
   * matrix of 1e-12 and mostly vanished). */
  double k = p->scale * linear_size(&s->xform);
  sh_vec3 oo = sh_xform_point(&s->inv, p->center);
#define SE__Q(v) ((v).x - oo.x) * k, ((v).y - oo.y) * k, ((v).z - oo.z) * k
  switch (s->type) {
  case SH_SHAPE_SPHERE:
    se_buf_printf(b, "sphere {\n  <%.17g, %.17g, %.17g>, %.17g\n", SE__Q(s->center),
                  s->radius * k);
    break;
  case SH_SHAPE_BOX:
    se_buf_printf(b, "box {\n  <%.17g, %.17g, %.17g>, <%.17g, %.17g, %.17g>\n",
                  SE__Q(s->bmin), SE__Q(s->bmax));
    break;
  case SH_SHAPE_CYLINDER:
    se_buf_printf(b, "cylinder {\n  <%.17g, %.17g, %.17g>, <%.17g, %.17g, %.17g>, %.17g%s\n",
                  SE__Q(s->base), SE__Q(s->top), s->radius * k, s->caps ? "" : " open");
    break;
  default: {
    sh_mesh m = {0};
    sh_status st = sh_mesh_tessellate_about(s, 1.0, oo, &m, err);
    if (st != SH_OK) return st;
    mesh2(p, &m, k);
    sh_mesh_free(&m);
    break;
  }
  }
#undef SE__Q
  se_buf_printf(b, "  SE_Material%d()\n  hollow\n  ", s->material);
  sh_mat4 undo = sh_mat4_mul(sh_mat4_translate(oo), sh_mat4_scale(sh_v3s(1.0 / k)));
  sh_mat4 xf = sh_mat4_mul(s->xform, undo);
  matrix(p, &xf);
  se_buf_puts(b, "\n}\n\n");
  return SH_OK;
}

/* The medium's coefficients at the box's lowest point (its densest, for
 * height fog) and, for a non-uniform medium, the POV-Ray density pattern
 * in [0, 1] that scales them: height fog's exp(-(y - y_lo) / H) with y_lo
 * the enlarged box's bottom, in POV-Ray units (y is not mirrored). The
 * density_map is the identity ramp, so the pattern's value is the density
 * (POV-Ray wraps pattern values above 1; min() keeps the bottom hair at 1). */
static double medium_peak(const pov *p, const sh_vec3 lo) {
  const sh_medium *m = &p->scene->medium;
  if (m->type == SH_MEDIUM_HEIGHT_FOG)
    return exp(-(lo.y - m->base_height) / m->scale_height);
  return 1.0;
}

static void medium_density(pov *p, const sh_vec3 lo) {
  const sh_medium *m = &p->scene->medium;
  se_buf *b = p->b;
  if (m->type != SH_MEDIUM_HEIGHT_FOG) return;
  se_buf_puts(b, "      // Height fog: the density relative to the box's bottom.\n"
                 "      density {\n        function { min(1, exp((");
  num(b, se_frame_point(&p->frame, lo).y);
  se_buf_puts(b, " - y) / ");
  num(b, se_frame_length(&p->frame, m->scale_height));
  se_buf_puts(b, ")) }\n        density_map { [0 rgb 0] [1 rgb 1] }\n      }\n");
}

/* The note for a phase POV-Ray only approximates (p->lobes), `what` the
 * scene's key. */
static void lobes_note(pov *p, const char *what, const sh_phase *phase) {
  if (p->lobes[0].exact) return;
  if (p->nlobes == 1) {
    se_note_one_lobe(p->notes, what, "POV-Ray", phase, p->lobes[0].g, "");
    return;
  }
  char list[SE_POV_MAX_LOBES * 40] = "";
  size_t len = 0;
  int negative = 0;
  for (int i = 0; i < p->nlobes && len < sizeof list; i++)
    len += (size_t)snprintf(list + len, sizeof list - len, "%s%.4g (weight %.4g)",
                            i == 0 ? "" : i == p->nlobes - 1 ? " and " : ", ", p->lobes[i].g,
                            p->lobe_w[i]);
  for (int i = 0; i < p->nlobes; i++) negative |= p->lobe_w[i] < 0.0;
  se_note(p->notes,
          "%s: POV-Ray has no %s phase; it is rendered as %d Henyey-Greenstein lobes fitted "
          "to it, g = %s, one frame each%s.",
          what, se_phase_name(phase->type), p->nlobes, list,
          negative ? ", a negative weight's frame subtracted" : "");
}

/* A scattering block of the lobe pp of weight w for scattering `ss` per
 * unit: colour |w| ss / k with `extinction` k / |w| (a negative weight's
 * frame is subtracted: frame_sign) (k = 4 pi times the mean of
 * POV-Ray's k), so that the extinction is the whole ss whatever the lobe's
 * share of the scattering. `indent` before each line. */
static void scattering(pov *p, const se_phase_pov *pp, double w, sh_vec3 ss,
                       const char *indent) {
  se_buf *b = p->b;
  double k = 4.0 * SH_PI * pp->mean;
  se_buf_printf(b, "%sscattering {\n%s  %d, ", indent, indent, pp->type);
  colour(b, sh_scale(ss, fabs(w) / k));
  se_buf_printf(b, "\n%s  extinction ", indent);
  num(b, k / fabs(w));
  if (pp->type == 5) {
    se_buf_printf(b, "\n%s  eccentricity ", indent);
    num(b, pp->g);
  }
  se_buf_printf(b, "\n%s}\n", indent);
}

static void medium(pov *p) {
  const sh_medium *m = &p->scene->medium;
  se_buf *b = p->b;
  lobes_note(p, "medium", &m->phase);
  /* POV-Ray 3.7 holds at most 255 intervals (more: "internal nesting
   * limit"); final quality takes 4 samples in each (with jitter 0, evenly
   * spread: a finer midpoint rule). */
  int final = p->opt->quality == SE_QUALITY_FINAL;
  int intervals = final ? 255 : 200, samples = final ? 4 : 1;
  sh_vec3 lo, hi;
  medium_box(p, &lo, &hi);
  double peak = medium_peak(p, lo);
  sh_vec3 ss = se_frame_per_length(&p->frame, sh_scale(m->sigma_s, peak));
  sh_vec3 sa = se_frame_per_length(&p->frame, sh_scale(m->sigma_a, peak));
  se_buf_puts(b, "// The medium: its box (enlarged by a hair), invisible and hollow, with\n"
                 "// interior media. Method 2 with jitter 0 and equal samples per interval is a\n"
                 "// midpoint rule (with exact transmittance in a homogeneous medium; method 3\n"
                 "// is biased).\n");
  se_buf_printf(b, "// Phase: %s; POV-Ray's k has sphere mean %.9g, so the scattering colour\n"
                   "// is |w| sigma_s / (4 pi mean) and `extinction` 4 pi mean / |w|, w the\n"
                   "// lobe's weight (a negative weight's frame is subtracted).\n",
                p->lobes[0].comment, p->lobes[0].mean);
  if (p->split)
    se_buf_puts(b, "// POV-Ray phases all media in an interior with the plain mean of their\n"
                   "// phases, so each lobe has a frame of its own (media.cpp,\n"
                   "// ComputeMediaScatteringAttenuation: k /= medias.size()).\n");
  se_buf_puts(b, "box {\n  ");
  point(p, sh_v3(lo.x, lo.y, hi.z));
  se_buf_puts(b, ", ");
  point(p, sh_v3(hi.x, hi.y, lo.z));
  se_buf_puts(b, "\n");
  helper_texture(b, "rgbt <1, 1, 1, 1>", 0);
  se_buf_puts(b, "  interior {\n");
  for (int i = 0; i < (p->split ? p->nlobes : 1); i++) {
    if (p->split)
      se_buf_printf(b, "  #if (frame_number %s %d) // lobe %d: g %.4g, weight %.4g\n",
                    i ? "=" : "<=", i + 1, i + 1, p->lobes[i].g, p->lobe_w[i]);
    se_buf_printf(b, "    media {\n      method 2\n      intervals %d\n"
                     "      samples %d, %d\n      jitter 0\n", intervals, samples, samples);
    if (!sh_is_black(ss)) scattering(p, &p->lobes[i], p->lobe_w[i], ss, "      ");
    if (!sh_is_black(sa)) {
      se_buf_puts(b, "      absorption ");
      colour(b, sa);
      se_buf_puts(b, "\n");
    }
    medium_density(p, lo);
    se_buf_puts(b, "    }\n");
    if (p->split) se_buf_puts(b, "  #end\n");
  }
  se_buf_puts(b, "  }\n}\n\n");
}

/* The atmosphere (docs/scene_export.md, "Non-uniform media"): the ground
 * as an opaque Lambert sphere and the air as interior media of the top
 * sphere, one medium per part with its density a function of the distance
 * to the centre. POV-Ray scatters the sum of its media's scattering with
 * the plain mean of their phases k (media.cpp,
 * ComputeMediaScatteringAttenuation: k /= medias.size()), whatever their
 * densities, so no set of media in one interior scatters with Rayleigh's
 * and Mie's phases weighted by their sigma_s at each point. Single
 * scattering is linear in the scattering, though: with Mie (p->split) the
 * export renders a frame per part and lobe, each with the whole extinction
 * and one part's scattering, every medium of that frame carrying that
 * part's phase type (so the mean of the k is that phase exactly): frame 1
 * Rayleigh's (and the surfaces'), frames 2 and on Mie's lobes (one for a
 * POV-Ray phase type, se_phase_to_pov_lobes' fitted lobes for
 * Cornette-Shanks). Their sum is the image. */
/* r, the distance to the centre in POV-Ray units, as a function text. */
static void atmo_radius(pov *p, const sh_atmosphere *a) {
  sh_vec3 c = se_frame_point(&p->frame, a->center);
  const double cc[3] = {c.x, c.y, c.z};
  static const char *const axis[3] = {"(x - ", "(y - ", "(z - "};
  se_buf_puts(p->b, "sqrt(");
  for (int i = 0; i < 3; i++) {
    if (i) se_buf_puts(p->b, " + ");
    se_buf_puts(p->b, axis[i]);
    num(p->b, cc[i]);
    se_buf_puts(p->b, ")*");
    se_buf_puts(p->b, axis[i]);
    num(p->b, cc[i]);
    se_buf_puts(p->b, ")");
  }
  se_buf_puts(p->b, ")");
}

/* A density exp((R_g - r) / H), at most 1 (at the ground). */
static void atmo_exp_density(pov *p, const sh_atmosphere *a, double H) {
  se_buf_puts(p->b, "        density { function { min(1, exp((");
  num(p->b, se_frame_length(&p->frame, a->ground_radius));
  se_buf_puts(p->b, " - ");
  atmo_radius(p, a);
  se_buf_puts(p->b, ") / ");
  num(p->b, se_frame_length(&p->frame, H));
  se_buf_puts(p->b, ")) }\n          density_map { [0 rgb 0] [1 rgb 1] } }\n");
}

/* One media block: its sampling, scattering `ss` per unit with the lobe pp
 * of weight w (scattering()), absorption, and the density, if any (kind
 * 0: none, 1: exp with H, 2: the ozone's tent). */
static void atmo_media(pov *p, const sh_atmosphere *a, const se_phase_pov *pp, double w,
                       sh_vec3 ss, sh_vec3 sa, int kind, double H) {
  se_buf *b = p->b;
  int final = p->opt->quality == SE_QUALITY_FINAL;
  se_buf_printf(b, "    media {\n      method 2\n      intervals %d\n      samples %d, %d\n"
                   "      jitter 0\n",
                final ? 255 : 200, final ? 4 : 1, final ? 4 : 1);
  scattering(p, pp, w, ss, "      ");
  if (!sh_is_black(sa)) {
    se_buf_puts(b, "      absorption ");
    colour(b, sa);
    se_buf_puts(b, "\n");
  }
  if (kind == 1) atmo_exp_density(p, a, H);
  if (kind == 2) {
    se_buf_puts(b, "        density { function { max(0, 1 - abs(");
    atmo_radius(p, a);
    se_buf_puts(b, " - ");
    num(b, se_frame_length(&p->frame, a->ground_radius + a->ozone_height));
    se_buf_puts(b, ") / ");
    num(b, se_frame_length(&p->frame, 0.5 * a->ozone_width));
    se_buf_puts(b, ") }\n          density_map { [0 rgb 0] [1 rgb 1] } }\n");
  }
  se_buf_puts(b, "    }\n");
}

static void atmosphere(pov *p) {
  const sh_atmosphere *a = &p->scene->medium.atmo;
  se_buf *b = p->b;
  sh_phase rayleigh = {SH_PHASE_RAYLEIGH, 0.0};
  se_phase_pov pr = se_phase_to_pov(&rayleigh);
  if (p->split) lobes_note(p, "medium.mie.phase", &a->mie_phase);
  se_buf_puts(b, "// The atmosphere: the ground, an opaque Lambert sphere");
  se_buf_puts(b, p->split ? " (black after frame 1).\nsphere {\n  " : ".\nsphere {\n  ");
  point(p, a->center);
  se_buf_puts(b, ", ");
  num(b, se_frame_length(&p->frame, a->ground_radius));
  se_buf_puts(b, "\n  pigment { ");
  vector(b, p->split ? "rgb SE_Lit * " : "rgb ", sh_scale(a->ground_albedo, SH_INV_PI));
  se_buf_puts(b, " }\n  finish { ambient 0 diffuse 1 emission 0 }\n}\n\n");
  se_buf_puts(b, "// The air: the top sphere's interior, media of one phase type; scattering\n"
                 "// colours |w| sigma_s / (4 pi S) with `extinction` 4 pi S / |w|, S the\n"
                 "// mean of that type's k over the sphere and w the lobe's weight, so that\n"
                 "// the extinction is exact and the in-scattering is |w| sigma_s times the\n"
                 "// lobe (a negative weight's frame is subtracted).\n");
  se_buf_puts(b, "sphere {\n  ");
  point(p, a->center);
  se_buf_puts(b, ", ");
  num(b, se_frame_length(&p->frame, a->top_radius * (1.0 + 1e-9)));
  se_buf_puts(b, "\n");
  helper_texture(b, "rgbt <1, 1, 1, 1>", 0);
  se_buf_puts(b, "  interior {\n");
  const sh_vec3 zero = sh_v3s(0.0);
  const se_frame *f = &p->frame;
  sh_vec3 mie_t = sh_add(a->mie_sigma_s, a->mie_sigma_a);
  for (int frame = 2; frame <= p->nframes; frame++) {
    /* Mie's scattering with lobe frame - 2; Rayleigh's extinction and the
     * ozone as absorbing media of the same lobe. */
    const se_phase_pov *pp = &p->lobes[frame - 2];
    double w = p->lobe_w[frame - 2];
    se_buf_printf(b, "  #if (frame_number = %d) // Mie's light, lobe %d: g %.4g, weight %.4g\n",
                  frame, frame - 1, pp->g, w);
    atmo_media(p, a, pp, w, se_frame_per_length(f, a->mie_sigma_s),
               se_frame_per_length(f, a->mie_sigma_a), 1, a->mie_H);
    atmo_media(p, a, pp, w, zero, se_frame_per_length(f, a->rayleigh_sigma_s), 1,
               a->rayleigh_H);
    if (a->has_ozone)
      atmo_media(p, a, pp, w, zero, se_frame_per_length(f, a->ozone_sigma_a), 2, 0.0);
    se_buf_puts(b, "  #end\n");
  }
  /* Frame 1 (or the only one): Rayleigh's scattering, Mie's extinction
   * (or, without Mie scattering, its absorption) and the ozone. Frame 0,
   * POV-Ray's frame_number without an animation (the .pov rendered
   * without its .ini), is frame 1 too. */
  if (p->split) se_buf_puts(b, "  #if (frame_number <= 1) // Rayleigh's light\n");
  atmo_media(p, a, &pr, 1.0, se_frame_per_length(f, a->rayleigh_sigma_s), zero, 1,
             a->rayleigh_H);
  if (a->has_mie)
    atmo_media(p, a, &pr, 1.0, zero, se_frame_per_length(f, p->split ? mie_t : a->mie_sigma_a),
               1, a->mie_H);
  if (a->has_ozone)
    atmo_media(p, a, &pr, 1.0, zero, se_frame_per_length(f, a->ozone_sigma_a), 2, 0.0);
  if (p->split) se_buf_puts(b, "  #end\n");
  se_buf_puts(b, "  }\n}\n\n");
}

static void ini(const pov *p, se_buf *b, const char *name, const sh_scene *s, int nframes) {
  se_buf_puts(b, "; POV-Ray 3.7 settings written by scene_export: run `povray ");
  se_buf_printf(b, "%s.ini` in this directory.\n", name);
  se_buf_printf(b, "Input_File_Name=%s.pov\n", name);
  if (nframes > 1)
    se_buf_printf(b, "; POV-Ray writes the frames %s1.exr to %s%d.exr, not %s.exr: %s.exr is\n"
                     "; their signed sum, made by the .pov header's oiiotool command.\n",
                  name, name, nframes, name, name);
  se_buf_printf(b, "Output_File_Name=%s.exr\n", name);
  se_buf_puts(b, "; Linear radiance, OpenEXR (POV-Ray writes half floats).\n");
  se_buf_puts(b, "Output_File_Type=E\nOutput_Alpha=Off\n");
  se_buf_printf(b, "Width=%d\nHeight=%d\n", s->camera.width, s->camera.height);
  se_buf_puts(b, "; One ray through each pixel centre.\n");
  se_buf_puts(b, "Antialias=Off\nJitter=Off\nQuality=9\n");
  se_buf_puts(b, "Display=Off\nPause_When_Done=Off\nVerbose=Off\n");
  if (nframes > 1) {
    se_buf_printf(b, "; %d frames, %s1.exr to %s%d.exr: the image is their signed sum, each\n"
                     "; frame added (+) or subtracted (-) as Frame_Signs says (a comment to\n"
                     "; POV-Ray; validation's pov_frames reads it).\n; Frame_Signs=",
                  nframes, name, name, nframes);
    for (int f = 1; f <= nframes; f++)
      se_buf_printf(b, "%s%c", f > 1 ? " " : "", frame_sign(p, f) < 0 ? '-' : '+');
    se_buf_printf(b, "\nInitial_Frame=1\nFinal_Frame=%d\n", nframes);
  }
}

/* POV-Ray's frame (se_scale.h), and the content sphere the tolerances
 * follow. */
static void choose_frame(pov *p) {
  se_content_sphere(p->scene, &p->center, &p->radius);
  p->frame = se_scale_pov(p->scene, p->opt, p->notes);
  p->scale = p->frame.scale;
}

static sh_status se__pov_build(const sh_scene *scene, const se_options *opt,
                               const char *pov_path, const char *base,
                               const char *name, se_output *out,
                               se_notes *notes, sh_error *err);

sh_status se_pov_build(const sh_scene *scene, const se_options *opt,
                       const char *pov_path, se_output *out, se_notes *notes,
                       sh_error *err) {
  size_t n = strlen(pov_path);
  if (n < 5 || strcmp(pov_path + n - 4, ".pov") != 0)
    return sh_error_set(err, SH_ERR_ARG,
                        "the POV-Ray output '%s' must end in .pov", pov_path);
  const char *base = se_base_name(pov_path);
  char *name = se_printf_alloc("%.*s", (int)(strlen(base) - 4), base);
  if (!name) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  sh_status st = se__pov_build(scene, opt, pov_path, base, name, out, notes,
                               err);
  free(name);
  return st;
}

static sh_status se__pov_build(const sh_scene *scene, const se_options *opt,
                               const char *pov_path, const char *base,
                               const char *name, se_output *out,
                               se_notes *notes, sh_error *err) {
  if (!se_is_plain_file_name(name))
    return sh_error_set(err, SH_ERR_ARG,
                        "the POV-Ray output name '%s' must consist of letters, "
                        "digits and '._+-' and not start with '.' or '-' "
                        "(it is written unquoted into the .ini file)",
                        name);
  pov p;
  memset(&p, 0, sizeof p);
  p.scene = scene;
  p.opt = opt;
  p.notes = notes;
  p.name = name;
  choose_frame(&p);
  const sh_medium *med = &scene->medium;
  /* The scattering phase's lobes and the frames they need. */
  int atmo = med->present && med->type == SH_MEDIUM_ATMOSPHERE;
  p.nlobes = se_phase_to_pov_lobes(atmo ? &med->atmo.mie_phase : &med->phase, p.lobes,
                                   p.lobe_w);
  if (atmo)
    p.nframes = med->atmo.has_mie && !sh_is_black(med->atmo.mie_sigma_s) ? 1 + p.nlobes : 1;
  else
    p.nframes = med->present && !sh_is_black(med->sigma_s) ? p.nlobes : 1;
  p.split = p.nframes > 1;
  p.pov_radius = se_frame_length(&p.frame, p.radius);
  out->has_frame = 1;
  out->frame = p.frame;

  /* The body first, so that the header can list every approximation. */
  se_buf body = {0};
  p.b = &body;
  globals(&p);
  for (int i = 0; i < scene->nlights; i++) {
    if (scene->lights[i].type == SH_LIGHT_DIRECTIONAL) directional(&p, i);
    else spot_or_point(&p, i);
  }
  for (int i = 0; i < scene->nmaterials; i++) material(&p, i);
  if (scene->medium.present && scene->medium.type == SH_MEDIUM_ATMOSPHERE)
    atmosphere(&p);
  else if (scene->medium.present)
    medium(&p);
  for (int i = 0; i < scene->nshapes; i++) {
    sh_status st = shape(&p, i, err);
    if (st != SH_OK) {
      se_buf_free(&body);
      return st;
    }
  }

  /* Files: the light maps, the .pov, then the .ini that names them. */
  size_t dir_len = (size_t)(base - pov_path);
  for (int i = 0; i < scene->nlights; i++) {
    if (!scene->lights[i].has_map) continue;
    char *path = se_printf_alloc("%.*s%s_map%d.exr", (int)dir_len, pov_path,
                                 name, i);
    int added = path && se_output_image(out, path, &scene->lights[i].map);
    free(path);
    if (!added) {
      se_buf_free(&body);
      return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
    }
  }
  se_buf *povb = se_output_text(out, pov_path);
  char *ini_path = se_replace_extension(pov_path, ".ini");
  se_buf *inib = ini_path ? se_output_text(out, ini_path) : NULL;
  free(ini_path);
  if (!povb || !inib) {
    se_buf_free(&body);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  p.b = povb;
  header(&p, name);
  if (body.data) se_buf_puts(povb, body.data);
  povb->failed |= body.failed;
  se_buf_free(&body);
  ini(&p, inib, name, scene, p.nframes);
  render_command(&p, &out->render, pov_path, dir_len, name);
  return SH_OK;
}
