#include "se_blender.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "se_blender_atmo.h"
#include "se_geom.h"
#include "se_jsontext.h"
#include "se_cycles_phase.h"
#include "se_frame.h"
#include "se_json.h"
#include "se_scale.h"
#include "se_text.h"
#include "sh_camera.h"
#include "sh_tessellate.h"

/* The state of one export. */
typedef struct blend {
  const sh_scene *scene;
  const se_options *opt;
  se_notes *notes;
  sh_vec3 center;
  double radius;
  const char *name; /* the output's base name, for the light-map files */
  const char *dir;  /* the output's directory, with its slash, dir_len long */
  int dir_len;
  se_output *out;
  se_notes eevee; /* what EEVEE alone approximates: the data's eevee_notes */
  se_frame frame; /* scene space (Y up) to Blender's (Z up): se_frame.h, se_scale.h */
} blend;

/* A scene point in Blender's space. */
static sh_vec3 to_blender(const blend *b, sh_vec3 p) { return se_frame_point(&b->frame, p); }

static json_t *vec(sh_vec3 v) { return json_pack("[fff]", v.x, v.y, v.z); }
/* Appends the three coordinates of scene point p, in Blender's space. */
static void push_point(const blend *b, json_t *a, sh_vec3 p) {
  sh_vec3 v = to_blender(b, p);
  json_array_append_new(a, json_real(v.x));
  json_array_append_new(a, json_real(v.y));
  json_array_append_new(a, json_real(v.z));
}

/* A 4x4 matrix, row-major, from its columns (directions in scene space,
 * unscaled: objects keep unit size) and a translation (a scene point). */
static json_t *frame(const blend *b, sh_vec3 x, sh_vec3 y, sh_vec3 z, sh_vec3 t) {
  const se_frame *f = &b->frame;
  sh_vec3 c[4] = {se_frame_dir(f, x), se_frame_dir(f, y), se_frame_dir(f, z),
                  se_frame_point(f, t)};
  json_t *m = json_array();
  for (int r = 0; r < 3; r++)
    for (int k = 0; k < 4; k++) json_array_append_new(m, json_real(sh_vget(c[k], r)));
  for (int k = 0; k < 4; k++) json_array_append_new(m, json_real(k == 3 ? 1.0 : 0.0));
  return m;
}

/* A colour as a Blender light colour (max channel 1) and a scale. */
static double split_colour(sh_vec3 c, sh_vec3 *unit) {
  double m = sh_max3(c);
  *unit = m > 0 ? sh_scale(c, 1.0 / m) : sh_v3s(1.0);
  return m;
}

/* The camera's clipping distances. Cycles starts a camera ray at
 * clip_start (its origin moved along the ray), and computes in single
 * precision: from a camera 5000 units away, its equiangular sampling of a
 * light (the light's distance from the ray, from |L - P|^2 - (D.(L - P))^2)
 * cancelled, 6.4% off (7% dark). Nothing is drawn nearer than the scene's
 * content (shapes, lights, medium), so a camera outside it starts its rays
 * just before it; clip_end reaches past it. Both keep a margin of 2^-20
 * of the camera's distance from the frame's origin and the content's depth:
 * Cycles computes the start, camera + clip_start D, in single precision
 * (spacing 2^-23 of those), and from a camera 1.7e8 units away a start 3.8
 * units before the content's centre landed in it (2.4% of the light). */
static void clipping(const blend *b, const sh_camera_frame *f, double *start,
                     double *end) {
  double r = b->radius;
  double depth = sh_dot(sh_sub(b->center, f->origin), f->forward);
  double margin = ldexp(sh_length(sh_sub(f->origin, b->frame.origin)) + fabs(depth), -20);
  *start = se_frame_length(&b->frame, fmax(1e-4 * r, depth - 1.1 * r - margin));
  *end = se_frame_length(&b->frame, fmax(100.0 * r, depth + 1.1 * r + margin));
  /* Under a planet's air the content surrounds the camera: start just
   * short of the nearest surface, the ground or the top. */
  const sh_medium *m = &b->scene->medium;
  if (m->present && m->type == SH_MEDIUM_ATMOSPHERE) {
    double atmo = se_frame_length(&b->frame, se_blender_atmo_clip_start(b->scene));
    /* Blender's clip start is at least 1e-6 units: beyond a hundredth of
     * the camera's height (1e-3 is asked for) the ground near it is lost. */
    if (atmo < 1e-8)
      se_note(b->notes,
              "the camera is %g units above the ground or below the top in Blender's "
              "frame, and Blender's clip start is at least 1e-6 units: what lies "
              "nearer the camera than that is not drawn (choose a larger --scale).",
              1e3 * atmo);
    *start = fmin(*start, fmax(atmo, 1e-6));
  }
}

