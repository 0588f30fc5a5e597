#include "sh_cli.h"

#include <errno.h>
#include <stdarg.h>
#include <getopt.h>
#include <jansson.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sh_file.h"
#include "sh_json_out.h"
#include "sh_medium.h"
#include "sh_parse.h"
#include "shafts.h"

/* ---- The option table ---- */

/* getopt_long's `val` of option i: its short letter, else 256 + i. */
static int opt_val(const sh_cli_tool *t, int i) {
  return t->options[i].short_name ? t->options[i].short_name : 256 + i;
}

enum { VAL_HELP = 'h', VAL_VERSION = 1000 };

static int nvalues_of(const sh_cli_option *o) {
  switch (o->type) {
  case SH_CLI_FLAG: return 0;
  case SH_CLI_TEXT:
  case SH_CLI_INT:
  case SH_CLI_NUMBER: return o->nvalues > 0 ? o->nvalues : 1;
  case SH_CLI_SETTER:
    return o->fixed ? 0 : o->nvalues > 0 ? o->nvalues : 1;
  default: return 1;
  }
}

/* The choices of an option as "a|b|c" into buf. */
static const char *choice_list(const sh_cli_tool *t, const sh_cli_option *o,
                               const char *sep, char *buf, size_t size) {
  size_t n = 0;
  buf[0] = '\0';
  if (o->type == SH_CLI_CHOICE) {
    for (int i = 0; o->choices[i].name && n < size; i++)
      n += (size_t)snprintf(buf + n, size - n, "%s%s", i ? sep : "",
                            o->choices[i].name);
  } else if (o->type == SH_CLI_SETTER && t->setter_choices) {
    const char *const *c = t->setter_choices(o->key);
    for (int i = 0; c && c[i] && n < size; i++)
      n += (size_t)snprintf(buf + n, size - n, "%s%s", i ? sep : "", c[i]);
  }
  return buf;
}

/* "-o, --output FILE" for the help's left column. */
static void option_label(const sh_cli_tool *t, const sh_cli_option *o,
                         char *buf, size_t size) {
  char choices[256];
  const char *meta = o->metavar;
  if (!meta && nvalues_of(o) > 0) {
    meta = choice_list(t, o, "|", choices, sizeof choices);
    if (!*meta) meta = "VALUE";
  }
  if (o->short_name)
    snprintf(buf, size, "-%c, --%s%s%s", o->short_name, o->name,
             meta ? " " : "", meta ? meta : "");
  else
    snprintf(buf, size, "--%s%s%s", o->name, meta ? " " : "",
             meta ? meta : "");
}

enum { HELP_COLUMN = 26, HELP_WIDTH = 79 };

/* Prints text word-wrapped from column `indent` (the first line starts at
 * column `at`). */
static void wrap(FILE *f, const char *text, int at, int indent) {
  int col = at;
  const char *p = text;
  while (*p) {
    while (*p == ' ') p++;
    size_t len = strcspn(p, " ");
    if (!len) break;
    if (col > indent && col + 1 + (int)len > HELP_WIDTH) {
      fprintf(f, "\n%*s", indent, "");
      col = indent;
    } else if (col > indent) {
      fputc(' ', f);
      col++;
    } else if (col < indent) {
      fprintf(f, "%*s", indent - col, "");
      col = indent;
    }
    fwrite(p, 1, len, f);
    col += (int)len;
    p += len;
  }
  fputc('\n', f);
}

void sh_cli_help_item(FILE *f, const char *label, const char *text) {
  fprintf(f, "  %s", label);
  int col = 2 + (int)strlen(label);
  if (col + 2 > HELP_COLUMN) {
    fputc('\n', f);
    col = 0;
  }
  wrap(f, text ? text : "", col, HELP_COLUMN);
}

void sh_cli_help(const sh_cli_tool *t, FILE *f) {
  fprintf(f, "usage: %s %s\n\n%s\n\noptions:\n", t->name, t->synopsis,
          t->description);
  for (int i = 0; i < t->noptions; i++) {
    const sh_cli_option *o = &t->options[i];
    char label[300], help[1024];
    option_label(t, o, label, sizeof label);
    snprintf(help, sizeof help, "%s%s%s%s", o->help ? o->help : "",
             o->def ? " (default: " : "", o->def ? o->def : "",
             o->def ? ")" : "");
    sh_cli_help_item(f, label, help);
  }
  sh_cli_help_item(f, "-h, --help", "show this help and exit");
  sh_cli_help_item(f, "--version", "print the version and exit");
  if (t->epilogue) {
    fputc('\n', f);
    t->epilogue(f);
  }
  char status[512];
  snprintf(status, sizeof status,
           "Exit status: 0 on success, 1 when the work fails, 2 for bad input "
           "(%s)%s%s",
           t->bad_input ? t->bad_input
                        : "arguments, a missing or bad scene, mesh or image file",
           t->exit_extra ? ", " : ".", t->exit_extra ? t->exit_extra : "");
  fputc('\n', f);
  wrap(f, status, 0, 0);
}

