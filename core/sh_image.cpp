// Image files through OpenImageIO: sh_image_read and sh_image_write of
// sh_image.h. OpenImageIO gives one API for PNG, EXR, HDR, JPEG, TIFF and the
// rest, with the colour-space metadata needed to decode sRGB files; this file
// is the only C++ in the core and no exception leaves it.
#include "sh_image.h"

#include <OpenImageIO/imageio.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace {

using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

std::string lower(std::string s) {
  for (char &c : s)
    if (c >= 'A' && c <= 'Z')
      c = (char)(c - 'A' + 'a');
  return s;
}

// The extension of a path's file name with its dot (".exr"), or "".
std::string extension_of(const std::string &path) {
  size_t slash = path.find_last_of('/');
  size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash) ||
      dot == (slash == std::string::npos ? 0 : slash + 1))
    return "";
  return path.substr(dot);
}

// True for the formats written as linear float rather than 8-bit sRGB.
bool is_float_format(const std::string &ext) {
  std::string e = lower(ext);
  return e == ".exr" || e == ".hdr" || e == ".pfm";
}

// How the stored values of a file map to linear radiance.
enum class Transfer { linear, srgb, gamma };

Transfer transfer_of(const ImageSpec &spec, double *gamma) {
  std::string cs = lower(spec.get_string_attribute("oiio:ColorSpace"));
  if (cs.find("linear") != std::string::npos || cs == "lin_srgb" ||
      cs == "lin_rec709" || cs == "acescg")
    return Transfer::linear;
  if (cs.find("srgb") != std::string::npos)
    return Transfer::srgb;
  if (cs.rfind("gammacorrected", 0) == 0) {
    double g = std::atof(cs.c_str() + std::strlen("gammacorrected"));
    if (g > 0 && std::isfinite(g)) {
      *gamma = g;
      return g == 1.0 ? Transfer::linear : Transfer::gamma;
    }
  }
  // No usable metadata: integer formats are display-encoded, float ones are
  // radiance.
  TypeDesc::BASETYPE b = (TypeDesc::BASETYPE)spec.format.basetype;
  if (b == TypeDesc::FLOAT || b == TypeDesc::HALF || b == TypeDesc::DOUBLE)
    return Transfer::linear;
  return Transfer::srgb;
}

sh_status read_impl(const char *path, sh_image *img, bool decode, sh_error *err) {
  struct stat st;
  if (stat(path, &st) != 0 || access(path, R_OK) != 0) {
    int e = errno;
    return sh_error_set(err, SH_ERR_IO, "cannot open '%s': %s", path,
                        std::strerror(e));
  }
  if (S_ISDIR(st.st_mode))
    return sh_error_set(err, SH_ERR_IO, "cannot open '%s': %s", path,
                        std::strerror(EISDIR));
  if (st.st_size == 0)
    return sh_error_set(err, SH_ERR_IMAGE,
                        "cannot read image '%s': the file is empty", path);

  // Keep colour channels as stored: alpha is dropped, so it must not have
  // been multiplied in.
  ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = ImageInput::open(path, &config);
  if (!in) {
    std::string msg = OIIO::geterror();
    return sh_error_set(err, SH_ERR_IMAGE, "cannot read image '%s': %s", path,
                        msg.empty() ? "not a known image format" : msg.c_str());
  }
  const ImageSpec spec = in->spec();
  int w = spec.width, h = spec.height, nch = spec.nchannels;
  if (w < 1 || h < 1 || nch < 1 || spec.depth > 1) {
    in->close();
    return sh_error_set(err, SH_ERR_IMAGE,
                        "cannot read image '%s': it has size %dx%d with %d "
                        "channels",
                        path, w, h, nch);
  }
  int nread = nch >= 3 ? 3 : 1; // grey, grey+alpha: channel 0 only
  std::vector<float> buf((size_t)w * (size_t)h * (size_t)nread);
  if (!in->read_image(0, 0, 0, nread, TypeDesc::FLOAT, buf.data())) {
    std::string msg = in->geterror();
    in->close();
    return sh_error_set(err, SH_ERR_IMAGE, "cannot decode image '%s': %s",
                        path, msg.empty() ? "read failed" : msg.c_str());
  }
  in->close();

  double gamma = 1.0;
  Transfer tf = decode ? transfer_of(spec, &gamma) : Transfer::linear;
  sh_image out;
  sh_status st_alloc = sh_image_alloc(&out, w, h, err);
  if (st_alloc != SH_OK)
    return st_alloc;
  size_t npix = (size_t)w * (size_t)h;
  for (size_t i = 0; i < npix; i++) {
    for (int c = 0; c < 3; c++) {
      double v = buf[i * nread + (nread == 3 ? c : 0)];
      if (tf == Transfer::srgb)
        v = sh_srgb_to_linear(v);
      else if (tf == Transfer::gamma)
        v = v > 0 ? std::pow(v, gamma) : v;
      out.rgb[3 * i + c] = (float)v;
    }
  }
  *img = out;
  return SH_OK;
}