static json_t *camera(blend *b) {
  sh_camera_frame f;
  sh_camera_frame_init(&b->scene->camera, &f);
  double start, end;
  clipping(b, &f, &start, &end);
  return json_pack("{s:o, s:f, s:f, s:f}", "matrix",
                   frame(b, f.right, f.up, sh_neg(f.forward), f.origin), "fov_y",
                   b->scene->camera.fov_y_deg * SH_PI / 180.0, "clip_start", start,
                   "clip_end", end);
}

/* The image of a spot's card that turns Cycles' profile cos(theta) *
 * smoothstep into the format's cos(theta)^exponent * smoothstep (times the
 * light map, if any): texel by texel cos(theta)^(exponent - 1) / k, k the
 * largest value inside the cone, by which the light's power is multiplied.
 * The texels cover the light map's square [-tan outer, tan outer]^2 at unit
 * distance, at the map's resolution (256 x 256 without a map). NULL if out
 * of memory. */
static sh_image *spot_profile_image(const sh_light *l, double *k) {
  double e1 = l->exponent - 1.0;
  *k = e1 < 0 ? pow(l->cos_outer, e1) : 1.0;
  sh_image *img = calloc(1, sizeof *img);
  int w = l->has_map ? l->map.width : 256, h = l->has_map ? l->map.height : 256;
  if (!img || sh_image_alloc(img, w, h, NULL) != SH_OK) {
    free(img);
    return NULL;
  }
  for (int j = 0; j < h; j++)
    for (int i = 0; i < w; i++) {
      double x = (2.0 * (i + 0.5) / w - 1.0) * l->tan_outer;
      double y = (1.0 - 2.0 * (j + 0.5) / h) * l->tan_outer;
      double c = 1.0 / sqrt(1.0 + x * x + y * y);
      double f = pow(c, e1) / *k;
      float *px = img->rgb + 3 * ((size_t)j * w + i);
      const float *m = l->has_map ? l->map.rgb + 3 * ((size_t)j * w + i) : NULL;
      for (int ch = 0; ch < 3; ch++) px[ch] = (float)(f * (m ? m[ch] : 1.0));
    }
  return img;
}

/* Adds an image file NAME_<stem><i>.exr (owned: the output frees it; else
 * borrowed) to the output and the data's images; returns its index, or -1
 * if out of memory. */
static int add_image(blend *b, const char *stem, int i, const sh_image *img, sh_image *owned,
                     json_t *images) {
  /* Heap strings: a fixed buffer cut a long path to another file's name
   * (issue 11, kind 5). */
  char *file = se_printf_alloc("%s_%s%d.exr", b->name, stem, i);
  char *path = file ? se_printf_alloc("%.*s%s", b->dir_len, b->dir, file) : NULL;
  int ok = path && (owned ? se_output_owned_image(b->out, path, owned)
                          : se_output_image(b->out, path, img));
  if (!path && owned) { /* as se_output_owned_image does on failure */
    sh_image_free(owned);
    free(owned);
  }
  if (ok) json_array_append_new(images, json_pack("{s:s}", "file", file));
  free(file);
  free(path);
  return ok ? (int)json_array_size(images) - 1 : -1;
}

/* Adds light l's card with the given image to the data's cards, for one
 * engine ("cycles", "eevee") or, engine NULL, both; a window's card comes
 * with its wall. */
