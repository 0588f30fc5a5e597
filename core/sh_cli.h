/* The command-line tools' shared machinery: one option table per tool, from
 * which getopt_long's table, the parse, the --help text and the value
 * checks all come; the exit-status table every tool follows; loading a
 * scene and checking output paths before any work; the --stats JSON file.
 * They print, so they live in the tools' static library (shafts_cli), not
 * in libshafts.so.
 *
 * A tool describes itself once (sh_cli_tool: name, synopsis, description,
 * options) and calls sh_cli_parse. Every tool gets -h/--help and --version
 * from here; an unknown option, a missing value, a value out of range and
 * a wrong number of operands each get a message naming the option or
 * value, and exit status 2. */
#ifndef SH_CLI_H
#define SH_CLI_H

#include <math.h>
#include <stddef.h>
#include <stdio.h>

#include "sh_camera.h"
#include "sh_error.h"
#include "sh_image.h"
#include "sh_outputs.h"
#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The exit statuses of every tool (README.md, "Exit status"). A missing or
 * unreadable scene, mesh or image given as input is bad input. */
enum {
  SH_EXIT_OK = 0,
  SH_EXIT_FAILURE = 1,   /* the work failed: GL, memory, writing a file */
  SH_EXIT_BAD_INPUT = 2, /* arguments, scene, mesh or image files */
  SH_EXIT_CHECK = 3      /* a check the user asked for failed
                            (shafts_compare --max-rel-rms) */
};

/* What an option's value is and where it goes. Values are stored at
 * `offset` bytes into the struct given to sh_cli_parse. */
typedef enum sh_cli_type {
  SH_CLI_FLAG,   /* no value: stores the int `set` */
  SH_CLI_TEXT,   /* const char *[nvalues]: the text as given */
  SH_CLI_LIST,   /* sh_cli_list: the option may be repeated */
  SH_CLI_INT,    /* long[nvalues], each an integer in [lo, hi] */
  SH_CLI_NUMBER, /* double[nvalues], each finite, in [lo, hi] (lo excluded
                    if lo_open) */
  SH_CLI_CHOICE, /* int: the value of the choice named (choices) */
  SH_CLI_SETTER  /* the text goes to the tool's setter under `key`, which
                    checks it (a renderer's options by name) */
} sh_cli_type;

typedef struct sh_cli_choice {
  const char *name;
  int value;
} sh_cli_choice;

#define SH_CLI_LIST_MAX 8
typedef struct sh_cli_list {
  const char *items[SH_CLI_LIST_MAX];
  int count;
} sh_cli_list;

#define SH_CLI_MAX_VALUES 4

typedef struct sh_cli_option {
  const char *name;      /* the long name without "--" */
  int short_name;        /* 'o' for -o, or 0 */
  sh_cli_type type;
  const char *metavar;   /* the value's name in --help: "N", "NU NV";
                            NULL for flags and choices (which list them) */
  int nvalues;           /* values the option takes (TEXT, INT, NUMBER,
                            SETTER): 1 when 0 */
  size_t offset;         /* where the value goes (not for SETTER) */
  double lo, hi;         /* INT and NUMBER limits */
  int lo_open;           /* NUMBER: lo itself is refused */
  int set;               /* FLAG: the value stored */
  const sh_cli_choice *choices; /* CHOICE: {NULL, 0} ends the list */
  const char *key;       /* SETTER: the name the setter knows */
  const char *fixed;     /* SETTER: the option takes no value and sets
                            this text ("--jitter": "1") */
  const char *def;       /* the default, appended to the help as
                            "(default: DEF)", or NULL */
  const char *help;      /* one or more sentences; wrapped by --help */
} sh_cli_option;

/* A renderer's option set by name from text (lmm_render_options_set's
 * shape): SH_ERR_ARG with a message on a bad value. */
typedef sh_status (*sh_cli_setter)(void *target, const char *key,
                                   const char *value, sh_error *err);
/* The choices a setter accepts for `key` (NULL-terminated), or NULL. */
typedef const char *const *(*sh_cli_setter_choices)(const char *key);

typedef struct sh_cli_tool {
  const char *name;        /* "gl_shafts" */
  const char *synopsis;    /* what follows the name in the usage line */
  const char *description; /* paragraphs before the options */
  const sh_cli_option *options;
  int noptions;
  int min_operands, max_operands;
  void (*epilogue)(FILE *f); /* prints more help after the options (with
                               sh_cli_help_item), or NULL */
  const char *exit_extra;  /* a line on a tool's own status (3), or NULL */
  sh_cli_setter setter;    /* SETTER options: checks and sets a value */
  void *setter_target;     /* a scratch target the parse checks on */
  sh_cli_setter_choices setter_choices;
  const char *bad_input; /* what bad input is, for the help's exit status
                            line ("arguments, a missing or unreadable
                            image"), or NULL for scenes, meshes and images */
} sh_cli_tool;

