#include "sh_compare.h"

#include <math.h>
#include <string.h>

static double luminance(const float *p) {
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

sh_status sh_image_compare(const sh_image *img, const sh_image *ref,
                           double lit_fraction, sh_image_error *out,
                           sh_image *diff, sh_error *err) {
  memset(out, 0, sizeof *out);
  if (img->width != ref->width || img->height != ref->height)
    return sh_error_set(err, SH_ERR_ARG,
                        "images differ in size: %dx%d against %dx%d",
                        img->width, img->height, ref->width, ref->height);
  size_t n = (size_t)img->width * img->height;
  if (diff) {
    sh_status st = sh_image_alloc(diff, img->width, img->height, err);
    if (st != SH_OK) return st;
  }
  double peak = 0, peak_lum = 0;
  for (size_t i = 0; i < n; i++) {
    const float *r = ref->rgb + 3 * i;
    peak_lum = fmax(peak_lum, luminance(r));
    for (int c = 0; c < 3; c++) peak = fmax(peak, r[c]);
  }
  double thresh = lit_fraction * peak_lum;
  double se = 0, se_lit = 0, ref_lit = 0, rel_sum = 0;
  for (size_t i = 0; i < n; i++) {
    const float *a = img->rgb + 3 * i, *r = ref->rgb + 3 * i;
    int lit = luminance(r) > thresh;
    for (int c = 0; c < 3; c++) {
      if (!isfinite(a[c]) || a[c] < 0) out->bad_values++;
      double d = (double)a[c] - (double)r[c];
      if (!isfinite(d)) d = peak;
      se += d * d;
      out->max_abs = fmax(out->max_abs, fabs(d));
      if (diff) diff->rgb[3 * i + c] = (float)fabs(d);
      if (lit) {
        se_lit += d * d;
        ref_lit += (double)r[c] * r[c];
      }
    }
    if (lit) {
      out->lit_pixels++;
      double la = luminance(a), lr = luminance(r);
      rel_sum += isfinite(la) ? fabs(la - lr) / lr : 1.0;
    }
  }
  out->rel_rms = ref_lit > 0 ? sqrt(se_lit / ref_lit) : 0.0;
  out->mean_rel = out->lit_pixels ? rel_sum / out->lit_pixels : 0.0;
  double mse = se / (3.0 * (double)n);
  out->psnr = mse > 0 && peak > 0 ? 10.0 * log10(peak * peak / mse) : INFINITY;
  return SH_OK;
}
