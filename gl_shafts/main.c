/* gl_shafts: renders a scene with the plane-sweep method of Dobashi et al.
 * (2000) on OpenGL through EGL or OSMesa. The command-line face of
 * gs_render.h: the renderer's options are set by name (gs_options_set), so
 * their limits and choices are the renderer's own. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gs_named.h"
#include "gs_render.h"
#include "sh_cli.h"
#include "sh_parse.h"

#define TOOL_NAME "gl_shafts"
static const char *const TOOL = TOOL_NAME;

#define STR_(x) #x
#define STR(x) STR_(x)

#define RENDERER(name, key_, meta, text)                                      \
  {name, 0, SH_CLI_SETTER, meta, 0, 0, 0, 0, 0, 0, NULL, key_, NULL, NULL, text}

static sh_cli_option options[] = {
    SH_CLI_RENDER_OPTIONS,
    RENDERER("planes", "planes", "N",
             "virtual planes per light (default: render.planes, else "
             STR(GS_DEFAULT_PLANES_LOCAL) " for point and spot lights, "
             STR(GS_DEFAULT_PLANES_DIRECTIONAL) " for directional ones)"),
    {"lattice", 0, SH_CLI_SETTER, "NU NV", 2, 0, 0, 0, 0, 0, NULL, "lattice",
     NULL, NULL,
     "lattice points per plane for xi (default: render.lattice, else "
     STR(GS_DEFAULT_LATTICE) " " STR(GS_DEFAULT_LATTICE) ")"},
    RENDERER("light-map-res", "light_map_res", "R",
             "resample light maps to R x R (default: render.light_map_res, "
             "else each map's own size)"),
    RENDERER("shadow-map-res", "shadow_map_res", "S",
             "shadow-map size (default: render.shadow_map_res, else "
             STR(GS_DEFAULT_SHADOW_LOCAL) " for point and spot lights, "
             STR(GS_DEFAULT_SHADOW_DIRECTIONAL) " for directional ones)"),
    RENDERER("xi", "xi", NULL,
             "xi on the lattice, interpolated (the paper's method), or per "
             "fragment; the scene's render.xi comes before the default"),
    {"jitter", 0, SH_CLI_SETTER, NULL, 0, 0, 0, 0, 0, 0, NULL, "jitter", "1",
     NULL,
     "per-pixel jitter of the sample depths (default: render.jitter, else "
     "off)"},
    {"no-jitter", 0, SH_CLI_SETTER, NULL, 0, 0, 0, 0, 0, 0, NULL, "jitter",
     "0", NULL, "no jitter"},
    RENDERER("sub-angle", "sub_angle_deg", "DEG",
             "point and spot lights: one sample per DEG degrees that a "
             "plane's part of a ray subtends at the light (default "
             STR(GS_DEFAULT_SUB_ANGLE_DEG) ")"),
    RENDERER("sub-texels", "sub_texels", "T",
             "lights with a map (a spot's gobo, a window): one sample per T "
             "map texels a plane's part of a ray crosses (default "
             STR(GS_DEFAULT_SUB_TEXELS) ")"),
    RENDERER("backend", "backend", NULL,
             "where the GL context comes from (default auto: EGL's devices, "
             "a GPU first, then EGL surfaceless, then OSMesa; the environment "
             "variable SHAFTS_GL_BACKEND narrows auto)"),
};

static sh_status set_option(void *target, const char *key, const char *value,
                            sh_error *err) {
  return gs_options_set(target, key, value, err);
}

static gs_options scratch; /* what options are checked on while parsing */
static const sh_cli_tool tool = {
    TOOL_NAME, "SCENE.json -o OUT.exr|OUT.png [options]",
    "Renders a scene (docs/scene-format.md) with shafts of light by the "
    "plane-sweep\nmethod of Dobashi, Yamamoto and Nishita (2000) on OpenGL "
    "4.5, through EGL (a\nGPU if there is one, else llvmpipe on the CPU) or "
    "OSMesa. Options override the\nscene's render keys; docs/gl_shafts.md "
    "has the details.",
    options, (int)(sizeof options / sizeof *options), 1, 1, NULL, NULL,
    set_option, &scratch, gs_option_choices, NULL};

/* The settings a render used: the --stats record's first keys and the
 * EXR header's shafts:settings. Every value is a number or a name. */
