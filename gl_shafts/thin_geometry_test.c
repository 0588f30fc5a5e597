/* Light through thin or closed geometry (issue 11, kind 2): the hard cases
 * of testdata/hard_cases/ (made by make_variants.py there), in which
 * the reference is exactly 0 everywhere, must be exactly 0 in gl_shafts
 * too: a closed room of zero-thickness walls with the sun outside and the
 * camera inside (the handed case, the sun from three more directions, the
 * room moved far from the origin), a plate just below a spot that blocks
 * its whole cone (2D shadow map), and a point light inside a closed box, a
 * box shape and six quads (cube map). Each is checked as it is and with
 * every material black (the medium alone), at 64 x 48 and at the handed
 * 96 x 72. The room with a window is held against the reference.
 *
 * What leaked before (the closed room: 2631 pixels up to 0.024, 28% of a
 * shaft's peak with a window): open casters were pushed away from the
 * light in the shadow map (the bias against a surface shadowing itself),
 * which let the medium behind a zero-thickness wall see the light through
 * a layer as thick as the wall's slope was steep; the medium's filtered
 * lookup mixed lit texels beyond a caster's outline into points behind it;
 * and a ray's end on a caster's face squarely facing the light (a light in
 * a box) compared equal to the stored depth, so lit. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_parse.h"
#include "sh_test.h"
#include "test_util.h"

static const char *const BLACK[] = {
    "closed_room",      "closed_room_sun_behind", "closed_room_sun_high",
    "closed_room_sun_grazing", "closed_room_far", "spot_blocked",
    "spot_blocked_near", "light_in_box",       "light_in_quads"};

/* The closed room with no medium (surfaces only): its sizes, lights and
 * positions (make_variants.py, surface_rooms). */
static const char *const SURFACE[] = {
    "surface_room",           "surface_room_sun_behind", "surface_room_sun_grazing",
    "surface_room_sun_corner", "surface_room_sun_below", "surface_room_small",
    "surface_room_long",      "surface_room_tall",      "surface_room_spot",
    "surface_room_point",     "surface_room_far"};

static sh_scene *load(const char *name) {
  return sh_test_load("testdata/hard_cases/%s.json", name);
}

/* Counts the pixels above 0 and finds the largest value. */
static long lit_pixels(const sh_image *img, double *largest) {
  long n = 0;
  *largest = 0;
  size_t count = (size_t)img->width * img->height;
  for (size_t i = 0; i < count; i++) {
    const float *p = img->rgb + 3 * i;
    double m = p[0] > p[1] ? p[0] : p[1];
    m = m > p[2] ? m : p[2];
    if (!(m <= 0)) n++;
    if (m > *largest) *largest = m;
  }
  return n;
}

static void check_black(const char *name, int width, int height, int black) {
  sh_scene *s = load(name);
  SH_CHECK(s != NULL);
  if (!s) return;
  s->camera.width = width;
  s->camera.height = height;
  if (black)
    for (int i = 0; i < s->nmaterials; i++) s->materials[i].diffuse = sh_v3s(0);
  sh_image img = {0};
  SH_CHECK(tu_gl(s, NULL, &img) == SH_OK);
  if (img.rgb) {
    double largest;
    long n = lit_pixels(&img, &largest);
    char what[160];
    snprintf(what, sizeof what, "%s at %dx%d%s: %ld pixels above 0 (largest %.3g), want 0",
             name, width, height, black ? ", black materials" : "", n, largest);
    tu_check(n == 0, what);
    sh_image zero = {0}; /* the reference's image: black */
    if (n && sh_image_alloc(&zero, width, height, NULL) == SH_OK) {
      memset(zero.rgb, 0, (size_t)width * height * 3 * sizeof *zero.rgb);
      tu_check_close(name, &img, &zero, 0.0); /* writes the images */
    }
    sh_image_free(&zero);
  }
  sh_image_free(&img);
  sh_scene_free(s);
}

int main(void) {
  for (size_t i = 0; i < sizeof BLACK / sizeof BLACK[0]; i++) {
    check_black(BLACK[i], 64, 48, 0);
    check_black(BLACK[i], 64, 48, 1);
  }
  /* The handed room at its own 96 x 72, with its materials: a floor pixel
   * 0.0008 from a wall's foot (3.9e-4) took light before open casters were
   * grown by a texel in the map (gs_shadow.c): its lookup's filter met the
   * empty texels just beyond the floor's edge, where the wall's foot is the
   * map's outline. */
  check_black("closed_room", 96, 72, 0);
  check_black("closed_room", 96, 72, 1);

  /* The rooms with their medium at the full validation run's 160 x 120
   * (and 192 x 144): two floor pixels at a wall's foot took up to 0.0075
   * in the handed room. With a medium below it the floor is a caster,
   * drawn open into the map, and its lookup, moved off its plane by the
   * receiver offset, was filtered alone; the check of whether it lies
   * behind what the four texels hold now covers open casters too
   * (surface.frag). */
  for (size_t i = 0; i < 5; i++) {
    check_black(BLACK[i], 160, 120, 0);
    check_black(BLACK[i], 192, 144, 0);
  }

  /* The room with no medium: floor points within a texel of a grazing
   * wall's foot (0.0008 from the wall, 0.005 behind it along the light)
   * took light, two pixels up to 0.058 at 96 x 72 in the handed room, 1
   * to 22 pixels at 64, 96 or 192 pixels wide in every variant: the
   * floor, not in the map, read it through a filtered lookup whose texels
   * reach where the steep wall's depth is beyond the point. A surface not
   * drawn open into the map now counts as lit only when all four texels
   * say so, as the medium does (surface.frag). */
  for (size_t i = 0; i < sizeof SURFACE / sizeof SURFACE[0]; i++) {
    check_black(SURFACE[i], 64, 48, 0);
    check_black(SURFACE[i], 96, 72, 0);
    check_black(SURFACE[i], 192, 144, 0);
  }

  /* The room with a 1 x 1 window: 7.0% before, 5.4% now, most of it where
   * a slab's part of a ray crosses the shaft between two shadowed ends
   * (docs/gl_shafts.md, limits). */
  sh_scene *s = load("window_room");
  SH_CHECK(s != NULL);
  if (s) {
    s->camera.width = 64;
    s->camera.height = 48;
    sh_image gl = {0}, ref = {0};
    SH_CHECK(tu_reference(s, 64, &ref) == SH_OK);
    SH_CHECK(tu_gl(s, NULL, &gl) == SH_OK);
    if (gl.rgb && ref.rgb) SH_CHECK(tu_check_close("window_room", &gl, &ref, 0.065));
    sh_image_free(&gl);
    sh_image_free(&ref);
    sh_scene_free(s);
  }
  SH_CHECK(tu_failures == 0);
  SH_TEST_DONE();
}
