#include "vc_visual.h"

#include <math.h>
#include <stdlib.h>

static double luminance(const float *p) {
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

double vc_robust_peak(const sh_image *ref, double fraction) {
  size_t n = (size_t)ref->width * ref->height, m = 0;
  double *lum = malloc(sizeof *lum * (n ? n : 1));
  if (!lum) return 0.0;
  for (size_t i = 0; i < n; i++) {
    double l = luminance(ref->rgb + 3 * i);
    if (isfinite(l) && l > 0) lum[m++] = l;
  }
  double peak = 0.0;
  if (m) {
    qsort(lum, m, sizeof *lum, cmp_double);
    size_t k = (size_t)(fraction * (double)(m - 1) + 0.5);
    peak = lum[k < m ? k : m - 1];
  }
  free(lum);
  return peak;
}

sh_status vc_signed_diff(const sh_image *img, const sh_image *ref,
                         double full_scale, sh_image *out, sh_error *err) {
  if (img->width != ref->width || img->height != ref->height)
    return sh_error_set(err, SH_ERR_ARG,
                        "images differ in size: %dx%d against %dx%d",
                        img->width, img->height, ref->width, ref->height);
  sh_status st = sh_image_alloc(out, img->width, img->height, err);
  if (st != SH_OK) return st;
  size_t n = (size_t)img->width * img->height;
  double gain = full_scale > 0 ? 1.0 / full_scale : 0.0;
  for (size_t i = 0; i < n; i++) {
    const float *a = img->rgb + 3 * i;
    float *o = out->rgb + 3 * i;
    int bad = 0;
    for (int c = 0; c < 3; c++)
      if (!isfinite(a[c]) || a[c] < 0) bad = 1;
    if (bad) {
      o[1] = 1.0f;
      continue;
    }
    double d = (luminance(a) - luminance(ref->rgb + 3 * i)) * gain;
    double v = fmin(fabs(d), 1.0);
    if (d > 0) {
      o[0] = (float)v;
      o[1] = o[2] = (float)(0.15 * v);
    } else {
      o[2] = (float)v;
      o[0] = o[1] = (float)(0.15 * v);
    }
  }
  return SH_OK;
}
