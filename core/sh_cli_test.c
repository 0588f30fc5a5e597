/* Command-line helpers: option values, operands and render outputs. Their
 * messages go to stderr, which the test leaves visible. */
#include "sh_cli.h"
#include "sh_test.h"

int main(void) {
  long n = 0;
  SH_CHECK(sh_cli_int("t", "--n", "12", 0, 100, &n) && n == 12);
  SH_CHECK(!sh_cli_int("t", "--n", "101", 0, 100, &n));
  SH_CHECK(!sh_cli_int("t", "--n", "1x", 0, 100, &n));
  SH_CHECK(!sh_cli_int("t", "--n", NULL, 0, 100, &n));
  double x = 0;
  SH_CHECK(sh_cli_double("t", "--x", "0.25", &x) && x == 0.25);
  SH_CHECK(!sh_cli_double("t", "--x", "inf", &x));
  SH_CHECK(!sh_cli_double("t", "--x", "", &x));

  const char *a = NULL, *b = NULL;
  const char **slots[] = {&a, &b};
  SH_CHECK(sh_cli_operand("t", "ref.exr", slots, 2) && a && !b);
  SH_CHECK(sh_cli_operand("t", "-", slots, 2) && b && b[0] == '-');
  SH_CHECK(!sh_cli_operand("t", "third", slots, 2));
  a = b = NULL;
  SH_CHECK(!sh_cli_operand("t", "--bogus", slots, 2) && !a);

  const char *outs[] = {"a.exr", "b.png"};
  SH_CHECK(sh_cli_check_render_outputs("t", "s.json", outs, 2));
  SH_CHECK(!sh_cli_check_render_outputs("t", NULL, outs, 2));
  SH_CHECK(!sh_cli_check_render_outputs("t", "s.json", outs, 0));
  const char *bad[] = {"a.exr", "b.tif"};
  SH_CHECK(!sh_cli_check_render_outputs("t", "s.json", bad, 2));
  SH_TEST_DONE();
}
