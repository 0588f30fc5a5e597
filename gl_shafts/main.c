/* gl_shafts: renders a scene with the plane-sweep method of Dobashi et al.
 * (2000) on OpenGL through EGL or OSMesa. The command-line face of
 * gs_render.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gs_named.h"
#include "gs_render.h"
#include "sh_cli.h"
#include "sh_file.h"
#include "sh_image.h"
#include "sh_parse.h"

static const char *const TOOL = "gl_shafts";

static void usage(FILE *f) {
  fprintf(f,
"usage: gl_shafts SCENE.json -o OUT.exr|OUT.png [options]\n"
"\n"
"Renders a scene (docs/scene-format.md) with shafts of light by the plane-sweep\n"
"method of Dobashi, Yamamoto and Nishita (2000) on OpenGL 4.5, through EGL (a\n"
"GPU if there is one, else llvmpipe on the CPU) or OSMesa.\n"
"Options override the scene's render keys; docs/gl_shafts.md has the details.\n"
"\n"
"options:\n"
"  -o, --output FILE      output image: .exr (linear 32-bit float radiance) or\n"
"                         .png (sRGB of radiance * 2^exposure, clamped);\n"
"                         repeat to write several formats from one render\n"
"  --planes N             virtual planes per light (default: render.planes, else\n"
"                         %d for point and spot lights, %d for directional ones)\n"
"  --lattice NU NV        lattice points per plane for xi (default: render.lattice,\n"
"                         else %d %d)\n"
"  --light-map-res R      resample light maps to R x R (default: render.light_map_res,\n"
"                         else each map's own size)\n"
"  --shadow-map-res S     shadow-map size (default: render.shadow_map_res, else\n"
"                         %d for point and spot lights, %d for directional ones)\n"
"  --xi lattice|exact     xi on the lattice, interpolated (the paper's method), or\n"
"                         per fragment (default: render.xi, else %s)\n"
"  --jitter, --no-jitter  per-pixel jitter of the sample depths (default:\n"
"                         render.jitter, else %s)\n"
"  --sub-angle DEG        point and spot lights: one sample per DEG degrees that a\n"
"                         plane's part of a ray subtends at the light (default %g)\n"
"  --sub-texels T         lights with a map (a spot's gobo, a window): one sample\n"
"                         per T map texels a plane's part of a ray crosses\n"
"                         (default %g)\n"
"  --backend auto|egl|osmesa\n"
"                         where the GL context comes from (default auto: EGL's\n"
"                         devices, a GPU first, then EGL surfaceless, then OSMesa;\n"
"                         the environment variable SHAFTS_GL_BACKEND narrows auto)\n"
"  --exposure E           PNG exposure in stops (default: render.exposure, else 0)\n"
"  --stats FILE.json      write the time (split by stage), the counts (shader\n"
"                         programs compiled among them), the backend and GL's\n"
"                         renderer and vendor strings as JSON\n"
"  -q, --quiet            no messages but errors\n"
"  -h, --help             show this help\n"
"\n"
"Exit status: 0 on success, 2 for bad input (arguments, scene), 1 otherwise.\n",
          GS_DEFAULT_PLANES_LOCAL, GS_DEFAULT_PLANES_DIRECTIONAL,
          GS_DEFAULT_LATTICE, GS_DEFAULT_LATTICE, GS_DEFAULT_SHADOW_LOCAL,
          GS_DEFAULT_SHADOW_DIRECTIONAL, GS_DEFAULT_XI == SH_XI_EXACT ? "exact" : "lattice",
          GS_DEFAULT_JITTER ? "on" : "off", GS_DEFAULT_SUB_ANGLE_DEG,
          GS_DEFAULT_SUB_TEXELS);
}

#define MAX_OUTPUTS 8

typedef struct args {
  const char *scene, *stats;
  const char *outputs[MAX_OUTPUTS];
  int noutputs;
  long planes, lattice_u, lattice_v, light_map_res, shadow_map_res;
  sh_xi_mode xi;
  int jitter; /* -1: not given */
  gs_backend backend;
  double exposure, sub_angle, sub_texels;
  int has_exposure, quiet;
} args;

