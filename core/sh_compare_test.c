/* Image comparison: known errors on small images. */
#include "sh_compare.h"
#include "sh_test.h"

int main(void) {
  sh_image a = {0}, b = {0}, d = {0};
  sh_image_alloc(&a, 2, 2, NULL);
  sh_image_alloc(&b, 2, 2, NULL);
  for (int i = 0; i < 12; i++) b.rgb[i] = 1.0f;
  b.rgb[9] = b.rgb[10] = b.rgb[11] = 0.001f; /* a dark pixel */
  for (int i = 0; i < 12; i++) a.rgb[i] = b.rgb[i] * 1.1f;
  a.rgb[9] = 5.0f; /* a large error in the dark pixel is not "lit" */
  sh_image_error e;
  SH_CHECK(sh_image_compare(&a, &b, 0.01, &e, &d, NULL) == SH_OK);
  SH_CHECK(e.lit_pixels == 3);
  SH_CHECK_NEAR(e.rel_rms, 0.1, 1e-6, 0);
  SH_CHECK_NEAR(e.mean_rel, 0.1, 1e-6, 0);
  SH_CHECK_NEAR(e.max_abs, 5.0 - 0.001, 1e-6, 0);
  SH_CHECK_NEAR(d.rgb[0], 0.1, 1e-6, 0);
  SH_CHECK(e.bad_values == 0);
  a.rgb[0] = -1.0f;
  SH_CHECK(sh_image_compare(&a, &b, 0.01, &e, NULL, NULL) == SH_OK);
  SH_CHECK(e.bad_values == 1);
  sh_image c = {0};
  sh_image_alloc(&c, 3, 2, NULL);
  SH_CHECK(sh_image_compare(&c, &b, 0.01, &e, NULL, NULL) == SH_ERR_ARG);
  sh_image_free(&a);
  sh_image_free(&b);
  sh_image_free(&c);
  sh_image_free(&d);
  SH_TEST_DONE();
}
