#include "se_export.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "se_text.h"
#include "sh_array.h"
#include "sh_outputs.h"

void se_note(se_notes *notes, const char *fmt, ...) {
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  for (int i = 0; i < notes->count; i++)
    if (!strcmp(notes->text[i], msg)) return; /* say each thing once */
  char **t = sh__array_grow(notes->text, notes->count, &notes->cap, 8,
                            sizeof *t);
  if (!t) {
    notes->failed = 1;
    return;
  }
  notes->text = t;
  char *copy = malloc(strlen(msg) + 1);
  if (!copy) {
    notes->failed = 1;
    return;
  }
  strcpy(copy, msg);
  notes->text[notes->count++] = copy;
}

void se_notes_free(se_notes *notes) {
  for (int i = 0; i < notes->count; i++) free(notes->text[i]);
  free(notes->text);
  memset(notes, 0, sizeof *notes);
}

void se_notes_comment(const se_notes *notes, se_buf *b, const char *prefix) {
  char line[1100];
  if (notes->count == 0) {
    se_buf_printf(b, "%sExact: no feature of the scene needed an approximation.\n",
                  prefix);
    return;
  }
  se_buf_printf(b, "%sApproximations (%d):\n", prefix, notes->count);
  for (int i = 0; i < notes->count; i++) {
    se_comment_text(notes->text[i], line, sizeof line);
    se_buf_printf(b, "%s- %s\n", prefix, line);
  }
}

static se_file *add_file(se_output *out, const char *path) {
  se_file *files = sh__array_grow(out->files, out->count, &out->cap, 4,
                                  sizeof *files);
  if (!files) return NULL;
  out->files = files;
  se_file *f = &files[out->count];
  f->path = malloc(strlen(path) + 1);
  if (!f->path) return NULL;
  strcpy(f->path, path);
  out->count++;
  return f;
}

se_buf *se_output_text(se_output *out, const char *path) {
  se_file *f = add_file(out, path);
  return f ? &f->text : NULL;
}

int se_output_image(se_output *out, const char *path, const sh_image *image) {
  se_file *f = add_file(out, path);
  if (!f) return 0;
  f->image = image;
  return 1;
}

int se_output_owned_image(se_output *out, const char *path, sh_image *image) {
  se_file *f = add_file(out, path);
  if (!f) {
    sh_image_free(image);
    free(image);
    return 0;
  }
  f->image = f->owned = image;
  return 1;
}

sh_status se_output_write(const se_output *out, const sh_scene *scene,
                          sh_error *err) {
  sh_outputs *set = sh_outputs_new();
  if (!set) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  sh_status st = scene ? sh_outputs_scene_inputs(set, scene, err) : SH_OK;
  for (int i = 0; st == SH_OK && i < out->count; i++)
    st = sh_outputs_add(set, out->files[i].path, "the export's file", err);
  for (int i = 0; st == SH_OK && i < out->count; i++) {
    const se_file *f = &out->files[i];
    if (f->image)
      st = sh_outputs_write_image(set, f->path, f->image, 0.0, NULL, err);
    else if (f->text.failed)
      st = sh_error_set(err, SH_ERR_NOMEM, "out of memory while writing '%s'",
                        f->path);
    else
      st = sh_outputs_write_bytes(set, f->path,
                                  f->text.data ? f->text.data : "",
                                  f->text.len, err);
  }
  if (st == SH_OK) st = sh_outputs_publish(set, err);
  sh_outputs_free(set);
  return st;
}

void se_output_free(se_output *out) {
  for (int i = 0; i < out->count; i++) {
    free(out->files[i].path);
    se_buf_free(&out->files[i].text);
    if (out->files[i].owned) {
      sh_image_free(out->files[i].owned);
      free(out->files[i].owned);
    }
  }
  free(out->files);
  se_buf_free(&out->render);
  memset(out, 0, sizeof *out);
}

const char *se_phase_name(sh_phase_type type) {
  switch (type) {
  case SH_PHASE_ISOTROPIC: return "isotropic";
  case SH_PHASE_HENYEY_GREENSTEIN: return "henyey_greenstein";
  case SH_PHASE_NISHITA_HAZY: return "nishita_hazy";
  case SH_PHASE_NISHITA_MURKY: return "nishita_murky";
  case SH_PHASE_RAYLEIGH: return "rayleigh";
  case SH_PHASE_CORNETTE_SHANKS: return "cornette_shanks";
  }
  return "isotropic";
}

double se_phase_cs_mean_cosine(double g) {
  return 3.0 * g * (4.0 + g * g) / (5.0 * (2.0 + g * g));
}

void se_note_one_lobe(se_notes *notes, const char *what, const char *renderer,
                      const sh_phase *phase, double g, const char *tail) {
  if (phase->type == SH_PHASE_CORNETTE_SHANKS)
    se_note(notes,
            "%s: %s has no %s phase; it is rendered as one Henyey-Greenstein lobe fitted "
            "to it, g = %.4g%s.",
            what, renderer, se_phase_name(phase->type), g, tail);
  else
    se_note(notes,
            "%s: %s has no %s phase; it is rendered as one Henyey-Greenstein lobe, "
            "g = %.4g, its mean cosine%s.",
            what, renderer, se_phase_name(phase->type), g, tail);
}
