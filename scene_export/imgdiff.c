/* se_imgdiff: compares two linear EXR images over the lit region of the
 * first (the reference) and prints the statistics as one JSON object.
 *
 *   se_imgdiff REF.exr TEST.exr [--lit FRACTION] [--mask MASK.exr] [--map]
 *
 * A pixel is lit when the mean of its reference channels exceeds FRACTION
 * (default 0.01) times the largest such mean in the image. Printed:
 *   lit        the number of lit pixels,
 *   mean_rel   the mean over lit pixels of |test - ref| / ref, on the
 *              channel means (the figure the tests bound),
 *   ratio      sum(test) / sum(ref) over lit pixels (a systematic scale
 *              error shows here),
 *   max_rel    the largest per-pixel relative difference,
 *   p90_rel    its 90th percentile.
 * --mask takes the lit region and the denominators from MASK.exr instead of
 * REF.exr: `se_imgdiff A.exr B.exr --mask REF.exr` measures how far two
 * noisy renders (two seeds) are apart, relative to the reference.
 * --map also prints a coarse grid of test/ref ratios for inspection.
 * Exit status: 0, or 2 for bad arguments, unreadable images or images of
 * different sizes. */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sh_cli.h"
#include "sh_image.h"

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

static double pixel_mean(const sh_image *img, int i) {
  const float *p = img->rgb + 3 * (size_t)i;
  return (p[0] + p[1] + p[2]) / 3.0;
}

typedef struct args {
  const char *mask;
  double lit;
  int map;
} args;

static const sh_cli_option options[] = {
    {"lit", 0, SH_CLI_NUMBER, "FRACTION", 1, offsetof(args, lit), 0, 1, 0, 0,
     NULL, NULL, NULL, "0.01",
     "lit: a reference pixel mean above FRACTION times the largest"},
    {"mask", 0, SH_CLI_TEXT, "MASK.exr", 1, offsetof(args, mask), 0, 0, 0, 0,
     NULL, NULL, NULL, NULL,
     "take the lit region and the denominators from MASK.exr"},
    {"map", 0, SH_CLI_FLAG, NULL, 0, offsetof(args, map), 0, 0, 0, 1, NULL,
     NULL, NULL, NULL, "also print a coarse grid of test/ref ratios"},
};

int main(int argc, char **argv) {
  const sh_cli_tool tool = {
      "se_imgdiff", "REF.exr TEST.exr [options]",
      "Compares two linear EXR images over the lit region of the first and "
      "prints\nthe statistics as one JSON object.",
      options, (int)(sizeof options / sizeof *options), 2, 2, NULL, NULL,
      NULL, NULL, NULL};
  args a = {NULL, 0.01, 0};
  sh_cli_args parsed;
  int rc = sh_cli_parse(&tool, argc, argv, &a, &parsed);
  if (rc >= 0) return rc;
  const char *paths[3] = {parsed.operands[0], parsed.operands[1], a.mask};
  int map = a.map;
  double frac = a.lit;
  sh_image img[3] = {{0}, {0}, {0}};
  sh_error err;
  int nimg = paths[2] ? 3 : 2;
  for (int k = 0; k < nimg; k++)
    if (sh_image_read(paths[k], &img[k], &err) != SH_OK) {
      int code = sh_cli_report("se_imgdiff", &err);
      for (int j = 0; j < k; j++) sh_image_free(&img[j]);
      return code;
    }
  for (int k = 1; k < nimg; k++)
    if (img[0].width != img[k].width || img[0].height != img[k].height) {
      fprintf(stderr, "se_imgdiff: the images differ in size: %dx%d and %dx%d\n",
              img[0].width, img[0].height, img[k].width, img[k].height);
      for (int j = 0; j < nimg; j++) sh_image_free(&img[j]);
      return 2;
    }
  const sh_image *mask = &img[nimg == 3 ? 2 : 0];
  int n = img[0].width * img[0].height;
  double peak = 0;
  for (int i = 0; i < n; i++) {
    double r = pixel_mean(mask, i);
    if (r > peak) peak = r;
  }
  double *rel = malloc(sizeof *rel * (size_t)(n > 0 ? n : 1));
  if (!rel) return 1;
  int lit = 0;
  double sum_rel = 0, sum_ref = 0, sum_test = 0;
  for (int i = 0; i < n; i++) {
    double m = pixel_mean(mask, i);
    double r = pixel_mean(&img[0], i), t = pixel_mean(&img[1], i);
    if (!(m > frac * peak) || peak <= 0) continue;
    double d = (t > r ? t - r : r - t) / m;
    if (!(d == d)) d = 1e30; /* NaN in the test image */
    rel[lit++] = d;
    sum_rel += d;
    sum_ref += r;
    sum_test += t;
  }
  qsort(rel, (size_t)lit, sizeof *rel, cmp_double);
  printf("{\"lit\": %d, \"pixels\": %d, \"mean_rel\": %.6f, \"ratio\": %.6f, "
         "\"max_rel\": %.6f, \"p90_rel\": %.6f}\n",
         lit, n, lit ? sum_rel / lit : 0.0, sum_ref > 0 ? sum_test / sum_ref : 0.0,
         lit ? rel[lit - 1] : 0.0, lit ? rel[(int)(0.9 * (lit - 1))] : 0.0);
  if (map) {
    int w = img[0].width, h = img[0].height;
    int sx = w / 16 > 0 ? w / 16 : 1, sy = h / 12 > 0 ? h / 12 : 1;
    for (int y = sy / 2; y < h; y += sy) {
      for (int x = sx / 2; x < w; x += sx) {
        double r = pixel_mean(&img[0], y * w + x), t = pixel_mean(&img[1], y * w + x);
        if (pixel_mean(mask, y * w + x) > frac * peak && r > 0) printf(" %5.2f", t / r);
        else printf("    . ");
      }
      printf("\n");
    }
  }
  free(rel);
  for (int k = 0; k < nimg; k++) sh_image_free(&img[k]);
  return 0;
}
