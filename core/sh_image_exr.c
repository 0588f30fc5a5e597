/* EXR through OpenEXRCore, OpenEXR's C library (sh__exr_read and
 * sh__exr_write of sh_image_int.h). OpenEXRCore reports errors through a
 * handler that would print to stderr; ours keeps the last message of the
 * calling thread for the error report instead. */
#include "sh_image_int.h"

#include <openexr.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static _Thread_local char sh__exr_last[256];

static void sh__exr_on_error(exr_const_context_t ctxt, exr_result_t code,
                             const char *msg) {
  (void)ctxt;
  snprintf(sh__exr_last, sizeof sh__exr_last, "%s",
           msg ? msg : exr_get_default_error_message(code));
}

static exr_context_initializer_t sh__exr_init(void) {
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = sh__exr_on_error;
  return init;
}

/* The message for a failed call: the handler's, else the code's. */
static const char *sh__exr_message(exr_result_t rv) {
  return sh__exr_last[0] ? sh__exr_last : exr_get_default_error_message(rv);
}

/* The index in 0..2 of channel R, G or B, else -1. */
static int sh__rgb_index(const char *name) {
  if (!name || !name[0] || name[1])
    return -1;
  return name[0] == 'R' ? 0 : name[0] == 'G' ? 1 : name[0] == 'B' ? 2 : -1;
}

/* Whether the part's layout is one this reader takes, and which channels
 * it reads: R, G, B if all three are there, else Y. */
static int sh__exr_layout_ok(exr_context_t ctxt, int *channels) {
  int parts = 0;
  exr_storage_t storage;
  const exr_attr_chlist_t *chl = NULL;
  if (exr_get_count(ctxt, &parts) != EXR_ERR_SUCCESS || parts != 1 ||
      exr_get_storage(ctxt, 0, &storage) != EXR_ERR_SUCCESS ||
      storage != EXR_STORAGE_SCANLINE ||
      exr_get_channels(ctxt, 0, &chl) != EXR_ERR_SUCCESS || !chl)
    return 0;
  int rgb = 0, y = 0;
  for (int i = 0; i < chl->num_channels; i++) {
    const exr_attr_chlist_entry_t *e = &chl->entries[i];
    int full = e->x_sampling == 1 && e->y_sampling == 1;
    int k = sh__rgb_index(e->name.str);
    if (k >= 0 && full)
      rgb |= 1 << k;
    else if (!strcmp(e->name.str, "Y") && full)
      y = 1;
  }
  *channels = rgb == 7 ? 3 : 1;
  return rgb == 7 || (rgb == 0 && y);
}

sh_status sh__exr_read(const char *path, sh__decoded *out, int *handled,
                       sh_error *err) {
  *handled = 0;
  sh__exr_last[0] = '\0';
  exr_context_initializer_t init = sh__exr_init();
  init.flags |= EXR_CONTEXT_FLAG_SILENT_HEADER_PARSE;
  exr_context_t ctxt = NULL;
  exr_result_t rv = exr_start_read(&ctxt, path, &init);
  if (rv != EXR_ERR_SUCCESS) {
    exr_finish(&ctxt);
    return SH_OK; /* OpenImageIO may make more of it, or say why not */
  }
  int channels = 0;
  exr_attr_box2i_t dw;
  int32_t lines = 0;
  if (!sh__exr_layout_ok(ctxt, &channels) ||
      exr_get_data_window(ctxt, 0, &dw) != EXR_ERR_SUCCESS ||
      exr_get_scanlines_per_chunk(ctxt, 0, &lines) != EXR_ERR_SUCCESS ||
      lines < 1) {
    exr_finish(&ctxt);
    return SH_OK;
  }
  *handled = 1;
  int64_t w = (int64_t)dw.max.x - dw.min.x + 1;
  int64_t h = (int64_t)dw.max.y - dw.min.y + 1;
  if (w < 1 || h < 1 || w > INT32_MAX / 4 || h > INT32_MAX / 4) {
    exr_finish(&ctxt);
    return sh_error_set(err, SH_ERR_IMAGE,
                        "cannot read image '%s': its data window is %lldx%lld",
                        path, (long long)w, (long long)h);
  }
  float *values = calloc((size_t)w * (size_t)h * (size_t)channels, sizeof(float));
  if (!values) {
    exr_finish(&ctxt);
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory reading image '%s'",
                        path);
  }
  exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
  int have_dec = 0;
  size_t row_bytes = (size_t)w * (size_t)channels * sizeof(float);
  for (int64_t y = dw.min.y; y <= dw.max.y && rv == EXR_ERR_SUCCESS; y += lines) {
    exr_chunk_info_t chunk;
    rv = exr_read_scanline_chunk_info(ctxt, 0, (int)y, &chunk);
    if (rv != EXR_ERR_SUCCESS)
      break;
    rv = have_dec ? exr_decoding_update(ctxt, 0, &chunk, &dec)
                  : exr_decoding_initialize(ctxt, 0, &chunk, &dec);
    if (rv != EXR_ERR_SUCCESS)
      break;
    have_dec = 1;
    uint8_t *row = (uint8_t *)values + (size_t)(chunk.start_y - dw.min.y) * row_bytes;
    for (int c = 0; c < dec.channel_count; c++) {
      exr_coding_channel_info_t *ch = &dec.channels[c];
      int k = channels == 3 ? sh__rgb_index(ch->channel_name)
                            : (strcmp(ch->channel_name, "Y") ? -1 : 0);
      ch->decode_to_ptr = k >= 0 ? row + (size_t)k * sizeof(float) : NULL;
      ch->user_pixel_stride = channels * (int32_t)sizeof(float);
      ch->user_line_stride = (int32_t)row_bytes;
      ch->user_bytes_per_element = sizeof(float);
      ch->user_data_type = EXR_PIXEL_FLOAT;
    }
    rv = exr_decoding_choose_default_routines(ctxt, 0, &dec);
    if (rv == EXR_ERR_SUCCESS)
      rv = exr_decoding_run(ctxt, 0, &dec);
  }
  if (have_dec)
    exr_decoding_destroy(ctxt, &dec);
  exr_finish(&ctxt);
  if (rv != EXR_ERR_SUCCESS) {
    free(values);
    return sh_error_set(err, SH_ERR_IMAGE, "cannot decode image '%s': %s",
                        path, sh__exr_message(rv));
  }
  out->width = (int)w;
  out->height = (int)h;
  out->channels = channels;
  out->values = values;
  out->transfer = SH__TRANSFER_LINEAR;
  out->gamma = 1.0;
  return SH_OK;
}