/* ---- Messages ---- */

void sh_cli_error(const char *tool, const char *format, ...) {
  va_list ap;
  va_start(ap, format);
  fprintf(stderr, "%s: error: ", tool);
  vfprintf(stderr, format, ap);
  fputc('\n', stderr);
  va_end(ap);
}

/* ---- Values ---- */

static int bad_value(const sh_cli_tool *t, const sh_cli_option *o,
                     const char *text, const char *expected) {
  sh_cli_error(t->name, "--%s: expected %s, found '%s'", o->name, expected,
               text);
  return 0;
}

static int parse_int(const sh_cli_tool *t, const sh_cli_option *o,
                     const char *text, long *out) {
  char *end = NULL;
  errno = 0;
  long v = strtol(text, &end, 10);
  if (end == text || *end || errno || v < o->lo || v > o->hi) {
    char expected[96];
    snprintf(expected, sizeof expected, "an integer from %.0f to %.0f", o->lo,
             o->hi);
    return bad_value(t, o, text, expected);
  }
  *out = v;
  return 1;
}

static int parse_number(const sh_cli_tool *t, const sh_cli_option *o,
                        const char *text, double *out) {
  char *end = NULL;
  double v = strtod(text, &end);
  int in = o->lo_open ? v > o->lo : v >= o->lo;
  if (end == text || *end || !isfinite(v) || !in || v > o->hi) {
    char expected[96];
    if (isinf(o->lo) && isinf(o->hi))
      snprintf(expected, sizeof expected, "a finite number");
    else if (isinf(o->hi))
      snprintf(expected, sizeof expected, "a number %s %g",
               o->lo_open ? ">" : ">=", o->lo);
    else
      snprintf(expected, sizeof expected, "a number in %c%g, %g]",
               o->lo_open ? '(' : '[', o->lo, o->hi);
    return bad_value(t, o, text, expected);
  }
  *out = v;
  return 1;
}

/* Stores value k of option o; returns 0 after a message. */
static int store(const sh_cli_tool *t, const sh_cli_option *o, int k,
                 const char *text, void *values) {
  void *field = (char *)values + o->offset;
  char list[256];
  switch (o->type) {
  case SH_CLI_FLAG: *(int *)field = o->set; return 1;
  case SH_CLI_TEXT:
    if (!*text) return bad_value(t, o, text, "a name");
    ((const char **)field)[k] = text;
    return 1;
  case SH_CLI_LIST: {
    sh_cli_list *l = field;
    if (l->count == SH_CLI_LIST_MAX) {
      fprintf(stderr, "%s: error: --%s may be given at most %d times\n", t->name,
              o->name, SH_CLI_LIST_MAX);
      return 0;
    }
    l->items[l->count++] = text;
    return 1;
  }
  case SH_CLI_INT: return parse_int(t, o, text, (long *)field + k);
  case SH_CLI_NUMBER: return parse_number(t, o, text, (double *)field + k);
  case SH_CLI_CHOICE:
    for (int i = 0; o->choices[i].name; i++)
      if (!strcmp(o->choices[i].name, text)) {
        *(int *)field = o->choices[i].value;
        return 1;
      }
    choice_list(t, o, ", ", list, sizeof list);
    sh_cli_error(t->name, "--%s: unknown value '%s'; expected one of: %s",
                 o->name, text, list);
    return 0;
  case SH_CLI_SETTER: break; /* setter() */
  }
  return 0;
}

/* A SETTER option: checks the values (joined by spaces) on the tool's
 * scratch target and records them for sh_cli_apply. */
