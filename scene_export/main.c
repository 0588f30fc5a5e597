/* scene_export: one scene for POV-Ray, Blender (Cycles and EEVEE) or as the
 * normalised scene file. The work is in the library (se_pov.h,
 * se_blender.h, se_json.h); this is the command line around it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "se_run.h"
#include "sh_cli.h"
#include "sh_parse.h"

static const char *const TOOL = "scene_export";

static void usage(FILE *f) {
  fprintf(f,
"usage: scene_export SCENE.json --to pov|blender|json -o OUT [options]\n"
"\n"
"Exports a scene (docs/scene-format.md) so that other renderers draw the same\n"
"image in linear radiance (docs/scene_export.md).\n"
"\n"
"  --to pov       OUT = DIR/NAME.pov: writes NAME.pov, NAME.ini and the light\n"
"                 maps NAME_map<i>.exr; `povray NAME.ini` in DIR renders\n"
"                 DIR/NAME.exr\n"
"  --to blender   OUT = DIR/NAME.py: writes NAME.py (a fixed script) and its\n"
"                 data NAME.json (and light maps NAME_map<i>.exr); render with\n"
"                 blender -b -P DIR/NAME.py -- --engine cycles|eevee --out IMG.exr\n"
"                     [--samples N] [--seed S]\n"
"                 (EEVEE needs a display: run it under xvfb-run)\n"
"  --to json      OUT = FILE.json: the normalised scene (defaults filled in,\n"
"                 transforms as matrices, files as absolute paths)\n"
"\n"
"options:\n"
"  -o, --output OUT         the output file, as above\n"
"  --quality draft|final   draft (default): quick settings for previews and\n"
"                           tests; final: medium intervals and samples for a\n"
"                           converged comparison\n"
"  --strict                 refuse (exit 2, nothing written) if the target\n"
"                           cannot represent the scene exactly\n"
"  -h, --help               show this help\n"
"\n"
"Approximations are printed as warnings on stderr and written into the\n"
"output. Exit status: 0 on success, 2 for bad input (arguments, scene, a\n"
"refused --strict export), 1 for other failures. Files are written whole\n"
"or not at all.\n");
}

enum { TO_NONE = -1 };

int main(int argc, char **argv) {
  const char *scene_path = NULL, *out_path = NULL;
  int to = TO_NONE, strict = 0; /* an se_target */
  se_options opt = {SE_QUALITY_DRAFT};
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    const char *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(a, "--to")) {
      if (!v) goto missing;
      i++;
      if (!strcmp(v, "pov")) to = SE_TARGET_POV;
      else if (!strcmp(v, "blender")) to = SE_TARGET_BLENDER;
      else if (!strcmp(v, "json")) to = SE_TARGET_JSON;
      else {
        fprintf(stderr, "%s: --to expects pov, blender or json, got '%s'\n", TOOL, v);
        return 2;
      }
    } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
      if (!v) goto missing;
      if (out_path) {
        fprintf(stderr, "%s: only one output (-o) is allowed\n", TOOL);
        return 2;
      }
      out_path = v;
      i++;
    } else if (!strcmp(a, "--quality")) {
      if (!v) goto missing;
      i++;
      if (!strcmp(v, "draft")) opt.quality = SE_QUALITY_DRAFT;
      else if (!strcmp(v, "final")) opt.quality = SE_QUALITY_FINAL;
      else {
        fprintf(stderr, "%s: --quality expects draft or final, got '%s'\n", TOOL, v);
        return 2;
      }
    } else if (!strcmp(a, "--strict")) {
      strict = 1;
    } else if (a[0] == '-' && a[1] != '\0') {
      fprintf(stderr, "%s: unknown option '%s' (see --help)\n", TOOL, a);
      return 2;
    } else if (!scene_path) {
      scene_path = a;
    } else {
      fprintf(stderr, "%s: one scene file only; '%s' is extra\n", TOOL, a);
      return 2;
    }
    continue;
  missing:
    fprintf(stderr, "%s: %s expects a value\n", TOOL, a);
    return 2;
  }
  if (!scene_path || to == TO_NONE || !out_path) {
    fprintf(stderr, "%s: %s is required\n%s", TOOL,
            !scene_path ? "a scene file" : to == TO_NONE ? "--to" : "-o OUT",
            "usage: scene_export SCENE.json --to pov|blender|json -o OUT "
            "[--quality draft|final] [--strict] [--help]\n");
    return 2;
  }

  sh_error err;
  sh_scene *scene = NULL;
  if (sh_scene_load(scene_path, &scene, &err) != SH_OK)
    return sh_cli_report(TOOL, &err);
  if (scene->nlights == 0)
    fprintf(stderr, "%s: warning: the scene has no light; its image is black but "
                    "for emission, ambient and background\n", TOOL);
  se_notes notes = {0};
  sh_status st = se_export_scene(scene, (se_target)to, &opt, out_path, strict, &notes, &err);
  int code = 0;
  if (st == SH_OK) {
    for (int i = 0; i < notes.count; i++)
      fprintf(stderr, "%s: warning: %s\n", TOOL, notes.text[i]);
  } else if (strict && notes.count > 0 && st == SH_ERR_SCENE) {
    for (int i = 0; i < notes.count; i++)
      fprintf(stderr, "%s: error: --strict: %s\n", TOOL, notes.text[i]);
    fprintf(stderr, "%s: error: --strict: %s\n", TOOL, err.message);
    code = 2;
  } else {
    code = sh_cli_report(TOOL, &err);
  }
  se_notes_free(&notes);
  sh_scene_free(scene);
  return code;
}