// A temporary file that is removed when the guard goes out of scope, on
// every error path and when an exception unwinds, unless its name has been
// cleared after a successful rename.
struct TempFile {
  std::string name;
  TempFile() = default;
  TempFile(const TempFile &) = delete;
  TempFile &operator=(const TempFile &) = delete;
  ~TempFile() {
    if (!name.empty())
      std::remove(name.c_str());
  }
};

// Creates a new, empty file next to `path`: "dir/.name.<pid>.<n>.ext". On
// success `tmp` holds its name.
sh_status make_temp(const std::string &path, const std::string &ext,
                    std::string *tmp, sh_error *err) {
  static std::atomic<unsigned> counter{0};
  size_t slash = path.find_last_of('/');
  std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  std::string stem = base.substr(0, base.size() - ext.size());
  int last_errno = 0;
  for (int attempt = 0; attempt < 100; attempt++) {
    unsigned n = counter.fetch_add(1);
    std::string name = dir + "." + stem + "." + std::to_string((long)getpid()) +
                       "." + std::to_string(n) + ext;
    int fd = open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0666);
    if (fd >= 0) {
      close(fd);
      *tmp = name;
      return SH_OK;
    }
    last_errno = errno;
    if (last_errno != EEXIST)
      break;
  }
  return sh_error_set(err, SH_ERR_IO, "cannot write '%s': %s", path.c_str(),
                      std::strerror(last_errno));
}

