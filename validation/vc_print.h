/* Printing a comparison's figures, as text for people or as one JSON object
 * for the validation scripts. */
#ifndef VC_PRINT_H
#define VC_PRINT_H

#include <stdio.h>

#include "sh_compare.h"

/* What shafts_compare reports about one image against its reference. */
typedef struct vc_result {
  sh_image_error e;     /* the figures of sh_image_compare */
  double scale;         /* sum of image luminance / sum of reference
                           luminance over the lit pixels: 1 when the image
                           is right on average, whatever its noise */
  double lit_fraction;  /* the --lit threshold used */
  double robust_peak;   /* the reference's 99th-percentile luminance */
  int width, height;
} vc_result;

/* The lit-region luminance ratio (vc_result.scale) of img against ref,
 * both of the same size, with the same lit threshold as sh_image_compare;
 * 1 when the reference has no lit pixel. */
double vc_lit_scale(const sh_image *img, const sh_image *ref,
                    double lit_fraction);

/* One JSON object on a line. An infinite PSNR (identical images) is
 * written as null, since JSON has no infinity. */
void vc_print_json(FILE *f, const vc_result *r);

/* Aligned "name value" lines with units. */
void vc_print_text(FILE *f, const vc_result *r);

#endif
