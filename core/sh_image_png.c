/* PNG through libpng (sh__png_read and sh__png_write of sh_image_int.h).
 * libpng reports errors by calling a handler that must not return: ours
 * keeps the message and jumps back to the setjmp in the calling function;
 * warnings are dropped (the library prints nothing). */
#include "sh_image_int.h"

#include <png.h>

#include <math.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct sh__png_msg {
  char text[256];
} sh__png_msg;

static void sh__png_on_error(png_structp png, png_const_charp msg) {
  sh__png_msg *m = png_get_error_ptr(png);
  if (m)
    snprintf(m->text, sizeof m->text, "%s", msg ? msg : "libpng failed");
  png_longjmp(png, 1);
}

static void sh__png_on_warning(png_structp png, png_const_charp msg) {
  (void)png;
  (void)msg;
}

/* A PNG file being read or written: the file, libpng's structures and the
 * message the error handler keeps. */
typedef struct sh__png_file {
  FILE *f;
  int write;
  png_structp png;
  png_infop info;
  sh__png_msg msg;
} sh__png_file;

/* Frees libpng's structures and closes the file: fclose's result (a write
 * whose last bytes did not reach the disk fails here). */
static int sh__png_close(sh__png_file *p) {
  png_structp *png = p->png ? &p->png : NULL;
  png_infop *info = p->info ? &p->info : NULL;
  if (p->write)
    png_destroy_write_struct(png, info);
  else
    png_destroy_read_struct(png, info, NULL);
  return fclose(p->f);
}

/* Opens open_path to read or to write (named `path` in messages: SH_ERR_IO
 * when it does not open) and makes libpng's structures with the handlers
 * above (SH_ERR_NOMEM). */
static sh_status sh__png_open(sh__png_file *p, const char *open_path,
                              const char *path, int write, sh_error *err) {
  memset(p, 0, sizeof *p);
  p->write = write;
  if (!(p->f = fopen(open_path, write ? "wb" : "rb")))
    return sh_error_set(err, SH_ERR_IO,
                        write ? "cannot write '%s'" : "cannot open '%s'", path);
  p->png = write ? png_create_write_struct(PNG_LIBPNG_VER_STRING, &p->msg,
                                           sh__png_on_error, sh__png_on_warning)
                 : png_create_read_struct(PNG_LIBPNG_VER_STRING, &p->msg,
                                          sh__png_on_error, sh__png_on_warning);
  p->info = p->png ? png_create_info_struct(p->png) : NULL;
  if (!p->info) {
    sh__png_close(p);
    return sh_error_set(err, SH_ERR_NOMEM, "cannot %s '%s': out of memory",
                        write ? "write" : "read image", path);
  }
  return SH_OK;
}

/* The curve the file says its values are stored with: an sRGB chunk, else
 * a gAMA chunk (its exponent rounded to hundredths, as OpenImageIO does),
 * else sRGB. */
static sh__transfer sh__png_transfer(png_structp png, png_infop info,
                                     double *gamma) {
  int intent;
  double file_gamma;
  if (png_get_sRGB(png, info, &intent))
    return SH__TRANSFER_SRGB;
  if (png_get_gAMA(png, info, &file_gamma) && file_gamma > 0) {
    double g = round(100.0 / file_gamma) / 100.0;
    if (g == 1.0)
      return SH__TRANSFER_LINEAR;
    *gamma = g;
    return SH__TRANSFER_GAMMA;
  }
  return SH__TRANSFER_SRGB;
}