static int setter(const sh_cli_tool *t, const sh_cli_option *o,
                  const char *const *texts, int n, sh_cli_args *args) {
  if (args->nsettings == SH_CLI_MAX_OPTIONS) return 0;
  char *value = args->settings[args->nsettings].value;
  size_t size = sizeof args->settings[0].value, len = 0;
  value[0] = '\0';
  for (int k = 0; k < n && len < size; k++)
    len += (size_t)snprintf(value + len, size - len, "%s%s", k ? " " : "",
                            texts[k]);
  sh_error err = SH_ERROR_INIT;
  if (t->setter(t->setter_target, o->key, value, &err) != SH_OK) {
    sh_cli_error(t->name, "--%s: %s", o->name, err.message);
    sh_error_clear(&err);
    return 0;
  }
  args->settings[args->nsettings++].key = o->key;
  return 1;
}

/* Writes sh_cli_option_names's text into out (NULL: only counts); returns
 * its length. */
static size_t option_names(const sh_cli_tool *t, const char *message,
                           char *out) {
  size_t n = 0;
  for (const char *p = message; *p;) {
    size_t len = strspn(p, "abcdefghijklmnopqrstuvwxyz_");
    int word = len && (p == message || !strchr("._-", p[-1])) &&
               !(p[len] && strchr(".-", p[len]));
    const sh_cli_option *o = NULL;
    for (int i = 0; word && i < t->noptions && !o; i++)
      if (t->options[i].type == SH_CLI_SETTER && t->options[i].key &&
          strlen(t->options[i].key) == len &&
          !strncmp(t->options[i].key, p, len))
        o = &t->options[i];
    const char *piece = o ? o->name : p;
    size_t plen = o ? strlen(o->name) : len ? len : 1;
    if (o) {
      if (out) memcpy(out + n, "--", 2);
      n += 2;
    }
    if (out) memcpy(out + n, piece, plen);
    n += plen;
    p += len ? len : 1;
  }
  if (out) out[n] = '\0';
  return n;
}

char *sh_cli_option_names(const sh_cli_tool *t, const char *message) {
  char *out = malloc(option_names(t, message, NULL) + 1);
  if (out) option_names(t, message, out);
  return out;
}

sh_status sh_cli_apply(const sh_cli_tool *t, const sh_cli_args *args,
                       void *target, sh_error *err) {
  for (int i = 0; i < args->nsettings; i++) {
    sh_status st = t->setter(target, args->settings[i].key,
                             args->settings[i].value, err);
    if (st != SH_OK) return st;
  }
  return SH_OK;
}

/* ---- Parsing ---- */

/* getopt_long takes any unambiguous prefix of a long option ("--wid" for
 * "--width") and refuses an ambiguous one as it refuses an unknown one. If
 * TEXT ("--pre" or "--pre=value") is a prefix of several long options,
 * prints them and returns 1; else returns 0 (README.md, "What every
 * command line shares"). */
static int report_ambiguous(const char *tool, const struct option *longs,
                            const char *text) {
  if (strncmp(text, "--", 2) != 0 || !text[2]) return 0;
  size_t n = strcspn(text + 2, "=");
  int count = 0;
  for (const struct option *o = longs; o->name; o++)
    count += !strncmp(o->name, text + 2, n);
  if (count < 2) return 0;
  fprintf(stderr, "%s: error: ambiguous option '%.*s': it could be", tool,
          (int)n + 2, text);
  int k = 0;
  for (const struct option *o = longs; o->name; o++)
    if (!strncmp(o->name, text + 2, n))
      fprintf(stderr, "%s--%s", k++ == 0 ? " " : k == count ? " or " : ", ",
              o->name);
  fprintf(stderr, " (see --help)\n");
  return 1;
}

