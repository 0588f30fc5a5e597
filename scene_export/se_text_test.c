/* Escaping user text: POV-Ray string literals, comments, side-file names. */
#include <string.h>

#include "se_pov_terms.h"
#include "se_text.h"
#include "sh_test.h"

static const char *const HOSTILE = "a\"b\\c\nd\t__import__('os').system('touch pwned') */ é";

int main(void) {
  se_buf b = {0};
  se_pov_string(&b, HOSTILE);
  SH_CHECK(b.data && !strcmp(b.data, "\"a\\\"b\\\\c\\nd\\t__import__('os').system('touch "
                                     "pwned') */ __\""));
  se_buf_free(&b);

  char c[200];
  se_comment_text(HOSTILE, c, sizeof c);
  /* Printable ASCII stays; line ends, control and non-ASCII bytes and a
   * block comment's star do not. */
  SH_CHECK(!strcmp(c, "a\"b\\c_d___import__('os').system('touch pwned') _/ __"));
  se_comment_text("x/*y*/z\r// ;#=:,()", c, sizeof c);
  SH_CHECK(!strcmp(c, "x/_y_/z_// ;#=:,()"));
  char small[12];
  se_comment_text("abcdefghijklmnopqrstuvwxyz", small, sizeof small);
  SH_CHECK(!strcmp(small, "abcdefgh...") && strlen(small) == sizeof small - 1);

  char p[64];
  se_plain_name("-ev\"il\\ name.py", p, sizeof p);
  SH_CHECK(!strcmp(p, "_ev_il__name.py"));
  se_plain_name("", p, sizeof p);
  SH_CHECK(!strcmp(p, "_"));
  SH_CHECK(se_is_plain_file_name("scene-1.v2_final+x"));
  SH_CHECK(!se_is_plain_file_name("a b"));
  SH_CHECK(!se_is_plain_file_name("-x"));
  SH_CHECK(!se_is_plain_file_name(".x"));
  SH_CHECK(!se_is_plain_file_name("a\"b"));
  SH_CHECK(!se_is_plain_file_name(""));

  /* Shell words: plain paths as they are, the rest in single quotes. */
  const char *words[][2] = {{"/tmp/out/s.pov", "/tmp/out/s.pov"},
                            {"it's $(x) `y`\n", "'it'\\''s $(x) `y`\n'"},
                            {"-o", "'-o'"},
                            {"", "''"}};
  for (size_t i = 0; i < sizeof words / sizeof *words; i++) {
    se_buf w = {0};
    se_shell_word(&w, words[i][0]);
    SH_CHECK(w.data && !strcmp(w.data, words[i][1]));
    se_buf_free(&w);
  }

  SH_CHECK(!strcmp(se_base_name("/a/b/c.pov"), "c.pov"));
  char *r = se_replace_extension("/a.b/c.pov", ".ini");
  SH_CHECK(r && !strcmp(r, "/a.b/c.ini"));
  free(r);
  r = se_replace_extension("/a.b/c", ".json");
  SH_CHECK(r && !strcmp(r, "/a.b/c.json"));
  free(r);
  SH_TEST_DONE();
}
