/* Command-line helpers: an option table parsed with getopt_long (values,
 * limits, choices, repeated and multi-valued options, operands, unknown
 * options and missing values), the --help text drawn from the table, and
 * output checks. Their messages go to stderr, which the test leaves
 * visible. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sh_cli.h"
#include "sh_options.h"
#include "sh_test.h"

typedef struct values {
  sh_cli_list out;
  long n, size[2];
  double x;
  int flag, choice;
  const char *name;
} values;

static const sh_cli_choice colours[] = {{"red", 1}, {"green", 2}, {NULL, 0}};

#define F(f) offsetof(values, f)
static const sh_cli_option options[] = {
    {"output", 'o', SH_CLI_LIST, "FILE", 0, F(out), 0, 0, 0, 0, NULL, NULL,
     NULL, NULL, "an output"},
    {"n", 0, SH_CLI_INT, "N", 1, F(n), 0, 100, 0, 0, NULL, NULL, NULL, "7",
     "a count"},
    {"size", 0, SH_CLI_INT, "W H", 2, F(size), 1, 10, 0, 0, NULL, NULL, NULL,
     NULL, "two counts"},
    {"x", 0, SH_CLI_NUMBER, "X", 1, F(x), 0, INFINITY, 1, 0, NULL, NULL, NULL,
     NULL, "a number > 0"},
    {"flag", 'f', SH_CLI_FLAG, NULL, 0, F(flag), 0, 0, 0, 1, NULL, NULL, NULL,
     NULL, "a flag"},
    {"colour", 0, SH_CLI_CHOICE, NULL, 0, F(choice), 0, 0, 0, 0, colours,
     NULL, NULL, NULL, "a colour"},
    {"name", 0, SH_CLI_TEXT, "NAME", 1, F(name), 0, 0, 0, 0, NULL, NULL, NULL,
     NULL, "a name"},
    {"level", 0, SH_CLI_SETTER, NULL, 0, 0, 0, 0, 0, 0, NULL, "level", NULL,
     NULL, "a renderer's option"},
};

/* A renderer's options: one int "level" in [1, 3]. */
typedef struct renderer {
  int level;
} renderer;
static const sh__opt level_def[] = {
    {"level", offsetof(renderer, level), SH__OPT_INT, 1, 3, 0, NULL, 0, 0, 0, 0}};
static sh_status set_level(void *t, const char *key, const char *value,
                           sh_error *err) {
  return sh__options_set(level_def, 1, t, key, value, err);
}

static renderer scratch;
static const sh_cli_tool tool = {
    "t", "IN [options]", "A test tool.", options,
    (int)(sizeof options / sizeof *options), 1, 2, NULL, NULL,
    set_level, &scratch, NULL, NULL};

/* Parses a NULL-terminated argument list. */
static int parse(values *v, sh_cli_args *a, ...) {
  char *argv[32] = {"t"};
  int argc = 1;
  va_list ap;
  va_start(ap, a);
  for (char *s; argc < 31 && (s = va_arg(ap, char *));) argv[argc++] = s;
  va_end(ap);
  memset(v, 0, sizeof *v);
  return sh_cli_parse(&tool, argc, argv, v, a);
}

