/* The canonical atmosphere scenes rendered by `lmm_tracer --mode reference`
 * at 64x48 (the tool itself, started by the test), checked for what the
 * scenes are made to show and for precision:
 * - scenes/sky_sunset.json (an eye 1 m above a ground of radius 6360 km):
 *   finite, the sky brighter towards the sun than away from it, every
 *   ground pixel lit (no acne: a false self-shadow would leave it black)
 *   and within 15% of its neighbours' mean (no banding);
 * - scenes/earth_from_space.json (30,000 km away): the corners are space
 *   (black), the disk's lit side bright and its night side dark (the
 *   terminator), the air lit beyond the ground's edge on the lit limb;
 * - the whole sunset scene moved 12,345 km away renders the same image to
 *   1e-4 (relative RMS): the reference works about the camera and the
 *   planet's centre, not about the world's origin. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sh_image.h"
#include "sh_test.h"

static char tmpdir[256];

/* Renders `scene` (a path) with the lmm_tracer binary into NAME.exr at
 * 64x48 and reads it. */
static int render(const char *scene, const char *name, sh_image *img) {
  const char *bin = getenv("SHAFTS_BINARY_DIR");
  char out[512], cmd[2048];
  snprintf(out, sizeof out, "%s/%s.exr", tmpdir, name);
  snprintf(cmd, sizeof cmd,
           "'%s/lmm_tracer/lmm_tracer' '%s' --mode reference --width 64 "
           "--height 48 --spp 16 -q -o '%s'",
           bin ? bin : "..", scene, out);
  int rc = system(cmd);
  SH_CHECK(rc == 0);
  if (rc != 0) return 0;
  sh_error err = SH_ERROR_INIT;
  sh_status st = sh_image_read(out, img, &err);
  SH_CHECK(st == SH_OK);
  sh_error_clear(&err);
  return st == SH_OK;
}

static double lum(const sh_image *im, int x, int y) {
  const float *p = im->rgb + 3 * ((size_t)y * im->width + x);
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

static int all_finite(const sh_image *im) {
  for (size_t i = 0; i < 3 * (size_t)im->width * im->height; i++)
    if (!isfinite(im->rgb[i]) || im->rgb[i] < 0) return 0;
  return 1;
}

static void scene_path(char *buf, size_t n, const char *name) {
  const char *src = getenv("SHAFTS_SOURCE_DIR");
  snprintf(buf, n, "%s/scenes/%s.json", src ? src : "../..", name);
}

static void test_sunset(void) {
  char path[512];
  scene_path(path, sizeof path, "sky_sunset");
  sh_image im;
  if (!render(path, "sunset", &im)) return;
  SH_CHECK(all_finite(&im));
  /* The camera looks 19 degrees to the side of the sun (on its left in
   * the image) and 12 degrees up: the horizon lies below the middle. */
  int horizon = -1;
  for (int y = 0; y < im.height && horizon < 0; y++)
    if (lum(&im, im.width / 2, y) < 0.2 * lum(&im, im.width / 2, y > 0 ? y - 1 : 0))
      horizon = y;
  SH_CHECK(horizon > im.height / 2 && horizon < im.height - 4);
  if (horizon < 0) horizon = im.height - 1;
  /* The glow: just above the horizon, the sun's side is brighter. */
  SH_CHECK(lum(&im, 2, horizon - 2) > 2 * lum(&im, im.width - 3, horizon - 2));
  /* The ground, two rows below the horizon on: lit, and smooth. */
  int lit = 1, smooth = 1;
  for (int y = horizon + 2; y < im.height - 1; y++)
    for (int x = 1; x < im.width - 1; x++) {
      double c = lum(&im, x, y);
      double m = 0.25 * (lum(&im, x - 1, y) + lum(&im, x + 1, y) +
                         lum(&im, x, y - 1) + lum(&im, x, y + 1));
      lit &= c > 0;
      if (y > horizon + 2) smooth &= fabs(c - m) <= 0.15 * m;
    }
  SH_CHECK(lit);
  SH_CHECK(smooth);
  /* The same scene 12,345 km away in every direction. */
  FILE *f = fopen(path, "rb");
  char text[8192];
  size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
  if (f) fclose(f);
  text[n] = 0;
  char moved[8192], *w = moved;
  const char *from[] = {"\"position\": [0, 0.001, 0]", "\"look_at\": [1, 0.213557, 0.35]",
                        "\"center\": [0, -6360, 0]"};
  const char *to[] = {"\"position\": [12345, 12345.001, -12345]",
                      "\"look_at\": [12346, 12345.213557, -12344.65]",
                      "\"center\": [12345, 5985, -12345]"};
  const char *r = text;
  for (;;) {
    const char *best = NULL;
    int k = -1;
    for (int i = 0; i < 3; i++) {
      const char *q = strstr(r, from[i]);
      if (q && (!best || q < best)) best = q, k = i;
    }
    if (!best) break;
    memcpy(w, r, (size_t)(best - r));
    w += best - r;
    w += sprintf(w, "%s", to[k]);
    r = best + strlen(from[k]);
  }
  strcpy(w, r);
  char mpath[512];
  snprintf(mpath, sizeof mpath, "%s/moved.json", tmpdir);
  f = fopen(mpath, "wb");
  SH_CHECK(f != NULL);
  if (f) {
    fputs(moved, f);
    fclose(f);
  }
  sh_image im2;
  if (render(mpath, "moved", &im2)) {
    double num = 0, den = 0;
    for (size_t i = 0; i < 3 * (size_t)im.width * im.height; i++) {
      num += (im.rgb[i] - im2.rgb[i]) * (double)(im.rgb[i] - im2.rgb[i]);
      den += im.rgb[i] * (double)im.rgb[i];
    }
    fprintf(stderr, "sky_sunset moved 12,345 km: relative RMS difference %.2e\n",
            sqrt(num / den));
    SH_CHECK(sqrt(num / den) < 1e-4);
    sh_image_free(&im2);
  }
  sh_image_free(&im);
}

static void test_earth(void) {
  char path[512];
  scene_path(path, sizeof path, "earth_from_space");
  sh_image im;
  if (!render(path, "earth", &im)) return;
  SH_CHECK(all_finite(&im));
  int W = im.width, H = im.height, cx = W / 2, cy = H / 2;
  SH_CHECK(lum(&im, 0, 0) == 0 && lum(&im, W - 1, H - 1) == 0);
  /* The sun comes from +x (the right): the disk's right is lit, its left
   * (beyond the terminator) dark. The disk's radius is about 21 pixels. */
  double right = lum(&im, cx + 12, cy), left = lum(&im, cx - 16, cy);
  SH_CHECK(right > 0);
  SH_CHECK(left < 0.05 * right);
  /* The lit limb: the air just outside the ground's edge on the right. */
  double limb = 0;
  for (int x = cx + 15; x < W; x++) limb = fmax(limb, lum(&im, x, cy));
  SH_CHECK(limb > 0.05 * right);
  sh_image_free(&im);
}

int main(void) {
  snprintf(tmpdir, sizeof tmpdir, "/tmp/atmo_scenes_test.XXXXXX");
  if (!mkdtemp(tmpdir)) return 1;
  test_sunset();
  test_earth();
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
  if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
  SH_TEST_DONE();
}