int sh_cli_parse(const sh_cli_tool *t, int argc, char **argv, void *values,
                 sh_cli_args *args) {
  struct option longs[SH_CLI_MAX_OPTIONS + 3];
  char shorts[3 * SH_CLI_MAX_OPTIONS + 8] = "+:h";
  size_t ns = strlen(shorts);
  memset(args, 0, sizeof *args);
  sh_cli_signals();
  if (t->noptions > SH_CLI_MAX_OPTIONS) {
    fprintf(stderr, "%s: error: too many options in the tool's table\n", t->name);
    return SH_EXIT_FAILURE;
  }
  for (int i = 0; i < t->noptions; i++) {
    const sh_cli_option *o = &t->options[i];
    longs[i] = (struct option){o->name, nvalues_of(o) ? required_argument
                                                       : no_argument,
                               NULL, opt_val(t, i)};
    if (o->short_name) {
      shorts[ns++] = (char)o->short_name;
      if (nvalues_of(o)) shorts[ns++] = ':';
    }
  }
  shorts[ns] = '\0';
  longs[t->noptions] = (struct option){"help", no_argument, NULL, VAL_HELP};
  longs[t->noptions + 1] =
      (struct option){"version", no_argument, NULL, VAL_VERSION};
  longs[t->noptions + 2] = (struct option){NULL, 0, NULL, 0};

  opterr = 0;
  optind = 1;
  int options_done = 0;
  while (optind < argc) {
    int c = options_done ? -1 : getopt_long(argc, argv, shorts, longs, NULL);
    if (c == -1) {
      /* An operand, or the end. "--" (which getopt consumed) ends the
       * options. */
      if (!options_done && optind > 1 && !strcmp(argv[optind - 1], "--"))
        options_done = 1;
      if (optind >= argc) break;
      if (args->noperands == SH_CLI_MAX_OPERANDS ||
          args->noperands == t->max_operands) {
        fprintf(stderr, "%s: error: unexpected argument '%s' (see --help)\n",
                t->name, argv[optind]);
        return SH_EXIT_BAD_INPUT;
      }
      args->operands[args->noperands++] = argv[optind++];
      continue;
    }
    const char *text = argv[optind - 1];
    if (c == VAL_HELP) {
      sh_cli_help(t, stdout);
      return SH_EXIT_OK;
    }
    if (c == VAL_VERSION) {
      printf("%s %s\n", t->name, sh_version());
      return SH_EXIT_OK;
    }
    if (c == '?') {
      if (optopt && optopt < 256)
        fprintf(stderr, "%s: error: unknown option '-%c' (see --help)\n", t->name,
                optopt);
      else if (!report_ambiguous(t->name, longs, text))
        fprintf(stderr, "%s: error: unknown option '%s' (see --help)\n", t->name,
                text);
      return SH_EXIT_BAD_INPUT;
    }
    if (c == ':') {
      if (optopt > 0 && optopt < 256 && text[1] != '-')
        fprintf(stderr, "%s: error: -%c needs a value (see --help)\n", t->name,
                optopt);
      else
        fprintf(stderr, "%s: error: %s needs a value (see --help)\n", t->name, text);
      return SH_EXIT_BAD_INPUT;
    }
    int i = 0;
    while (i < t->noptions && opt_val(t, i) != c) i++;
    if (i == t->noptions) return SH_EXIT_FAILURE;
    const sh_cli_option *o = &t->options[i];
    args->given[i] = 1;
    int n = nvalues_of(o);
    const char *texts[SH_CLI_MAX_VALUES] = {optarg};
    for (int k = 1; k < n; k++) {
      if (optind >= argc) {
        fprintf(stderr, "%s: error: --%s needs %d values: %s (see --help)\n",
                t->name, o->name, n, o->metavar ? o->metavar : "");
        return SH_EXIT_BAD_INPUT;
      }
      texts[k] = argv[optind++];
    }
    if (o->type == SH_CLI_SETTER) {
      if (o->fixed) texts[0] = o->fixed;
      if (!setter(t, o, texts, o->fixed ? 1 : n, args))
        return SH_EXIT_BAD_INPUT;
      continue;
    }
    if (n == 0 && !store(t, o, 0, NULL, values)) return SH_EXIT_BAD_INPUT;
    for (int k = 0; k < n; k++)
      if (!store(t, o, k, texts[k], values)) return SH_EXIT_BAD_INPUT;
  }
  if (args->noperands < t->min_operands) {
    fprintf(stderr, "%s: error: missing operand%s: usage: %s %s\n", t->name,
            t->min_operands - args->noperands > 1 ? "s" : "", t->name,
            t->synopsis);
    return SH_EXIT_BAD_INPUT;
  }
  return -1;
}

int sh_cli_given(const sh_cli_tool *t, const sh_cli_args *args,
                 const char *name) {
  for (int i = 0; i < t->noptions; i++)
    if (!strcmp(t->options[i].name, name)) return args->given[i];
  return 0;
}

const char *sh_cli_choice_name(const sh_cli_choice *choices, int value) {
  for (int i = 0; choices[i].name; i++)
    if (choices[i].value == value) return choices[i].name;
  return "?";
}

/* ---- Files ---- */

/* The directories this run made for -p, newest (deepest) first, for
 * sh_cli_dirs_undo: a list whose nodes are complete before an atomic store
 * publishes them, so that a signal handler can walk it without locks, and
 * with no limit on how many. */