/* Returns -1 to go on, else an exit status. */
static int parse_args(int argc, char **argv, args *a) {
  memset(a, 0, sizeof *a);
  a->jitter = -1;
  a->xi = SH_XI_DEFAULT;
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    const char *v = i + 1 < argc ? argv[i + 1] : NULL;
    int ok = 1;
    if (!strcmp(o, "-h") || !strcmp(o, "--help")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(o, "-q") || !strcmp(o, "--quiet")) {
      a->quiet = 1;
      continue;
    } else if (!strcmp(o, "--jitter") || !strcmp(o, "--no-jitter")) {
      a->jitter = !strcmp(o, "--jitter");
      continue;
    } else if (o[0] == '-' && o[1] != '\0' && !v) {
      fprintf(stderr, "%s: %s needs a value\n", TOOL, o);
      return 2;
    } else if (!strcmp(o, "-o") || !strcmp(o, "--output")) {
      if (a->noutputs == MAX_OUTPUTS) {
        fprintf(stderr, "%s: at most %d outputs\n", TOOL, MAX_OUTPUTS);
        return 2;
      }
      a->outputs[a->noutputs++] = v;
    } else if (!strcmp(o, "--stats")) {
      a->stats = v;
    } else if (!strcmp(o, "--planes")) {
      ok = sh_cli_int(TOOL, o, v, 1, 100000, &a->planes);
    } else if (!strcmp(o, "--lattice")) {
      const char *v2 = i + 2 < argc ? argv[i + 2] : NULL;
      ok = sh_cli_int(TOOL, "--lattice NU", v, 2, 4096, &a->lattice_u) &&
           sh_cli_int(TOOL, "--lattice NV", v2, 2, 4096, &a->lattice_v);
      i++;
    } else if (!strcmp(o, "--light-map-res")) {
      ok = sh_cli_int(TOOL, o, v, 1, 16384, &a->light_map_res);
    } else if (!strcmp(o, "--shadow-map-res")) {
      ok = sh_cli_int(TOOL, o, v, 1, 16384, &a->shadow_map_res);
    } else if (!strcmp(o, "--xi")) {
      if (!strcmp(v, "lattice")) a->xi = SH_XI_LATTICE;
      else if (!strcmp(v, "exact")) a->xi = SH_XI_EXACT;
      else {
        fprintf(stderr, "%s: --xi expects lattice or exact, got '%s'\n", TOOL, v);
        return 2;
      }
    } else if (!strcmp(o, "--backend")) {
      if (!strcmp(v, "auto")) a->backend = GS_BACKEND_AUTO;
      else if (!strcmp(v, "egl")) a->backend = GS_BACKEND_EGL;
      else if (!strcmp(v, "osmesa")) a->backend = GS_BACKEND_OSMESA;
      else {
        fprintf(stderr, "%s: --backend expects auto, egl or osmesa, got '%s'\n",
                TOOL, v);
        return 2;
      }
    } else if (!strcmp(o, "--sub-angle")) {
      ok = sh_cli_double(TOOL, o, v, &a->sub_angle);
      if (ok && !(a->sub_angle > 0 && a->sub_angle <= 30)) {
        fprintf(stderr, "%s: --sub-angle expects degrees in (0, 30], got '%s'\n", TOOL, v);
        return 2;
      }
    } else if (!strcmp(o, "--sub-texels")) {
      ok = sh_cli_double(TOOL, o, v, &a->sub_texels);
      if (ok && !(a->sub_texels > 0 && a->sub_texels <= 1e6)) {
        fprintf(stderr, "%s: --sub-texels expects a number in (0, 1e6], got '%s'\n", TOOL, v);
        return 2;
      }
    } else if (!strcmp(o, "--exposure")) {
      ok = sh_cli_double(TOOL, o, v, &a->exposure);
      a->has_exposure = 1;
    } else {
      const char **operands[] = {&a->scene};
      if (!sh_cli_operand(TOOL, o, operands, 1)) return 2;
      continue;
    }
    if (!ok) return 2;
    i++;
  }
  if (!sh_cli_check_render_outputs(TOOL, a->scene, a->outputs, a->noutputs))
    return 2;
  return -1;
}

