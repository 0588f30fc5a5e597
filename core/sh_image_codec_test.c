/* Tests of the image codecs behind sh_image.h (sh_image_int.h): EXR through
 * OpenEXRCore and PNG through libpng decode every layout they take exactly
 * as OpenImageIO (the plugin, which read everything before) decodes it;
 * layouts they leave to OpenImageIO still read; formats only OpenImageIO
 * knows round-trip through its plugin; a missing plugin is a clear error
 * that leaves EXR and PNG working; and EXR and PNG files never load
 * OpenImageIO.
 *
 * The EXR variants are written by oiiotool (OpenImageIO's, which writes
 * with OpenEXR's C++ library: half, tiled, data windows, PIZ), the PNG
 * variants by libpng here (palette, 1 to 16 bits, alpha, gAMA, Adam7). */
#include "sh_image.h"
#include "sh_image_int.h"
#include "sh_test.h"

#include <png.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static char tmpdir[256];

static void path_in_tmp(char *buf, size_t size, const char *name) {
  snprintf(buf, size, "%s/%s", tmpdir, name);
}

/* Decodes `path` natively and through OpenImageIO and checks that both
 * give the same pixels and transfer curve. `want_native` says whether the
 * native codec must take the file (EXR layouts it leaves are allowed). */
static void check_same_as_oiio(const char *path, int want_native) {
  sh__decoded a, b;
  memset(&a, 0, sizeof a);
  memset(&b, 0, sizeof b);
  sh_error err = SH_ERROR_INIT;
  sh_status sa;
  int handled = 1;
  const char *ext = strrchr(path, '.');
  if (ext && !strcmp(ext, ".png"))
    sa = sh__png_read(path, &a, &err);
  else
    sa = sh__exr_read(path, &a, &handled, &err);
  SH_CHECK(sa == SH_OK);
  SH_CHECK(handled == want_native);
  sh_status sb = sh__oiio_read(path, &b, &err);
  SH_CHECK(sb == SH_OK);
  if (sa == SH_OK && sb == SH_OK && handled) {
    SH_CHECK(a.width == b.width && a.height == b.height);
    SH_CHECK(a.channels == b.channels);
    SH_CHECK(a.transfer == b.transfer);
    if (a.transfer == SH__TRANSFER_GAMMA)
      SH_CHECK_NEAR(a.gamma, b.gamma, 0, 1e-6);
    if (a.width == b.width && a.height == b.height && a.channels == b.channels) {
      size_t n = (size_t)a.width * a.height * a.channels;
      double worst = 0;
      for (size_t i = 0; i < n; i++) {
        double d = fabs((double)a.values[i] - b.values[i]);
        if (d > worst)
          worst = d;
      }
      if (worst > 1e-6)
        fprintf(stderr, "%s: values differ by up to %g\n", path, worst);
      SH_CHECK(worst <= 1e-6);
    }
  } else if (sa != SH_OK || sb != SH_OK) {
    fprintf(stderr, "%s: %s\n", path, err.message);
  }
  free(a.values);
  free(b.values);
  sh_error_clear(&err);
}

/* Runs oiiotool with `args` (file names relative to tmpdir). */
static int oiiotool(const char *args) {
  char cmd[1024];
  snprintf(cmd, sizeof cmd, "cd '%s' && oiiotool %s", tmpdir, args);
  return system(cmd) == 0;
}