typedef struct made_node {
  struct made_node *next;
  char dir[]; /* the directory's path as given to mkdir */
} made_node;
static made_node *_Atomic made_head;
static atomic_int undo_registered;
static atomic_int dirs_kept;

static void undo_at_exit(void) {
  if (!atomic_load(&dirs_kept)) sh_cli_dirs_undo();
}

/* Records a directory this run made (out of memory: it is left behind on
 * failure). */
static void made_dir(const char *dir) {
  size_t len = strlen(dir) + 1;
  made_node *node = malloc(sizeof *node + len);
  if (!node) return;
  memcpy(node->dir, dir, len);
  if (!atomic_exchange(&undo_registered, 1)) atexit(undo_at_exit);
  node->next = atomic_load(&made_head);
  atomic_store(&made_head, node);
}

void sh_cli_dirs_undo(void) {
  /* Newest first: the deepest is removed before its parent. rmdir removes
   * only an empty directory, so whatever another process put there stays.
   * The nodes are never freed: a signal handler may run this, and
   * reachable names are no leak to LeakSanitizer. */
  for (made_node *n = atomic_load(&made_head); n; n = n->next) rmdir(n->dir);
}

void sh_cli_dirs_keep(void) { atomic_store(&dirs_kept, 1); }

/* mkdir -p: makes dir and its missing parents, recording each one made. */
static int make_dirs(char *dir) {
  for (char *p = dir + 1;; p++) {
    if (*p && *p != '/') continue;
    char c = *p;
    *p = '\0';
    int r = mkdir(dir, 0777);
    if (r == 0) made_dir(dir);
    int e = errno;
    *p = c;
    if (r && e != EEXIST) {
      errno = e;
      return -1;
    }
    if (!c) return 0;
  }
}

/* The longest name in a component and the longest path the file system
 * under `path`'s deepest existing directory takes (pathconf; -1: no
 * limit). */
static void name_limits(const char *path, long *name_max, long *path_max) {
  size_t n = strlen(path);
  char *a = malloc(n + 2);
  *name_max = *path_max = -1;
  if (!a) return;
  memcpy(a, path, n + 1);
  struct stat sb;
  for (;;) {
    char *slash = strrchr(a, '/');
    if (!slash) {
      strcpy(a, ".");
    } else if (slash == a) {
      a[1] = '\0';
    } else {
      *slash = '\0';
    }
    if (stat(a, &sb) == 0 || !strcmp(a, ".") || !strcmp(a, "/")) break;
  }
  *name_max = pathconf(a, _PC_NAME_MAX);
  *path_max = pathconf(a, _PC_PATH_MAX);
  free(a);
}

int sh_cli_check_name(const char *tool, const char *option, const char *path) {
  long name_max, path_max;
  name_limits(path, &name_max, &path_max);
  size_t n = strlen(path);
  if (path_max > 0 && n >= (size_t)path_max) {
    sh_cli_error(tool,
                 "%s: the path of %zu bytes is longer than the file system "
                 "takes (%ld): %s",
                 option, n, path_max - 1, strerror(ENAMETOOLONG));
    return 0;
  }
  for (const char *p = path; *p;) {
    size_t len = strcspn(p, "/");
    if (name_max > 0 && len > (size_t)name_max) {
      sh_cli_error(tool,
                   "%s: the name '%.*s...' of %zu bytes in '%.40s...' is "
                   "longer than the file system takes (%ld): %s",
                   option, 16, p, len, path, name_max,
                   strerror(ENAMETOOLONG));
      return 0;
    }
    p += len + (p[len] == '/');
  }
  return 1;
}