/* The --stats record: the frame's statistics (gs_stats_json) with the tool,
 * the scene and the options. */
static sh_stats *stats_record(const args *a, const gs_options *o,
                              const gs_stats *st) {
  size_t n = gs_stats_json(st, NULL, 0);
  char *text = n ? malloc(n + 1) : NULL;
  if (text) gs_stats_json(st, text, n + 1);
  sh_stats *s = sh_stats_from_json(text);
  free(text);
  sh_stats_str(s, "tool", TOOL);
  sh_stats_str(s, "scene", a->scene);
  if (o->planes) sh_stats_num(s, "planes_per_light", o->planes);
  else sh_stats_str(s, "planes_per_light", "by light kind");
  sh_stats_num(s, "lattice_u", o->lattice_u);
  sh_stats_num(s, "lattice_v", o->lattice_v);
  sh_stats_num(s, "light_map_res", o->light_map_res);
  if (o->shadow_map_res) sh_stats_num(s, "shadow_map_res", o->shadow_map_res);
  else sh_stats_str(s, "shadow_map_res", "by light kind");
  sh_stats_str(s, "xi", o->xi == SH_XI_EXACT ? "exact" : "lattice");
  sh_stats_num(s, "jitter", o->jitter);
  sh_stats_num(s, "sub_angle_deg", o->sub_angle_deg);
  sh_stats_num(s, "sub_texels", o->sub_texels);
  return s;
}

int main(int argc, char **argv) {
  args a;
  int rc = parse_args(argc, argv, &a);
  if (rc >= 0) return rc;

  sh_error err;
  sh_scene *scene = NULL;
  if (sh_scene_load(a.scene, &scene, &err) != SH_OK)
    return sh_cli_report(TOOL, &err);
  if (scene->nlights == 0 && !a.quiet)
    fprintf(stderr, "%s: warning: the scene has no lights; the image is "
                    "black but for emission and background\n", TOOL);

  gs_options opt = gs_options_defaults(scene);
  if (a.planes) opt.planes = (int)a.planes;
  if (a.lattice_u) {
    opt.lattice_u = (int)a.lattice_u;
    opt.lattice_v = (int)a.lattice_v;
  }
  if (a.light_map_res) opt.light_map_res = (int)a.light_map_res;
  if (a.shadow_map_res) opt.shadow_map_res = (int)a.shadow_map_res;
  if (a.xi != SH_XI_DEFAULT) opt.xi = a.xi;
  if (a.jitter >= 0) opt.jitter = a.jitter;
  if (a.sub_angle > 0) opt.sub_angle_deg = a.sub_angle;
  if (a.sub_texels > 0) opt.sub_texels = a.sub_texels;
  opt.backend = a.backend;
  double exposure = a.has_exposure ? a.exposure : scene->render.exposure;
  if (!a.quiet)
    for (int i = 0; i < scene->nmaterials; i++) {
      const sh_material *m = &scene->materials[i];
      if (!sh_is_black(m->reflect) || !sh_is_black(m->transmit)) {
        fprintf(stderr, "%s: warning: material '%s' reflects or transmits; "
                        "gl_shafts draws it opaque without reflections\n",
                TOOL, m->name);
      }
    }

  sh_image img = {0};
  gs_stats st;
  sh_status status = gs_render(scene, &opt, &img, &st, &err);
  for (int k = 0; status == SH_OK && k < a.noutputs; k++)
    status = sh_image_write(a.outputs[k], &img, exposure, &err);
  rc = 0;
  if (status != SH_OK) {
    rc = sh_cli_report(TOOL, &err);
  } else if (a.stats) {
    sh_stats *s = stats_record(&a, &opt, &st);
    if (sh_stats_write(s, a.stats, &err) != SH_OK) rc = sh_cli_report(TOOL, &err);
    sh_stats_free(s);
  }
  if (rc == 0 && !a.quiet)
    for (int k = 0; k < a.noutputs; k++)
      fprintf(stderr, "%s: wrote %s (%dx%d, %.3f s a frame + %.3f s setup)\n",
              TOOL, a.outputs[k], img.width, img.height, st.seconds,
              st.setup_seconds);
  sh_image_free(&img);
  sh_scene_free(scene);
  return rc;
}
