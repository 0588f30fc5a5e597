/* Tests of sh_image.h: EXR and PNG round trips, the sRGB curve, atomic
 * writes, grey images and bilinear look-up. */
#include "sh_image.h"
#include "sh_test.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmpdir[256];

static void path_in_tmp(char *buf, size_t size, const char *name) {
  snprintf(buf, size, "%s/%s", tmpdir, name);
}

/* The number of directory entries other than "." and "..". */
static int count_entries(const char *dir) {
  DIR *d = opendir(dir);
  if (!d)
    return -1;
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d)))
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
      n++;
  closedir(d);
  return n;
}

static void test_srgb(void) {
  SH_CHECK_NEAR(sh_srgb_to_linear(0.5), 0.21404114, 0, 1e-8);
  SH_CHECK_NEAR(sh_srgb_to_linear(0.0), 0.0, 0, 1e-15);
  SH_CHECK_NEAR(sh_srgb_to_linear(1.0), 1.0, 0, 1e-12);
  SH_CHECK_NEAR(sh_srgb_to_linear(0.04045), 0.04045 / 12.92, 0, 1e-15);
  SH_CHECK_NEAR(sh_srgb_to_linear(0.02), 0.02 / 12.92, 0, 1e-15);
  SH_CHECK_NEAR(sh_linear_to_srgb(0.21404114), 0.5, 0, 1e-8);
  SH_CHECK_NEAR(sh_linear_to_srgb(0.18), 0.46135612, 0, 1e-7);
  SH_CHECK_NEAR(sh_linear_to_srgb(0.001), 0.01292, 0, 1e-12);
  SH_CHECK_NEAR(sh_linear_to_srgb(1.0), 1.0, 0, 1e-12);
  /* The two pieces meet, and the functions invert each other. */
  SH_CHECK_NEAR(sh_linear_to_srgb(0.0031308), 0.0031308 * 12.92, 0, 1e-6);
  for (int i = 0; i <= 100; i++) {
    double v = i / 100.0;
    SH_CHECK_NEAR(sh_linear_to_srgb(sh_srgb_to_linear(v)), v, 0, 1e-12);
  }
}

static void fill_test_image(sh_image *img) {
  for (int y = 0; y < img->height; y++)
    for (int x = 0; x < img->width; x++) {
      float *p = img->rgb + 3 * (y * img->width + x);
      p[0] = (float)(x + 1) / (float)img->width;
      p[1] = (float)(y + 1) / (float)img->height * 0.5f;
      p[2] = (float)((x * 7 + y * 3) % 11) / 10.0f;
    }
}

static void test_exr_roundtrip(void) {
  sh_error err = SH_ERROR_INIT;
  sh_image img, back;
  SH_CHECK(sh_image_alloc(&img, 7, 5, &err) == SH_OK);
  fill_test_image(&img);
  img.rgb[0] = 1234.5f;  /* beyond 1 and unclamped */
  img.rgb[1] = 1e-7f;    /* tiny */
  img.rgb[2] = 0.1f;     /* not exactly representable as half */
  char path[512];
  path_in_tmp(path, sizeof path, "round.exr");
  SH_CHECK(sh_image_write(path, &img, 3.0, &err) == SH_OK);
  SH_CHECK(sh_image_read(path, &back, &err) == SH_OK);
  SH_CHECK(back.width == 7 && back.height == 5);
  if (back.rgb && back.width == 7 && back.height == 5)
    SH_CHECK(memcmp(back.rgb, img.rgb, 7 * 5 * 3 * sizeof(float)) == 0);
  sh_image_free(&back);
  /* Overwriting an existing file works and leaves one file. */
  img.rgb[3] = 42.0f;
  SH_CHECK(sh_image_write(path, &img, 0.0, &err) == SH_OK);
  SH_CHECK(sh_image_read(path, &back, &err) == SH_OK);
  SH_CHECK(back.rgb && back.rgb[3] == 42.0f);
  sh_image_free(&back);
  sh_image_free(&img);
  SH_CHECK(img.rgb == NULL && img.width == 0);
  sh_image_free(&img); /* twice is safe */
  sh_error_clear(&err);
}