static void add_card(blend *b, const sh_light *l, int image, const char *engine,
                     json_t *cards) {
  se_card c;
  json_t *wall = NULL;
  if (l->type == SH_LIGHT_SPOT) {
    c = se_spot_card(l, 2e-3 * b->radius);
  } else {
    se_window w = se_window_card(l, b->center, b->radius);
    c = w.card;
    /* The wall: the rectangle around the window with the window cut out,
     * eight vertices (outer 0-3, inner 4-7) and eight triangles. */
    double x[2] = {w.wall_lo_x, w.wall_hi_x}, y[2] = {w.wall_lo_y, w.wall_hi_y};
    sh_vec3 p[8] = {se_card_point(&c, x[0], y[0]), se_card_point(&c, x[1], y[0]),
                    se_card_point(&c, x[1], y[1]), se_card_point(&c, x[0], y[1]),
                    se_card_point(&c, 0, 0),       se_card_point(&c, 1, 0),
                    se_card_point(&c, 1, 1),       se_card_point(&c, 0, 1)};
    json_t *v = json_array(), *tri = json_array();
    for (int k = 0; k < 8; k++) push_point(b, v, p[k]);
    static const int idx[24] = {0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5,
                                2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
    for (int k = 0; k < 24; k++) json_array_append_new(tri, json_integer(idx[k]));
    wall = json_pack("{s:s, s:i, s:o, s:o}", "label", "wall", "image", -1, "vertices", v,
                     "triangles", tri);
  }
  sh_vec3 p[4] = {se_card_point(&c, 0, 0), se_card_point(&c, 1, 0),
                  se_card_point(&c, 1, 1), se_card_point(&c, 0, 1)};
  json_t *v = json_array();
  for (int k = 0; k < 4; k++) push_point(b, v, p[k]);
  json_t *card = json_pack("{s:s, s:i, s:o, s:[iiiiii], s:[ffffffff]}", "label",
                           "light map", "image", image, "vertices", v, "triangles", 0, 1, 2,
                           0, 2, 3, "uvs", 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0);
  if (engine) {
    if (wall) json_object_set_new(wall, "engine", json_string(engine));
    if (card) json_object_set_new(card, "engine", json_string(engine));
  }
  if (wall) json_array_append_new(cards, wall);
  json_array_append_new(cards, card);
}

/* The sun's disks (docs/scene-format.md, "The sun's disk") for the world
 * shader, which draws them where camera, mirror and refracted rays leave
 * the scene: per directional light with a disk, the direction towards the
 * sun (Blender's frame), the chord |d - s| at the disk's edge, 2 sin(half
 * angle / 2), which the shader tests in single precision without the loss
 * of 1 - cos, and the radiance irradiance / Omega. */
static json_t *sun_disks(const blend *b) {
  const sh_scene *s = b->scene;
  json_t *a = json_array();
  for (int i = 0; a && i < s->nlights; i++) {
    const sh_light *l = &s->lights[i];
    if (l->type != SH_LIGHT_DIRECTIONAL || !(l->disk_solid_angle > 0)) continue;
    json_array_append_new(
        a, json_pack("{s:o, s:f, s:o}", "direction",
                     vec(se_frame_dir(&b->frame, sh_neg(l->direction))), "chord",
                     sqrt(l->disk_solid_angle / SH_PI), "radiance",
                     vec(sh_scale(l->irradiance, 1.0 / l->disk_solid_angle))));
  }
  return a;
}

static json_t *light(blend *b, int i, json_t *images, json_t *cards) {
  const sh_light *l = &b->scene->lights[i];
  sh_vec3 unit, t, bt;
  json_t *o;
  sh_image *profile = NULL; /* a spot's profile card for Cycles, when it needs one */
  if (l->type == SH_LIGHT_DIRECTIONAL) {
    double e = split_colour(l->irradiance, &unit);
    /* The lamp's angle stays 0: the format shades with one direction, and
     * a Cycles 3.4 sun lamp with an angle is seen by no camera ray (a 10
     * degree sun straight ahead rendered 0 on a black world); the disk is
     * drawn by the world instead (sun_disks). */
    sh_basis(l->direction, &t, &bt);
    o = json_pack("{s:s, s:o, s:o, s:f}", "type", "SUN", "matrix",
                  frame(b, t, bt, sh_neg(l->direction),
                        sh_madd(b->center, l->direction, -2.0 * b->radius)),
                  "color", vec(unit), "energy", e);
  } else {
    /* Blender: a point light of P watts has intensity P / (4 pi) W/sr; a spot
     * light the same on its axis. The intensity in the frame's units. */
    double e = 4.0 * SH_PI * split_colour(se_frame_intensity(&b->frame, l->intensity), &unit);
    if (l->type == SH_LIGHT_POINT) {
      o = json_pack("{s:s, s:o, s:o, s:f}", "type", "POINT", "matrix",
                    frame(b, sh_v3(1, 0, 0), sh_v3(0, 1, 0), sh_v3(0, 0, 1), l->position),
                    "color", vec(unit), "energy", e);
    } else {
      double outer = l->outer_deg;
      if (outer > 90.0) {
        se_note(b->notes,
                "lights[%d]: Blender's spot cone is at most 180 degrees wide; the "
                "half-angle %g is cut to 90.",
                i, outer);
        outer = 90.0;
      }
      if (outer < 0.5) {
        /* bpy clamps spot_size to [1, 180] degrees without a word. */
        se_note(b->notes,
                "lights[%d]: Blender's spot cone is at least 1 degree wide "
                "(spot_size); the half-angle %g is widened to 0.5, with the same "
                "intensity on the axis (%.3g times the cone's power).",
                i, outer, (1.0 - cos(0.5 * SH_PI / 180.0)) / (1.0 - l->cos_outer));
        outer = 0.5;
      }
      double co = cos(outer * SH_PI / 180.0);
      double ci = cos(fmin(l->inner_deg, outer) * SH_PI / 180.0);
      double blend = co < 1.0 ? (ci - co) / (1.0 - co) : 0.0;
      /* Cycles 3.4 spots carry cos(theta), the format's exponent 1; another
       * exponent takes a card that filters by cos(theta)^(exponent - 1).
       * EEVEE's spot is the plain smoothstep (lights_lib.glsl,
       * spot_attenuation), the format's exponent 0, and its hashed shadows
       * ignore a card's partly transparent texels (a cos card of 0.78 to 1
       * changed nothing, measured): EEVEE gets neither the card nor its
       * power factor. */
      double e_eevee = e;
      if (l->exponent != 1.0 && outer <= 80.0) {
        double k;
        profile = spot_profile_image(l, &k);
        if (!profile) return NULL;
        e *= k;
      } else if (l->exponent != 1.0) {
        se_note(b->notes,
                "lights[%d]: a Cycles 3.4 spot multiplies its profile by cos(theta), "
                "the format's exponent 1, and a cone over 80 degrees takes no "
                "correcting card; the exponent %g is rendered as 1 (off by "
                "cos(theta)^%g, a factor %.4g at the cone's edge).",
                i, l->exponent, l->exponent - 1.0, pow(co, l->exponent - 1.0));
      }
      if (l->exponent != 0.0)
        se_note(&b->eevee,
                "lights[%d]: EEVEE's spot has no cos(theta) term (the format's "
                "exponent 0), and a card cannot add it (EEVEE's hashed shadows "
                "ignore partly transparent texels); the exponent %g is rendered as 0 "
                "(off by cos(theta)^%g, a factor %.4g at the cone's edge).",
                i, l->exponent, l->exponent, pow(co, l->exponent));
      sh_basis(l->direction, &t, &bt);
      o = json_pack("{s:s, s:o, s:o, s:f, s:f, s:f}", "type", "SPOT", "matrix",
                    frame(b, t, bt, sh_neg(l->direction), l->position), "color", vec(unit),
                    "energy", e, "spot_size", 2.0 * outer * SH_PI / 180.0, "spot_blend",
                    blend);
      if (o && e_eevee != e) json_object_set_new(o, "eevee_energy", json_real(e_eevee));
    }
  }
  if (!o) {
    if (profile) {
      sh_image_free(profile);
      free(profile);
    }
    return NULL;
  }
  if (l->has_map)
    se_note(&b->eevee,
            "lights[%d]: EEVEE's hashed shadows hold no colour and ignore partly "
            "transparent texels: the light map's card casts grey shadows of its "
            "nearly opaque texels only (sun_window: scale 0.82, docs/scene_export.md).",
            i);
  /* The light map, or the profile (times the map) for Cycles and the plain
   * map for EEVEE: image files and cards. */
  int ok = 1;
  if (profile) {
    int image = add_image(b, "blender_map", i, NULL, profile, images);
    ok = image >= 0;
    if (ok) add_card(b, l, image, "cycles", cards);
    if (ok && l->has_map) {
      image = add_image(b, "blender_eevee_map", i, &l->map, NULL, images);
      ok = image >= 0;
      if (ok) add_card(b, l, image, "eevee", cards);
    }
  } else if (l->has_map) {
    int image = add_image(b, "blender_map", i, &l->map, NULL, images);
    ok = image >= 0;
    if (ok) add_card(b, l, image, NULL, cards);
  }
  if (!ok) {
    json_decref(o);
    return NULL;
  }
  return o;
}

static json_t *material(blend *b, int i) {
  const sh_material *m = &b->scene->materials[i];
  char name[80];
  se_comment_text(m->name, name, sizeof name);
  json_t *o = json_pack("{s:s, s:o, s:o, s:o, s:f}", "label", name, "diffuse",
                        vec(m->diffuse), "mirror", vec(m->reflect), "transmit",
                        vec(m->transmit), "ior", m->ior);
  if (!o) return NULL;
  /* Emission, plus the constant ambient term ambient * diffuse. */
  sh_vec3 e = sh_add(m->emission, sh_mul(b->scene->ambient, m->diffuse));
  json_object_set_new(o, "emission", vec(e));
  if (!sh_is_black(m->specular)) {
    /* The Phong highlight specular (R.V)^n E reflects, at normal incidence,
     * about specular 2 pi / (n + 2) of the light; a Glossy BSDF with that
     * colour and the Beckmann roughness of a Blinn lobe of exponent 4n
     * (alpha = sqrt(2 / (4n + 2)), roughness = sqrt(alpha)) has a similar
     * highlight. */
    double n = m->shininess;
    double alpha = sqrt(2.0 / (4.0 * n + 2.0));
    sh_vec3 c = sh_scale(m->specular, 2.0 * SH_PI / (n + 2.0));
    c = sh_vmin(c, sh_v3s(1.0));
    json_object_set_new(o, "glossy", vec(c));
    json_object_set_new(o, "roughness", json_real(fmin(sqrt(alpha), 1.0)));
    se_note(b->notes,
            "materials[%d] (%s): Cycles has no Phong highlight; it is a Glossy BSDF "
            "of similar lobe and reflectance, which also reflects other surfaces "
            "dimly.",
            i, name);
  }
  if (!sh_is_black(m->transmit) && m->ior != 1.0)
    se_note(b->notes,
            "materials[%d] (%s): at total internal reflection Cycles' sharp "
            "Refraction BSDF reflects nothing, where the reference sends the "
            "transmit weight along the mirror direction.",
            i, name);
  return o;
}

static int det_negative(const sh_mat4 *m) {
  double a = m->m[0][0], bb = m->m[0][1], c = m->m[0][2];
  double d = m->m[1][0], e = m->m[1][1], f = m->m[1][2];
  double g = m->m[2][0], h = m->m[2][1], k = m->m[2][2];
  return a * (e * k - f * h) - bb * (d * k - f * g) + c * (d * h - e * g) < 0;
}

static sh_status shape(blend *b, int i, json_t *meshes, sh_error *err) {
  const sh_shape *s = &b->scene->shapes[i];
  int curved = s->type == SH_SHAPE_SPHERE || s->type == SH_SHAPE_CYLINDER;
  double size = s->radius; /* sphere and cylinder; unused for the others */
  double rel = b->opt->quality == SE_QUALITY_FINAL ? 2e-4 : 1e-3;
  /* The float positions about the frame's origin in object space, where
   * they keep their precision however far the shape lies from the scene's
   * origin (an export left in place keeps the plain tessellation). */
  const sh_vec3 fo = b->frame.origin;
  sh_vec3 oo = fo.x == 0 && fo.y == 0 && fo.z == 0 ? fo : sh_xform_point(&s->inv, fo);
  sh_mesh m = {0};
  sh_status st = sh_mesh_tessellate_about(s, curved ? rel * size : 1.0, oo, &m, err);
  if (st != SH_OK) return st;
  json_t *v = json_array(), *t = json_array();
  for (int k = 0; k < m.nverts; k++) {
    const float *q = m.positions + 3 * k;
    push_point(b, v, sh_xform_point(&s->xform, sh_add(oo, sh_v3(q[0], q[1], q[2]))));
  }
  /* A mirroring transform turns the triangles inside out: swap two corners
   * to keep them counter-clockwise seen from outside. */
  int flip = det_negative(&s->xform);
  for (int k = 0; k < m.ntris; k++) {
    const unsigned *q = m.indices + 3 * k;
    json_array_append_new(t, json_integer(q[0]));
    json_array_append_new(t, json_integer(q[flip ? 2 : 1]));
    json_array_append_new(t, json_integer(q[flip ? 1 : 2]));
  }
  sh_mesh_free(&m);
  static const char *names[] = {"mesh", "sphere", "box", "cylinder", "quad",
                                "heightfield"};
  json_t *o = json_pack("{s:s, s:i, s:b, s:o, s:o}", "label", names[s->type],
                        "material", s->material, "smooth", curved, "vertices", v,
                        "triangles", t);
  if (!o) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  json_array_append_new(meshes, o);
  if (curved)
    se_note(b->notes,
            "shapes[%d]: Cycles has no exact %s; it is tessellated within %g of "
            "the surface and smooth-shaded.",
            i, names[s->type], rel * size);
  return SH_OK;
}

/* The data's "height_fog" object (scale_height in the frame's units):
 * Blender's Z is the scene's Y, and the
 * coefficients written are those at the box's bottom z_lo (its densest
 * point), so the density factor exp((z_lo - z) / H) stays in [0, 1] in
 * single precision however far the box lies from base_height. Cycles
 * ray-marches a varying density in steps of 0.1 of the box's mean extent
 * times the material's step rate (Cycles 3.4, Object::compute_volume_step_size):
 * the rate makes the step H / 16 (the density changes by 6% over a step),
 * and volume_max_steps lets a ray cross the box's diagonal in such steps. */
static json_t *height_fog(double scale_height, sh_vec3 blo, sh_vec3 bhi) {
  sh_vec3 size = sh_sub(bhi, blo);
  double mean = (size.x + size.y + size.z) / 3.0;
  double step = scale_height / 16.0;
  double rate = fmin(1.0, step / (0.1 * mean));
  double steps = ceil(1.5 * sh_length(size) / (0.1 * mean * rate));
  return json_pack("{s:f, s:f, s:f, s:i}", "bottom", blo.z, "scale_height",
                   scale_height, "step_rate", rate, "max_steps",
                   (int)fmin(65536.0, fmax(1024.0, steps)));
}

static json_t *medium(blend *b) {
  const sh_medium *m = &b->scene->medium;
  double eps = 1e-4 * b->radius;
  sh_vec3 lo = to_blender(b, sh_sub(m->bmin, sh_v3s(eps)));
  sh_vec3 hi = to_blender(b, sh_add(m->bmax, sh_v3s(eps)));
  sh_vec3 blo = sh_vmin(lo, hi), bhi = sh_vmax(lo, hi);
  /* The coefficients at the box's bottom (scene height bmin.y - eps) for
   * height fog (above), else everywhere; per unit length of the frame. */
  double peak = m->type == SH_MEDIUM_HEIGHT_FOG
                    ? exp(-(m->bmin.y - eps - m->base_height) / m->scale_height)
                    : 1.0;
  const sh_vec3 sigma_s = se_frame_per_length(&b->frame, sh_scale(m->sigma_s, peak));
  const sh_vec3 sigma_a = se_frame_per_length(&b->frame, sh_scale(m->sigma_a, peak));
  int exact;
  double gs[SE_HG_MAX_LOBES];
  int n = se_phase_to_hg_lobes(&m->phase, gs, &exact);
  sh_vec3 unit;
  double ds = split_colour(sigma_s, &unit);
  /* Cycles drops a closure whose mean weight is below 1e-5 (its
   * CLOSURE_WEIGHT_CUTOFF) but keeps its extinction: a mixture is used only
   * while every lobe stays well above that. */
  if (n > 1 && ds * (unit.x + unit.y + unit.z) / 3.0 / ((double)n * n) < 1e-4) {
    gs[0] = se_phase_to_hg(&m->phase, &exact);
    n = 1;
  }
  double g1 = se_phase_to_hg(&m->phase, &exact);
  if (!exact && n > 1)
    se_note(b->notes,
            "medium: Cycles has no %s phase; it is an equal-weight mixture of %d "
            "Henyey-Greenstein lobes fitted to it (EEVEE: one lobe, g = %.4g, its "
            "mean cosine).",
            se_phase_name(m->phase.type), n, g1);
  else if (!exact)
    se_note_one_lobe(b->notes, "medium", "Cycles", &m->phase, g1,
                     m->phase.type == SH_PHASE_HENYEY_GREENSTEIN ? " clamped to Cycles' range"
                                                                 : "");
  /* One Principled Volume for both engines (Cycles' svm_node_principled_volume
   * and EEVEE's node_volume_principled compute the same coefficients):
   * sigma_s = Color Density, sigma_a = (1 - Color) (1 - sqrt(Absorption
   * Color)) Density, Henyey-Greenstein g = Anisotropy. With Density the
   * largest extinction, Color = sigma_s / Density <= 1, and sqrt(Absorption
   * Color) = 1 - sigma_a / (Density - sigma_s) per channel (any value where
   * Density = sigma_s, which leaves no absorption). One closure, so EEVEE
   * keeps g (it averages the g of closures joined by an Add Shader, the
   * absorption's 0 included). */
  sh_vec3 st = sh_add(sigma_s, sigma_a);
  double dt = sh_max3(st);
  double c[3], ac[3];
  for (int k = 0; k < 3; k++) {
    double ss = sh_vget(sigma_s, k), sa = sh_vget(sigma_a, k);
    c[k] = dt > 0 ? fmin(ss / dt, 1.0) : 0.0;
    double room = dt - ss; /* what the channel's absorption may take */
    double root = room > 0 ? fmax(1.0 - sa / room, 0.0) : 1.0;
    ac[k] = root * root;
  }
  json_t *o = json_pack("{s:o, s:o, s:o, s:{s:[fff], s:f, s:[fff], s:f}}", "min", vec(blo),
                        "max", vec(bhi), "sigma_t", vec(st), "volume", "color", c[0], c[1],
                        c[2], "density", dt, "absorption_color", ac[0], ac[1], ac[2],
                        "anisotropy", g1);
  if (o && m->type == SH_MEDIUM_HEIGHT_FOG)
    json_object_set_new(o, "height_fog",
                        height_fog(se_frame_length(&b->frame, m->scale_height), blo, bhi));
  if (o && n > 1) {
    /* Cycles' mixture: n Volume Scatter lobes of density sigma_s / n^2 (it
     * sums their phases unweighted, se_cycles_phase.h) and the scattering
     * they leave out, sigma_s (1 - 1/n), as Volume Absorption. EEVEE, which
     * averages the g of added closures, keeps the Principled Volume with the
     * mean cosine. */
    json_t *scatter = json_array();
    for (int i = 0; ds > 0 && i < n; i++)
      json_array_append_new(scatter, json_pack("{s:o, s:f, s:f}", "color", vec(unit),
                                               "density", ds / ((double)n * n),
                                               "anisotropy", gs[i]));
    json_t *mix = json_pack("{s:o}", "scatter", scatter);
    sh_vec3 sa = sh_add(sigma_a, sh_scale(sigma_s, 1.0 - 1.0 / n));
    double da = sh_max3(sa);
    if (mix && da > 0)
      json_object_set_new(mix, "absorption",
                          json_pack("{s:o, s:f}", "color",
                                    vec(sh_sub(sh_v3s(1.0), sh_scale(sa, 1.0 / da))),
                                    "density", da));
    if (mix) json_object_set_new(o, "cycles_mixture", mix);
  }
  return o;
}

sh_status se_blender_build(const sh_scene *scene, const se_options *opt,
                           const char *py_path, se_output *out, se_notes *notes,
                           sh_error *err) {
  size_t n = strlen(py_path);
  if (n < 4 || strcmp(py_path + n - 3, ".py") != 0)
    return sh_error_set(err, SH_ERR_ARG, "the Blender output '%s' must end in .py",
                        py_path);
  const char *base = se_base_name(py_path);
  size_t name_len = strlen(base) - 3;
  if (name_len == 0)
    return sh_error_set(err, SH_ERR_ARG, "the Blender output '%s' has no name", py_path);
  /* Side files (light maps) get a plain version of the name: Blender reads
   * backslashes in image paths as directory separators. */
  char *name = malloc(name_len + 1);
  if (!name) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  memcpy(name, base, name_len);
  name[name_len] = '\0';
  se_plain_name(name, name, name_len + 1);
  blend b = {scene, opt, notes, {0, 0, 0}, 0, name, py_path,
             (int)(base - py_path), out, {0}, se_scale_blender(scene, opt, notes)};
  se_content_sphere(scene, &b.center, &b.radius);
  out->has_frame = 1;
  out->frame = b.frame;
  char *frame_text = se_scale_describe(&b.frame);
  char *comment = frame_text ? se_printf_alloc(
      "Data for the fixed script next to this file (scene_export --to blender). "
      "Blender coordinates (Z up, or as the frame's axes say), metres, radians, "
      "watts; from the scene: %s "
      "(docs/scene_export.md, \"Precision\").", frame_text) : NULL;
  free(frame_text);
  /* The frame's axes as the scene's: Blender's X is the scene's "+x", ... */
  char axis_names[3][3];
  for (int i = 0; i < 3; i++)
    snprintf(axis_names[i], sizeof axis_names[i], "%c%c", b.frame.sign[i] < 0 ? '-' : '+',
             "xyz"[b.frame.axis[i]]);
  if (!comment) {
    free(name);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }

  json_t *images = json_array(), *cards = json_array(), *lights = json_array();
  json_t *materials = json_array(), *meshes = json_array();
  sh_status st = SH_OK;
  for (int i = 0; st == SH_OK && i < scene->nlights; i++) {
    json_t *o = light(&b, i, images, cards);
    if (!o) st = sh_error_set(err, SH_ERR_NOMEM, "out of memory");
    json_array_append_new(lights, o);
  }
  for (int i = 0; i < scene->nmaterials; i++)
    json_array_append_new(materials, material(&b, i));
  for (int i = 0; st == SH_OK && i < scene->nshapes; i++) st = shape(&b, i, meshes, err);
  int samples = opt->quality == SE_QUALITY_FINAL ? 1024 : 64;
  json_t *root = json_pack(
      "{s:s, s:i, s:s, s:{s:f, s:[fff], s:[sss]}, s:{s:i, s:i, s:i, s:i, s:i, s:I}, "
      "s:{s:o}, s:o, s:o, s:o, s:o, s:o, s:o}",
      "format", "shafts-blender", "version", 1, "comment", comment, "frame", "scale",
      b.frame.scale, "origin", b.frame.origin.x, b.frame.origin.y, b.frame.origin.z,
      "axes", axis_names[0], axis_names[1], axis_names[2],
      "render", "width", scene->camera.width, "height", scene->camera.height,
      "max_depth", scene->render.max_depth, "samples_cycles", samples, "samples_eevee",
      opt->quality == SE_QUALITY_FINAL ? 64 : 16, "seed", (json_int_t)scene->render.seed,
      "world", "background", vec(scene->background), "camera", camera(&b), "lights",
      lights, "materials", materials, "meshes", meshes, "images", images, "cards",
      cards);
  if (root && scene->medium.present && scene->medium.type == SH_MEDIUM_ATMOSPHERE)
    json_object_set_new(root, "medium",
                        se_blender_atmosphere(scene, &b.frame, materials, meshes, notes));
  else if (root && scene->medium.present)
    json_object_set_new(root, "medium", medium(&b));
  /* The scene's own medium (its units and frame), which the add-on's
   * medium properties take (blender_build.medium_properties): its import
   * reads height fog and the atmosphere from them exactly. */
  json_t *medium_data = root ? json_object_get(root, "medium") : NULL;
  if (medium_data) json_object_set_new(medium_data, "scene", se_json_medium(&scene->medium));
  if (root) json_object_set_new(json_object_get(root, "world"), "sun_disks", sun_disks(&b));
  if (root) {
    /* The notes as sentences (a JSON string is data, so the punctuation
     * stays; the add-on's import shows them as its warnings); a note that
     * is not valid UTF-8 is sanitised as for a comment. */
    json_t *nt = json_array();
    for (int i = 0; i < notes->count; i++) {
      json_t *t = json_string(notes->text[i]);
      if (!t) {
        char line[1100];
        se_comment_text(notes->text[i], line, sizeof line);
        t = json_string(line);
      }
      json_array_append_new(nt, t);
    }
    json_object_set_new(root, "notes", nt);
    /* What EEVEE alone approximates (the script prints these when it
     * renders with EEVEE; they are no approximation of the export, so
     * --strict does not refuse them). */
    if (scene->medium.present && scene->nlights > 1)
      se_note(&b.eevee,
              "EEVEE does not attenuate the light reaching a surface through the "
              "medium, and with one light the script multiplies the surfaces' "
              "diffuse and glossy colours by that light's transmittance; with %d "
              "lights it cannot, so surfaces in or behind the medium are too bright.",
              scene->nlights);
    json_t *en = json_array();
    for (int i = 0; i < b.eevee.count; i++)
      json_array_append_new(en, json_string(b.eevee.text[i]));
    json_object_set_new(root, "eevee_notes", en);
    if (b.eevee.failed) st = sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  }
  if (st == SH_OK && !root) st = sh_error_set(err, SH_ERR_NOMEM, "out of memory");

  /* Files: the light maps (added by light()), the data, then the script
   * that reads them. */
  if (st == SH_OK) {
    char *json_path = se_replace_extension(py_path, ".blender.json");
    se_buf *jb = json_path ? se_output_text(out, json_path) : NULL;
    se_buf *pb = jb ? se_output_text(out, py_path) : NULL;
    free(json_path);
    if (!pb) {
      st = sh_error_set(err, SH_ERR_NOMEM, "out of memory");
    } else {
      se_json_text(jb, root, 0);
      se_buf_puts(jb, "\n");
      se_buf_append(pb, (const char *)se_blender_script, se_blender_script_size);
      /* The command that renders it (se_output.render), into NAME.exr. */
      char *exr = se_replace_extension(py_path, ".exr");
      if (!exr) st = sh_error_set(err, SH_ERR_NOMEM, "out of memory");
      else {
        se_buf_puts(&out->render, "blender -b -P ");
        se_shell_word(&out->render, py_path);
        se_buf_puts(&out->render, " -- --engine cycles --out ");
        se_shell_word(&out->render, exr);
        free(exr);
      }
    }
  }
  json_decref(root);
  se_notes_free(&b.eevee);
  free(comment);
  free(name);
  return st;
}