sh_status sh__exr_write(const char *tmp_path, const char *path, int width,
                        int height, const float *rgb,
                        const char *const *attrs, sh_error *err) {
  sh__exr_last[0] = '\0';
  exr_context_initializer_t init = sh__exr_init();
  exr_context_t ctxt = NULL;
  int part = 0;
  exr_result_t rv = exr_start_write(&ctxt, tmp_path, EXR_WRITE_FILE_DIRECTLY, &init);
  if (rv == EXR_ERR_SUCCESS)
    rv = exr_add_part(ctxt, NULL, EXR_STORAGE_SCANLINE, &part);
  if (rv == EXR_ERR_SUCCESS)
    rv = exr_initialize_required_attr_simple(ctxt, part, width, height,
                                             EXR_COMPRESSION_RLE);
  static const char *const names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3 && rv == EXR_ERR_SUCCESS; c++)
    rv = exr_add_channel(ctxt, part, names[c], EXR_PIXEL_FLOAT,
                         EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
  for (int i = 0; attrs && attrs[i] && attrs[i + 1] && rv == EXR_ERR_SUCCESS; i += 2)
    rv = exr_attr_set_string(ctxt, part, attrs[i], attrs[i + 1]);
  if (rv == EXR_ERR_SUCCESS)
    rv = exr_write_header(ctxt);
  int32_t lines = 0;
  if (rv == EXR_ERR_SUCCESS)
    rv = exr_get_scanlines_per_chunk(ctxt, part, &lines);
  exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
  int have_enc = 0;
  size_t row_bytes = (size_t)width * 3 * sizeof(float);
  for (int y = 0; y < height && rv == EXR_ERR_SUCCESS; y += lines) {
    exr_chunk_info_t chunk;
    rv = exr_write_scanline_chunk_info(ctxt, part, y, &chunk);
    if (rv != EXR_ERR_SUCCESS)
      break;
    rv = have_enc ? exr_encoding_update(ctxt, part, &chunk, &enc)
                  : exr_encoding_initialize(ctxt, part, &chunk, &enc);
    if (rv != EXR_ERR_SUCCESS)
      break;
    const uint8_t *row = (const uint8_t *)rgb + (size_t)y * row_bytes;
    for (int c = 0; c < enc.channel_count; c++) {
      exr_coding_channel_info_t *ch = &enc.channels[c];
      int k = sh__rgb_index(ch->channel_name);
      ch->encode_from_ptr = row + (size_t)(k < 0 ? 0 : k) * sizeof(float);
      ch->user_pixel_stride = 3 * (int32_t)sizeof(float);
      ch->user_line_stride = (int32_t)row_bytes;
      ch->user_bytes_per_element = sizeof(float);
      ch->user_data_type = EXR_PIXEL_FLOAT;
    }
    if (!have_enc)
      rv = exr_encoding_choose_default_routines(ctxt, part, &enc);
    have_enc = 1;
    if (rv == EXR_ERR_SUCCESS)
      rv = exr_encoding_run(ctxt, part, &enc);
  }
  if (have_enc)
    exr_encoding_destroy(ctxt, &enc);
  exr_result_t fin = exr_finish(&ctxt);
  if (rv == EXR_ERR_SUCCESS)
    rv = fin;
  if (rv != EXR_ERR_SUCCESS)
    return sh_error_set(err, SH_ERR_IMAGE, "cannot write '%s': %s", path,
                        sh__exr_message(rv));
  return SH_OK;
}
