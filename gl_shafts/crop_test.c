/* A crop (gs_options.crop) renders an off-axis part of the camera's
 * frustum at the whole image's resolution: the same pixels as that region
 * of the whole image, up to what follows the drawn window rather than the
 * pixel (the lit volumes are clipped to the window's frustum, which moves
 * the planes' depths; a directional light's shadow map is fitted to it;
 * the lattice covers the light's part of the window). The window that is
 * the whole image is the whole image to the bit, a kept renderer draws the
 * crop as gs_render does, and a crop outside the image is refused with its
 * key, also when a sync makes the image smaller. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_test.h"
#include "shafts.h"
#include "test_util.h"

/* A spot with a gobo and a shadow-casting ball, a directional light
 * through a window, a floor (invariance_test.c's scene at scale 1). */
static const char *SCENE =
    "{\"format\": \"shafts-scene\", \"version\": 1,"
    " \"camera\": {\"position\": [2.5, 2, 3], \"look_at\": [0, 0.7, 0],"
    "  \"fov_y_deg\": 50, \"width\": 96, \"height\": 72},"
    " \"medium\": {\"sigma_s\": [0.2, 0.2, 0.2], \"sigma_a\": [0.02, 0.03, 0.04],"
    "  \"phase\": {\"type\": \"henyey_greenstein\", \"g\": 0.3},"
    "  \"bounds\": {\"min\": [-3, 0, -3], \"max\": [3, 4, 3]}},"
    " \"lights\": [{\"type\": \"spot\", \"position\": [-0.5, 3.2, 0.2],"
    "   \"look_at\": [0, 0, 0], \"intensity\": [12, 11, 10],"
    "   \"outer_angle_deg\": 28, \"inner_angle_deg\": 20, \"exponent\": 1,"
    "   \"light_map\": {\"image\": \"assets/gobo_star.png\", \"up\": [0, 0, -1]}},"
    "  {\"type\": \"directional\", \"direction\": [1, -0.8, 0.3],"
    "   \"irradiance\": [1.5, 1.4, 1.3],"
    "   \"light_map\": {\"image\": \"assets/stained_glass.png\","
    "    \"origin\": [-3, 2.5, -1], \"u\": [0, 0, 2], \"v\": [0, -1.2, 0]}}],"
    " \"materials\": {\"m\": {\"diffuse\": [0.5, 0.5, 0.5], \"specular\": [0.2, 0.2, 0.2]}},"
    " \"shapes\": [{\"type\": \"quad\", \"material\": \"m\", \"corner\": [-3, 0, 3],"
    "   \"u\": [6, 0, 0], \"v\": [0, 0, -6]},"
    "  {\"type\": \"sphere\", \"material\": \"m\", \"center\": [0.2, 0.8, 0.1],"
    "   \"radius\": 0.35}]}";

/* The region `c` of img, as an image of its own. */
static sh_image region(const sh_image *img, sh_crop c) {
  sh_image out = {0};
  if (sh_image_alloc(&out, c.x1 - c.x0, c.y1 - c.y0, NULL) != SH_OK) return out;
  for (int y = 0; y < out.height; y++)
    memcpy(out.rgb + 3 * (size_t)y * out.width,
           img->rgb + 3 * ((size_t)(y + c.y0) * img->width + c.x0),
           sizeof *out.rgb * 3 * (size_t)out.width);
  return out;
}

/* Renders the whole image and the crop with `o` and checks the crop
 * against the region within `bound` (relative RMS). */
static void check_crop(const sh_scene *s, gs_options o, sh_crop c,
                       const char *name, double bound) {
  sh_image whole = {0}, part = {0};
  if (tu_gl(s, &o, &whole) != SH_OK) {
    tu_check(0, name);
    return;
  }
  o.crop = c;
  if (tu_gl(s, &o, &part) == SH_OK) {
    sh_image cut = region(&whole, c);
    SH_CHECK(part.width == c.x1 - c.x0 && part.height == c.y1 - c.y0);
    SH_CHECK(tu_check_close(name, &part, &cut, bound));
    sh_image_free(&cut);
  } else {
    tu_check(0, name);
  }
  sh_image_free(&whole);
  sh_image_free(&part);
}

