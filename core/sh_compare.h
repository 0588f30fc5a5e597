/* Image comparison in linear radiance, the measure every renderer of the
 * project is judged by. */
#ifndef SH_COMPARE_H
#define SH_COMPARE_H

#include "sh_error.h"
#include "sh_image.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sh_image_error {
  /* sqrt(sum (a - r)^2 / sum r^2) over the lit pixels: those whose
   * reference luminance exceeds `lit_fraction` of the reference's largest. */
  double rel_rms;
  /* Mean of |a - r| / r over the lit pixels (luminance). */
  double mean_rel;
  double psnr;    /* dB, with the reference's largest value as peak */
  double max_abs; /* largest |a - r| over all pixels and channels */
  long lit_pixels;
  long bad_values; /* NaN, infinite or negative values in the image */
} sh_image_error;

/* Compares `img` with the reference `ref` (same size, else SH_ERR_ARG).
 * If `diff` is not NULL it receives |img - ref| per channel (caller frees
 * with sh_image_free). */
sh_status sh_image_compare(const sh_image *img, const sh_image *ref,
                           double lit_fraction, sh_image_error *out,
                           sh_image *diff, sh_error *err);

#ifdef __cplusplus
}
#endif
#endif
