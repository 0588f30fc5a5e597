/* shafts_compare: one rendering against its reference, in linear radiance,
 * with the figures the validation report quotes (relative RMS over the lit
 * region, mean relative error, PSNR, largest error, bad values) and,
 * optionally, a difference image and an sRGB preview. The figures are those
 * of sh_image_compare (core/sh_compare.h), the measure every renderer of the
 * project is judged by. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "sh_cli.h"
#include "sh_compare.h"
#include "sh_file.h"
#include "sh_image.h"
#include "vc_print.h"
#include "vc_visual.h"

static const char *const TOOL = "shafts_compare";

typedef struct args {
  const char *ref, *img, *diff, *preview;
  double lit, gain, exposure, max_rel_rms;
  int json, parents;
} args;

#define FIELD(f) offsetof(args, f)
static const sh_cli_option options[] = {
    {"lit", 0, SH_CLI_NUMBER, "F", 1, FIELD(lit), 0, 1, 0, 0, NULL, NULL, NULL,
     "0.01",
     "lit region: pixels whose reference luminance exceeds F times the "
     "reference's largest, F in [0, 1)"},
    {"json", 0, SH_CLI_FLAG, NULL, 0, FIELD(json), 0, 0, 0, 1, NULL, NULL,
     NULL, NULL, "print one JSON object instead of text"},
    {"diff", 0, SH_CLI_TEXT, "FILE", 0, FIELD(diff), 0, 0, 0, 0, NULL, NULL,
     NULL, NULL,
     "write the difference image: .exr holds |IMG - REF| per channel; .png a "
     "false-colour picture of the signed luminance difference (red: IMG "
     "brighter, blue: darker, green: NaN, infinite or negative values)"},
    {"diff-gain", 0, SH_CLI_NUMBER, "G", 1, FIELD(gain), 0, INFINITY, 1, 0,
     NULL, NULL, NULL, "10",
     ".png difference: a difference of 1/G of the reference's "
     "99th-percentile luminance is full intensity"},
    {"preview", 0, SH_CLI_TEXT, "FILE", 0, FIELD(preview), 0, 0, 0, 0, NULL,
     NULL, NULL, NULL, "write IMG as an sRGB preview (.png)"},
    {"exposure", 0, SH_CLI_NUMBER, "E", 1, FIELD(exposure), -INFINITY,
     INFINITY, 0, 0, NULL, NULL, NULL, "0", "preview exposure in stops"},
    {"max-rel-rms", 0, SH_CLI_NUMBER, "X", 1, FIELD(max_rel_rms), 0, INFINITY,
     0, 0, NULL, NULL, NULL, NULL,
     "exit with status 3 if rel_rms exceeds X or IMG holds a bad value"},
    {"parents", 'p', SH_CLI_FLAG, NULL, 0, FIELD(parents), 0, 0, 0, 1, NULL,
     NULL, NULL, NULL, "make the directories of --diff and --preview if missing; a run that "
     "fails or is interrupted removes the directories it made"},
};

/* The figures, defined for --help (sh_image_compare in core/sh_compare.h
 * computes them; vc_print.c prints them). */
static void epilogue(FILE *f) {
  fprintf(f, "figures (luminance L = 0.2126 R + 0.7152 G + 0.0722 B; the lit "
             "region:\nthe pixels whose reference L exceeds --lit times the "
             "reference's largest):\n");
  sh_cli_help_item(f, "rel_rms",
                   "relative RMS error over the lit region: sqrt(sum (IMG - "
                   "REF)^2 / sum REF^2) over its pixels and channels; the "
                   "figure the validation reports and bounds");
  sh_cli_help_item(f, "mean_rel",
                   "mean over the lit pixels of |L(IMG) - L(REF)| / L(REF)");
  sh_cli_help_item(f, "psnr",
                   "10 log10(peak^2 / mean squared error) in dB over all "
                   "pixels and channels, peak the reference's largest channel "
                   "value; null (json) for identical images");
  sh_cli_help_item(f, "max_abs",
                   "the largest |IMG - REF| of any pixel and channel, in "
                   "radiance");
  sh_cli_help_item(f, "scale",
                   "sum L(IMG) / sum L(REF) over the lit region: 1 when IMG is "
                   "right on average, 1.1 when 10% too bright");
  sh_cli_help_item(f, "bad_values",
                   "the NaN, infinite and negative values in IMG");
  sh_cli_help_item(f, "lit_pixels", "the size of the lit region");
  sh_cli_help_item(f, "robust_peak",
                   "the reference's 99th-percentile L, which scales the "
                   "--diff picture");
  fprintf(f, "\nBoth images should be linear radiance (EXR, HDR, PFM). An "
             "8-bit image (PNG,\nJPEG) is decoded from sRGB, but it was "
             "clamped to [0, 1] and exposed when\nwritten: compared with a "
             "linear one, the figures measure that too, and a\nwarning says "
             "so.\n");
}

static const sh_cli_tool tool = {
    "shafts_compare", "REF.exr IMG.exr [options]",
    "Compares IMG with the reference REF (same size; any format OpenImageIO\n"
    "reads, taken as linear radiance for float formats) and prints the errors.",
    options, (int)(sizeof options / sizeof *options), 2, 2, epilogue,
    "3 if --max-rel-rms is exceeded.", NULL, NULL, NULL,
    "arguments, a missing or unreadable image"};

/* True if `path` holds linear float radiance: an EXR (by its first bytes)
 * or a Radiance HDR or PFM file (by its name); sh_image_read decodes the
 * other formats, 8 or 16 bits a channel, from sRGB. */
