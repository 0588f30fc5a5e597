/* Shafts crossing the view within one slab (docs/gl_shafts.md, "Shafts
 * crossing the view within one slab"): testdata/side_comb.json, a fog box
 * lit from the side through a comb of thin slats, whose shadow sheets
 * cross each view ray several times between two of the default 8 planes,
 * against the reference at 256 samples per pixel, 96x72. Before the
 * sweep sampled a step's visibility per shadow-map texel (plane_dir.frag's
 * vis_step) it was 17.5% from the reference at 8 planes; measured since,
 * 2.2%; bound 3%. A failure writes the images and their difference. */
#include "sh_test.h"
#include "test_util.h"

int main(void) {
  sh_scene *s = sh_test_load("gl_shafts/testdata/%s", "side_comb.json");
  SH_CHECK(s != NULL);
  if (s) SH_CHECK(tu_check_reference("side_comb", s, 256, 0.03));
  sh_scene_free(s);
  if (tu_failures) sh_test_failures += tu_failures;
  SH_TEST_DONE();
}