static void test_exr_variants(void) {
  if (system("oiiotool --version >/dev/null 2>&1") != 0) {
    fprintf(stderr, "note: no oiiotool, the EXR variants are not checked\n");
    return;
  }
  static const struct {
    const char *args, *name;
    int native;
  } v[] = {
      /* As Cycles writes: half RGBA, here with an offset data window. */
      {"--pattern fill:topleft=0.1,0.2,0.3,1:topright=4,0.5,0.25,0.5:"
       "bottomleft=0,1,2,1:bottomright=9,8,7,0 7x5 4 --origin +3+2 -d half "
       "--compression piz -o half_rgba.exr",
       "half_rgba.exr", 1},
      {"--pattern noise:type=uniform:min=0:max=3 33x19 3 -d float "
       "--compression zip -o float_zip.exr",
       "float_zip.exr", 1},
      {"--pattern fill:top=0.25:bottom=2 5x6 1 --chnames Y -d half -o y.exr",
       "y.exr", 1},
      /* Left to OpenImageIO: tiled, and channels named otherwise. */
      {"--pattern fill:top=0.1,0.2,0.3:bottom=1,2,3 9x7 3 --tile 4 4 -d half "
       "-o tiled.exr",
       "tiled.exr", 0},
      {"--pattern constant:color=0.5,0.25 4x3 2 --chnames U,V -o uv.exr",
       "uv.exr", 0},
  };
  for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
    char path[512];
    path_in_tmp(path, sizeof path, v[i].name);
    SH_CHECK(oiiotool(v[i].args));
    check_same_as_oiio(path, v[i].native);
    /* And through the public call, whichever codec takes it. */
    sh_image img;
    sh_error err = SH_ERROR_INIT;
    SH_CHECK(sh_image_read(path, &img, &err) == SH_OK);
    sh_image_free(&img);
    remove(path);
    sh_error_clear(&err);
  }
}

/* Writes a w x h PNG of the given colour type and depth with libpng; the
 * samples follow a pattern that covers the whole range. */
static int write_png(const char *path, int color_type, int depth, int w, int h,
                     double file_gamma, int srgb, int interlace) {
  FILE *f = fopen(path, "wb");
  if (!f)
    return 0;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    fclose(f);
    return 0;
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, color_type,
               interlace ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (color_type == PNG_COLOR_TYPE_PALETTE) {
    png_color pal[16];
    for (int i = 0; i < 16; i++) {
      pal[i].red = (png_byte)(i * 17);
      pal[i].green = (png_byte)(255 - i * 13);
      pal[i].blue = (png_byte)(i * i);
    }
    png_set_PLTE(png, info, pal, 1 << (depth < 4 ? depth : 4));
    png_byte trns[2] = {0, 128};
    png_set_tRNS(png, info, trns, 2, NULL);
  }
  if (srgb)
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  if (file_gamma > 0)
    png_set_gAMA(png, info, file_gamma);
  png_write_info(png, info);
  int channels = color_type == PNG_COLOR_TYPE_RGB ? 3
                 : color_type == PNG_COLOR_TYPE_RGBA ? 4
                 : color_type == PNG_COLOR_TYPE_GRAY_ALPHA ? 2 : 1;
  int maxv = color_type == PNG_COLOR_TYPE_PALETTE ? (1 << (depth < 4 ? depth : 4)) - 1
                                                   : (1 << depth) - 1;
  size_t row_bytes = ((size_t)w * channels * depth + 7) / 8;
  png_bytep *rows = calloc((size_t)h, sizeof *rows);
  png_bytep data = calloc((size_t)h, row_bytes);
  for (int y = 0; y < h; y++) {
    rows[y] = data + (size_t)y * row_bytes;
    for (int x = 0; x < w; x++)
      for (int c = 0; c < channels; c++) {
        long s = (long)(x * 7 + y * 13 + c * 5) * 2654435761L % (maxv + 1);
        size_t bit = ((size_t)x * channels + c) * depth;
        if (depth == 16) {
          rows[y][bit / 8] = (png_byte)(s >> 8);
          rows[y][bit / 8 + 1] = (png_byte)s;
        } else if (depth == 8) {
          rows[y][bit / 8] = (png_byte)s;
        } else {
          rows[y][bit / 8] |= (png_byte)(s << (8 - depth - bit % 8));
        }
      }
  }
  png_set_rows(png, info, rows);
  png_write_image(png, rows);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  free(rows);
  free(data);
  return fclose(f) == 0;
}

