// libshafts_oiio.so: image files through OpenImageIO, behind the C
// interface of sh_oiio_plugin.h. Only sh_image_oiio.c loads it, with dlopen,
// for the formats that OpenEXRCore and libpng do not cover. No exception
// leaves this file.
#include "sh_oiio_plugin.h"

#include <OpenImageIO/imageio.h>

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>

#define SH_OIIO_EXPORT extern "C" __attribute__((visibility("default")))

namespace {

using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

int fail(char *msg, size_t size, const char *fmt, ...) {
  if (msg && size) {
    va_list ap;
    va_start(ap, fmt);
    std::vsnprintf(msg, size, fmt, ap);
    va_end(ap);
  }
  return 1;
}

int read_impl(const char *path, sh_oiio_pixels *out, char *msg, size_t size) {
  // Keep colour channels as stored: alpha is dropped, so it must not have
  // been multiplied in.
  ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = ImageInput::open(path, &config);
  if (!in) {
    std::string e = OIIO::geterror();
    return fail(msg, size, "%s", e.empty() ? "not a known image format" : e.c_str());
  }
  const ImageSpec spec = in->spec();
  int w = spec.width, h = spec.height, nch = spec.nchannels;
  if (w < 1 || h < 1 || nch < 1 || spec.depth > 1) {
    in->close();
    return fail(msg, size, "it has size %dx%d with %d channels", w, h, nch);
  }
  int nread = nch >= 3 ? 3 : 1; // grey, grey+alpha: channel 0 only
  size_t n = (size_t)w * (size_t)h * (size_t)nread;
  float *values = static_cast<float *>(std::malloc(n * sizeof(float)));
  if (!values) {
    in->close();
    return fail(msg, size, "out of memory for %dx%d pixels", w, h);
  }
  if (!in->read_image(0, 0, 0, nread, TypeDesc::FLOAT, values)) {
    std::string e = in->geterror();
    in->close();
    std::free(values);
    return fail(msg, size, "%s", e.empty() ? "read failed" : e.c_str());
  }
  in->close();
  TypeDesc::BASETYPE b = (TypeDesc::BASETYPE)spec.format.basetype;
  out->width = w;
  out->height = h;
  out->channels = nread;
  out->values = values;
  out->is_float = b == TypeDesc::FLOAT || b == TypeDesc::HALF || b == TypeDesc::DOUBLE;
  std::snprintf(out->colorspace, sizeof out->colorspace, "%s",
                spec.get_string_attribute("oiio:ColorSpace").c_str());
  return 0;
}

int write_impl(const char *format_path, const char *tmp_path, int w, int h,
               int is_float, const void *data, const char *const *attrs,
               char *msg, size_t size) {
  // Chosen by the destination's name, not the temporary file's.
  auto out = ImageOutput::create(format_path);
  if (!out) {
    std::string e = OIIO::geterror();
    return fail(msg, size, "%s", e.empty() ? "OpenImageIO knows no such format" : e.c_str());
  }
  ImageSpec spec(w, h, 3, is_float ? TypeDesc::FLOAT : TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", is_float ? "linear" : "sRGB");
  for (int i = 0; attrs && attrs[i] && attrs[i + 1]; i += 2)
    spec.attribute(attrs[i], attrs[i + 1]);
  bool ok = out->open(tmp_path, spec) &&
            out->write_image(is_float ? TypeDesc::FLOAT : TypeDesc::UINT8, data);
  std::string e = ok ? "" : out->geterror();
  if (!out->close() && ok) {
    ok = false;
    e = out->geterror();
  }
  if (!ok)
    return fail(msg, size, "%s", e.empty() ? "the encoder failed" : e.c_str());
  return 0;
}

// Runs f, turning any exception into a message: none may leave the plugin.
template <class F> int guarded(F f, char *msg, size_t size) {
  try {
    return f();
  } catch (const std::bad_alloc &) {
    return fail(msg, size, "out of memory");
  } catch (const std::exception &e) {
    return fail(msg, size, "%s", e.what());
  } catch (...) {
    return fail(msg, size, "unknown exception");
  }
}

} // namespace

SH_OIIO_EXPORT int shafts_oiio_abi(void) { return SH_OIIO_PLUGIN_ABI; }

SH_OIIO_EXPORT int shafts_oiio_read(const char *path, sh_oiio_pixels *out,
                                    char *msg, size_t size) {
  if (!path || !out)
    return fail(msg, size, "no path or no output");
  std::memset(out, 0, sizeof *out);
  return guarded([&] { return read_impl(path, out, msg, size); }, msg, size);
}

SH_OIIO_EXPORT int shafts_oiio_write(const char *format_path, const char *tmp_path,
                                     int width, int height, int is_float,
                                     const void *data, const char *const *attrs,
                                     char *msg, size_t size) {
  if (!format_path || !tmp_path || !data || width < 1 || height < 1)
    return fail(msg, size, "no path, no pixels or a size below 1x1");
  return guarded([&] {
    return write_impl(format_path, tmp_path, width, height, is_float, data, attrs,
                      msg, size);
  }, msg, size);
}