static void test_png_roundtrip(void) {
  sh_error err = SH_ERROR_INIT;
  sh_image img, back;
  SH_CHECK(sh_image_alloc(&img, 9, 4, &err) == SH_OK);
  fill_test_image(&img);
  char path[512];
  path_in_tmp(path, sizeof path, "round.png");
  SH_CHECK(sh_image_write(path, &img, 0.0, &err) == SH_OK);
  SH_CHECK(sh_image_read(path, &back, &err) == SH_OK);
  SH_CHECK(back.width == 9 && back.height == 4);
  if (back.rgb && back.width == 9 && back.height == 4) {
    double worst = 0;
    for (int i = 0; i < 9 * 4 * 3; i++) {
      double a = sh_linear_to_srgb(img.rgb[i]);
      double b = sh_linear_to_srgb(back.rgb[i]);
      /* Rounding to nearest: within half a step of 1/255. */
      if (fabs(a - b) > worst)
        worst = fabs(a - b);
    }
    SH_CHECK(worst <= 0.5 / 255 + 1e-6);
  }
  sh_image_free(&back);

  /* Exposure: +1 stop doubles the radiance before clamping and encoding. */
  sh_image_free(&img);
  SH_CHECK(sh_image_alloc(&img, 2, 1, &err) == SH_OK);
  img.rgb[0] = img.rgb[1] = img.rgb[2] = 0.1f;
  img.rgb[3] = 5.0f;           /* clamps to 1 */
  img.rgb[4] = -3.0f;          /* clamps to 0 */
  img.rgb[5] = 0.0f / 0.0f;    /* NaN maps to 0 */
  SH_CHECK(sh_image_write(path, &img, 1.0, &err) == SH_OK);
  SH_CHECK(sh_image_read(path, &back, &err) == SH_OK);
  if (back.rgb) {
    double want = sh_srgb_to_linear(
        floor(sh_linear_to_srgb(0.2) * 255 + 0.5) / 255.0);
    SH_CHECK_NEAR(back.rgb[0], want, 1e-5, 0);
    SH_CHECK_NEAR(back.rgb[3], 1.0, 0, 1e-6);
    SH_CHECK_NEAR(back.rgb[4], 0.0, 0, 1e-9);
    SH_CHECK_NEAR(back.rgb[5], 0.0, 0, 1e-9);
  }
  sh_image_free(&back);
  sh_image_free(&img);
  sh_error_clear(&err);
}

/* A hand-made 8-bit grey PNG: 3x2 pixels, stored uncompressed in a zlib
 * stream, so the test needs no encoder. */
static unsigned long crc_table[256];
static void make_crc_table(void) {
  for (unsigned long n = 0; n < 256; n++) {
    unsigned long c = n;
    for (int k = 0; k < 8; k++)
      c = (c & 1) ? 0xedb88320UL ^ (c >> 1) : c >> 1;
    crc_table[n] = c;
  }
}
static unsigned long crc(const unsigned char *buf, size_t len) {
  unsigned long c = 0xffffffffUL;
  for (size_t n = 0; n < len; n++)
    c = crc_table[(c ^ buf[n]) & 0xff] ^ (c >> 8);
  return c ^ 0xffffffffUL;
}
static void put32(unsigned char *p, unsigned long v) {
  p[0] = (unsigned char)(v >> 24);
  p[1] = (unsigned char)(v >> 16);
  p[2] = (unsigned char)(v >> 8);
  p[3] = (unsigned char)v;
}
static void write_chunk(FILE *f, const char *type, const unsigned char *data,
                        size_t len) {
  unsigned char buf[256];
  put32(buf, (unsigned long)len);
  fwrite(buf, 1, 4, f);
  memcpy(buf, type, 4);
  if (len)
    memcpy(buf + 4, data, len);
  fwrite(buf, 1, 4 + len, f);
  put32(buf + 200, crc(buf, 4 + len));
  fwrite(buf + 200, 1, 4, f);
}
static int write_grey_png(const char *path, const unsigned char *pix, int w,
                          int h) {
  make_crc_table();
  FILE *f = fopen(path, "wb");
  if (!f)
    return 0;
  static const unsigned char sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
  fwrite(sig, 1, 8, f);
  unsigned char ihdr[13];
  put32(ihdr, (unsigned long)w);
  put32(ihdr + 4, (unsigned long)h);
  ihdr[8] = 8;  /* bit depth */
  ihdr[9] = 0;  /* grey */
  ihdr[10] = ihdr[11] = ihdr[12] = 0;
  write_chunk(f, "IHDR", ihdr, 13);
  /* Raw scanlines with filter byte 0. */
  unsigned char raw[128];
  size_t n = 0;
  for (int y = 0; y < h; y++) {
    raw[n++] = 0;
    for (int x = 0; x < w; x++)
      raw[n++] = pix[y * w + x];
  }
  unsigned char z[160];
  size_t m = 0;
  z[m++] = 0x78;
  z[m++] = 0x01;
  z[m++] = 1; /* final stored block */
  z[m++] = (unsigned char)(n & 0xff);
  z[m++] = (unsigned char)(n >> 8);
  z[m++] = (unsigned char)(~n & 0xff);
  z[m++] = (unsigned char)((~n >> 8) & 0xff);
  memcpy(z + m, raw, n);
  m += n;
  unsigned long a = 1, b = 0;
  for (size_t i = 0; i < n; i++) {
    a = (a + raw[i]) % 65521;
    b = (b + a) % 65521;
  }
  put32(z + m, (b << 16) | a);
  m += 4;
  write_chunk(f, "IDAT", z, m);
  write_chunk(f, "IEND", NULL, 0);
  return fclose(f) == 0;
}

