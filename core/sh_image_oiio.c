/* The OpenImageIO plugin (sh_oiio_plugin.h), loaded with dlopen the first
 * time a file needs it: sh__oiio_read and sh__oiio_write of sh_image_int.h.
 *
 * Where the plugin is looked for, in order: the file named by the
 * environment variable SHAFTS_OIIO_PLUGIN (only there, when it is set and
 * not empty); libshafts_oiio.so in the directory of the module holding this
 * code (libshafts.so's directory, or the program's); the build tree's copy
 * (SH_OIIO_PLUGIN_PATH, set by CMake); then the loader's own search
 * (LD_LIBRARY_PATH). The plugin is loaded once per process and never
 * unloaded. */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE /* dladdr */
#endif
#include "sh_image_int.h"
#include "sh_oiio_plugin.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SH__OIIO_PLUGIN_NAME "libshafts_oiio.so"

static pthread_mutex_t sh__oiio_lock = PTHREAD_MUTEX_INITIALIZER;
static int sh__oiio_tried;
static sh_oiio_read_fn sh__oiio_read_fn;
static sh_oiio_write_fn sh__oiio_write_fn;
static char sh__oiio_why[512]; /* why loading failed, once it has */

/* Tries one candidate file; returns its handle with the right ABI, or NULL
 * and a reason appended to why. */
static void *sh__oiio_try(const char *path, char *why, size_t size) {
  void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  size_t used = strlen(why);
  if (!h) {
    const char *e = dlerror();
    snprintf(why + used, size - used, "%s%s", used ? "; " : "",
             e ? e : path);
    return NULL;
  }
  sh_oiio_abi_fn abi = (sh_oiio_abi_fn)dlsym(h, SH_OIIO_ABI_SYMBOL);
  if (!abi || abi() != SH_OIIO_PLUGIN_ABI) {
    snprintf(why + used, size - used, "%s%s: not a shafts OpenImageIO plugin "
             "of interface %d", used ? "; " : "", path, SH_OIIO_PLUGIN_ABI);
    return NULL; /* left loaded: unloading OpenImageIO is not safe */
  }
  return h;
}

static void *sh__oiio_find(char *why, size_t size) {
  const char *env = getenv("SHAFTS_OIIO_PLUGIN");
  if (env && *env)
    return sh__oiio_try(env, why, size);
  void *h = NULL;
  Dl_info info;
  if (dladdr((void *)&sh__oiio_find, &info) && info.dli_fname) {
    const char *slash = strrchr(info.dli_fname, '/');
    if (slash) {
      size_t n = (size_t)(slash - info.dli_fname) + sizeof SH__OIIO_PLUGIN_NAME + 1;
      char *path = malloc(n);
      if (path) {
        snprintf(path, n, "%.*s/%s", (int)(slash - info.dli_fname),
                 info.dli_fname, SH__OIIO_PLUGIN_NAME);
        h = sh__oiio_try(path, why, size);
        free(path);
      }
    }
  }
#ifdef SH_OIIO_PLUGIN_PATH
  if (!h)
    h = sh__oiio_try(SH_OIIO_PLUGIN_PATH, why, size);
#endif
  if (!h)
    h = sh__oiio_try(SH__OIIO_PLUGIN_NAME, why, size);
  return h;
}

/* Loads the plugin once; SH_OK, or SH_ERR_IMAGE with the reason. */
static sh_status sh__oiio_load(sh_error *err, const char *what,
                               const char *path) {
  pthread_mutex_lock(&sh__oiio_lock);
  if (!sh__oiio_tried) {
    sh__oiio_tried = 1;
    void *h = sh__oiio_find(sh__oiio_why, sizeof sh__oiio_why);
    if (h) {
      sh__oiio_read_fn = (sh_oiio_read_fn)dlsym(h, SH_OIIO_READ_SYMBOL);
      sh__oiio_write_fn = (sh_oiio_write_fn)dlsym(h, SH_OIIO_WRITE_SYMBOL);
      if (!sh__oiio_read_fn || !sh__oiio_write_fn)
        snprintf(sh__oiio_why, sizeof sh__oiio_why,
                 "the OpenImageIO plugin lacks its functions");
    }
  }
  int ok = sh__oiio_read_fn && sh__oiio_write_fn;
  pthread_mutex_unlock(&sh__oiio_lock);
  if (ok)
    return SH_OK;
  return sh_error_set(err, SH_ERR_IMAGE,
                      "cannot %s '%s': formats other than EXR and PNG need "
                      "OpenImageIO, whose plugin (" SH__OIIO_PLUGIN_NAME
                      ") could not be loaded: %s",
                      what, path, sh__oiio_why);
}

sh_status sh__oiio_read(const char *path, sh__decoded *out, sh_error *err) {
  sh_status st = sh__oiio_load(err, "read image", path);
  if (st != SH_OK)
    return st;
  sh_oiio_pixels px;
  char msg[512] = "";
  if (sh__oiio_read_fn(path, &px, msg, sizeof msg) != 0)
    return sh_error_set(err, SH_ERR_IMAGE, "cannot read image '%s': %s", path,
                        msg[0] ? msg : "OpenImageIO failed");
  out->width = px.width;
  out->height = px.height;
  out->channels = px.channels;
  out->values = px.values;
  out->gamma = 1.0;
  out->transfer =
      sh__transfer_of_colorspace(px.colorspace, px.is_float, &out->gamma);
  return SH_OK;
}

sh_status sh__oiio_write(const char *tmp_path, const char *path, int width,
                         int height, int is_float, const void *data,
                         const char *const *attrs, sh_error *err) {
  sh_status st = sh__oiio_load(err, "write", path);
  if (st != SH_OK)
    return st;
  char msg[512] = "";
  if (sh__oiio_write_fn(path, tmp_path, width, height, is_float, data, attrs,
                        msg, sizeof msg) != 0)
    return sh_error_set(err, SH_ERR_IMAGE, "cannot write '%s': %s", path,
                        msg[0] ? msg : "OpenImageIO failed");
  return SH_OK;
}
