/* Shadow maps kept across draws (gs_renderer_draw redraws a light's map
 * only when its key changed, gs_shadow.h): a second draw draws no map and
 * equals the first bit for bit; after a light move, a shape move, a camera
 * move and an ambient change, made with sh_scene_update and
 * gs_renderer_sync, the kept renderer's frame equals a fresh renderer's
 * bit for bit, in baked and in live mode, and a spot's move redraws its
 * map alone.
 *
 * The scene has a spot (a 2D map), a point light inside the medium (a
 * cube map) and a directional light (an orthographic map fitted to the
 * view), a sphere and a floor. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_test.h"
#include "shafts.h"
#include "test_util.h"

typedef struct params {
  double cam[3], spot[3], ball[3], ambient;
} params;

static const params BASE = {{2.5, 2.0, 3.0}, {-0.5, 3.2, 0.2}, {0, 0, 0}, 0.01};

enum { PART = 4096 };

/* The scene's changing members, as JSON. */
static void members(const params *p, char *out, size_t size) {
  snprintf(out, size,
    "\"camera\": {\"position\": [%.17g, %.17g, %.17g], \"look_at\": [0, 0.7, 0],"
    " \"fov_y_deg\": 50, \"width\": 64, \"height\": 48},"
    " \"ambient\": [%.17g, %.17g, %.17g],"
    " \"lights\": [{\"type\": \"spot\", \"position\": [%.17g, %.17g, %.17g],"
    "   \"look_at\": [0, 0, 0], \"intensity\": [12, 11, 10],"
    "   \"outer_angle_deg\": 28, \"inner_angle_deg\": 20},"
    "  {\"type\": \"point\", \"position\": [1.2, 1.4, -0.5], \"intensity\": [3, 2.5, 2]},"
    "  {\"type\": \"directional\", \"direction\": [1, -0.8, 0.3],"
    "   \"irradiance\": [1.5, 1.4, 1.3]}],"
    " \"transforms\": [null, {\"translate\": [%.17g, %.17g, %.17g]}]",
    p->cam[0], p->cam[1], p->cam[2], p->ambient, p->ambient, p->ambient, p->spot[0],
    p->spot[1], p->spot[2], p->ball[0], p->ball[1], p->ball[2]);
}

static sh_scene *scene(const params *p) {
  char m[PART], json[2 * PART];
  members(p, m, sizeof m);
  /* The transforms member is a patch's; the scene gives the sphere its own. */
  char *xf = strstr(m, ", \"transforms\"");
  char ball[256];
  snprintf(ball, sizeof ball, "{\"translate\": [%.17g, %.17g, %.17g]}", p->ball[0],
           p->ball[1], p->ball[2]);
  *xf = '\0';
  snprintf(json, sizeof json,
    "{\"format\": \"shafts-scene\", \"version\": 1, %s,"
    " \"medium\": {\"sigma_s\": [0.2, 0.2, 0.2], \"sigma_a\": [0.02, 0.03, 0.04],"
    "  \"phase\": {\"type\": \"henyey_greenstein\", \"g\": 0.3},"
    "  \"bounds\": {\"min\": [-3, 0, -3], \"max\": [3, 4, 3]}},"
    " \"materials\": {\"m\": {\"diffuse\": [0.5, 0.5, 0.5]}},"
    " \"shapes\": [{\"type\": \"quad\", \"material\": \"m\", \"corner\": [-3, 0, 3],"
    "   \"u\": [6, 0, 0], \"v\": [0, 0, -6]},"
    "  {\"type\": \"sphere\", \"material\": \"m\", \"center\": [0.2, 0.8, 0.1],"
    "   \"radius\": 0.35, \"transform\": %s}]}",
    m, ball);
  return tu_scene(json);
}

static gs_renderer *create(const sh_scene *s, int live) {
  gs_options o = gs_options_defaults(s);
  o.live = live;
  gs_renderer *r = NULL;
  sh_error err = SH_ERROR_INIT;
  if (gs_renderer_create(s, &o, &r, &err) != SH_OK)
    fprintf(stderr, "create: %s\n", err.message);
  sh_error_clear(&err);
  return r;
}

/* Moves the kept renderer's scene to p (sh_scene_update, sync), draws, and
 * compares with a fresh renderer's frame of a scene parsed at p. Returns
 * the maps the kept renderer drew, -1 on failure. */
static int step(const char *name, gs_renderer *r, sh_scene *s, const params *p,
                int live) {
  char m[PART], patch[PART + 2];
  members(p, m, sizeof m);
  snprintf(patch, sizeof patch, "{%s}", m);
  unsigned changed = 0;
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(sh_scene_update(s, patch, "patch.json", &changed, &err) == SH_OK);
  SH_CHECK(changed != 0);
  SH_CHECK(gs_renderer_sync(r, changed, &err) == SH_OK);
  sh_scene *to = scene(p);
  gs_renderer *f = to ? create(to, live) : NULL;
  SH_CHECK(f != NULL);
  int drawn = -1;
  sh_image kept = {0}, ref = {0};
  gs_stats st, fst;
  if (f && tu_draw(r, s, &kept, &st) && tu_draw(f, to, &ref, &fst)) {
    char what[96];
    snprintf(what, sizeof what, "%s_%s", name, live ? "live" : "baked");
    fprintf(stderr, "%s: changed 0x%x, maps drawn %d (fresh %d)\n", what, changed,
            st.shadow_maps, fst.shadow_maps);
    SH_CHECK(tu_equal_bits(what, &kept, &ref));
    drawn = st.shadow_maps;
  }
  SH_CHECK(drawn >= 0);
  sh_image_free(&kept);
  sh_image_free(&ref);
  gs_renderer_free(f);
  sh_scene_free(to);
  sh_error_clear(&err);
  return drawn;
}

int main(void) {
  for (int live = 0; live < 2; live++) {
    sh_scene *s = scene(&BASE);
    gs_renderer *r = s ? create(s, live) : NULL;
    SH_CHECK(r != NULL);
    if (!r) {
      sh_scene_free(s);
      continue;
    }
    sh_image first = {0}, again = {0};
    gs_stats a, b;
    SH_CHECK(tu_draw(r, s, &first, &a) && tu_draw(r, s, &again, &b));
    fprintf(stderr, "%s: maps drawn %d, then %d\n", live ? "live" : "baked",
            a.shadow_maps, b.shadow_maps);
    SH_CHECK(a.shadow_maps == 3 && b.shadow_maps == 0);
    if (first.rgb && again.rgb) SH_CHECK(tu_equal_bits("second_draw", &again, &first));
    sh_image_free(&first);
    sh_image_free(&again);

    params p = BASE;
    p.ambient = 0.03;
    SH_CHECK(step("ambient_changed", r, s, &p, live) == 0);
    p.spot[0] += 0.3;
    p.spot[1] -= 0.4;
    SH_CHECK(step("spot_moved", r, s, &p, live) == 1);
    p.ball[0] = 0.5;
    p.ball[2] = -0.3;
    SH_CHECK(step("sphere_moved", r, s, &p, live) >= 1);
    p.cam[0] = -2.0;
    p.cam[1] = 1.2;
    SH_CHECK(step("camera_moved", r, s, &p, live) >= 1);
    gs_renderer_free(r);
    sh_scene_free(s);
  }
  SH_TEST_DONE();
}