int main(void) {
  values v;
  sh_cli_args a;
  SH_CHECK(parse(&v, &a, "in", "-o", "a.exr", "--output", "b.png", "--n",
                 "12", "--size", "3", "4", "-f", "--colour", "green", "--x",
                 "0.25", "--name=k", "--level", "2", "in2", NULL) == -1);
  SH_CHECK(v.out.count == 2 && !strcmp(v.out.items[1], "b.png"));
  SH_CHECK(v.n == 12 && v.size[0] == 3 && v.size[1] == 4 && v.flag == 1);
  SH_CHECK(v.choice == 2 && v.x == 0.25 && !strcmp(v.name, "k"));
  SH_CHECK(a.noperands == 2 && !strcmp(a.operands[1], "in2"));
  SH_CHECK(sh_cli_given(&tool, &a, "n") && !sh_cli_given(&tool, &a, "name") == 0);
  renderer r = {0};
  SH_CHECK(sh_cli_apply(&tool, &a, &r, NULL) == SH_OK && r.level == 2);

  /* Bad values, unknown options (last, too), missing values, operands. */
  SH_CHECK(parse(&v, &a, "in", "--n", "101", NULL) == 2);
  SH_CHECK(parse(&v, &a, "in", "--n", "1x", NULL) == 2);
  SH_CHECK(parse(&v, &a, "in", "--x", "0", NULL) == 2);
  SH_CHECK(parse(&v, &a, "in", "--x", "inf", NULL) == 2);
  SH_CHECK(parse(&v, &a, "in", "--colour", "blue", NULL) == 2);
  SH_CHECK(parse(&v, &a, "in", "--level", "4", NULL) == 2);
  SH_CHECK(parse(&v, &a, "in", "--size", "3", NULL) == 2);
  SH_CHECK(parse(&v, &a, "in", "--bogus", NULL) == 2);
  /* A long option's unambiguous prefix stands for it, as getopt_long
   * allows; an ambiguous prefix, refused naming the options it could be, is
   * checked by the tools' tests (render_cli_common, tools/cli_test_lib.sh). */
  SH_CHECK(parse(&v, &a, "in", "--fla", "--si", "1", "2", NULL) == -1 &&
           v.flag == 1 && v.size[1] == 2);
  SH_CHECK(parse(&v, &a, "in", "--na=k", NULL) == -1 && !strcmp(v.name, "k"));
  SH_CHECK(parse(&v, &a, "in", "--n", NULL) == 2);
  SH_CHECK(parse(&v, &a, "in", "-x", NULL) == 2);
  SH_CHECK(parse(&v, &a, NULL) == 2);
  SH_CHECK(parse(&v, &a, "a", "b", "c", NULL) == 2);
  SH_CHECK(parse(&v, &a, "in", "--", "-dash", NULL) == -1 &&
           !strcmp(a.operands[1], "-dash"));
  SH_CHECK(parse(&v, &a, "-", NULL) == -1 && !strcmp(a.operands[0], "-"));
  SH_CHECK(parse(&v, &a, "--version", NULL) == 0);
  SH_CHECK(parse(&v, &a, "--help", NULL) == 0);

  /* --width/--height: the side not given follows the aspect, and is at
   * least one pixel (a wide image narrowed to 40 columns was left at its
   * own height when the other side rounded to 0). */
  sh_scene sc = {0};
  sc.camera.width = 1000, sc.camera.height = 10;
  sh_cli_resize(&sc, 40, 0);
  SH_CHECK(sc.camera.width == 40 && sc.camera.height == 1);
  sc.camera.width = 64, sc.camera.height = 48;
  sh_cli_resize(&sc, 0, 24);
  SH_CHECK(sc.camera.width == 32 && sc.camera.height == 24);
  sh_cli_resize(&sc, 0, 0);
  SH_CHECK(sc.camera.width == 32 && sc.camera.height == 24);
  sh_cli_resize(&sc, 10, 20);
  SH_CHECK(sc.camera.width == 10 && sc.camera.height == 20);

  /* Outputs: extensions and directories, made with create. */
  SH_CHECK(sh_cli_check_output("t", "-o", "a.exr", "exr,png", 0));
  SH_CHECK(!sh_cli_check_output("t", "-o", "a.tif", "exr,png", 0));
  char dir[] = "/tmp/sh_cli_testXXXXXX";
  SH_CHECK(mkdtemp(dir) != NULL);
  char path[256];
  snprintf(path, sizeof path, "%s/x/y/a.exr", dir);
  SH_CHECK(!sh_cli_check_output("t", "-o", path, "exr", 0));
  SH_CHECK(sh_cli_check_output("t", "-o", path, "exr", 1));
  SH_CHECK(sh_cli_check_output("t", "-o", path, "exr", 0));
  /* A failed run undoes what -p made, deepest first, never the directory
   * that was there before (issue 11). */
  sh_cli_dirs_undo();
  struct stat sb;
  snprintf(path, sizeof path, "%s/x", dir);
  SH_CHECK(stat(path, &sb) != 0 && errno == ENOENT);
  SH_CHECK(stat(dir, &sb) == 0);
  /* A name longer than the file system takes is refused before any
   * directory is made. */
  char name[300];
  memset(name, 'z', sizeof name - 1);
  name[sizeof name - 1] = '\0';
  char longpath[400];
  snprintf(longpath, sizeof longpath, "%s/x/%s.png", dir, name);
  SH_CHECK(!sh_cli_check_name("t", "-o", longpath));
  SH_CHECK(!sh_cli_check_output("t", "-o", longpath, "png", 1));
  SH_CHECK(stat(path, &sb) != 0);
  snprintf(path, sizeof path, "%s/x/a.png", dir);
  SH_CHECK(sh_cli_check_name("t", "-o", path));
  /* However many directories -p made (the record once held 64), all are
   * undone. */
  size_t deep_len = strlen(dir) + 200 * 2 + 8;
  char *deep = malloc(deep_len);
  SH_CHECK(deep != NULL);
  if (deep) {
    size_t at = (size_t)snprintf(deep, deep_len, "%s", dir);
    for (int i = 0; i < 200; i++) at += (size_t)snprintf(deep + at, deep_len - at, "/d");
    snprintf(deep + at, deep_len - at, "/a.exr");
    SH_CHECK(sh_cli_check_output("t", "-o", deep, "exr", 1));
    snprintf(path, sizeof path, "%s/d", dir);
    SH_CHECK(stat(path, &sb) == 0);
    sh_cli_dirs_undo();
    SH_CHECK(stat(path, &sb) != 0 && errno == ENOENT);
    free(deep);
  }
  rmdir(dir);

  /* A directory where no file can be made is refused before the work, even
   * for root (who passes access()); the probe leaves nothing behind. */
  SH_CHECK(!sh_cli_check_output("t", "-o", "/proc/x.png", "png", 0));
  char tmp[] = "/tmp/sh_cli_probe_XXXXXX", out[64];
  SH_CHECK(mkdtemp(tmp) != NULL);
  snprintf(out, sizeof out, "%s/x.png", tmp);
  SH_CHECK(sh_cli_check_output("t", "-o", out, "png", 0));
  SH_CHECK(rmdir(tmp) == 0); /* empty: the probe file is gone */

  /* A renderer's message about its options by key, in the tool's names:
   * words only, not parts of dotted or hyphenated names. */
  char *named = sh_cli_option_names(&tool, "level needs render.level, level-x and level");
  SH_CHECK(named && !strcmp(named, "--level needs render.level, level-x and --level"));
  free(named);

  SH_CHECK(sh_exit_code(SH_ERR_SCENE) == SH_EXIT_BAD_INPUT);
  SH_CHECK(sh_exit_code(SH_ERR_DEVICE) == SH_EXIT_FAILURE);
  SH_TEST_DONE();
}