static void test_grey_png(void) {
  static const unsigned char pix[6] = {0, 64, 128, 191, 255, 10};
  char path[512];
  path_in_tmp(path, sizeof path, "grey.png");
  SH_CHECK(write_grey_png(path, pix, 3, 2));
  sh_image img;
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(sh_image_read(path, &img, &err) == SH_OK);
  SH_CHECK(img.width == 3 && img.height == 2);
  if (img.rgb && img.width == 3 && img.height == 2) {
    for (int i = 0; i < 6; i++) {
      const float *p = img.rgb + 3 * i;
      SH_CHECK(p[0] == p[1] && p[1] == p[2]);
      SH_CHECK_NEAR(p[0], sh_srgb_to_linear(pix[i] / 255.0), 1e-5, 1e-7);
    }
  }
  sh_image_free(&img);
  /* As data (heightfields): the stored levels, undecoded. */
  SH_CHECK(sh_image_read_data(path, &img, &err) == SH_OK);
  if (img.rgb && img.width == 3 && img.height == 2)
    for (int i = 0; i < 6; i++)
      SH_CHECK_NEAR(img.rgb[3 * i], pix[i] / 255.0, 1e-6, 1e-7);
  sh_image_free(&img);
  sh_error_clear(&err);
}

static void test_errors(void) {
  sh_error err = SH_ERROR_INIT;
  sh_image img;
  char path[512], dir[512];

  /* A missing file. */
  path_in_tmp(path, sizeof path, "missing.png");
  SH_CHECK(sh_image_read(path, &img, &err) == SH_ERR_IO);
  SH_CHECK(err.status == SH_ERR_IO);
  SH_CHECK(strstr(err.message, "missing.png") != NULL);
  SH_CHECK(strstr(err.message, "No such file") != NULL);
  SH_CHECK(img.rgb == NULL);

  /* An empty file, and one that is not an image. */
  path_in_tmp(path, sizeof path, "empty.png");
  FILE *f = fopen(path, "wb");
  SH_CHECK(f != NULL);
  if (f)
    fclose(f);
  SH_CHECK(sh_image_read(path, &img, &err) == SH_ERR_IMAGE);
  path_in_tmp(path, sizeof path, "garbage.png");
  f = fopen(path, "wb");
  if (f) {
    fputs("this is not a PNG file at all\n", f);
    fclose(f);
  }
  SH_CHECK(sh_image_read(path, &img, &err) == SH_ERR_IMAGE);
  SH_CHECK(img.rgb == NULL);

  /* Writing into a directory that does not exist fails and leaves nothing. */
  SH_CHECK(sh_image_alloc(&img, 4, 4, &err) == SH_OK);
  int before = count_entries(tmpdir);
  path_in_tmp(path, sizeof path, "no/such/dir/out.exr");
  SH_CHECK(sh_image_write(path, &img, 0, &err) != SH_OK);
  path_in_tmp(path, sizeof path, "no/such/dir/out.png");
  SH_CHECK(sh_image_write(path, &img, 0, &err) != SH_OK);
  SH_CHECK(access(path, F_OK) != 0);
  /* An unknown format leaves nothing either. */
  path_in_tmp(path, sizeof path, "out.nosuchformat");
  SH_CHECK(sh_image_write(path, &img, 0, &err) != SH_OK);
  path_in_tmp(path, sizeof path, "noextension");
  SH_CHECK(sh_image_write(path, &img, 0, &err) == SH_ERR_ARG);
  /* A destination that is a directory is refused before anything is
   * written (sh_outputs.h). */
  path_in_tmp(dir, sizeof dir, "adir.png");
  SH_CHECK(mkdir(dir, 0700) == 0);
  SH_CHECK(sh_image_write(dir, &img, 0, &err) == SH_ERR_ARG);
  SH_CHECK(strstr(err.message, "not a regular file") != NULL);
  rmdir(dir);
  SH_CHECK(count_entries(tmpdir) == before);

  /* Bad arguments. */
  sh_image_free(&img);
  SH_CHECK(sh_image_alloc(&img, 0, 3, &err) == SH_ERR_ARG);
  SH_CHECK(sh_image_write(path, &img, 0, &err) == SH_ERR_ARG);
  SH_CHECK(sh_image_read(NULL, &img, &err) == SH_ERR_ARG);
  sh_error_clear(&err);
}

