/* Pictures made from a comparison: the false-colour difference image and
 * the sRGB preview of a rendering, for the validation report. */
#ifndef VC_VISUAL_H
#define VC_VISUAL_H

#include "sh_error.h"
#include "sh_image.h"

/* The luminance below which `fraction` of the reference's non-black pixels
 * lie (fraction in [0, 1]); 0 for an all-black image. The report scales its
 * difference images by this robust peak instead of the largest value, which
 * a visible point light would make meaningless. */
double vc_robust_peak(const sh_image *ref, double fraction);

/* Fills `out` (allocated by the call, caller frees) with a false-colour
 * picture of the signed luminance difference img - ref: red where the image
 * is brighter than the reference, blue where it is darker, black where they
 * agree. A difference of `full_scale` (in radiance) is full intensity. NaN,
 * infinite and negative values of `img` are shown in pure green. */
sh_status vc_signed_diff(const sh_image *img, const sh_image *ref,
                         double full_scale, sh_image *out, sh_error *err);

#endif
