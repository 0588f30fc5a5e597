/* scene_export: one scene for POV-Ray, Blender (Cycles and EEVEE) or as the
 * normalised scene file. The work is in the library (the targets' table,
 * se_run.h); this is the command line around it: --to's choices, its help
 * and the dispatch all come from that table. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "se_run.h"
#include "se_scale.h"
#include "sh_cli.h"
#include "sh_parse.h"

static const char *const TOOL = "scene_export";

typedef struct args {
  const char *output, *scale;
  int to, quality, strict, parents, verbose, quiet;
  long width, height; /* --width, --height; 0: the scene's */
} args;

enum { MAX_TARGETS = 16 };

static const sh_cli_choice qualities[] = {
    {"draft", SE_QUALITY_DRAFT}, {"final", SE_QUALITY_FINAL}, {NULL, 0}};

#define FIELD(f) offsetof(args, f)
static sh_cli_option options[] = {
    {"to", 0, SH_CLI_CHOICE, NULL, 0, FIELD(to), 0, 0, 0, 0, NULL, NULL, NULL,
     NULL, "the target (below)"},
    {"output", 'o', SH_CLI_TEXT, "OUT", 0, FIELD(output), 0, 0, 0, 0, NULL,
     NULL, NULL, NULL, "the output file, named as its target says below"},
    {"parents", 'p', SH_CLI_FLAG, NULL, 0, FIELD(parents), 0, 0, 0, 1, NULL,
     NULL, NULL, NULL, "make the output's directory (and its parents) if missing; a run that "
     "fails or is interrupted removes the directories it made"},
    {"quality", 0, SH_CLI_CHOICE, NULL, 0, FIELD(quality), 0, 0, 0, 0,
     qualities, NULL, NULL, "draft",
     "draft: quick settings for previews and tests; final: medium intervals "
     "and samples for a converged comparison"},
    {"strict", 0, SH_CLI_FLAG, NULL, 0, FIELD(strict), 0, 0, 0, 1, NULL, NULL,
     NULL, NULL,
     "refuse (exit 2, nothing written) if the target cannot represent the "
     "scene exactly"},
    {"scale", 0, SH_CLI_TEXT, "S", 0, FIELD(scale), 0, 0, 0, 0, NULL, NULL,
     NULL, "auto",
     "the POV-Ray and Blender exports' length scale: auto (chosen from the "
     "scene's size, with its content or camera moved to the origin when far "
     "from it: the same image, docs/scene_export.md \"Precision\"), a "
     "positive number of target units per scene unit (the origin still "
     "chosen), or none (the scene's own units and position)"},
    SH_CLI_SIZE_OPTIONS(FIELD(width), FIELD(height)),
    {"verbose", 'v', SH_CLI_FLAG, NULL, 0, FIELD(verbose), 0, 0, 0, 1, NULL,
     NULL, NULL, NULL, "print the scale and origin the export chose"},
    {"quiet", 'q', SH_CLI_FLAG, NULL, 0, FIELD(quiet), 0, 0, 0, 1, NULL, NULL,
     NULL, NULL, "no messages but errors: no warnings, no `wrote` and `render` lines"},
};

/* --scale's value into opt: 1, or prints the problem and returns 0. */
static int parse_scale(const char *text, se_options *opt) {
  if (!text || !strcmp(text, "auto")) return 1;
  if (!strcmp(text, "none")) {
    opt->scale_mode = SE_SCALE_NONE;
    return 1;
  }
  char *end;
  double v = strtod(text, &end);
  if (end == text || *end || !isfinite(v) || !(v > 0)) {
    sh_cli_error(TOOL, "--scale: expected auto, none or a positive number, not '%s'", text);
    return 0;
  }
  opt->scale_mode = SE_SCALE_FIXED;
  opt->scale = v;
  return 1;
}

/* --to's choices and the targets' help, from the targets' table. */
static sh_cli_choice targets[MAX_TARGETS + 1];

static void describe_targets(void) {
  int k = 0;
  for (const se_target *t = se_targets; t->name && k < MAX_TARGETS; t++, k++)
    targets[k] = (sh_cli_choice){t->name, k};
  targets[k] = (sh_cli_choice){NULL, 0};
  options[0].choices = targets;
}