static void test_png_variants(void) {
  static const struct {
    int type, depth;
    double gamma;
    int srgb, interlace;
  } v[] = {
      {PNG_COLOR_TYPE_PALETTE, 4, 0, 0, 0},
      {PNG_COLOR_TYPE_PALETTE, 8, 0, 1, 1},
      {PNG_COLOR_TYPE_GRAY, 1, 0, 0, 0},
      {PNG_COLOR_TYPE_GRAY, 2, 0, 0, 1},
      {PNG_COLOR_TYPE_GRAY, 16, 1.0, 0, 0},   /* gAMA 1: linear */
      {PNG_COLOR_TYPE_GRAY_ALPHA, 8, 0, 0, 0},
      {PNG_COLOR_TYPE_GRAY_ALPHA, 16, 0, 0, 0},
      {PNG_COLOR_TYPE_RGB, 8, 0.45455, 0, 0}, /* gAMA 1/2.2 */
      {PNG_COLOR_TYPE_RGB, 16, 0, 0, 1},
      {PNG_COLOR_TYPE_RGBA, 8, 0, 1, 0},
      {PNG_COLOR_TYPE_RGBA, 16, 0.5, 0, 0},
  };
  for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
    char path[512];
    char name[64];
    snprintf(name, sizeof name, "variant%zu.png", i);
    path_in_tmp(path, sizeof path, name);
    SH_CHECK(write_png(path, v[i].type, v[i].depth, 11, 6, v[i].gamma,
                       v[i].srgb, v[i].interlace));
    check_same_as_oiio(path, 1);
    remove(path);
  }
}

/* Formats only OpenImageIO writes and reads: TIFF (8-bit sRGB, exact to
 * the byte) and Radiance HDR (float, RGBE: 1% steps). */
static void test_plugin_formats(void) {
  sh_error err = SH_ERROR_INIT;
  sh_image img, back;
  SH_CHECK(sh_image_alloc(&img, 5, 3, &err) == SH_OK);
  for (int i = 0; i < 5 * 3 * 3; i++)
    img.rgb[i] = (float)((i * 37) % 19) / 18.0f;
  char path[512];
  path_in_tmp(path, sizeof path, "plugin.tif");
  SH_CHECK(sh_image_write(path, &img, 0.0, &err) == SH_OK);
  SH_CHECK(sh_image_read(path, &back, &err) == SH_OK);
  if (back.rgb && back.width == 5 && back.height == 3)
    for (int i = 0; i < 5 * 3 * 3; i++)
      SH_CHECK_NEAR(sh_linear_to_srgb(back.rgb[i]),
                    sh_linear_to_srgb(img.rgb[i]), 0, 0.5 / 255 + 1e-6);
  sh_image_free(&back);
  remove(path);
  path_in_tmp(path, sizeof path, "plugin.hdr");
  SH_CHECK(sh_image_write(path, &img, 0.0, &err) == SH_OK);
  SH_CHECK(sh_image_read(path, &back, &err) == SH_OK);
  if (back.rgb && back.width == 5 && back.height == 3)
    for (int i = 0; i < 5 * 3 * 3; i++)
      SH_CHECK_NEAR(back.rgb[i], img.rgb[i], 0.01, 1.0 / 128);
  sh_image_free(&back);
  remove(path);
  /* A format no one writes: an error, and nothing left behind. */
  path_in_tmp(path, sizeof path, "plugin.nosuchformat");
  SH_CHECK(sh_image_write(path, &img, 0.0, &err) == SH_ERR_IMAGE);
  SH_CHECK(access(path, F_OK) != 0);
  sh_image_free(&img);
  sh_error_clear(&err);
}

/* sh_image_write_meta's attributes reach the header of every writer's
 * files, as OpenImageIO (iinfo) reads them (TIFF has a tag for Software
 * only: OpenImageIO drops the others there). */