static void test_lookup(void) {
  sh_image img;
  sh_error err = SH_ERROR_INIT;
  SH_CHECK(sh_image_alloc(&img, 2, 2, &err) == SH_OK);
  /* Red channel: 0 1 / 2 3; green constant 5; blue = row. */
  for (int i = 0; i < 4; i++) {
    img.rgb[3 * i] = (float)i;
    img.rgb[3 * i + 1] = 5.0f;
    img.rgb[3 * i + 2] = (float)(i / 2);
  }
  float o[3];
  sh_image_lookup(&img, 0.25, 0.25, o); /* the centre of texel (0, 0) */
  SH_CHECK_NEAR(o[0], 0.0, 0, 1e-6);
  sh_image_lookup(&img, 0.75, 0.75, o);
  SH_CHECK_NEAR(o[0], 3.0, 0, 1e-6);
  sh_image_lookup(&img, 0.5, 0.5, o); /* the average of all four */
  SH_CHECK_NEAR(o[0], 1.5, 0, 1e-6);
  SH_CHECK_NEAR(o[1], 5.0, 0, 1e-6);
  SH_CHECK_NEAR(o[2], 0.5, 0, 1e-6);
  sh_image_lookup(&img, 0.5, 0.25, o); /* between (0,0) and (1,0) */
  SH_CHECK_NEAR(o[0], 0.5, 0, 1e-6);
  sh_image_lookup(&img, 0.375, 0.625, o); /* fx = 0.25, fy = 0.75 */
  SH_CHECK_NEAR(o[0], 0.25 + 2 * 0.75, 0, 1e-6);
  SH_CHECK_NEAR(o[2], 0.75, 0, 1e-6);
  /* Clamped to the edge: inside the outer half texel and beyond [0, 1]. */
  sh_image_lookup(&img, 0.1, 0.0, o);
  SH_CHECK_NEAR(o[0], 0.0, 0, 1e-6);
  sh_image_lookup(&img, 1.0, 1.0, o);
  SH_CHECK_NEAR(o[0], 3.0, 0, 1e-6);
  sh_image_lookup(&img, -4.0, 7.0, o);
  SH_CHECK_NEAR(o[0], 2.0, 0, 1e-6);
  sh_image_lookup(&img, 0.0 / 0.0, 0.75, o);
  SH_CHECK_NEAR(o[0], 2.0, 0, 1e-6);
  sh_image_free(&img);
  /* An empty image gives black. */
  o[0] = o[1] = o[2] = 1;
  sh_image_lookup(&img, 0.5, 0.5, o);
  SH_CHECK(o[0] == 0 && o[1] == 0 && o[2] == 0);
  sh_error_clear(&err);
}

int main(void) {
  if (!sh_test_tmpdir(tmpdir, sizeof tmpdir, "sh_image_test")) return EXIT_FAILURE;
  test_srgb();
  test_exr_roundtrip();
  test_png_roundtrip();
  test_grey_png();
  test_errors();
  test_lookup();

  /* Clean up the files the tests wrote. */
  static const char *names[] = {"round.exr", "round.png", "grey.png",
                                "empty.png", "garbage.png"};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
    char path[512];
    path_in_tmp(path, sizeof path, names[i]);
    remove(path);
  }
  SH_CHECK(count_entries(tmpdir) == 0);
  rmdir(tmpdir);
  SH_TEST_DONE();
}
