#include "vc_print.h"

#include <math.h>

static double luminance(const float *p) {
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

double vc_lit_scale(const sh_image *img, const sh_image *ref,
                    double lit_fraction) {
  size_t n = (size_t)ref->width * ref->height;
  double peak = 0;
  for (size_t i = 0; i < n; i++) peak = fmax(peak, luminance(ref->rgb + 3 * i));
  double sa = 0, sr = 0;
  for (size_t i = 0; i < n; i++) {
    double r = luminance(ref->rgb + 3 * i);
    if (!(r > lit_fraction * peak)) continue;
    sa += luminance(img->rgb + 3 * i);
    sr += r;
  }
  return sr > 0 ? sa / sr : 1.0;
}

/* JSON numbers must be finite: NaN and infinities become null. */
static void json_number(FILE *f, const char *key, double v, int last) {
  if (isfinite(v))
    fprintf(f, "\"%s\": %.9g%s", key, v, last ? "" : ", ");
  else
    fprintf(f, "\"%s\": null%s", key, last ? "" : ", ");
}

void vc_print_json(FILE *f, const vc_result *r) {
  fputc('{', f);
  fprintf(f, "\"width\": %d, \"height\": %d, ", r->width, r->height);
  json_number(f, "lit_fraction", r->lit_fraction, 0);
  fprintf(f, "\"lit_pixels\": %ld, ", r->e.lit_pixels);
  json_number(f, "rel_rms", r->e.rel_rms, 0);
  json_number(f, "mean_rel", r->e.mean_rel, 0);
  json_number(f, "psnr", r->e.psnr, 0);
  json_number(f, "max_abs", r->e.max_abs, 0);
  json_number(f, "scale", r->scale, 0);
  json_number(f, "robust_peak", r->robust_peak, 0);
  fprintf(f, "\"bad_values\": %ld}\n", r->e.bad_values);
}

void vc_print_text(FILE *f, const vc_result *r) {
  fprintf(f, "image        %d x %d, %ld lit pixels (reference luminance above "
             "%g of its largest)\n",
          r->width, r->height, r->e.lit_pixels, r->lit_fraction);
  fprintf(f, "rel_rms      %.4f %%  (relative RMS error over the lit pixels)\n",
          100.0 * r->e.rel_rms);
  fprintf(f, "mean_rel     %.4f %%  (mean relative luminance error, lit pixels)\n",
          100.0 * r->e.mean_rel);
  if (isfinite(r->e.psnr))
    fprintf(f, "psnr         %.2f dB\n", r->e.psnr);
  else
    fprintf(f, "psnr         infinite (the images are identical)\n");
  fprintf(f, "max_abs      %.6g  (largest absolute difference, radiance)\n",
          r->e.max_abs);
  fprintf(f, "scale        %.5f  (image / reference luminance, lit pixels)\n",
          r->scale);
  fprintf(f, "bad_values   %ld  (NaN, infinite or negative values)\n",
          r->e.bad_values);
}