static void help_targets(FILE *f) {
  fprintf(f, "targets:\n");
  for (const se_target *t = se_targets; t->name; t++) {
    char label[64];
    snprintf(label, sizeof label, "--to %s", t->name);
    sh_cli_help_item(f, label, t->help);
  }
  fprintf(f, "\nApproximations are printed as warnings on stderr and written "
             "into the output.\nFiles are written whole or not at all; a "
             "refused --strict export exits 2.\nA successful export prints "
             "(on stderr, as the renderers do) `scene_export: wrote\nFILES` "
             "and `scene_export: render: COMMANDS`, the shell commands that "
             "make the image\n(for POV-Ray frames, povray then oiiotool's "
             "signed sum).\n");
}

/* The renderers' last line (sh_cli_render_done's form), then the commands
 * that make the image from the files. */
static void print_done(const se_output *result) {
  fprintf(stderr, "%s: wrote", TOOL);
  for (int k = 0; k < result->count; k++)
    fprintf(stderr, "%s %s", k ? "," : "", result->files[k].path);
  fputc('\n', stderr);
  if (result->render.data && !result->render.failed)
    fprintf(stderr, "%s: render: %s\n", TOOL, result->render.data);
}

int main(int argc, char **argv) {
  describe_targets();
  const sh_cli_tool tool = {
      TOOL, "SCENE.json --to TARGET -o OUT [options]",
      "Exports a scene (docs/scene-format.md) so that other renderers draw "
      "the same\nimage in linear radiance (docs/scene_export.md).",
      options, (int)(sizeof options / sizeof *options), 1, 1, help_targets, NULL,
      NULL, NULL, NULL, NULL};
  args a = {NULL, NULL, -1, SE_QUALITY_DRAFT, 0, 0, 0, 0, 0, 0};
  sh_cli_args parsed;
  int rc = sh_cli_parse(&tool, argc, argv, &a, &parsed);
  if (rc >= 0) return rc;
  if (a.to < 0 || !a.output) {
    sh_cli_error(TOOL, "%s is required (see --help)",
            a.to < 0 ? "--to" : "-o OUT");
    return SH_EXIT_BAD_INPUT;
  }
  const se_target *target = &se_targets[a.to];
  if (!sh_cli_check_output(TOOL, "-o", a.output, target->extension, a.parents))
    return SH_EXIT_BAD_INPUT;

  se_options opt = {(se_quality)a.quality, SE_SCALE_AUTO, 0.0};
  if (!parse_scale(a.scale, &opt)) return SH_EXIT_BAD_INPUT;

  sh_scene *scene = NULL;
  if ((rc = sh_cli_load_scene(TOOL, parsed.operands[0], a.quiet, &scene))) return rc;
  /* The image size every target writes (the .ini's Width/Height and the
   * .pov's aspect, the Blender data's render size, the JSON camera) is the
   * camera's: --width/--height change it as they do the renderers'. */
  sh_cli_resize(scene, a.width, a.height);
  sh_error err = SH_ERROR_INIT;
  se_notes notes = {0};
  se_output result;
  sh_status st = se_export_scene(scene, target, &opt, a.output, a.strict, &notes,
                                 &result, &err);
  if (a.verbose && result.has_frame && result.frame.scale > 0) {
    char *text = se_scale_describe(&result.frame);
    fprintf(stderr, "%s: frame: %s\n", TOOL, text ? text : "out of memory");
    free(text);
  }
  if (st == SH_OK) {
    sh_cli_dirs_keep();
    if (!a.quiet) {
      for (int i = 0; i < notes.count; i++)
        fprintf(stderr, "%s: warning: %s\n", TOOL, notes.text[i]);
      print_done(&result);
    }
  } else if (a.strict && notes.count > 0 && st == SH_ERR_SCENE) {
    for (int i = 0; i < notes.count; i++)
      fprintf(stderr, "%s: error: --strict: %s\n", TOOL, notes.text[i]);
    fprintf(stderr, "%s: error: --strict: %s\n", TOOL, err.message);
    sh_error_clear(&err);
    rc = SH_EXIT_BAD_INPUT;
  } else {
    rc = sh_cli_report(TOOL, &err);
  }
  se_output_free(&result);
  se_notes_free(&notes);
  sh_scene_free(scene);
  return rc;
}