int sh_cli_check_output(const char *tool, const char *option,
                        const char *path, const char *exts, int create) {
  if (exts) {
    char ext[16];
    sh_file_extension(path, ext, sizeof ext);
    size_t n = strlen(ext);
    int ok = 0;
    for (const char *p = exts; *p && n;) {
      size_t len = strcspn(p, ",");
      if (len == n && !strncmp(p, ext, n)) ok = 1;
      p += len + (p[len] == ',');
    }
    if (!ok) {
      fprintf(stderr, "%s: error: %s '%s' must end in .%.*s", tool, option, path,
              (int)strcspn(exts, ","), exts);
      for (const char *p = exts + strcspn(exts, ","); *p == ',';) {
        p++;
        size_t len = strcspn(p, ",");
        fprintf(stderr, "%s.%.*s", p[len] ? ", " : " or ", (int)len, p);
        p += len;
      }
      fputc('\n', stderr);
      return 0;
    }
  }
  if (!sh_cli_check_name(tool, option, path)) return 0;
  const char *slash = strrchr(path, '/');
  /* The directory: the working one, the root, or the path's. */
  size_t len = !slash ? 1 : slash == path ? 1 : (size_t)(slash - path);
  char *dir = malloc(len + sizeof "/.shafts-probe-XXXXXX");
  if (!dir) {
    fprintf(stderr, "%s: error: out of memory\n", tool);
    return 0;
  }
  memcpy(dir, !slash ? "." : path, len);
  dir[len] = '\0';
  int ok = 1;
  struct stat sb;
  if (stat(dir, &sb) != 0) {
    if (!(create && make_dirs(dir) == 0)) {
      ok = 0;
      if (create)
        sh_cli_error(tool, "%s: cannot make directory '%s': %s", option, dir,
                     strerror(errno));
      else
        sh_cli_error(tool,
                     "%s: directory '%s' does not exist (-p, --parents makes "
                     "it)",
                     option, dir);
    }
  } else if (!S_ISDIR(sb.st_mode) || access(dir, W_OK | X_OK) != 0) {
    ok = 0;
    sh_cli_error(tool, "%s: '%s' is not a directory this user can write to",
                 option, dir);
  }
  if (ok) {
    /* Permissions do not tell everything (/proc, a read-only mount, root):
     * a file made and removed there before the work does. */
    strcat(dir, "/.shafts-probe-XXXXXX");
    int fd = mkstemp(dir);
    if (fd < 0) {
      ok = 0;
      dir[len] = '\0';
      sh_cli_error(tool, "%s: cannot create a file in '%s': %s", option, dir,
                   strerror(errno));
    } else {
      close(fd);
      unlink(dir);
    }
  }
  free(dir);
  return ok;
}

void sh_cli_render_init(sh_cli_render *r) {
  memset(r, 0, sizeof *r);
  r->exposure = NAN;
  r->crop_args[0] = -1; /* not given */
}

int sh_cli_render_check(const char *tool, const sh_cli_render *r) {
  if (r->outputs.count == 0) {
    fprintf(stderr, "%s: error: need -o OUTPUT (see --help)\n", tool);
    return SH_EXIT_BAD_INPUT;
  }
  /* Every name checked before -p makes any directory. */
  for (int k = 0; k < r->outputs.count; k++)
    if (!sh_cli_check_name(tool, "-o", r->outputs.items[k]))
      return SH_EXIT_BAD_INPUT;
  if (r->stats && !sh_cli_check_name(tool, "--stats", r->stats))
    return SH_EXIT_BAD_INPUT;
  for (int k = 0; k < r->outputs.count; k++)
    if (!sh_cli_check_output(tool, "-o", r->outputs.items[k], "exr,png",
                             r->parents))
      return SH_EXIT_BAD_INPUT;
  if (r->stats && !sh_cli_check_output(tool, "--stats", r->stats, NULL, r->parents))
    return SH_EXIT_BAD_INPUT;
  return SH_EXIT_OK;
}

int sh_cli_render_scene(const char *tool, sh_cli_render *r,
                        const char *path, sh_scene **scene) {
  int rc = sh_cli_load_scene(tool, path, r->quiet, scene);
  if (rc != SH_EXIT_OK) return rc;
  sh_cli_resize(*scene, r->width, r->height);
  const long *c = r->crop_args;
  if (c[0] < 0) return SH_EXIT_OK; /* no --crop */
  r->crop = (sh_crop){(int)c[0], (int)c[1], (int)c[2], (int)c[3]};
  sh_error err = SH_ERROR_INIT;
  /* All zero would read as no crop: given, it is an empty one. */
  if (!sh_crop_given(&r->crop))
    sh_error_set(&err, SH_ERR_ARG, "the crop 0 0 0 0 is empty");
  else if (sh_crop_check(&r->crop, &(*scene)->camera, &err) == SH_OK)
    return SH_EXIT_OK;
  fprintf(stderr, "%s: error: --crop: %s\n", tool, err.message);
  sh_error_clear(&err);
  sh_scene_free(*scene);
  *scene = NULL;
  return SH_EXIT_BAD_INPUT;
}

