/* The normalised scene writer (--to json): loading its output gives the same
 * scene, field by field, for every canonical scene, every export test scene
 * and a scene built to use every key (testdata/everything.json). Values
 * the loader derives again (a unit axis normalised once more, its cosines)
 * may differ in the last bits; everything else is equal. */
#include <dirent.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "se_json.h"
#include "sh_parse.h"
#include "sh_test.h"

/* Doubles the loader derives again (unit directions, cosines) may differ in
 * the last bits; everything else must be equal. */
#define NEAR(a, b) SH_CHECK_NEAR((a), (b), 1e-14, 1e-15)
#define VNEAR(a, b) \
  do {              \
    NEAR((a).x, (b).x); \
    NEAR((a).y, (b).y); \
    NEAR((a).z, (b).z); \
  } while (0)

/* The export names a file in its own tree (relative) holding the same
 * bytes: the original where it lies in the export's tree, else a copy. */
static void same_file(const char *a, const char *b, const char *b_dir) {
  char *rb = realpath(b, NULL), *rd = realpath(b_dir ? b_dir : ".", NULL);
  SH_CHECK(rb && rd && !strncmp(rb, rd, strlen(rd)) && rb[strlen(rd)] == '/');
  free(rb);
  free(rd);
  FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
  SH_CHECK(fa && fb);
  int same = fa && fb;
  while (same) {
    int ca = getc(fa), cb = getc(fb);
    if (ca != cb) same = 0;
    if (ca == EOF) break;
  }
  SH_CHECK(same);
  if (fa) fclose(fa);
  if (fb) fclose(fb);
}

static void same_image(const sh_image *a, const sh_image *b) {
  SH_CHECK(a->width == b->width && a->height == b->height);
  if (a->width == b->width && a->height == b->height && a->rgb && b->rgb)
    SH_CHECK(!memcmp(a->rgb, b->rgb, sizeof(float) * 3 * (size_t)a->width * a->height));
}

static void same_mesh(const sh_mesh *a, const sh_mesh *b) {
  SH_CHECK(a->nverts == b->nverts && a->ntris == b->ntris);
  if (a->nverts == b->nverts && a->nverts > 0)
    SH_CHECK(!memcmp(a->positions, b->positions, sizeof(float) * 3 * (size_t)a->nverts));
  if (a->ntris == b->ntris && a->ntris > 0)
    SH_CHECK(!memcmp(a->indices, b->indices, sizeof(unsigned) * 3 * (size_t)a->ntris));
}

static void same_matrix(const sh_mat4 *a, const sh_mat4 *b) {
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++) NEAR(a->m[r][c], b->m[r][c]);
}

