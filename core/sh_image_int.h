/* Internal to sh_image (not installed, not exported): the codecs behind
 * sh_image_read and sh_image_write of sh_image.h.
 *
 * EXR goes through OpenEXR's C library (OpenEXRCore) and PNG through
 * libpng, both linked: together they load in about a millisecond. Every
 * other format goes through OpenImageIO, which is not linked: its plugin,
 * libshafts_oiio.so (sh_oiio_plugin.h), is loaded with dlopen the first time
 * a file needs it, because Debian's OpenImageIO pulls in some 260 shared
 * libraries (OpenCV, FFmpeg, GDAL, OpenVDB, LLVM) and 0.3-0.9 s of start-up
 * into every process that links it.
 *
 * A codec reads into an sh__decoded: the values as stored (integer formats
 * mapped to [0, 1]) and the transfer curve they were stored with, which
 * sh_image_io.c undoes. A codec writes a whole file at a temporary path
 * that sh_image_io.c created and later renames or removes. */
#ifndef SH_IMAGE_INT_H
#define SH_IMAGE_INT_H

#include "sh_error.h"
#include "sh_image.h"

#include <stddef.h>

/* How stored values map to linear radiance. */
typedef enum sh__transfer {
  SH__TRANSFER_LINEAR,
  SH__TRANSFER_SRGB,
  SH__TRANSFER_GAMMA /* linear = stored^gamma */
} sh__transfer;

/* Decoded pixels: width * height * channels floats (channels 1 for grey or
 * 3 for RGB), rows from the top; `values` is malloc'ed, the caller frees. */
typedef struct sh__decoded {
  int width, height, channels;
  float *values;
  sh__transfer transfer;
  double gamma; /* for SH__TRANSFER_GAMMA */
} sh__decoded;

/* The transfer named by an OpenImageIO "oiio:ColorSpace" string; with no
 * usable name, integer formats are display-encoded (sRGB) and float ones
 * linear. */
sh__transfer sh__transfer_of_colorspace(const char *colorspace, int is_float,
                                        double *gamma);

/* EXR through OpenEXRCore. Reads a single-part scanline file with R, G, B
 * (or Y) channels of any pixel type. Layouts it leaves to OpenImageIO
 * (tiled, multi-part, deep, subsampled, other channel names) set *handled
 * to 0 and return SH_OK with nothing read. */
sh_status sh__exr_read(const char *path, sh__decoded *out, int *handled,
                       sh_error *err);
/* The writers below also store `attrs` (key, value pairs ending with NULL;
 * NULL for none: sh_image_write_meta) as text in the file's header.
 *
 * Writes 32-bit float R, G, B, RLE-compressed (lossless), at tmp_path;
 * messages name `path`. rgb has width * height * 3 floats. RLE, not ZIP:
 * on the renderers' images it takes a fifth of ZIP's CPU time (4 against
 * 20 ms at 320x240) for files 8-9% larger, both on a smooth gl_shafts
 * image and on a noisy 4-sample reference. */
sh_status sh__exr_write(const char *tmp_path, const char *path, int width,
                        int height, const float *rgb,
                        const char *const *attrs, sh_error *err);

/* PNG through libpng: every bit depth and colour type (palette, grey, grey
 * and alpha, RGB, RGBA, 1 to 16 bits, interlaced); alpha is dropped. The
 * transfer follows the sRGB and gAMA chunks, sRGB without either. */
sh_status sh__png_read(const char *path, sh__decoded *out, sh_error *err);
/* Writes 8-bit RGB (width * height * 3 bytes, already sRGB-encoded) with
 * an sRGB chunk, and the attributes as tEXt chunks, at tmp_path; messages
 * name `path`. */
sh_status sh__png_write(const char *tmp_path, const char *path, int width,
                        int height, const unsigned char *rgb,
                        const char *const *attrs, sh_error *err);

/* Any format OpenImageIO reads, through its plugin (loaded on first use;
 * SH_ERR_IMAGE naming why if it cannot be). */
sh_status sh__oiio_read(const char *path, sh__decoded *out, sh_error *err);
/* Writes through OpenImageIO, the format chosen by `path`'s extension, at
 * tmp_path: 3 floats a pixel if is_float, else 3 bytes. */
sh_status sh__oiio_write(const char *tmp_path, const char *path, int width,
                         int height, int is_float, const void *data,
                         const char *const *attrs, sh_error *err);

/* The checks of sh_image_write_meta: an image with pixels, a path with an
 * extension, a finite exposure. */
sh_status sh__image_check(const char *path, const sh_image *img,
                          double exposure, sh_error *err);
/* Encodes img as `path`'s extension asks, writing the bytes to write_path
 * (a staged temporary, sh_outputs.c); messages name `path`. */
sh_status sh__image_encode(const char *write_path, const char *path,
                           const sh_image *img, double exposure,
                           const char *const *attrs, sh_error *err);

#endif