static int linear_float_file(const char *path) {
  static const unsigned char exr_sig[4] = {0x76, 0x2f, 0x31, 0x01};
  unsigned char magic[4] = {0};
  FILE *f = fopen(path, "rb");
  size_t got = f ? fread(magic, 1, sizeof magic, f) : 0;
  if (f) fclose(f);
  if (got == 4 && !memcmp(magic, exr_sig, 4)) return 1;
  char ext[16];
  sh_file_extension(path, ext, sizeof ext);
  return !strcasecmp(ext, "hdr") || !strcasecmp(ext, "pfm");
}

/* Warns when one image is linear float and the other display-encoded. */
static void warn_mixed_encoding(const char *ref, const char *img) {
  int lr = linear_float_file(ref), li = linear_float_file(img);
  if (lr == li) return;
  fprintf(stderr,
          "%s: warning: %s is linear float radiance and %s a display-encoded "
          "(sRGB, 8 or 16 bits) image: it is decoded from sRGB, but it was "
          "clamped to [0, 1] and exposed when written, so the figures measure "
          "that as well; compare the renderers' EXR output\n",
          TOOL, lr ? ref : img, lr ? img : ref);
}

/* Returns -1 to go on, else an exit status. */
static int parse_args(int argc, char **argv, args *a) {
  memset(a, 0, sizeof *a);
  a->lit = 0.01;
  a->gain = 10.0;
  a->max_rel_rms = -1.0;
  sh_cli_args parsed;
  int rc = sh_cli_parse(&tool, argc, argv, a, &parsed);
  if (rc >= 0) return rc;
  if (a->lit >= 1) {
    sh_cli_error(TOOL, "--lit: expected a number in [0, 1), found '%g'", a->lit);
    return SH_EXIT_BAD_INPUT;
  }
  a->ref = parsed.operands[0];
  a->img = parsed.operands[1];
  /* Both names checked before -p makes any directory. */
  if ((a->diff && !sh_cli_check_name(TOOL, "--diff", a->diff)) ||
      (a->preview && !sh_cli_check_name(TOOL, "--preview", a->preview)))
    return SH_EXIT_BAD_INPUT;
  if ((a->diff &&
       !sh_cli_check_output(TOOL, "--diff", a->diff, "exr,png", a->parents)) ||
      (a->preview &&
       !sh_cli_check_output(TOOL, "--preview", a->preview, "png", a->parents)))
    return SH_EXIT_BAD_INPUT;
  return -1;
}

/* Writes the difference image the extension of a->diff asks for. */
static sh_status write_diff(const args *a, sh_outputs *set, const sh_image *img,
                            const sh_image *ref, const sh_image *absdiff,
                            double robust_peak, sh_error *err) {
  char ext[16];
  sh_file_extension(a->diff, ext, sizeof ext);
  if (!strcmp(ext, "exr"))
    return sh_outputs_write_image(set, a->diff, absdiff, 0.0, NULL, err);
  sh_image vis = {0};
  sh_status st = vc_signed_diff(img, ref, robust_peak / a->gain, &vis, err);
  if (st == SH_OK) st = sh_outputs_write_image(set, a->diff, &vis, 0.0, NULL, err);
  sh_image_free(&vis);
  return st;
}

int main(int argc, char **argv) {
  args a;
  int rc = parse_args(argc, argv, &a);
  if (rc >= 0) return rc;
  /* The images compared are the inputs; --diff and --preview the outputs,
   * distinct from them and from each other, written together or not at
   * all. */
  sh_outputs *set;
  if ((rc = sh_cli_files(TOOL, NULL, &set))) return rc;
  sh_error err = SH_ERROR_INIT;
  if (sh_outputs_input(set, a.ref, "the reference", &err) != SH_OK ||
      sh_outputs_input(set, a.img, "the image", &err) != SH_OK) {
    sh_outputs_free(set);
    return sh_cli_report(TOOL, &err);
  }
  if ((a.diff && (rc = sh_cli_file_out(TOOL, set, a.diff, "--diff"))) ||
      (a.preview && (rc = sh_cli_file_out(TOOL, set, a.preview, "--preview")))) {
    sh_outputs_free(set);
    return rc;
  }

  sh_image ref = {0}, img = {0}, absdiff = {0};
  vc_result r;
  memset(&r, 0, sizeof r);
  sh_status st = sh_image_read(a.ref, &ref, &err);
  if (st == SH_OK) st = sh_image_read(a.img, &img, &err);
  if (st != SH_OK) {
    /* A missing or unreadable input is bad input, whatever its cause. */
    sh_cli_report(TOOL, &err);
    sh_image_free(&ref);
    sh_outputs_free(set);
    return 2;
  }
  if (img.width != ref.width || img.height != ref.height) {
    /* sh_image_compare refuses it too, without the files' names. */
    fprintf(stderr,
            "%s: error: '%s' is %dx%d and the reference '%s' %dx%d: the "
            "images must be the same size (render both at one --width and "
            "--height)\n",
            TOOL, a.img, img.width, img.height, a.ref, ref.width, ref.height);
    sh_image_free(&ref);
    sh_image_free(&img);
    sh_outputs_free(set);
    return 2;
  }
  warn_mixed_encoding(a.ref, a.img);
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
    st = write_diff(&a, set, &img, &ref, &absdiff, r.robust_peak, &err);
  if (st == SH_OK && a.preview)
    st = sh_outputs_write_image(set, a.preview, &img, a.exposure, NULL, &err);
  if (st == SH_OK) st = sh_outputs_publish(set, &err);
  if (st == SH_OK) sh_cli_dirs_keep();
  sh_outputs_free(set);
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
      rc = SH_EXIT_CHECK;
    }
  }
  sh_image_free(&ref);
  sh_image_free(&img);
  sh_image_free(&absdiff);
  return rc;
}
