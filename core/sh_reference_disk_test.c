/* The sun's disk in the reference renderer (docs/scene-format.md, "The
 * sun's disk"), against closed forms:
 * - in vacuum, the ray at the disk's centre sees exactly the background
 *   plus irradiance / (2 pi (1 - cos(half angle))), and a ray outside the
 *   cone the background alone;
 * - through an absorbing homogeneous medium, that times exp(-sigma_t l), l
 *   the ray's length inside the box;
 * - through a scattering one, the image with the disk minus the image
 *   without it is the disk's radiance times the transmittance at the
 *   disk's pixel and 0 at every other pixel, a lit floor included: the
 *   disk is seen, never used for shading, and it draws no random number.
 * Images are 32-bit floats, hence the 1e-6 tolerances. */
#include <stdio.h>
#include <string.h>

#include "sh_camera.h"
#include "sh_reference.h"
#include "sh_test.h"

/* A camera at the origin looking towards the sun, the sun coming from
 * (0, 0.3, -1), a 9x7 image whose middle pixel (4, 3) looks exactly at
 * the sun's centre and whose neighbours are 8.6 degrees away; the bottom
 * rows see the floor at y = -1. */
#define CAMERA                                                               \
  "\"camera\": {\"position\": [0, 0, 0], \"look_at\": [0, 0.3, -1],"         \
  " \"fov_y_deg\": 60, \"width\": 9, \"height\": 7},"                        \
  " \"background\": [0.1, 0.05, 0.02],"
#define SUN(diameter)                                                        \
  "\"lights\": [{\"type\": \"directional\", \"direction\": [0, -0.3, 1],"    \
  " \"irradiance\": [2, 3, 4], \"angular_diameter_deg\": " diameter "}]"
#define HEAD "{\"format\": \"shafts-scene\", \"version\": 1, " CAMERA " "

static const char *VACUUM = HEAD SUN("4") "}";
/* The box holds the centre ray for z in [-4, -1]: 3 sqrt(1.09) long. */
#define BOX "\"bounds\": {\"min\": [-2, -1, -4], \"max\": [2, 3, -1]}"
static const char *ABSORBING =
    HEAD SUN("4") ", \"medium\": {\"sigma_s\": [0, 0, 0],"
                  " \"sigma_a\": [0.1, 0.2, 0.3], " BOX "}}";
#define SCATTERING(diameter)                                                 \
  HEAD SUN(diameter) ", \"medium\": {\"sigma_s\": [0.2, 0.3, 0.1],"          \
                     " \"sigma_a\": [0.05, 0.05, 0.05], " BOX "},"           \
  " \"materials\": {\"floor\": {\"diffuse\": [0.5, 0.5, 0.5]}},"            \
  " \"shapes\": [{\"type\": \"quad\", \"corner\": [-5, -1, 2],"              \
  " \"u\": [10, 0, 0], \"v\": [0, 0, -12], \"material\": \"floor\"}]}"

static sh_image render(const char *json, const char *name) {
  sh_image img;
  memset(&img, 0, sizeof img);
  sh_scene *s = sh_test_parse(json, name);
  SH_CHECK(s != NULL);
  if (!s) return img;
  sh_reference_options opt = sh_reference_defaults(s);
  opt.spp = 16;
  opt.threads = 2;
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(sh_render_reference(s, &opt, &img, NULL, &err) == SH_OK);
  sh_scene_free(s);
  sh_error_clear(&err);
  return img;
}

static const float *pixel(const sh_image *img, int x, int y) {
  return img->rgb + 3 * ((size_t)y * img->width + x);
}

int main(void) {
  const double irr[3] = {2, 3, 4}, bg[3] = {0.1, 0.05, 0.02};
  const double omega = 2 * SH_PI * (1 - cos(2 * SH_PI / 180));
  const double len = 3 * sqrt(1.09);

  sh_image v = render(VACUUM, "vacuum.json");
  if (v.rgb) {
    for (int c = 0; c < 3; c++) {
      SH_CHECK_NEAR(pixel(&v, 4, 3)[c], bg[c] + irr[c] / omega, 1e-6, 0);
      SH_CHECK_NEAR(pixel(&v, 3, 3)[c], bg[c], 1e-6, 0);
      SH_CHECK_NEAR(pixel(&v, 4, 2)[c], bg[c], 1e-6, 0);
      SH_CHECK_NEAR(pixel(&v, 0, 0)[c], bg[c], 1e-6, 0);
    }
    fprintf(stderr, "vacuum: centre %.8g, expected %.8g\n",
            pixel(&v, 4, 3)[0], bg[0] + irr[0] / omega);
  }
  sh_image_free(&v);

  const double sigma_a[3] = {0.1, 0.2, 0.3};
  sh_image a = render(ABSORBING, "absorbing.json");
  if (a.rgb)
    for (int c = 0; c < 3; c++)
      SH_CHECK_NEAR(pixel(&a, 4, 3)[c],
                    (bg[c] + irr[c] / omega) * exp(-sigma_a[c] * len), 1e-6,
                    0);
  sh_image_free(&a);

  const double sigma_t[3] = {0.25, 0.35, 0.15};
  sh_image with = render(SCATTERING("4"), "scattering.json");
  sh_image without = render(SCATTERING("0"), "scattering0.json");
  if (with.rgb && without.rgb) {
    int others_equal = 1;
    for (int y = 0; y < 7; y++)
      for (int x = 0; x < 9; x++)
        for (int c = 0; c < 3; c++) {
          double dl = pixel(&with, x, y)[c] - pixel(&without, x, y)[c];
          if (x == 4 && y == 3)
            SH_CHECK_NEAR(dl, irr[c] / omega * exp(-sigma_t[c] * len), 1e-6,
                          0);
          else if (dl != 0)
            others_equal = 0;
        }
    SH_CHECK(others_equal);
    /* The bottom row sees the lit floor, so a surface shaded by the sun
     * was among the pixels compared. */
    sh_scene *s = sh_test_parse(SCATTERING("4"), "scattering.json");
    if (s) {
      sh_camera_frame frame;
      sh_camera_frame_init(&s->camera, &frame);
      sh_vec3 d = sh_camera_dir(&frame, 4.5, 6.5);
      SH_CHECK(d.y < 0 && -1.0 / d.y * d.z > -12 && -1.0 / d.y * d.z < 2);
      sh_scene_free(s);
    }
  }
  sh_image_free(&with);
  sh_image_free(&without);
  SH_TEST_DONE();
}
