/* The C interface of libshafts_oiio.so, the plugin through which sh_image
 * reads and writes the formats that only OpenImageIO handles (JPEG, TIFF,
 * HDR, multi-part or tiled EXR...). sh_image_oiio.c loads it with dlopen on
 * first use, so that no program pays OpenImageIO's start-up (some 260
 * shared libraries on Debian) unless it opens such a file.
 *
 * The plugin is C++ inside and C at its edge: no exception crosses it, and
 * it links nothing of the core (it may be loaded into a program that holds
 * the core statically), so errors come back as text in the caller's buffer
 * and pixels in memory from malloc, which the caller frees. */
#ifndef SH_OIIO_PLUGIN_H
#define SH_OIIO_PLUGIN_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Raised whenever the functions below change shape. */
#define SH_OIIO_PLUGIN_ABI 1

/* What shafts_oiio_read returns: the first three channels (or the first
 * one, for grey and grey with alpha) as float, integer formats mapped to
 * [0, 1], rows from the top. */
typedef struct sh_oiio_pixels {
  int width, height, channels; /* channels: 1 or 3 */
  float *values;               /* malloc'ed; the caller frees */
  int is_float;                /* the file stores floating-point values */
  char colorspace[128];        /* the file's "oiio:ColorSpace", or "" */
} sh_oiio_pixels;

/* Returns SH_OIIO_PLUGIN_ABI. */
typedef int (*sh_oiio_abi_fn)(void);
/* Reads `path`. Returns 0, or 1 with a message in msg (size bytes). */
typedef int (*sh_oiio_read_fn)(const char *path, sh_oiio_pixels *out,
                               char *msg, size_t size);
/* Writes width x height pixels, 3 channels, float (is_float) or 8-bit, to
 * tmp_path in the format `format_path`'s extension names, with `attrs`
 * (key, value pairs ending with NULL, or NULL) as header attributes.
 * Returns 0, or 1 with a message; a partial file at tmp_path is the
 * caller's to remove. */
typedef int (*sh_oiio_write_fn)(const char *format_path, const char *tmp_path,
                                int width, int height, int is_float,
                                const void *data, const char *const *attrs,
                                char *msg, size_t size);

/* The plugin's exported names. */
#define SH_OIIO_ABI_SYMBOL "shafts_oiio_abi"
#define SH_OIIO_READ_SYMBOL "shafts_oiio_read"
#define SH_OIIO_WRITE_SYMBOL "shafts_oiio_write"

#ifdef __cplusplus
}
#endif
#endif