/* What the parse found besides the values: the operands (arguments that
 * are no option), in order, and which options were given. */
#define SH_CLI_MAX_OPERANDS 64
#define SH_CLI_MAX_OPTIONS 64
typedef struct sh_cli_args {
  const char *operands[SH_CLI_MAX_OPERANDS];
  int noperands;
  unsigned char given[SH_CLI_MAX_OPTIONS]; /* by the option's index */
  struct {
    const char *key;
    char value[128];
  } settings[SH_CLI_MAX_OPTIONS]; /* SETTER options, in order */
  int nsettings;
} sh_cli_args;

/* Parses argv against the tool's table into `values` (the tool's struct,
 * filled with its defaults beforehand) and `args`. Returns -1 to go on, or
 * the status to exit with: 0 after --help or --version (printed on
 * stdout), 2 after a message on stderr. Options and operands may come in
 * any order; "--" ends the options. */
int sh_cli_parse(const sh_cli_tool *tool, int argc, char **argv,
                 void *values, sh_cli_args *args);

/* Applies the SETTER options given (checked by the parse on the tool's
 * setter_target) to `target`, in order: the renderer's options once the
 * scene has given their defaults. */
sh_status sh_cli_apply(const sh_cli_tool *tool, const sh_cli_args *args,
                       void *target, sh_error *err);

/* Prints the --help text to f. */
void sh_cli_help(const sh_cli_tool *tool, FILE *f);

/* Prints one item of a help list: the label indented by two, the text
 * word-wrapped in the help's second column. */
void sh_cli_help_item(FILE *f, const char *label, const char *text);

/* Whether the option with this long name was given. */
int sh_cli_given(const sh_cli_tool *tool, const sh_cli_args *args,
                 const char *name);

/* The name of the choice with `value`, or "?". */
const char *sh_cli_choice_name(const sh_cli_choice *choices, int value);

/* What the renderers' command lines share (gl_shafts, lmm_tracer): the
 * scene, their outputs, --stats, --width/--height, --exposure, -q and -p.
 * The sh_cli_render is the values sh_cli_parse fills, and
 * SH_CLI_RENDER_OPTIONS stands first in the tool's option table. */
typedef struct sh_cli_render {
  const char *scene; /* the operand: the scene file */
  sh_cli_list outputs;
  const char *stats;
  long width, height;
  long crop_args[4]; /* --crop X0 Y0 X1 Y1 as given */
  sh_crop crop;      /* the crop, checked against the image by
                        sh_cli_render_start (all zero: none) */
  double exposure;   /* NAN: the scene's render.exposure */
  int quiet, parents;
  sh_outputs *files; /* the run's inputs and outputs (sh_outputs.h): made
                        by sh_cli_render_start, freed by
                        sh_cli_render_free */
} sh_cli_render;

/* The --width W and --height H options of every tool that makes an image
 * (the renderers, scene_export): two `long` fields at these offsets, 0
 * when not given, each from 1 to 65536; sh_cli_resize applies them. */
#define SH_CLI_SIZE_OPTIONS(width_offset, height_offset)                      \
  {"width", 0, SH_CLI_INT, "W", 1, (width_offset), 1, 65536, 0, 0, NULL,     \
   NULL, NULL, NULL,                                                          \
   "image width in pixels instead of the scene's (the height follows the "   \
   "scene's aspect unless given)"},                                           \
  {"height", 0, SH_CLI_INT, "H", 1, (height_offset), 1, 65536, 0, 0, NULL,   \
   NULL, NULL, NULL, "image height in pixels instead of the scene's"}