int sh_cli_render_start(const sh_cli_tool *tool, int argc, char **argv,
                        sh_cli_render *r, sh_cli_args *parsed,
                        sh_scene **scene) {
  *scene = NULL;
  sh_cli_render_init(r);
  int rc = sh_cli_parse(tool, argc, argv, r, parsed);
  if (rc >= 0) return rc; /* --help, --version or a bad argument */
  r->scene = parsed->operands[0];
  if ((rc = sh_cli_render_check(tool->name, r))) return rc;
  if ((rc = sh_cli_render_scene(tool->name, r, parsed->operands[0], scene)))
    return rc;
  rc = sh_cli_files(tool->name, *scene, &r->files);
  for (int k = 0; rc == 0 && k < r->outputs.count; k++)
    rc = sh_cli_file_out(tool->name, r->files, r->outputs.items[k], "-o");
  if (rc == 0 && r->stats)
    rc = sh_cli_file_out(tool->name, r->files, r->stats, "--stats");
  if (rc) {
    sh_cli_render_free(r);
    sh_scene_free(*scene);
    *scene = NULL;
    return rc;
  }
  return -1;
}

void sh_cli_render_free(sh_cli_render *r) {
  sh_outputs_free(r->files);
  r->files = NULL;
}

int sh_cli_files(const char *tool, const sh_scene *scene, sh_outputs **set) {
  sh_error err = SH_ERROR_INIT;
  *set = sh_outputs_new();
  if (!*set) {
    fprintf(stderr, "%s: error: out of memory\n", tool);
    return SH_EXIT_FAILURE;
  }
  if (scene && sh_outputs_scene_inputs(*set, scene, &err) != SH_OK) {
    sh_outputs_free(*set);
    *set = NULL;
    return sh_cli_report(tool, &err);
  }
  return SH_EXIT_OK;
}

int sh_cli_file_out(const char *tool, sh_outputs *set, const char *path,
                    const char *option) {
  sh_error err = SH_ERROR_INIT;
  if (sh_outputs_add(set, path, option, &err) == SH_OK) return SH_EXIT_OK;
  sh_cli_report(tool, &err);
  return SH_EXIT_BAD_INPUT;
}

static void sh_cli__on_signal(int sig) {
  sh_outputs_on_signal();
  sh_cli_dirs_undo();
  signal(sig, SIG_DFL);
  raise(sig);
}

void sh_cli_signals(void) {
  static const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
  for (size_t i = 0; i < sizeof sigs / sizeof *sigs; i++) {
    struct sigaction sa, old;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = sh_cli__on_signal;
    sigemptyset(&sa.sa_mask);
    /* A signal ignored by whoever started us stays ignored. */
    if (sigaction(sigs[i], NULL, &old) == 0 && old.sa_handler == SIG_IGN)
      continue;
    sigaction(sigs[i], &sa, NULL);
  }
}

double sh_cli_render_exposure(const sh_cli_render *r, const sh_scene *scene) {
  return isnan(r->exposure) ? scene->render.exposure : r->exposure;
}

void sh_cli_render_done(const char *tool, const sh_cli_render *r, int width,
                        int height, double seconds, const char *detail) {
  sh_cli_dirs_keep();
  if (r->quiet) return;
  fprintf(stderr, "%s: wrote", tool);
  for (int k = 0; k < r->outputs.count; k++)
    fprintf(stderr, "%s %s", k ? "," : "", r->outputs.items[k]);
  fprintf(stderr, " (%dx%d, rendered in %.3g s%s)\n", width, height, seconds,
          detail ? detail : "");
}

int sh_cli_load_scene(const char *tool, const char *path, int quiet,
                      sh_scene **scene) {
  sh_error err = SH_ERROR_INIT;
  *scene = NULL;
  sh_status st = sh_scene_load(path, scene, &err);
  if (st != SH_OK) {
    sh_cli_report(tool, &err);
    /* A scene or mesh file that is missing or unreadable is bad input. */
    return st == SH_ERR_IO ? SH_EXIT_BAD_INPUT : sh_exit_code(st);
  }
  if ((*scene)->nlights == 0 && !quiet)
    fprintf(stderr, "%s: warning: the scene has no lights; the image is "
                    "black but for emission, ambient light and background\n",
            tool);
  int at = sh_scene_camera_at_light(*scene);
  if (at >= 0 && !quiet)
    fprintf(stderr,
            "%s: warning: the camera is at lights[%d] inside the medium, where the "
            "scattered radiance is unbounded; rays are taken to pass no nearer "
            "than %.3g to a light (docs/scene-format.md)\n",
            tool, at, sh_medium_light_min_distance(&(*scene)->medium));
  return SH_EXIT_OK;
}