sh_status write_impl(const char *path, const sh_image *img, double exposure,
                     const char *const *attrs, sh_error *err) {
  if (!img->rgb || img->width < 1 || img->height < 1)
    return sh_error_set(err, SH_ERR_ARG, "cannot write '%s': the image is empty",
                        path);
  if (!std::isfinite(exposure))
    return sh_error_set(err, SH_ERR_ARG,
                        "cannot write '%s': the exposure is not finite", path);
  std::string spath(path);
  std::string ext = extension_of(spath);
  if (ext.empty())
    return sh_error_set(err, SH_ERR_ARG,
                        "cannot write '%s': the file name has no extension to "
                        "choose the image format by",
                        path);
  // Chosen by the destination's name, before any file exists.
  auto out = ImageOutput::create(spath);
  if (!out) {
    std::string msg = OIIO::geterror();
    return sh_error_set(err, SH_ERR_IMAGE,
                        "cannot write '%s': no image format for '%s'%s%s", path,
                        ext.c_str(), msg.empty() ? "" : ": ", msg.c_str());
  }

  int w = img->width, h = img->height;
  size_t n = (size_t)w * (size_t)h * 3;
  bool linear = is_float_format(ext);
  ImageSpec spec(w, h, 3, linear ? TypeDesc::FLOAT : TypeDesc::UINT8);
  std::vector<unsigned char> bytes;
  const void *data = img->rgb;
  if (linear) {
    spec.attribute("oiio:ColorSpace", "linear");
    if (lower(ext) == ".exr")
      spec.attribute("compression", "zip"); // lossless
  } else {
    spec.attribute("oiio:ColorSpace", "sRGB");
    bytes.resize(n);
    double scale = std::exp2(exposure);
    for (size_t i = 0; i < n; i++) {
      double v = img->rgb[i] * scale;
      v = v > 0 ? (v < 1 ? v : 1) : 0; // NaN maps to 0
      bytes[i] = (unsigned char)std::lround(sh_linear_to_srgb(v) * 255.0);
    }
    data = bytes.data();
  }
  for (int i = 0; attrs && attrs[i] && attrs[i + 1]; i += 2)
    spec.attribute(attrs[i], attrs[i + 1]);
  TempFile guard;
  sh_status st = make_temp(spath, ext, &guard.name, err);
  if (st != SH_OK)
    return st;
  const std::string &tmp = guard.name;
  bool ok = out->open(tmp, spec) &&
            out->write_image(linear ? TypeDesc::FLOAT : TypeDesc::UINT8, data);
  std::string msg = ok ? "" : out->geterror();
  if (!out->close() && ok) {
    ok = false;
    msg = out->geterror();
  }
  out.reset();
  if (!ok)
    return sh_error_set(err, SH_ERR_IMAGE, "cannot write '%s': %s", path,
                        msg.empty() ? "the encoder failed" : msg.c_str());
  if (std::rename(tmp.c_str(), path) != 0) {
    int e = errno;
    return sh_error_set(err, SH_ERR_IO, "cannot write '%s': %s", path,
                        std::strerror(e));
  }
  guard.name.clear(); // renamed: nothing left to remove
  return SH_OK;
}

} // namespace

// Reads with or without decoding the transfer curve, catching everything.
static sh_status read_guarded(const char *path, sh_image *img, bool decode,
                              sh_error *err) {
  if (!img)
    return sh_error_set(err, SH_ERR_ARG, "sh_image_read was given no image");
  std::memset(img, 0, sizeof *img);
  if (!path || !*path)
    return sh_error_set(err, SH_ERR_ARG, "sh_image_read was given no path");
  try {
    return read_impl(path, img, decode, err);
  } catch (const std::bad_alloc &) {
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory reading image '%s'",
                        path);
  } catch (const std::exception &e) {
    return sh_error_set(err, SH_ERR_IMAGE, "cannot read image '%s': %s", path,
                        e.what());
  } catch (...) {
    return sh_error_set(err, SH_ERR_IMAGE,
                        "cannot read image '%s': unknown exception", path);
  }
}

extern "C" sh_status sh_image_read(const char *path, sh_image *img,
                                   sh_error *err) {
  return read_guarded(path, img, true, err);
}

extern "C" sh_status sh_image_read_data(const char *path, sh_image *img,
                                        sh_error *err) {
  return read_guarded(path, img, false, err);
}

extern "C" sh_status sh_image_write_meta(const char *path,
                                         const sh_image *img, double exposure,
                                         const char *const *attrs,
                                         sh_error *err) {
  if (!img || !path || !*path)
    return sh_error_set(err, SH_ERR_ARG,
                        "sh_image_write was given no image or no path");
  // write_impl's TempFile guard removes the temporary file on every failure,
  // exceptions included.
  try {
    return write_impl(path, img, exposure, attrs, err);
  } catch (const std::bad_alloc &) {
    return sh_error_set(err, SH_ERR_NOMEM, "out of memory writing image '%s'",
                        path);
  } catch (const std::exception &e) {
    return sh_error_set(err, SH_ERR_IMAGE, "cannot write image '%s': %s", path,
                        e.what());
  } catch (...) {
    return sh_error_set(err, SH_ERR_IMAGE,
                        "cannot write image '%s': unknown exception", path);
  }
}

extern "C" sh_status sh_image_write(const char *path, const sh_image *img,
                                    double exposure, sh_error *err) {
  return sh_image_write_meta(path, img, exposure, NULL, err);
}