static void compare(const sh_scene *a, const sh_scene *b) {
  VNEAR(a->camera.position, b->camera.position);
  VNEAR(a->camera.look_at, b->camera.look_at);
  VNEAR(a->camera.up, b->camera.up);
  NEAR(a->camera.fov_y_deg, b->camera.fov_y_deg);
  SH_CHECK(a->camera.width == b->camera.width && a->camera.height == b->camera.height);
  VNEAR(a->background, b->background);
  VNEAR(a->ambient, b->ambient);

  SH_CHECK(a->medium.present == b->medium.present);
  if (a->medium.present && b->medium.present) {
    VNEAR(a->medium.sigma_s, b->medium.sigma_s);
    VNEAR(a->medium.sigma_a, b->medium.sigma_a);
    VNEAR(a->medium.sigma_t, b->medium.sigma_t);
    SH_CHECK(a->medium.phase.type == b->medium.phase.type);
    NEAR(a->medium.phase.g, b->medium.phase.g);
    VNEAR(a->medium.bmin, b->medium.bmin);
    VNEAR(a->medium.bmax, b->medium.bmax);
  }

  SH_CHECK(a->nlights == b->nlights);
  for (int i = 0; i < a->nlights && i < b->nlights; i++) {
    const sh_light *p = &a->lights[i], *q = &b->lights[i];
    SH_CHECK(p->type == q->type);
    SH_CHECK(p->soft_shadows == q->soft_shadows);
    SH_CHECK(p->has_map == q->has_map);
    if (p->type != SH_LIGHT_DIRECTIONAL) {
      VNEAR(p->position, q->position);
      VNEAR(p->intensity, q->intensity);
    } else {
      VNEAR(p->irradiance, q->irradiance);
    }
    if (p->type != SH_LIGHT_POINT) VNEAR(p->direction, q->direction);
    if (p->type == SH_LIGHT_SPOT) {
      NEAR(p->outer_deg, q->outer_deg);
      NEAR(p->inner_deg, q->inner_deg);
      NEAR(p->exponent, q->exponent);
      NEAR(p->cos_outer, q->cos_outer);
      NEAR(p->cos_inner, q->cos_inner);
      NEAR(p->tan_outer, q->tan_outer);
    }
    if (p->has_map && q->has_map) {
      same_file(p->map_file, q->map_file, b->base_dir);
      same_image(&p->map, &q->map);
      if (p->type == SH_LIGHT_SPOT) {
        VNEAR(p->map_up, q->map_up);
        VNEAR(p->map_right, q->map_right);
      } else {
        VNEAR(p->map_origin, q->map_origin);
        VNEAR(p->map_u, q->map_u);
        VNEAR(p->map_v, q->map_v);
        VNEAR(p->map_normal, q->map_normal);
      }
    }
  }

  SH_CHECK(a->nmaterials == b->nmaterials);
  for (int i = 0; i < a->nmaterials && i < b->nmaterials; i++) {
    const sh_material *p = &a->materials[i], *q = &b->materials[i];
    SH_CHECK(!strcmp(p->name, q->name));
    VNEAR(p->diffuse, q->diffuse);
    VNEAR(p->specular, q->specular);
    NEAR(p->shininess, q->shininess);
    VNEAR(p->reflect, q->reflect);
    VNEAR(p->transmit, q->transmit);
    NEAR(p->ior, q->ior);
    VNEAR(p->emission, q->emission);
    SH_CHECK(p->casts_soft_shadows == q->casts_soft_shadows);
    SH_CHECK(p->receives_soft_shadows == q->receives_soft_shadows);
  }

  SH_CHECK(a->nshapes == b->nshapes);
  for (int i = 0; i < a->nshapes && i < b->nshapes; i++) {
    const sh_shape *p = &a->shapes[i], *q = &b->shapes[i];
    SH_CHECK(p->type == q->type);
    SH_CHECK(p->material == q->material);
    same_matrix(&p->xform, &q->xform);
    same_matrix(&p->inv, &q->inv);
    VNEAR(p->center, q->center);
    NEAR(p->radius, q->radius);
    VNEAR(p->bmin, q->bmin);
    VNEAR(p->bmax, q->bmax);
    VNEAR(p->base, q->base);
    VNEAR(p->top, q->top);
    SH_CHECK(p->caps == q->caps);
    VNEAR(p->corner, q->corner);
    VNEAR(p->u, q->u);
    VNEAR(p->v, q->v);
    SH_CHECK(!p->file == !q->file);
    if (p->file && q->file) same_file(p->file, q->file, b->base_dir);
    same_mesh(&p->mesh, &q->mesh);
  }

  const sh_render_settings *r = &a->render, *s = &b->render;
  SH_CHECK(r->spp == s->spp && r->max_depth == s->max_depth && r->seed == s->seed);
  NEAR(r->exposure, s->exposure);
  /* The renderers' keys come back as given, in order. */
  SH_CHECK(r->nparams == s->nparams);
  for (int i = 0; i < r->nparams && i < s->nparams; i++)
    SH_CHECK(!strcmp(r->params[i].key, s->params[i].key) &&
             !strcmp(r->params[i].json, s->params[i].json));
}

/* Exports `path` to JSON in `dir`, reloads it and compares. */
static void roundtrip(const char *path, const char *dir) {
  sh_error err = SH_ERROR_INIT;
  sh_scene *a = NULL, *b = NULL;
  if (sh_scene_load(path, &a, &err) != SH_OK) {
    char buf[1200];
    sh_error_format(&err, buf, sizeof buf);
    fprintf(stderr, "cannot load %s: %s\n", path, buf);
    SH_CHECK(0);
    return;
  }
  char out1[PATH_MAX];
  snprintf(out1, sizeof out1, "%s/normalised.json", dir);
  se_output o = {0};
  SH_CHECK(se_json_build(a, NULL, out1, &o, NULL, &err) == SH_OK);
  SH_CHECK(se_output_write(&o, NULL, &err) == SH_OK);
  if (sh_scene_load(out1, &b, &err) != SH_OK) {
    char buf[1200];
    sh_error_format(&err, buf, sizeof buf);
    fprintf(stderr, "cannot reload the export of %s: %s\n", path, buf);
    SH_CHECK(0);
  } else {
    fprintf(stderr, "%s: %d lights, %d materials, %d shapes\n", path, a->nlights,
            a->nmaterials, a->nshapes);
    compare(a, b);
  }
  for (int i = 0; i < o.count; i++) unlink(o.files[i].path);
  se_output_free(&o);
  sh_scene_free(a);
  sh_scene_free(b);
  sh_error_clear(&err);
}

static void scenes_in(const char *dir, const char *tmp, int *count) {
  DIR *d = opendir(dir);
  SH_CHECK(d != NULL);
  if (!d) return;
  struct dirent *e;
  while ((e = readdir(d))) {
    size_t n = strlen(e->d_name);
    if (n < 6 || strcmp(e->d_name + n - 5, ".json")) continue;
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    roundtrip(path, tmp);
    (*count)++;
  }
  closedir(d);
}

int main(void) {
  const char *src = getenv("SHAFTS_SOURCE_DIR");
  if (!src) src = "../..";
  char tmp[256];
  if (!sh_test_tmpdir(tmp, sizeof tmp, "se_json_test")) return EXIT_FAILURE;
  char dir[PATH_MAX];
  int count = 0;
  snprintf(dir, sizeof dir, "%s/scenes", src);
  scenes_in(dir, tmp, &count);
  snprintf(dir, sizeof dir, "%s/scene_export/testdata", src);
  scenes_in(dir, tmp, &count);
  SH_CHECK(count >= 10);
  rmdir(tmp);
  SH_TEST_DONE();
}