static void put_settings(sh_stats *s, const sh_scene *scene,
                         const gs_options *o, const gs_stats *st) {
  /* The image written: the crop's, which the crop_ keys place. */
  sh_crop win = sh_crop_window(&o->crop, &scene->camera);
  sh_stats_num(s, "width", win.x1 - win.x0);
  sh_stats_num(s, "height", win.y1 - win.y0);
  sh_stats_crop(s, &o->crop);
  /* Only what applies: a kind's planes and maps where the scene has a
   * light of that kind, the lattice with xi on it, the light maps'
   * resolution and sub-samples where a light has a map, the angular
   * sub-samples where there is a point or spot light. */
  int kinds[2] = {0, 0}, maps = 0; /* local, directional lights present */
  for (int i = 0; i < scene->nlights; i++) {
    kinds[scene->lights[i].type == SH_LIGHT_DIRECTIONAL] = 1;
    maps |= scene->lights[i].has_map;
  }
  if (o->planes) sh_stats_num(s, "planes_per_light", o->planes);
  if (o->shadow_map_res) sh_stats_num(s, "shadow_map_res", o->shadow_map_res);
  if (kinds[0]) {
    sh_stats_num(s, "planes_local", gs_light_planes(o, SH_LIGHT_POINT));
    sh_stats_num(s, "shadow_map_res_local",
                 gs_light_shadow_map_res(o, SH_LIGHT_POINT));
  }
  if (kinds[1]) {
    sh_stats_num(s, "planes_directional",
                 gs_light_planes(o, SH_LIGHT_DIRECTIONAL));
    sh_stats_num(s, "shadow_map_res_directional",
                 gs_light_shadow_map_res(o, SH_LIGHT_DIRECTIONAL));
  }
  sh_stats_str(s, "xi", gs_option_name("xi", o->xi));
  if (o->xi == GS_XI_LATTICE) {
    sh_stats_num(s, "lattice_u", o->lattice_u);
    sh_stats_num(s, "lattice_v", o->lattice_v);
  }
  sh_stats_num(s, "jitter", o->jitter);
  if (kinds[0]) sh_stats_num(s, "sub_angle_deg", o->sub_angle_deg);
  if (maps) {
    sh_stats_num(s, "light_map_res", o->light_map_res);
    sh_stats_num(s, "sub_texels", o->sub_texels);
  }
  if (st) sh_stats_str(s, "backend", st->backend);
}

/* The --stats record: the frame's statistics (gs_stats_json) with the
 * tool, the scene and the settings. */
static sh_stats *stats_record(const char *scene_path, const char *settings,
                              const gs_stats *st) {
  size_t n = gs_stats_json(st, NULL, 0);
  char *text = n ? malloc(n + 1) : NULL;
  if (text) gs_stats_json(st, text, n + 1);
  sh_stats *s = sh_stats_from_json(text);
  free(text);
  sh_stats *set = sh_stats_from_json(settings);
  sh_stats_str(s, "tool", TOOL);
  sh_stats_str(s, "scene", scene_path);
  sh_stats_merge(s, set);
  sh_stats_free(set);
  return s;
}

/* Writes the images and the statistics; returns the exit status. */
static int finish(const sh_cli_render *r, const sh_scene *scene,
                  const gs_options *o, const sh_image *img,
                  const gs_stats *st) {
  sh_error err = SH_ERROR_INIT;
  sh_stats *settings = sh_stats_new();
  put_settings(settings, scene, o, st);
  char *settings_text = sh_stats_text(settings);
  sh_stats_free(settings);
  sh_status status = sh_cli_write_images(
      TOOL, r->files, &r->outputs, img, sh_cli_render_exposure(r, scene),
      "plane-sweep", settings_text, r->scene, &err);
  if (status == SH_OK && r->stats) {
    sh_stats *s = stats_record(r->scene, settings_text, st);
    status = sh_stats_write(s, r->files, r->stats, &err);
    sh_stats_free(s);
  }
  free(settings_text);
  if (status == SH_OK) status = sh_outputs_publish(r->files, &err);
  if (status != SH_OK) return sh_cli_report(TOOL, &err);
  char detail[96];
  snprintf(detail, sizeof detail, ": %.3f s a frame + %.3f s setup",
           st->seconds, st->setup_seconds);
  sh_cli_render_done(TOOL, r, img->width, img->height,
                     st->seconds + st->setup_seconds, detail);
  return SH_EXIT_OK;
}

int main(int argc, char **argv) {
  for (size_t i = 0; i < sizeof options / sizeof *options; i++)
    if (!strcmp(options[i].name, "xi"))
      options[i].def = gs_option_name("xi", GS_DEFAULT_XI);
  /* Options are checked while parsing on the built-in defaults (a scene
   * without render keys), and applied once the scene is loaded. */
  sh_scene no_keys;
  memset(&no_keys, 0, sizeof no_keys);
  scratch = gs_options_defaults(&no_keys);
  sh_cli_render r;
  sh_cli_args parsed;
  sh_scene *scene;
  int rc = sh_cli_render_start(&tool, argc, argv, &r, &parsed, &scene);
  if (rc >= 0) return rc;
  sh_error err = SH_ERROR_INIT;
  gs_options opt = gs_options_defaults(scene);
  opt.crop = r.crop;
  if (sh_cli_apply(&tool, &parsed, &opt, &err) != SH_OK) {
    sh_cli_render_free(&r);
    sh_scene_free(scene);
    return sh_cli_report(TOOL, &err);
  }
  if (!r.quiet)
    for (int i = 0; i < scene->nmaterials; i++) {
      const sh_material *m = &scene->materials[i];
      if (!sh_is_black(m->reflect) || !sh_is_black(m->transmit))
        fprintf(stderr, "%s: warning: material '%s' reflects or transmits; "
                        "gl_shafts draws it opaque without reflections\n",
                TOOL, m->name);
    }

  sh_image img = {0};
  gs_stats st;
  if (gs_render(scene, &opt, &img, &st, &err) != SH_OK)
    rc = sh_cli_report(TOOL, &err);
  else
    rc = finish(&r, scene, &opt, &img, &st);
  sh_image_free(&img);
  sh_cli_render_free(&r);
  sh_scene_free(scene);
  return rc;
}
