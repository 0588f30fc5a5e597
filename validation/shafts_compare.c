/* shafts_compare: one rendering against its reference, in linear radiance,
 * with the figures the validation report quotes (relative RMS over the lit
 * region, mean relative error, PSNR, largest error, bad values) and,
 * optionally, a difference image and an sRGB preview. The figures are those
 * of sh_image_compare (core/sh_compare.h), the measure every renderer of the
 * project is judged by. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sh_cli.h"
#include "sh_compare.h"
#include "sh_file.h"
#include "sh_image.h"
#include "vc_print.h"
#include "vc_visual.h"

static const char *const TOOL = "shafts_compare";

static void usage(FILE *f) {
  fprintf(f,
"usage: shafts_compare REF.exr IMG.exr [options]\n"
"\n"
"Compares IMG with the reference REF (same size; any format OpenImageIO\n"
"reads, taken as linear radiance for float formats) and prints the errors.\n"
"\n"
"options:\n"
"  --lit F            lit region: pixels whose reference luminance exceeds F\n"
"                     times the reference's largest (default 0.01)\n"
"  --json             print one JSON object instead of text\n"
"  --diff FILE        write the difference image: .exr holds |IMG - REF| per\n"
"                     channel; .png a false-colour picture of the signed\n"
"                     luminance difference (red: IMG brighter, blue: darker,\n"
"                     green: NaN, infinite or negative values)\n"
"  --diff-gain G      .png difference: a difference of 1/G of the reference's\n"
"                     99th-percentile luminance is full intensity (default 10)\n"
"  --preview FILE     write IMG as an sRGB preview (.png)\n"
"  --exposure E       preview exposure in stops (default 0)\n"
"  --max-rel-rms X    exit with status 3 if rel_rms exceeds X or IMG holds a\n"
"                     bad value\n"
"  -h, --help         show this help\n"
"\n"
"Exit status: 0 on success, 2 for bad input (arguments, unreadable images,\n"
"different sizes), 3 if --max-rel-rms is exceeded, 1 otherwise.\n");
}

typedef struct args {
  const char *ref, *img, *diff, *preview;
  double lit, gain, exposure, max_rel_rms;
  int json;
} args;

/* Returns -1 to go on, else an exit status. */
static int parse_args(int argc, char **argv, args *a) {
  memset(a, 0, sizeof *a);
  a->lit = 0.01;
  a->gain = 10.0;
  a->max_rel_rms = -1.0;
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    const char *v = i + 1 < argc ? argv[i + 1] : NULL;
    int ok = 1;
    if (!strcmp(o, "-h") || !strcmp(o, "--help")) {
      usage(stdout);
      return 0;
    } else if (!strcmp(o, "--json")) {
      a->json = 1;
      continue;
    } else if (o[0] == '-' && o[1] != '\0' && !v) {
      fprintf(stderr, "%s: %s needs a value\n", TOOL, o);
      return 2;
    } else if (!strcmp(o, "--lit")) {
      ok = sh_cli_double(TOOL, o, v, &a->lit);
      if (ok && !(a->lit >= 0 && a->lit < 1)) {
        fprintf(stderr, "%s: --lit expects a number in [0, 1), got '%s'\n",
                TOOL, v);
        ok = 0;
      }
    } else if (!strcmp(o, "--diff")) {
      a->diff = v;
    } else if (!strcmp(o, "--diff-gain")) {
      ok = sh_cli_double(TOOL, o, v, &a->gain);
      if (ok && !(a->gain > 0)) {
        fprintf(stderr, "%s: --diff-gain expects a number > 0, got '%s'\n",
                TOOL, v);
        ok = 0;
      }
    } else if (!strcmp(o, "--preview")) {
      a->preview = v;
    } else if (!strcmp(o, "--exposure")) {
      ok = sh_cli_double(TOOL, o, v, &a->exposure);
    } else if (!strcmp(o, "--max-rel-rms")) {
      ok = sh_cli_double(TOOL, o, v, &a->max_rel_rms) && a->max_rel_rms >= 0;
      if (!ok) fprintf(stderr, "%s: --max-rel-rms expects a number >= 0\n", TOOL);
    } else {
      const char **operands[] = {&a->ref, &a->img};
      if (!sh_cli_operand(TOOL, o, operands, 2)) return 2;
      continue;
    }
    if (!ok) return 2;
    i++;
  }
  if (!a->ref || !a->img) {
    fprintf(stderr, "%s: need REF and IMG (see --help)\n", TOOL);
    return 2;
  }
  const char *outs[2] = {a->diff, a->preview};
  for (int k = 0; k < 2; k++) {
    if (!outs[k]) continue;
    char ext[16];
    sh_file_extension(outs[k], ext, sizeof ext);
    if (strcmp(ext, "png") && (k == 1 || strcmp(ext, "exr"))) {
      fprintf(stderr, "%s: '%s' must end in %s\n", TOOL, outs[k],
              k == 0 ? ".exr or .png" : ".png");
      return 2;
    }
  }
  return -1;
}