static void test_attributes(void) {
  if (system("iinfo --help >/dev/null 2>&1") != 0) {
    fprintf(stderr, "note: no iinfo, the attributes are not checked\n");
    return;
  }
  sh_image img;
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(sh_image_alloc(&img, 4, 3, &err) == SH_OK);
  static const char *const attrs[] = {"Software", "codec_test 1.0",
                                      "shafts:settings", "{\"planes\":4}", NULL};
  static const char *const names[] = {"meta.exr", "meta.png", "meta.tif"};
  for (int k = 0; k < 3; k++) {
    char path[512], cmd[1200];
    path_in_tmp(path, sizeof path, names[k]);
    SH_CHECK(sh_image_write_meta(path, &img, 0.0, attrs, &err) == SH_OK);
    snprintf(cmd, sizeof cmd,
             "iinfo -v '%s' | grep -q 'Software: \"codec_test 1.0\"' && "
             "{ %s || iinfo -v '%s' | grep -Fq 'shafts:settings: \"{\\\"planes\\\":4}\"'; }",
             path, k == 2 ? "true" : "false", path);
    if (system(cmd) != 0) {
      fprintf(stderr, "%s: the attributes are not in its header\n", names[k]);
      SH_CHECK(0);
    }
    remove(path);
  }
  sh_image_free(&img);
  sh_error_clear(&err);
}

/* Whether this process has mapped a library whose name contains `name`. */
static int has_mapped(const char *name) {
  FILE *f = fopen("/proc/self/maps", "r");
  if (!f)
    return -1;
  char line[1024];
  int found = 0;
  while (!found && fgets(line, sizeof line, f))
    found = strstr(line, name) != NULL;
  fclose(f);
  return found;
}

/* Runs fn in a child process; returns its exit status. */
static int in_child(int (*fn)(void)) {
  fflush(NULL);
  pid_t pid = fork();
  if (pid == 0)
    _exit(fn());
  int status = 0;
  if (pid < 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status))
    return -1;
  return WEXITSTATUS(status);
}

/* EXR and PNG, read and written, do not load OpenImageIO. */
static int child_no_oiio(void) {
  sh_image img, back;
  sh_error err = SH_ERROR_INIT;
  char path[512];
  if (sh_image_alloc(&img, 3, 2, &err) != SH_OK)
    return 10;
  int bad = 0;
  static const char *const names[] = {"light.exr", "light.png"};
  for (int k = 0; k < 2; k++) {
    path_in_tmp(path, sizeof path, names[k]);
    bad |= sh_image_write(path, &img, 0, &err) != SH_OK;
    bad |= sh_image_read(path, &back, &err) != SH_OK;
    sh_image_free(&back);
    remove(path);
  }
  sh_image_free(&img);
  if (bad)
    return 11;
  sh_error_clear(&err);
  return has_mapped("libOpenImageIO") == 0 ? 0 : 12;
}

/* With the plugin made unfindable, other formats fail with a message
 * naming it, and EXR and PNG still work. */
static int child_no_plugin(void) {
  setenv("SHAFTS_OIIO_PLUGIN", "/nonexistent/libshafts_oiio.so", 1);
  sh_image img, back;
  sh_error err = SH_ERROR_INIT;
  char path[512];
  if (sh_image_alloc(&img, 2, 2, &err) != SH_OK)
    return 10;
  path_in_tmp(path, sizeof path, "noplugin.tif");
  if (sh_image_write(path, &img, 0, &err) != SH_ERR_IMAGE ||
      !strstr(err.message, "libshafts_oiio.so") || access(path, F_OK) == 0)
    return 11;
  path_in_tmp(path, sizeof path, "noplugin.exr");
  if (sh_image_write(path, &img, 0, &err) != SH_OK ||
      sh_image_read(path, &back, &err) != SH_OK)
    return 12;
  sh_image_free(&back);
  remove(path);
  sh_image_free(&img);
  sh_error_clear(&err);
  return 0;
}

int main(void) {
  if (!sh_test_tmpdir(tmpdir, sizeof tmpdir, "sh_image_codec_test"))
    return EXIT_FAILURE;
  /* Before anything loads the plugin into this process. */
  SH_CHECK(in_child(child_no_oiio) == 0);
  SH_CHECK(in_child(child_no_plugin) == 0);
  test_png_variants();
  test_exr_variants();
  test_plugin_formats();
  test_attributes();
  rmdir(tmpdir);
  SH_TEST_DONE();
}