#define SH_CLI__R(f) offsetof(sh_cli_render, f)
#define SH_CLI_RENDER_OPTIONS                                        \
  {"output", 'o', SH_CLI_LIST, "FILE", 0, SH_CLI__R(outputs), 0, 0,  \
   0, 0, NULL, NULL, NULL, NULL,                                              \
   "output image: .exr (linear 32-bit float radiance, with the tool, "        \
   "version, mode, settings and scene in its header) or .png (sRGB of "      \
   "radiance * 2^exposure, clamped); repeat to write several formats from "  \
   "one render"},                                                             \
  {"parents", 'p', SH_CLI_FLAG, NULL, 0, SH_CLI__R(parents), 0, 0,   \
   0, 1, NULL, NULL, NULL, NULL,                                              \
   "make the outputs' directories (and their parents) if missing; without "  \
   "it a missing directory is an error before rendering; a run that fails "  \
   "or is interrupted removes the directories it made"},                      \
  SH_CLI_SIZE_OPTIONS(SH_CLI__R(width), SH_CLI__R(height)),                   \
  {"crop", 0, SH_CLI_INT, "X0 Y0 X1 Y1", 4, SH_CLI__R(crop_args), 0, 65536,  \
   0, 0, NULL, NULL, NULL, NULL,                                              \
   "render only the pixels [X0, X1) x [Y0, Y1) of the image (after --width " \
   "and --height; y down from the top), each as in the whole image (as "     \
   "pbrt-v4's --pixelbounds); the outputs hold that region alone"},          \
  {"exposure", 0, SH_CLI_NUMBER, "E", 1, SH_CLI__R(exposure),        \
   -INFINITY, INFINITY, 0, 0, NULL, NULL, NULL, NULL,                         \
   "PNG exposure in stops (default: render.exposure, else 0)"},               \
  {"stats", 0, SH_CLI_TEXT, "FILE.json", 0, SH_CLI__R(stats), 0, 0,  \
   0, 0, NULL, NULL, NULL, NULL,                                              \
   "write the settings used and the statistics of the render as JSON"},       \
  {"quiet", 'q', SH_CLI_FLAG, NULL, 0, SH_CLI__R(quiet), 0, 0, 0, 1, \
   NULL, NULL, NULL, NULL, "no progress bar, no messages but errors"}

/* The defaults of an sh_cli_render (exposure NAN). */
void sh_cli_render_init(sh_cli_render *r);

/* After the parse: at least one output, each .exr or .png, and every
 * output's and the --stats file's directory there (or made with -p).
 * Prints the problem and returns 2, else 0. */
int sh_cli_render_check(const char *tool, const sh_cli_render *r);

/* Loads the scene (sh_cli_load_scene), applies --width/--height and
 * checks --crop against the image (sh_crop_check; r->crop is set).
 * Returns 0 or the exit status. */
int sh_cli_render_scene(const char *tool, sh_cli_render *r,
                        const char *path, sh_scene **scene);

/* A renderer's start: r's defaults, sh_cli_parse into r, the output
 * checks (sh_cli_render_check), the scene loaded from the one operand
 * (r->scene) at the requested size (sh_cli_render_scene) and r->files:
 * the scene and its files as inputs, every -o and --stats as outputs (an
 * output that is an input or another output is refused, exit 2). Returns
 * -1 with *scene set, or the status to exit with. */
int sh_cli_render_start(const sh_cli_tool *tool, int argc, char **argv,
                        sh_cli_render *r, sh_cli_args *parsed,
                        sh_scene **scene);

/* Frees r->files: whatever was staged and not published is discarded. */
void sh_cli_render_free(sh_cli_render *r);

/* The run's files for a tool: a set (sh_outputs.h) with the scene and its
 * files as inputs when scene is not NULL. Prints the problem and returns
 * its exit status, or 0 with *set. */
int sh_cli_files(const char *tool, const sh_scene *scene, sh_outputs **set);

/* Records an output in the tool's set (sh_outputs_add); prints the
 * refusal and returns its exit status (2), or 0. */
int sh_cli_file_out(const char *tool, sh_outputs *set, const char *path,
                    const char *option);

/* Installs the handlers of SIGINT, SIGTERM and SIGHUP that remove the
 * run's temporary files (sh_outputs_on_signal) and end the process as the
 * signal would. sh_cli_parse calls it. */
void sh_cli_signals(void);

/* The PNG exposure: --exposure, else the scene's. */
double sh_cli_render_exposure(const sh_cli_render *r, const sh_scene *scene);

/* Unless quiet: "TOOL: wrote A, B (WxH, rendered in T s<detail>)". */
void sh_cli_render_done(const char *tool, const sh_cli_render *r, int width,
                        int height, double seconds, const char *detail);

/* Checks an output path before any work: its extension is one of `exts`
 * ("exr,png"; NULL: any) and its directory exists and is writable, or,
 * with `create`, is made (with its parents). Prints the problem and
 * returns 0, else 1. */
int sh_cli_check_output(const char *tool, const char *option,
                        const char *path, const char *exts, int create);

