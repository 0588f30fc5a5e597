/* The sun's disk in gl_shafts (docs/scene-format.md, "The sun's disk"):
 * the image with the disk minus the image without it is, per pixel, the
 * disk's radiance times the medium's transmittance where the pixel's ray
 * lies in the cone, 0 elsewhere, as in the reference (sh_light_disk_radiance
 * and sh_reference_disk_test.c). Checked against the closed form at the
 * disk's centre, against the reference's set of disk pixels (the rays at
 * the edge may fall either way in single precision: at most 2% of them),
 * baked and live (gs_options.live), and in a kept renderer whose scene
 * patch turns the disk on and then changes its size. */
#include <stdio.h>
#include <string.h>

#include "sh_camera.h"
#include "sh_test.h"
#include "shafts.h"
#include "test_util.h"

/* The camera looks at the sun's centre through an absorbing and
 * scattering box; the middle of the 96x72 image is the ray at the disk's
 * centre (pixel spacing 0.42 degrees: the 4 degree disk is about 10 pixels
 * across, 68 of them). */
#define SCENE(diameter)                                                      \
  "{\"format\": \"shafts-scene\", \"version\": 1,"                           \
  " \"camera\": {\"position\": [0, 0, 0], \"look_at\": [0, 0.3, -1],"        \
  "  \"fov_y_deg\": 30, \"width\": 96, \"height\": 72},"                     \
  " \"background\": [0.1, 0.05, 0.02],"                                      \
  " \"medium\": {\"sigma_s\": [0.05, 0.05, 0.05],"                           \
  "  \"sigma_a\": [0.1, 0.2, 0.3],"                                          \
  "  \"bounds\": {\"min\": [-2, -1, -4], \"max\": [2, 3, -1]}},"             \
  " \"lights\": [{\"type\": \"directional\", \"direction\": [0, -0.3, 1],"   \
  "  \"irradiance\": [2, 3, 4], \"angular_diameter_deg\": " diameter "}]}"

static const double IRR[3] = {2, 3, 4}, SIGMA_T[3] = {0.15, 0.25, 0.35};

/* The disk's part of img: img - base, where above 10 in green (the
 * disk's green radiance there is about 360, the rest below 1). Counts the
 * disk's pixels into *n and returns the green difference at the pixel
 * (48, 36), whose ray passes 0.29 degrees from the disk's centre. */
static double disk_part(const sh_image *img, const sh_image *base, int *n) {
  *n = 0;
  for (int i = 0; i < img->width * img->height; i++)
    if (img->rgb[3 * i + 1] - base->rgb[3 * i + 1] > 10) (*n)++;
  int c = 3 * (36 * img->width + 48);
  return img->rgb[c + 1] - base->rgb[c + 1];
}

/* The closed form at pixel (48, 36): irradiance / Omega times the
 * transmittance along its ray, which crosses the box from z = -1 to -4. */
static double closed_form(const sh_scene *s) {
  sh_camera_frame frame;
  sh_camera_frame_init(&s->camera, &frame);
  sh_vec3 d = sh_camera_dir(&frame, 48.5, 36.5);
  double omega = 2 * SH_PI * (1 - cos(2 * SH_PI / 180));
  double len = 3.0 / fabs(d.z) * sh_length(d);
  return IRR[1] / omega * exp(-SIGMA_T[1] * len);
}

static void check(const char *name, const sh_image *with,
                  const sh_image *without, int nref, double want) {
  int n;
  double got = disk_part(with, without, &n);
  char what[256];
  snprintf(what, sizeof what,
           "%s: disk %.6g at the centre (closed form %.6g), %d pixels "
           "(reference %d)",
           name, got, want, n, nref);
  tu_check(fabs(got - want) <= 1e-4 * want && abs(n - nref) <= nref / 50,
           what);
}

int main(void) {
  sh_scene *with = tu_scene(SCENE("4")), *without = tu_scene(SCENE("0"));
  if (!with || !without) return 1;
  sh_image rw = {0}, ro = {0}, gw = {0}, go = {0};
  int nref = 0;
  if (tu_reference(with, 4, &rw) != SH_OK ||
      tu_reference(without, 4, &ro) != SH_OK)
    return 1;
  double want = closed_form(with);
  double centre = disk_part(&rw, &ro, &nref);
  tu_check(nref > 50 && fabs(centre - want) <= 1e-5 * want,
           "the reference sees the disk");
  for (int live = 0; live < 2; live++) {
    gs_options o = gs_options_defaults(with);
    o.live = live;
    if (tu_gl(with, &o, &gw) != SH_OK || tu_gl(without, &o, &go) != SH_OK)
      return 1;
    check(live ? "live" : "baked", &gw, &go, nref, want);
    sh_image_free(&gw);
    sh_image_free(&go);
  }

  /* A kept renderer: the patch that turns the disk on shows it. */
  gs_options o = gs_options_defaults(without);
  o.live = 1;
  gs_renderer *r = NULL;
  sh_error err = SH_ERROR_INIT;
  if (gs_renderer_create(without, &o, &r, &err) != SH_OK) return 1;
  if (tu_draw(r, without, &go, NULL)) {
    unsigned changed = 0;
    const char *patch = "{\"lights\": [{\"type\": \"directional\","
                        " \"direction\": [0, -0.3, 1],"
                        " \"irradiance\": [2, 3, 4],"
                        " \"angular_diameter_deg\": 4}]}";
    tu_check(sh_scene_update(without, patch, "patch", &changed, &err) ==
                     SH_OK &&
                 gs_renderer_sync(r, changed, &err) == SH_OK,
             "the patch is taken");
    if (tu_draw(r, without, &gw, NULL)) check("patched", &gw, &go, nref, want);
  }
  gs_renderer_free(r);
  sh_image_free(&gw);
  sh_image_free(&go);
  sh_image_free(&rw);
  sh_image_free(&ro);
  sh_scene_free(with);
  sh_scene_free(without);
  sh_error_clear(&err);
  return tu_failures != 0;
}
