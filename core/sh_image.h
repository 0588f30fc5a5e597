/* Images in linear RGB float, read and written as files: EXR through
 * OpenEXR's C library, PNG through libpng, every other format OpenImageIO
 * handles (JPEG, TIFF, HDR, tiled or multi-part EXR...) through OpenImageIO,
 * loaded only when such a file is met (sh_image_int.h).
 *
 * Reading decodes sRGB-encoded files (8- and 16-bit PNG, JPEG, ...) to linear
 * radiance; float formats (EXR, HDR) are taken as linear. Writing is atomic:
 * the image goes to a temporary file in the destination's directory, which is
 * renamed over the destination only once it is complete, so a failed or
 * interrupted write never leaves a half-written image. */
#ifndef SH_IMAGE_H
#define SH_IMAGE_H

#include "sh_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A linear RGB image, row-major from the top-left pixel, 3 floats a pixel. */
typedef struct sh_image {
  int width, height;
  float *rgb; /* width * height * 3 floats; owned, free with sh_image_free */
} sh_image;

/* Allocates a black image. Returns SH_ERR_NOMEM or SH_ERR_ARG on failure. */
sh_status sh_image_alloc(sh_image *img, int width, int height, sh_error *err);
/* Frees the pixels and zeroes the struct; safe on a zeroed struct. */
void sh_image_free(sh_image *img);

/* Reads `path` into `img` (caller frees with sh_image_free). Grey images
 * are replicated to RGB and alpha is dropped. A missing file is SH_ERR_IO,
 * an undecodable or zero-size one SH_ERR_IMAGE. */
sh_status sh_image_read(const char *path, sh_image *img, sh_error *err);

/* As sh_image_read, but the stored values are taken as data, not colour:
 * no transfer curve is decoded (integer formats map to [0, 1]). For
 * heightfields, whose grey levels are heights. */
sh_status sh_image_read_data(const char *path, sh_image *img, sh_error *err);

/* Writes `img` to `path`; the format follows the extension. ".exr" stores
 * 32-bit float linear radiance unchanged. ".png" (and other 8-bit formats)
 * stores clamp(radiance * 2^exposure) encoded with the sRGB curve. */
sh_status sh_image_write(const char *path, const sh_image *img,
                         double exposure, sh_error *err);

/* As sh_image_write, from the caller's pixels (width * height * 3 floats,
 * rows from the top), for bindings that should not mirror sh_image. */
sh_status sh_image_write_rgb(const char *path, int width, int height,
                             const float *rgb, double exposure, sh_error *err);

/* As sh_image_write, with text attributes in the file's header: `attrs`
 * holds key, value pairs and ends with NULL (NULL: none). EXR keeps them
 * as string attributes, PNG as text chunks (OpenImageIO's metadata names:
 * "Software", "ImageDescription", or "prefix:name" of one's own). */
sh_status sh_image_write_meta(const char *path, const sh_image *img,
                              double exposure, const char *const *attrs,
                              sh_error *err);

/* Bilinear look-up at texture coordinates (s, t) in [0, 1]^2, s to the right
 * and t downwards, clamped to the edge. Writes 3 floats to out. */
void sh_image_lookup(const sh_image *img, double s, double t, float out[3]);

/* The sRGB transfer functions on one value. */
double sh_srgb_to_linear(double v);
double sh_linear_to_srgb(double v);

#ifdef __cplusplus
}
#endif
#endif