sh_status sh__png_read(const char *path, sh__decoded *out, sh_error *err) {
  /* Set before the jump may happen, read after it: volatile. */
  unsigned char *volatile pixels = NULL;
  png_bytep *volatile rows = NULL;
  sh__png_file p;
  sh_status st = sh__png_open(&p, path, path, 0, err);
  if (st != SH_OK)
    return st;
  png_structp png = p.png;
  png_infop info = p.info;
  if (setjmp(png_jmpbuf(png))) {
    sh__png_close(&p);
    free(pixels);
    free(rows);
    return sh_error_set(err, SH_ERR_IMAGE, "cannot read image '%s': %s", path,
                        p.msg.text);
  }
  png_init_io(png, p.f);
  png_read_info(png, info);
  /* Palette to RGB, grey below 8 bits to 8, tRNS to alpha; 16-bit samples
   * in the machine's byte order. */
  png_set_expand(png);
  if (png_get_bit_depth(png, info) == 16) {
    const unsigned short one = 1;
    if (*(const unsigned char *)&one)
      png_set_swap(png);
  }
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  png_uint_32 w = png_get_image_width(png, info);
  png_uint_32 h = png_get_image_height(png, info);
  int depth = png_get_bit_depth(png, info);
  int nch = png_get_channels(png, info);
  size_t row_bytes = png_get_rowbytes(png, info);
  double gamma = 1.0;
  sh__transfer tf = sh__png_transfer(png, info, &gamma);
  pixels = malloc(row_bytes * h);
  rows = malloc(sizeof(png_bytep) * h);
  if (!pixels || !rows)
    png_error(png, "out of memory");
  for (png_uint_32 y = 0; y < h; y++)
    rows[y] = pixels + (size_t)y * row_bytes;
  png_read_image(png, rows);
  png_read_end(png, NULL);

  int keep = nch >= 3 ? 3 : 1; /* grey, grey+alpha: channel 0 only */
  float *values = malloc((size_t)w * h * keep * sizeof(float));
  if (!values)
    png_error(png, "out of memory");
  for (png_uint_32 y = 0; y < h; y++)
    for (png_uint_32 x = 0; x < w; x++)
      for (int c = 0; c < keep; c++) {
        size_t i = (size_t)x * nch + c;
        float v = depth == 16
                      ? ((const unsigned short *)rows[y])[i] / 65535.0f
                      : rows[y][i] / 255.0f;
        values[((size_t)y * w + x) * keep + c] = v;
      }
  sh__png_close(&p);
  free(pixels);
  free(rows);
  out->width = (int)w;
  out->height = (int)h;
  out->channels = keep;
  out->values = values;
  out->transfer = tf;
  out->gamma = gamma;
  return SH_OK;
}

sh_status sh__png_write(const char *tmp_path, const char *path, int width,
                        int height, const unsigned char *rgb,
                        const char *const *attrs, sh_error *err) {
  sh__png_file p;
  sh_status st = sh__png_open(&p, tmp_path, path, 1, err);
  if (st != SH_OK)
    return st;
  if (setjmp(png_jmpbuf(p.png))) {
    sh__png_close(&p);
    return sh_error_set(err, SH_ERR_IMAGE, "cannot write '%s': %s", path,
                        p.msg.text);
  }
  png_init_io(p.png, p.f);
  png_set_IHDR(p.png, p.info, (png_uint_32)width, (png_uint_32)height, 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB_gAMA_and_cHRM(p.png, p.info, PNG_sRGB_INTENT_PERCEPTUAL);
  /* zlib level 3 with the Sub filter on every row: half the CPU time of
   * libpng's defaults (level 6, adaptive filters) for files 8% larger
   * (gl_shafts/cli_bench.sh's PNG row; docs/gl_shafts.md). */
  png_set_compression_level(p.png, 3);
  png_set_filter(p.png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  for (int i = 0; attrs && attrs[i] && attrs[i + 1]; i += 2) {
    png_text t;
    memset(&t, 0, sizeof t);
    t.compression = PNG_TEXT_COMPRESSION_NONE;
    t.key = (png_charp)attrs[i];
    t.text = (png_charp)attrs[i + 1];
    png_set_text(p.png, p.info, &t, 1);
  }
  png_write_info(p.png, p.info);
  for (int y = 0; y < height; y++)
    png_write_row(p.png, rgb + (size_t)y * width * 3);
  png_write_end(p.png, NULL);
  if (sh__png_close(&p) != 0)
    return sh_error_set(err, SH_ERR_IO, "cannot write '%s': the file could "
                        "not be completed", path);
  return SH_OK;
}
