/* sh_image_read and sh_image_write of sh_image.h: the file checks, the
 * choice of codec (sh_image_int.h), the transfer curve; writing goes
 * through sh_outputs.h (an unnamed temporary file beside the destination,
 * given its name once complete). */
#include "sh_image.h"
#include "sh_file.h"
#include "sh_image_int.h"
#include "sh_outputs.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

sh__transfer sh__transfer_of_colorspace(const char *colorspace, int is_float,
                                        double *gamma) {
  char cs[128];
  size_t n = 0;
  for (; colorspace && colorspace[n] && n + 1 < sizeof cs; n++) {
    char c = colorspace[n];
    cs[n] = (char)(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  }
  cs[n] = '\0';
  if (strstr(cs, "linear") || !strcmp(cs, "lin_srgb") ||
      !strcmp(cs, "lin_rec709") || !strcmp(cs, "acescg"))
    return SH__TRANSFER_LINEAR;
  if (strstr(cs, "srgb"))
    return SH__TRANSFER_SRGB;
  /* "Gamma2.2" (OpenImageIO 2.4 and later) or "GammaCorrected2.2". */
  static const char gc[] = "gammacorrected", g_[] = "gamma";
  const char *num = !strncmp(cs, gc, sizeof gc - 1)   ? cs + sizeof gc - 1
                    : !strncmp(cs, g_, sizeof g_ - 1) ? cs + sizeof g_ - 1
                                                      : NULL;
  if (num) {
    double g = atof(num);
    if (g > 0 && isfinite(g)) {
      *gamma = g;
      return g == 1.0 ? SH__TRANSFER_LINEAR : SH__TRANSFER_GAMMA;
    }
  }
  return is_float ? SH__TRANSFER_LINEAR : SH__TRANSFER_SRGB;
}

/* The extension of a path's file name, without its dot ("exr"), or NULL. */
static const char *sh__extension(const char *path) {
  const char *slash = strrchr(path, '/');
  const char *base = slash ? slash + 1 : path;
  const char *dot = strrchr(base, '.');
  return dot && dot != base ? dot + 1 : NULL;
}

/* True for the formats written as linear float rather than 8-bit sRGB. */
static int sh__is_float_format(const char *ext) {
  return !strcasecmp(ext, "exr") || !strcasecmp(ext, "hdr") ||
         !strcasecmp(ext, "pfm");
}

/* Picks the codec by the file's first bytes: EXR and PNG have their own,
 * everything else (and EXR layouts OpenEXRCore is not asked to read) goes
 * to OpenImageIO. */
static sh_status sh__decode_file(const char *path, sh__decoded *d,
                                 sh_error *err) {
  unsigned char magic[8] = {0};
  FILE *f = fopen(path, "rb");
  size_t got = f ? fread(magic, 1, sizeof magic, f) : 0;
  if (f)
    fclose(f);
  static const unsigned char png_sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
  static const unsigned char exr_sig[4] = {0x76, 0x2f, 0x31, 0x01};
  if (got == 8 && !memcmp(magic, png_sig, 8))
    return sh__png_read(path, d, err);
  if (got >= 4 && !memcmp(magic, exr_sig, 4)) {
    int handled = 0;
    sh_status st = sh__exr_read(path, d, &handled, err);
    if (st != SH_OK || handled)
      return st;
  }
  return sh__oiio_read(path, d, err);
}

static sh_status sh__read(const char *path, sh_image *img, int decode,
                          sh_error *err) {
  long long size = 0;
  sh_status s = sh__file_load_begin("sh_image_read", "image", img, sizeof *img,
                                    path, &size, err);
  if (s != SH_OK)
    return s;
  if (size == 0)
    return sh_error_set(err, SH_ERR_IMAGE,
                        "cannot read image '%s': the file is empty", path);

  sh__decoded d;
  memset(&d, 0, sizeof d);
  s = sh__decode_file(path, &d, err);
  if (s != SH_OK) {
    free(d.values);
    return s;
  }
  if (d.width < 1 || d.height < 1 || (d.channels != 1 && d.channels != 3)) {
    free(d.values);
    return sh_error_set(err, SH_ERR_IMAGE,
                        "cannot read image '%s': it has size %dx%d with %d "
                        "channels",
                        path, d.width, d.height, d.channels);
  }
  sh__transfer tf = decode ? d.transfer : SH__TRANSFER_LINEAR;
  s = sh_image_alloc(img, d.width, d.height, err);
  if (s != SH_OK) {
    free(d.values);
    return s;
  }
  size_t npix = (size_t)d.width * (size_t)d.height;
  for (size_t i = 0; i < npix; i++)
    for (int c = 0; c < 3; c++) {
      double v = d.values[i * d.channels + (d.channels == 3 ? c : 0)];
      if (tf == SH__TRANSFER_SRGB)
        v = sh_srgb_to_linear(v);
      else if (tf == SH__TRANSFER_GAMMA)
        v = v > 0 ? pow(v, d.gamma) : v;
      img->rgb[3 * i + c] = (float)v;
    }
  free(d.values);
  return SH_OK;
}

sh_status sh_image_read(const char *path, sh_image *img, sh_error *err) {
  return sh__read(path, img, 1, err);
}

sh_status sh_image_read_data(const char *path, sh_image *img, sh_error *err) {
  return sh__read(path, img, 0, err);
}

/* The pixels a format stores: the radiance itself for float formats, else
 * clamp(radiance * 2^exposure) through the sRGB curve in bytes (NaN to 0).
 * Returns the buffer to free, or NULL out of memory. */
static unsigned char *sh__encode_srgb8(const sh_image *img, double exposure) {
  size_t n = (size_t)img->width * (size_t)img->height * 3;
  unsigned char *bytes = malloc(n);
  if (!bytes)
    return NULL;
  double scale = exp2(exposure);
  for (size_t i = 0; i < n; i++) {
    double v = img->rgb[i] * scale;
    v = v > 0 ? (v < 1 ? v : 1) : 0;
    bytes[i] = (unsigned char)lround(sh_linear_to_srgb(v) * 255.0);
  }
  return bytes;
}

sh_status sh_image_write(const char *path, const sh_image *img,
                         double exposure, sh_error *err) {
  return sh_image_write_meta(path, img, exposure, NULL, err);
}

sh_status sh__image_check(const char *path, const sh_image *img,
                          double exposure, sh_error *err) {
  if (!img || !path || !*path)
    return sh_error_set(err, SH_ERR_ARG,
                        "sh_image_write was given no image or no path");
  if (!img->rgb || img->width < 1 || img->height < 1)
    return sh_error_set(err, SH_ERR_ARG, "cannot write '%s': the image is empty",
                        path);
  if (!isfinite(exposure))
    return sh_error_set(err, SH_ERR_ARG,
                        "cannot write '%s': the exposure is not finite", path);
  if (!sh__extension(path))
    return sh_error_set(err, SH_ERR_ARG,
                        "cannot write '%s': the file name has no extension to "
                        "choose the image format by",
                        path);
  return SH_OK;
}

sh_status sh__image_encode(const char *write_path, const char *path,
                           const sh_image *img, double exposure,
                           const char *const *attrs, sh_error *err) {
  sh_status st = sh__image_check(path, img, exposure, err);
  if (st != SH_OK) return st;
  const char *ext = sh__extension(path);
  int is_exr = !strcasecmp(ext, "exr"), is_png = !strcasecmp(ext, "png");
  int is_float = sh__is_float_format(ext);
  unsigned char *bytes = NULL;
  if (!is_float && !(bytes = sh__encode_srgb8(img, exposure)))
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory writing image '%s'",
                        path);
  int w = img->width, h = img->height;
  if (is_exr)
    st = sh__exr_write(write_path, path, w, h, img->rgb, attrs, err);
  else if (is_png)
    st = sh__png_write(write_path, path, w, h, bytes, attrs, err);
  else
    st = sh__oiio_write(write_path, path, w, h, is_float,
                        is_float ? (const void *)img->rgb : bytes, attrs, err);
  free(bytes);
  return st;
}

sh_status sh_image_write_meta(const char *path, const sh_image *img,
                              double exposure, const char *const *attrs,
                              sh_error *err) {
  sh_status st = sh__image_check(path, img, exposure, err);
  if (st != SH_OK) return st;
  sh_outputs *set = sh_outputs_new();
  if (!set) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  st = sh_outputs_write_image(set, path, img, exposure, attrs, err);
  if (st == SH_OK) st = sh_outputs_publish(set, err);
  sh_outputs_free(set);
  return st;
}
