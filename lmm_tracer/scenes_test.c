/* Every canonical scene (the .json files in scenes/) loads and renders in
 * reference mode at a reduced size: finite, non-negative radiance, and not black. */
#include <dirent.h>
#include <stdio.h>
#include <string.h>

#include "sh_parse.h"
#include "sh_reference.h"
#include "sh_test.h"

static void render_one(const char *path) {
  sh_error err = SH_ERROR_INIT;
  sh_scene *s = NULL;
  if (sh_scene_load(path, &s, &err) != SH_OK) {
    char buf[2048];
    sh_error_format(&err, buf, sizeof buf);
    fprintf(stderr, "%s\n", buf);
    SH_CHECK(!"scene loads");
    return;
  }
  s->camera.width = 64;
  s->camera.height = 48;
  sh_reference_options opt = sh_reference_defaults(s);
  opt.spp = 2;
  sh_image img = {0};
  SH_CHECK(sh_render_reference(s, &opt, &img, NULL, &err) == SH_OK);
  size_t n = (size_t)img.width * img.height * 3, bad = 0;
  double sum = 0;
  for (size_t i = 0; i < n; i++) {
    if (!isfinite(img.rgb[i]) || img.rgb[i] < 0) bad++;
    else sum += img.rgb[i];
  }
  fprintf(stderr, "%s: mean radiance %.4g, %zu bad values\n", path, sum / n,
          bad);
  SH_CHECK(bad == 0);
  SH_CHECK(sum > 0);
  sh_image_free(&img);
  sh_scene_free(s);
  sh_error_clear(&err);
}

int main(void) {
  const char *src = getenv("SHAFTS_SOURCE_DIR");
  char dir[1024];
  snprintf(dir, sizeof dir, "%s/scenes", src ? src : ".");
  DIR *d = opendir(dir);
  SH_CHECK(d != NULL);
  if (!d) SH_TEST_DONE();
  int count = 0;
  struct dirent *e;
  while ((e = readdir(d))) {
    size_t len = strlen(e->d_name);
    if (len < 6 || strcmp(e->d_name + len - 5, ".json")) continue;
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    render_one(path);
    count++;
  }
  closedir(d);
  SH_CHECK(count >= 7);
  SH_TEST_DONE();
}