int main(void) {
  sh_scene *s = tu_scene(SCENE);
  SH_CHECK(s != NULL);
  if (!s) SH_TEST_DONE();
  gs_options o = gs_options_defaults(s);

  /* The whole image as a crop: the same frustum, to the bit. */
  sh_image whole = {0}, same = {0};
  gs_options all = o;
  all.crop = (sh_crop){0, 0, s->camera.width, s->camera.height};
  if (tu_gl(s, &o, &whole) == SH_OK && tu_gl(s, &all, &same) == SH_OK)
    SH_CHECK(tu_equal_bits("crop_whole", &same, &whole));
  else
    tu_check(0, "the whole image as a crop");
  sh_image_free(&whole);
  sh_image_free(&same);

  /* Off-axis windows: a corner, a part through the spot's cone and the
   * ball, one pixel; with the lattice and jitter too (the jitter follows
   * the whole image's pixels). Measured on llvmpipe with the defaults of
   * 3459393 (one plane a point or spot light): 0.31%, 0.03%, 0.00% and
   * 0.08% (0.66%, 0.13%, 0.09% and 0.24% with four planes); the bound is
   * 1%, the level renderers are judged at (docs/validation.md). */
  check_crop(s, o, (sh_crop){0, 0, 40, 30}, "crop_corner", 0.01);
  check_crop(s, o, (sh_crop){30, 20, 75, 61}, "crop_middle", 0.01);
  check_crop(s, o, (sh_crop){50, 40, 51, 41}, "crop_pixel", 0.01);
  gs_options lj = o;
  lj.xi = GS_XI_LATTICE;
  lj.jitter = 1;
  check_crop(s, lj, (sh_crop){30, 20, 75, 61}, "crop_lattice_jitter", 0.01);

  /* A kept renderer draws the crop into a buffer of the crop's size, as
   * gs_render does; an image made smaller under it than its crop is
   * refused at the sync. */
  gs_options kept = o;
  kept.crop = (sh_crop){10, 12, 50, 40};
  gs_renderer *r = NULL;
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(gs_renderer_create(s, &kept, &r, &err) == SH_OK);
  sh_image drawn = {0}, rendered = {0};
  if (r && sh_image_alloc(&drawn, 40, 28, NULL) == SH_OK &&
      tu_gl(s, &kept, &rendered) == SH_OK) {
    SH_CHECK(gs_renderer_draw(r, drawn.rgb, NULL, &err) == SH_OK);
    SH_CHECK(tu_equal_bits("crop_kept_renderer", &drawn, &rendered));
    s->camera.width = 48;
    s->camera.height = 36;
    int refused = gs_renderer_sync(r, SH_CHANGED_SIZE | SH_CHANGED_CAMERA,
                                   &err) == SH_ERR_ARG &&
                  !strcmp(err.path, "crop") && strstr(err.message, "x1 = 50");
    SH_CHECK(refused);
    if (!refused) fprintf(stderr, "sync: %s\n", err.message);
    s->camera.width = 96;
    s->camera.height = 72;
  }
  sh_image_free(&drawn);
  sh_image_free(&rendered);
  gs_renderer_free(r);

  /* Outside the image: refused before any GL work, with the key. */
  static const sh_crop bad[] = {{0, 0, 97, 72}, {0, 0, 96, 73}, {5, 5, 5, 9}};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
    gs_options b = o;
    b.crop = bad[i];
    sh_image img = {0};
    int ok = gs_render(s, &b, &img, NULL, &err) == SH_ERR_ARG &&
             !strcmp(err.path, "crop") && img.rgb == NULL;
    SH_CHECK(ok);
    if (!ok) fprintf(stderr, "bad crop %zu: %s\n", i, err.message);
  }
  sh_scene_free(s);
  sh_error_clear(&err);
  SH_TEST_DONE();
}