/* Writes the difference image the extension of a->diff asks for. */
static sh_status write_diff(const args *a, const sh_image *img,
                            const sh_image *ref, const sh_image *absdiff,
                            double robust_peak, sh_error *err) {
  char ext[16];
  sh_file_extension(a->diff, ext, sizeof ext);
  if (!strcmp(ext, "exr")) return sh_image_write(a->diff, absdiff, 0.0, err);
  sh_image vis = {0};
  sh_status st = vc_signed_diff(img, ref, robust_peak / a->gain, &vis, err);
  if (st == SH_OK) st = sh_image_write(a->diff, &vis, 0.0, err);
  sh_image_free(&vis);
  return st;
}

int main(int argc, char **argv) {
  args a;
  int rc = parse_args(argc, argv, &a);
  if (rc >= 0) return rc;

  sh_error err;
  sh_image ref = {0}, img = {0}, absdiff = {0};
  vc_result r;
  memset(&r, 0, sizeof r);
  sh_status st = sh_image_read(a.ref, &ref, &err);
  if (st == SH_OK) st = sh_image_read(a.img, &img, &err);
  if (st != SH_OK) {
    /* A missing or unreadable input is bad input, whatever its cause. */
    sh_cli_report(TOOL, &err);
    sh_image_free(&ref);
    return 2;
  }
  st = sh_image_compare(&img, &ref, a.lit, &r.e, a.diff ? &absdiff : NULL,
                          &err);
  if (st == SH_OK) {
    r.width = img.width;
    r.height = img.height;
    r.lit_fraction = a.lit;
    r.scale = vc_lit_scale(&img, &ref, a.lit);
    r.robust_peak = vc_robust_peak(&ref, 0.99);
  }
  if (st == SH_OK && a.diff)
    st = write_diff(&a, &img, &ref, &absdiff, r.robust_peak, &err);
  if (st == SH_OK && a.preview)
    st = sh_image_write(a.preview, &img, a.exposure, &err);
  if (st != SH_OK) {
    rc = sh_cli_report(TOOL, &err);
  } else {
    if (a.json)
      vc_print_json(stdout, &r);
    else
      vc_print_text(stdout, &r);
    rc = 0;
    if (a.max_rel_rms >= 0 &&
        (r.e.rel_rms > a.max_rel_rms || r.e.bad_values > 0)) {
      fprintf(stderr,
              "%s: %s: relative RMS error %.4g%% (bound %.4g%%), %ld bad "
              "values\n",
              TOOL, a.img, 100.0 * r.e.rel_rms, 100.0 * a.max_rel_rms,
              r.e.bad_values);
      rc = 3;
    }
  }
  sh_image_free(&ref);
  sh_image_free(&img);
  sh_image_free(&absdiff);
  return rc;
}