void sh_cli_resize(sh_scene *scene, long width, long height) {
  sh_camera *cam = &scene->camera;
  /* The side not given follows the aspect, at least one pixel (a side
   * rounded to 0 would have left the scene's). */
  if (width > 0 && height <= 0)
    height = lround(fmax(1.0, (double)width * cam->height / cam->width));
  else if (height > 0 && width <= 0)
    width = lround(fmax(1.0, (double)height * cam->width / cam->height));
  if (width > 0) cam->width = (int)width;
  if (height > 0) cam->height = (int)height;
}

int sh_cli_report(const char *tool, sh_error *err) {
  char *text = sh_error_text(err);
  fprintf(stderr, "%s: error: %s\n", tool, text ? text : sh_error_message(err));
  free(text);
  int rc = sh_exit_code(err->status);
  sh_error_clear(err);
  return rc;
}

int sh_exit_code(sh_status status) {
  switch (status) {
  case SH_OK: return SH_EXIT_OK;
  case SH_ERR_SYNTAX:
  case SH_ERR_SCENE:
  case SH_ERR_IMAGE:
  case SH_ERR_MESH:
  case SH_ERR_ARG: return SH_EXIT_BAD_INPUT;
  default: return SH_EXIT_FAILURE;
  }
}

/* ---- Statistics ---- */

struct sh_stats {
  json_t *obj;
};

sh_stats *sh_stats_new(void) {
  sh_stats *s = malloc(sizeof *s);
  if (!s) return NULL;
  s->obj = json_object();
  if (!s->obj) {
    free(s);
    return NULL;
  }
  return s;
}

sh_stats *sh_stats_from_json(const char *text) {
  json_t *o = text ? json_loads(text, 0, NULL) : NULL;
  sh_stats *s = o && json_is_object(o) ? malloc(sizeof *s) : NULL;
  if (!s) {
    json_decref(o);
    return NULL;
  }
  s->obj = o;
  return s;
}

void sh_stats_num(sh_stats *s, const char *key, double value) {
  if (s) sh__json_num(s->obj, key, value);
}

void sh_stats_str(sh_stats *s, const char *key, const char *value) {
  if (s) json_object_set_new(s->obj, key, json_string(value));
}

void sh_stats_merge(sh_stats *s, const sh_stats *from) {
  if (s && from) json_object_update(s->obj, from->obj);
}

void sh_stats_crop(sh_stats *s, const sh_crop *crop) {
  if (!sh_crop_given(crop)) return;
  const int v[4] = {crop->x0, crop->y0, crop->x1, crop->y1};
  static const char *const keys[4] = {"crop_x0", "crop_y0", "crop_x1",
                                      "crop_y1"};
  for (int i = 0; i < 4; i++) sh_stats_num(s, keys[i], v[i]);
}

char *sh_stats_text(const sh_stats *s) {
  return s ? json_dumps(s->obj, JSON_COMPACT | JSON_REAL_PRECISION(10)) : NULL;
}

sh_status sh_stats_write(const sh_stats *s, sh_outputs *set, const char *path,
                         sh_error *err) {
  char *text = s ? sh__json_dumps(json_incref(s->obj)) : NULL;
  if (!text) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  size_t n = strlen(text);
  text[n] = '\n'; /* replaces the terminator; the size below includes it */
  sh_status st = sh_outputs_write_bytes(set, path, text, n + 1, err);
  free(text);
  return st;
}

void sh_stats_free(sh_stats *s) {
  if (!s) return;
  json_decref(s->obj);
  free(s);
}

/* ---- Images with provenance ---- */

sh_status sh_cli_write_images(const char *tool, sh_outputs *set,
                              const sh_cli_list *outputs,
                              const sh_image *img, double exposure,
                              const char *mode, const char *settings_json,
                              const char *scene, sh_error *err) {
  char software[128];
  snprintf(software, sizeof software, "%s %s", tool, sh_version());
  char *abs_scene = realpath(scene, NULL);
  const char *attrs[] = {"Software", software,
                         "shafts:tool", tool,
                         "shafts:version", sh_version(),
                         "shafts:mode", mode,
                         "shafts:settings", settings_json ? settings_json : "{}",
                         "shafts:scene", abs_scene ? abs_scene : scene,
                         NULL};
  sh_status st = SH_OK;
  for (int k = 0; st == SH_OK && k < outputs->count; k++)
    st = sh_outputs_write_image(set, outputs->items[k], img, exposure, attrs,
                                err);
  free(abs_scene);
  return st;
}
