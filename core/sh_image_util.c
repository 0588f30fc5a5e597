/* The parts of sh_image.h that need no image library: allocation, bilinear
 * look-up and the sRGB transfer curve. Reading and writing files is in
 * sh_image_io.c and the codecs of sh_image_int.h. */
#include "sh_image.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

sh_status sh_image_alloc(sh_image *img, int width, int height, sh_error *err) {
  if (!img)
    return sh_error_set(err, SH_ERR_ARG, "sh_image_alloc was given no image");
  memset(img, 0, sizeof *img);
  if (width < 1 || height < 1)
    return sh_error_set(err, SH_ERR_ARG,
                        "an image must be at least 1x1 pixels, not %dx%d",
                        width, height);
  size_t n = (size_t)width * (size_t)height;
  if (n > ((size_t)-1) / (3 * sizeof(float)))
    return sh_error_set(err, SH_ERR_NOMEM,
                        "a %dx%d image does not fit in memory", width, height);
  img->rgb = calloc(n * 3, sizeof(float));
  if (!img->rgb)
    return sh_error_set(err, SH_ERR_NOMEM,
                        "out of memory allocating a %dx%d image", width,
                        height);
  img->width = width;
  img->height = height;
  return SH_OK;
}

void sh_image_free(sh_image *img) {
  if (!img)
    return;
  free(img->rgb);
  memset(img, 0, sizeof *img);
}

/* Splits a texture coordinate into the two texel indices to blend and the
 * weight of the second, with texel centres at (i + 0.5) / n and the edge
 * texels repeated beyond the border. */
static void sh__texel_span(double s, int n, int *i0, int *i1, double *f) {
  double x = s * n - 0.5;
  if (!(x > 0)) { /* also catches NaN */
    *i0 = *i1 = 0;
    *f = 0;
    return;
  }
  if (x >= n - 1) {
    *i0 = *i1 = n - 1;
    *f = 0;
    return;
  }
  double fl = floor(x);
  *i0 = (int)fl;
  *i1 = *i0 + 1;
  *f = x - fl;
}

void sh_image_lookup(const sh_image *img, double s, double t, float out[3]) {
  if (!img || !img->rgb || img->width < 1 || img->height < 1) {
    out[0] = out[1] = out[2] = 0.0f;
    return;
  }
  int x0, x1, y0, y1;
  double fx, fy;
  sh__texel_span(s, img->width, &x0, &x1, &fx);
  sh__texel_span(t, img->height, &y0, &y1, &fy);
  const float *r00 = img->rgb + 3 * ((size_t)y0 * img->width + x0);
  const float *r10 = img->rgb + 3 * ((size_t)y0 * img->width + x1);
  const float *r01 = img->rgb + 3 * ((size_t)y1 * img->width + x0);
  const float *r11 = img->rgb + 3 * ((size_t)y1 * img->width + x1);
  for (int c = 0; c < 3; c++) {
    double top = r00[c] + (r10[c] - (double)r00[c]) * fx;
    double bottom = r01[c] + (r11[c] - (double)r01[c]) * fx;
    out[c] = (float)(top + (bottom - top) * fy);
  }
}

double sh_srgb_to_linear(double v) {
  if (v <= 0.04045)
    return v / 12.92;
  return pow((v + 0.055) / 1.055, 2.4);
}

double sh_linear_to_srgb(double v) {
  if (v <= 0.0031308)
    return v * 12.92;
  return 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

sh_status sh_image_write_rgb(const char *path, int width, int height,
                             const float *rgb, double exposure, sh_error *err) {
  if (!rgb || width < 1 || height < 1)
    return sh_error_set(err, SH_ERR_ARG,
                        "sh_image_write_rgb: no pixels or a size below 1x1");
  sh_image img = {width, height, (float *)rgb};
  return sh_image_write(path, &img, exposure, err);
}
