/* The exporters' common ground: options, the list of approximations an
 * export had to make, and the set of files an export produces.
 *
 * An export runs in two steps. A target's build function (se_pov_build,
 * se_blender_build, se_json_build) turns a loaded scene into files held in
 * memory and records every feature it could not represent exactly as a note;
 * it writes nothing. The caller then refuses the export (--strict with notes)
 * or writes the files with se_output_write. So a refused or failed export
 * leaves no file behind. */
#ifndef SE_EXPORT_H
#define SE_EXPORT_H

#include "se_buf.h"
#include "se_frame.h"
#include "sh_error.h"
#include "sh_image.h"
#include "sh_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum se_quality {
  SE_QUALITY_DRAFT, /* quick renders for tests and previews */
  SE_QUALITY_FINAL  /* the settings for a converged comparison */
} se_quality;

/* How an export's length scale and origin are chosen (scene_export
 * --scale; the rules: se_scale.h). */
typedef enum se_scale_mode {
  SE_SCALE_AUTO,  /* from what the image needs */
  SE_SCALE_FIXED, /* se_options.scale; the origin chosen as for AUTO */
  SE_SCALE_NONE   /* the scene's own units and position */
} se_scale_mode;

typedef struct se_options {
  se_quality quality;
  se_scale_mode scale_mode; /* 0: SE_SCALE_AUTO */
  double scale;             /* SE_SCALE_FIXED: target units per scene unit */
} se_options;

/* Approximations made by an export: one full sentence each, naming the
 * scene element ("lights[2]", "materials[0] (glass)") and saying what the
 * target does instead. */
typedef struct se_notes {
  int count, cap;
  char **text; /* owned */
  int failed;  /* an allocation failed; the list is incomplete */
} se_notes;

void se_note(se_notes *notes, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
void se_notes_free(se_notes *notes);

/* One file of an export: text, or an image written as 32-bit float EXR. */
typedef struct se_file {
  char *path;          /* owned */
  se_buf text;         /* the contents, when image is NULL */
  const sh_image *image; /* borrowed from the scene, or owned (below) */
  sh_image *owned;       /* an image the output frees */
} se_file;

typedef struct se_output {
  int count, cap;
  se_file *files; /* written in this order; put the main file last */
  int has_frame;  /* the target chose a frame (POV-Ray, Blender) ... */
  se_frame frame; /* ... this one: its scale and origin (se_scale.h) */
  /* The shell commands that make the image from the files, one line
   * (empty for a target without one, json): what scene_export prints as
   * `render: ...`. */
  se_buf render;
} se_output;

/* Adds a text file and returns its buffer to fill (NULL if out of memory).
 * `path` is copied. */
se_buf *se_output_text(se_output *out, const char *path);
/* Adds an image file; the image must outlive the output. Returns 0 if out
 * of memory. */
int se_output_image(se_output *out, const char *path, const sh_image *image);
/* Adds an image file that the output takes over (and frees, also on
 * failure). Returns 0 if out of memory. */
int se_output_owned_image(se_output *out, const char *path, sh_image *image);
/* Writes every file through one sh_outputs set (sh_outputs.h): a file
 * that is one of the scene's files (when scene is not NULL) or another
 * file of the export is refused (SH_ERR_ARG) before anything is written,
 * and the files appear together once all are complete, or none does. */
sh_status se_output_write(const se_output *out, const sh_scene *scene,
                          sh_error *err);
void se_output_free(se_output *out);

/* A target's build, the one signature every exporter has (se_run.h's
 * table holds them): turns `scene` into files held in `out` (written by
 * the caller, se_output_write), named after out_path, recording every
 * approximation in `notes`; it writes nothing. A bad out_path is
 * SH_ERR_ARG. A target declares its build as `se_build se_NAME_build;`. */
typedef sh_status se_build(const sh_scene *scene, const se_options *opt,
                           const char *out_path, se_output *out,
                           se_notes *notes, sh_error *err);

/* The name of a phase type as the scene format spells it. */
const char *se_phase_name(sh_phase_type type);

/* The mean cosine of the Cornette-Shanks phase of asymmetry g (the
 * integral of cos alpha times the normalised phase over the sphere):
 * 3 g (4 + g^2) / (5 (2 + g^2)), from the integrals of (1 + c^2) c and
 * (1 + c^2) against the Henyey-Greenstein shape. Neither POV-Ray nor
 * Cycles has that phase; both targets render it as Henyey-Greenstein lobes
 * fitted to it (se_phase_fit.h; this g only if the fit's work space cannot
 * be allocated). */
double se_phase_cs_mean_cosine(double g);

/* Notes that `renderer` has no phase of the type at `what` and renders it
 * as one Henyey-Greenstein lobe g: "fitted to it" for Cornette-Shanks,
 * else "its mean cosine"; `tail` ends the sentence (e.g. " clamped to
 * Cycles' range"). */
void se_note_one_lobe(se_notes *notes, const char *what, const char *renderer,
                      const sh_phase *phase, double g, const char *tail);

/* Appends the notes as comment lines: each line starts with `prefix` (such
 * as "// " or "# "), and the text is sanitised for a comment. */
void se_notes_comment(const se_notes *notes, se_buf *b, const char *prefix);

#ifdef __cplusplus
}
#endif
#endif
