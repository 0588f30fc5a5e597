/* Helpers for the command-line tools: option values with clear errors,
 * reporting a library error, and the --stats JSON file. They print, so they
 * live in the tools' static library (shafts_cli), not in libshafts.so. */
#ifndef SH_CLI_H
#define SH_CLI_H

#include "sh_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Parses an integer option value in [lo, hi]. On failure prints
 * "TOOL: OPTION expects an integer in [lo, hi], got 'text'" and returns 0. */
int sh_cli_int(const char *tool, const char *option, const char *text,
               long lo, long hi, long *out);
/* Parses a finite number option value. */
int sh_cli_double(const char *tool, const char *option, const char *text,
                  double *out);

/* Takes an argument that matched no option as the next operand: it fills
 * the first of the n slots still NULL. An unknown option ("-x"; a lone "-"
 * is an operand) or one operand too many prints an error naming it and
 * returns 0; else returns 1. */
int sh_cli_operand(const char *tool, const char *arg, const char **slots[],
                   int n);

/* Checks what a renderer's command line must give: a scene file and at
 * least one output, each ending in .exr or .png. Prints the problem and
 * returns 0, else returns 1. */
int sh_cli_check_render_outputs(const char *tool, const char *scene,
                                const char *const *outputs, int noutputs);

/* The process exit status a tool should return for a status: 2 for bad
 * input (syntax, scene, image, mesh, argument errors), 1 for the rest. */
int sh_exit_code(sh_status status);

/* Prints "TOOL: error: <formatted error>" on stderr and returns the exit
 * status for it (sh_exit_code). */
int sh_cli_report(const char *tool, const sh_error *err);

/* A flat statistics record written as a JSON object. Keys must be
 * identifiers; values numbers or strings. */
typedef struct sh_stats sh_stats;
sh_stats *sh_stats_new(void);
/* A record from a library's statistics as JSON text (lmm_render_stats_json,
 * gs_stats_json); NULL if it is not a JSON object or out of memory. */
sh_stats *sh_stats_from_json(const char *text);
void sh_stats_num(sh_stats *s, const char *key, double value);
void sh_stats_str(sh_stats *s, const char *key, const char *value);
/* Writes the record atomically to path. */
sh_status sh_stats_write(const sh_stats *s, const char *path, sh_error *err);
/* Frees the record; NULL is allowed. */
void sh_stats_free(sh_stats *s);

#ifdef __cplusplus
}
#endif
#endif