/* Checks that the file system takes an output path before any directory
 * is made for it: no component longer than the longest name
 * (pathconf _PC_NAME_MAX) and the whole shorter than the longest path
 * (_PC_PATH_MAX), both asked of the path's deepest existing directory.
 * Prints the problem and returns 0, else 1. sh_cli_check_output calls it;
 * a tool with several outputs calls it on all of them first. */
int sh_cli_check_name(const char *tool, const char *option, const char *path);

/* The directories -p made (sh_cli_check_output with `create`) belong to
 * the run: unless sh_cli_dirs_keep was called, they are removed at exit
 * (and on SIGINT, SIGTERM or SIGHUP, with the outputs' temporaries),
 * deepest first and only when empty; a directory that existed before the
 * run is never removed. A tool calls sh_cli_dirs_keep once its outputs
 * are published (sh_cli_render_done does); sh_cli_dirs_undo removes them
 * at once. */
void sh_cli_dirs_keep(void);
void sh_cli_dirs_undo(void);

/* Loads a scene for a tool: prints the located error and returns its exit
 * status (a missing or unreadable scene or mesh file is bad input, 2), or
 * returns 0 with *scene set. Warns (unless quiet) when the scene has no
 * lights, and when the camera is at a light inside the medium (the
 * convention of sh_medium_light_min_distance makes its radiance finite). */
int sh_cli_load_scene(const char *tool, const char *path, int quiet,
                      sh_scene **scene);

/* Overrides the camera's size by --width/--height (0: the scene's). The
 * aspect ratio follows the new size; the vertical field of view stays. */
void sh_cli_resize(sh_scene *scene, long width, long height);

/* The process exit status for a library status: 2 for bad input (syntax,
 * scene, image, mesh, argument errors), 1 for the rest. */
int sh_exit_code(sh_status status);

/* `message` (a renderer's error about its options by name: "area_radius
 * needs mode whitted") with each word that is the key of one of t's SETTER
 * options replaced by the option ("--area-radius needs --mode whitted"),
 * on the heap (the caller frees it; NULL when out of memory). Words in
 * dotted or hyphenated names (render.scheme, refract-both) are left
 * alone. */
char *sh_cli_option_names(const sh_cli_tool *t, const char *message);

/* Prints "TOOL: error: " and the printf-formatted message on stderr, with
 * a newline: every tool's error messages have this one form. */
void sh_cli_error(const char *tool, const char *format, ...)
    __attribute__((format(printf, 2, 3)));

/* Prints "TOOL: error: <formatted error>" on stderr (whole, however long
 * its file, key and message), clears the report (sh_error_clear) and
 * returns the exit status for it (sh_exit_code). */
int sh_cli_report(const char *tool, sh_error *err);

/* A flat statistics record written as a JSON object. Keys must be
 * identifiers; values numbers or strings. */
typedef struct sh_stats sh_stats;
sh_stats *sh_stats_new(void);
/* A record from a library's statistics as JSON text (lmm_render_stats_json,
 * gs_stats_json); NULL if it is not a JSON object or out of memory. */
sh_stats *sh_stats_from_json(const char *text);
void sh_stats_num(sh_stats *s, const char *key, double value);
void sh_stats_str(sh_stats *s, const char *key, const char *value);
/* Adds (or replaces) every key of `from` in s; either may be NULL. */
void sh_stats_merge(sh_stats *s, const sh_stats *from);
/* Adds a crop's crop_x0, crop_y0, crop_x1 and crop_y1 when one is set. */
void sh_stats_crop(sh_stats *s, const sh_crop *crop);
/* Stages the record as the output `path` of the run's set (published with
 * the rest by sh_outputs_publish). */
sh_status sh_stats_write(const sh_stats *s, sh_outputs *set, const char *path,
                         sh_error *err);
/* Frees the record; NULL is allowed. */
void sh_stats_free(sh_stats *s);

/* The record's text (compact JSON), malloc'd; NULL if out of memory. */
char *sh_stats_text(const sh_stats *s);

/* Stages one rendered image as every output in the run's set, each
 * carrying its provenance in the header (sh_image_write_meta): "Software"
 * (tool and version) and shafts:tool, shafts:version, shafts:mode,
 * shafts:settings (JSON) and shafts:scene (the scene file's absolute
 * path). */
sh_status sh_cli_write_images(const char *tool, sh_outputs *set,
                              const sh_cli_list *outputs,
                              const sh_image *img, double exposure,
                              const char *mode, const char *settings_json,
                              const char *scene, sh_error *err);

#ifdef __cplusplus
}
#endif
#endif
