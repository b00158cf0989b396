// SPDX-License-Identifier: Apache-2.0
// Arrays in and out: Camera.warp on numpy arrays read in place, and artcam.read_image /
// write_image, the CLI's reader and writer (orientation, metadata, ICC profile and quality kept).
#include "app/cli/write_args.h"
#include "core/colour/icc_profile.h"
#include "core/effects/finish.h"
#include "core/io/photo_metadata.h"
#include "core/io/stored_image.h"
#include "core/pipeline/render.h"
#include "python/src/common.h"

#include <algorithm>
#include <cmath>

namespace artcam::python {
namespace {

// The photo's numbers as stored, seen through the array's own memory.
struct ArrayImage {
  ConstImageView view;
  bool grey_ndim2 = false;  // an H×W array (one channel): the output is H×W too
};

PixelType pixelTypeOf(const py::array& a, const std::string& what) {
  if (a.dtype().is(py::dtype::of<uint8_t>())) return PixelType::UInt8;
  if (a.dtype().is(py::dtype::of<uint16_t>())) return PixelType::UInt16;
  if (a.dtype().is(py::dtype::of<float>())) return PixelType::Float;
  raiseValueError(what + ": dtype " + py::str(a.dtype()).cast<std::string>() +
                  " is not one artcam renders (uint8, uint16 or float32)");
}

ArrayImage viewOfArray(const py::array& a, const std::string& what) {
  const PixelType type = pixelTypeOf(a, what);
  if (a.ndim() != 2 && a.ndim() != 3)
    raiseValueError(what + ": expected an H×W or H×W×C array, got " + std::to_string(a.ndim()) +
                    " dimensions");
  const py::ssize_t h = a.shape(0), w = a.shape(1), c = a.ndim() == 3 ? a.shape(2) : 1;
  if (c < 1 || c > 4)
    raiseValueError(what + ": " + std::to_string(c) +
                    " channels; artcam renders 1 to 4 "
                    "(grey, grey+alpha, RGB, RGBA)");
  if (w < 1 || h < 1 || w > kMaxFrameSide || h > kMaxFrameSide)
    raiseValueError(what + ": " + std::to_string(w) + "x" + std::to_string(h) +
                    " is not an image size artcam takes (1 to 2^20 pixels a side)");
  const py::ssize_t item = a.itemsize();
  const bool packed_pixels = (a.ndim() == 2 || a.strides(2) == item) && a.strides(1) == c * item &&
                             a.strides(0) >= w * c * item;
  if (!packed_pixels)
    raiseValueError(what + ": not contiguous (strides " +
                    py::str(py::cast(std::vector<py::ssize_t>(a.strides(), a.strides() + a.ndim())))
                        .cast<std::string>() +
                    "): each row's pixels must be packed; numpy.ascontiguousarray(image) makes "
                    "such a copy");
  ArrayImage image;
  image.view = packedView<const void>(a.data(), static_cast<int>(w), static_cast<int>(h),
                                      static_cast<int>(c), type, c == 2 || c == 4 ? c - 1 : -1);
  image.view.row_bytes = a.strides(0);
  image.grey_ndim2 = a.ndim() == 2;
  return image;
}

py::dtype dtypeOf(PixelType type) {
  return type == PixelType::UInt8    ? py::dtype::of<uint8_t>()
         : type == PixelType::UInt16 ? py::dtype::of<uint16_t>()
                                     : py::dtype::of<float>();
}

// An output array over the engine's own pixel buffer (huge pages, left uninitialised for a
// render that writes every pixel, pixel_buffer.h), as the CLI's output is: numpy's allocator
// would fault 72 MB of small pages in on the render's first touch.
py::array newArray(PixelType type, int width, int height, int channels, bool ndim2) {
  auto buffer = std::make_shared<PixelBuffer>(
      static_cast<size_t>(width) * height * channels * pixelTypeSize(type),
      PixelBuffer::Init::Uninitialised);
  const py::ssize_t item = pixelTypeSize(type);
  std::vector<py::ssize_t> shape{height, width}, strides{py::ssize_t(width) * channels * item};
  if (ndim2) {
    strides.push_back(item);
  } else {
    shape.push_back(channels);
    strides.push_back(channels * item);
    strides.push_back(item);
  }
  void* data = buffer->data();
  const py::capsule owner(new std::shared_ptr<PixelBuffer>(std::move(buffer)),
                          [](void* p) { delete static_cast<std::shared_ptr<PixelBuffer>*>(p); });
  return py::array(dtypeOf(type), shape, strides, data, owner);
}

// The stored numbers as linear float RGBA, premultiplied, for the cameras that render from the
// linear photo (render.h): integers are sRGB-encoded, float is linear (as the CLI reads files
// without a profile).
ImageF linearRgba(const ConstImageView& v, const StoredEncoding& encoding) {
  ImageF out(v.width, v.height, 4, 3);
  const float scale = 1.0f / pixelTypeFullScale(v.type);
  const int colours = v.alpha_channel >= 0 ? v.channels - 1 : v.channels;
  for (int y = 0; y < v.height; ++y) {
    const void* row = v.row(y);
    float* o = out.pixel(0, y);
    for (int x = 0; x < v.width; ++x, o += 4) {
      float s[4];
      for (int k = 0; k < v.channels; ++k) {
        const size_t i = static_cast<size_t>(x) * v.channels + k;
        s[k] = v.type == PixelType::UInt8    ? static_cast<const uint8_t*>(row)[i] * scale
               : v.type == PixelType::UInt16 ? static_cast<const uint16_t*>(row)[i] * scale
                                             : static_cast<const float*>(row)[i];
      }
      for (int k = 0; k < 3; ++k) o[k] = s[colours == 1 ? 0 : k];
      o[3] = v.alpha_channel >= 0 ? s[v.alpha_channel] : 1.0f;
    }
  }
  encoding.decode(out.data.data(), static_cast<size_t>(out.width) * out.height, 4, 3);
  return out;
}

// Linear RGBA back into the stored encoding and `type`: RGB (+ alpha when kept).
void storeRgba(ImageF& linear, const StoredEncoding& encoding, PixelType type, bool keep_alpha,
               void* data) {
  encoding.encode(linear.data.data(), static_cast<size_t>(linear.width) * linear.height, 4, 3);
  const int channels = keep_alpha ? 4 : 3;
  const float full = pixelTypeFullScale(type);
  const size_t pixels = static_cast<size_t>(linear.width) * linear.height;
  for (size_t p = 0; p < pixels; ++p)
    for (int k = 0; k < channels; ++k) {
      const float v = linear.data[p * 4 + k];  // premultiplied: over black without alpha
      const size_t i = p * channels + k;
      if (type == PixelType::Float)
        static_cast<float*>(data)[i] = v;
      else if (type == PixelType::UInt8)
        static_cast<uint8_t*>(data)[i] =
            static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * full));
      else
        static_cast<uint16_t*>(data)[i] =
            static_cast<uint16_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * full));
    }
}

std::optional<ImageF> depthOf(const py::object& depth) {
  if (depth.is_none()) return std::nullopt;
  const auto d = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(depth);
  if (!d || (d.ndim() != 2 && !(d.ndim() == 3 && d.shape(2) == 1)))
    raiseValueError("depth: expected an H×W array of depths");
  ImageF out(static_cast<int>(d.shape(1)), static_cast<int>(d.shape(0)), 1);
  std::copy(d.data(), d.data() + out.data.size(), out.data.begin());
  return out;
}

}  // namespace

py::array warpArray(const PyCamera& self, const py::array& image, const py::object& depth_in,
                    const py::object& size, const std::string& filter_name,
                    const std::string& edge_name, bool alpha, int threads,
                    const py::object& out_given, const py::object& finish) {
  const Artcam& camera = *self.camera;
  const ArrayImage in = viewOfArray(image, "image");
  RenderOptions options;
  const auto filter = filterFromName(filter_name);
  if (!filter)
    raiseValueError("filter: expected nearest, bilinear or bicubic, got \"" + filter_name + "\"");
  const auto edge = edgeModeFromName(edge_name);
  if (!edge)
    raiseValueError("edge: expected transparent, extend or black, got \"" + edge_name + "\"");
  if (threads < 0 || threads > 1024)
    raiseValueError("threads: expected a whole number from 0 to 1024, got " +
                    std::to_string(threads));
  options.warp.filter = *filter;
  options.warp.edge = *edge;
  options.warp.threads = threads;
  if (!size.is_none()) {
    const auto wh = size.cast<std::vector<long long>>();
    if (wh.size() != 2 || wh[0] < 0 || wh[1] < 0 || wh[0] > kMaxFrameSide ||
        wh[1] > kMaxFrameSide || (wh[0] == 0 && wh[1] == 0))
      raiseValueError("size: expected (width, height), each 0 to 2^20 and not both 0");
    options.warp.width = static_cast<int>(wh[0]);
    options.warp.height = static_cast<int>(wh[1]);
  }
  const std::string finish_name = finish.is_none() ? std::string() : finish.cast<std::string>();
  if (!finish_name.empty() && !finishByName(finish_name)) {
    std::string names;
    for (const FinishInfo& f : finishes()) names += (names.empty() ? "" : ", ") + f.name;
    raiseValueError("finish: unknown finish \"" + finish_name + "\" (" + names + ")");
  }
  const std::optional<ImageF> depth = depthOf(depth_in);
  if (readsDepth(camera) && !depth)
    raiseValueError(self.name + ": the camera reads depth: pass depth=");
  const OutputFrame frame = outputFrameFor(camera, {in.view.width, in.view.height},
                                           options.warp.width, options.warp.height);
  if (!frame.warning.empty())
    if (PyErr_WarnEx(PyExc_UserWarning, (self.name + ": " + frame.warning).c_str(), 1) < 0)
      throw py::error_already_set();
  RenderSummary summary;
  RenderInputs inputs;
  inputs.photo = in.view;
  inputs.depth = depth ? &*depth : nullptr;
  py::array out;
  Status marked;
  try {
    if (!needsLinearPhoto(camera)) {
      // The stored numbers resampled as they are (core/render/warp.h), straight into the
      // output array: no copy of the input, none of the output.
      const bool add_alpha = alpha && in.view.alpha_channel < 0;
      const int channels = in.view.channels + (add_alpha ? 1 : 0);
      const bool ndim2 = in.grey_ndim2 && channels == 1;
      ImageView view;
      if (out_given.is_none()) {
        out = newArray(in.view.type, frame.size.width, frame.size.height, channels, ndim2);
        view = packedView<void>(out.mutable_data(), frame.size.width, frame.size.height, channels,
                                in.view.type, add_alpha ? in.view.channels : in.view.alpha_channel);
      } else {
        // Rendered into the caller's array (numpy's out=, OpenCV's dst): its shape and dtype must
        // be the output's; a render that reuses one array pays no allocation.
        out = out_given.cast<py::array>();
        const ArrayImage target = viewOfArray(out, "out");
        if (!out.writeable()) raiseValueError("out: the array is read-only");
        if (target.view.type != in.view.type || target.view.width != frame.size.width ||
            target.view.height != frame.size.height || target.view.channels != channels)
          raiseValueError("out: expected a " + std::to_string(frame.size.height) + "×" +
                          std::to_string(frame.size.width) + "×" + std::to_string(channels) +
                          " array of the image's dtype");
        view = packedView<void>(out.mutable_data(), frame.size.width, frame.size.height, channels,
                                in.view.type, add_alpha ? in.view.channels : in.view.alpha_channel);
        view.row_bytes = target.view.row_bytes;
      }
      py::gil_scoped_release release;
      render(inputs, camera, options, view, &summary);
      // Marks on the stored values, as artcam warp --finish applies them.
      if (!summary.cancelled && !finish_name.empty()) marked = applyFinish(view, finish_name);
    } else {
      // Colour, depth, layers or patches: the linear photo, decoded as the CLI decodes a file
      // without a profile, and the result encoded back the same way.
      const StoredEncoding encoding = in.view.type == PixelType::Float
                                          ? StoredEncoding()
                                          : StoredEncoding::ofTransfer(Transfer::srgb());
      if (!out_given.is_none())
        raiseValueError(self.name +
                        ": out= is for cameras of position alone (this one renders "
                        "from the linear photo into a new array)");
      const bool keep_alpha = alpha || in.view.alpha_channel >= 0;
      out = newArray(in.view.type, frame.size.width, frame.size.height, keep_alpha ? 4 : 3, false);
      void* data = out.mutable_data();
      py::gil_scoped_release release;
      const ImageF linear = linearRgba(in.view, encoding);
      inputs.linear = &linear;
      inputs.encoding = &encoding;
      ImageF rendered = render(inputs, camera, options, &summary);
      if (!summary.cancelled) storeRgba(rendered, encoding, in.view.type, keep_alpha, data);
      if (!summary.cancelled && !finish_name.empty())
        marked =
            applyFinish(packedView<void>(data, frame.size.width, frame.size.height,
                                         keep_alpha ? 4 : 3, in.view.type, keep_alpha ? 3 : -1),
                        finish_name);
    }
  } catch (const std::invalid_argument& e) {
    raiseValueError(self.name + ": cannot render: " + e.what());
  } catch (const std::bad_alloc&) {
    PyErr_NoMemory();
    throw py::error_already_set();
  }
  if (!marked) raiseValueError(marked.message);
  return out;
}

namespace {

// A photo as the CLI reads it: stored numbers, upright, with what the file said about itself.
struct PyImage {
  std::shared_ptr<StoredImage> stored;
};

py::array pixelsOf(const PyImage& self) {
  const StoredImage& s = *self.stored;
  const py::ssize_t item = pixelTypeSize(s.type);
  const py::capsule owner(new std::shared_ptr<StoredImage>(self.stored),
                          [](void* p) { delete static_cast<std::shared_ptr<StoredImage>*>(p); });
  return py::array(
      dtypeOf(s.type), {py::ssize_t(s.height), py::ssize_t(s.width), py::ssize_t(s.channels)},
      {py::ssize_t(s.width) * s.channels * item, s.channels * item, item}, s.bytes.data(), owner);
}

py::dict infoOf(const PyImage& self) {
  const ImageInfo& i = self.stored->info;
  py::dict d;
  d["path"] = i.path;
  d["format"] = i.format_name;
  d["pixel_type"] = i.pixel_type;
  d["colour_space"] = i.colour_space;
  d["orientation"] = i.stored_orientation;
  d["icc_profile"] = i.icc ? py::object(py::str(i.icc->description())) : py::object(py::none());
  d["jpeg_quality"] =
      i.jpeg_quality ? py::object(py::int_(i.jpeg_quality)) : py::object(py::none());
  d["jpeg_subsampling"] =
      i.jpeg_subsampling.empty() ? py::object(py::none()) : py::object(py::str(i.jpeg_subsampling));
  d["left_out_channels"] = i.dropped_channels;
  d["other_parts"] = i.other_parts;
  if (i.metadata) {
    const PhotoLensTags tags = photoLensTags(*i.metadata);
    d["camera"] = tags.camera_maker.empty() && tags.camera_model.empty()
                      ? py::object(py::none())
                      : py::object(py::str(tags.camera_maker + " " + tags.camera_model));
    d["lens"] =
        tags.lens_model.empty() ? py::object(py::none()) : py::object(py::str(tags.lens_model));
    d["focal_mm"] =
        tags.focal_mm > 0 ? py::object(py::float_(tags.focal_mm)) : py::object(py::none());
  }
  return d;
}

PyImage readImageFile(const std::string& path) {
  Result<StoredImage> stored;
  {
    py::gil_scoped_release release;
    stored = readStoredImage(path);
  }
  if (!stored) raiseReadError(path, stored.status.message);
  return {std::make_shared<StoredImage>(std::move(*stored.value))};
}

const std::vector<cli::OptionSpec> kWriteSpecs = {{"--quality", "", true},
                                                  {"--subsampling", "", true},
                                                  {"--bit-depth", "", true},
                                                  {"--colourspace", "", true},
                                                  {"--colourspace-out", "", true}};

void writeImageFile(const std::string& path, const py::array& pixels, const py::object& like,
                    const py::kwargs& keywords) {
  const ArrayImage in = viewOfArray(pixels, path + ": pixels");
  WriteImageOptions options;
  cli::parseWriteOptions(argsFromKeywords(keywords, kWriteSpecs), options);
  const ImageInfo* info = nullptr;
  if (!like.is_none()) {
    if (!py::isinstance<PyImage>(like))
      raiseValueError("like: expected an artcam.Image (from artcam.read_image)");
    info = &like.cast<const PyImage&>().stored->info;
  }
  Status s;
  {
    py::gil_scoped_release release;
    if (options.pixel_type.empty() && options.ocio_colour_space.empty() &&
        options.colour_space == WriteImageOptions::ColourSpace::Input &&
        storedWriteKeepsEncoding(path, in.view.type)) {
      s = writeStoredImage(path, in.view, info, options);
    } else {
      // Another kind of number (8-bit into EXR, float into PNG) or another encoding: through
      // linear light, as the CLI writes a re-encoded photo.
      const StoredEncoding encoding = info ? storedEncodingOf(*info)
                                      : in.view.type == PixelType::Float
                                          ? StoredEncoding()
                                          : StoredEncoding::ofTransfer(Transfer::srgb());
      ImageF linear = linearRgba(in.view, encoding);
      if (in.view.alpha_channel < 0) dropOpaqueAlpha(linear);
      s = writeImage(path, linear, info, options);
    }
  }
  if (!s) raiseOSError(s.message);
}

}  // namespace

void registerImages(py::module_& m) {
  py::class_<PyImage>(m, "Image", R"doc(
A photo as artcam reads it (artcam.read_image): `pixels` holds the stored numbers (uint8, uint16
or float32; H×W×C, turned upright by its EXIF orientation, alpha premultiplied), `info` what the
file said about itself. Pass it as write_image's `like` to keep its metadata, ICC profile,
quality and chroma subsampling in the output, as `artcam warp` does.)doc")
      .def_property_readonly("pixels", &pixelsOf,
                             "The pixels as an H×W×C numpy array over the image's own memory.")
      .def_property_readonly("info", &infoOf,
                             "What the file said: format, pixel_type, colour_space, orientation "
                             "(the stored raster's EXIF turn), icc_profile, jpeg_quality, "
                             "jpeg_subsampling, camera, lens, focal_mm, …")
      .def_property_readonly("width", [](const PyImage& i) { return i.stored->width; })
      .def_property_readonly("height", [](const PyImage& i) { return i.stored->height; })
      .def_property_readonly("channels", [](const PyImage& i) { return i.stored->channels; })
      .def("__repr__", [](const PyImage& i) {
        const StoredImage& s = *i.stored;
        return "<artcam.Image " + std::to_string(s.width) + "x" + std::to_string(s.height) + "x" +
               std::to_string(s.channels) + " " + s.info.pixel_type + " (" + s.info.path + ")>";
      });
  m.def(
      "finishes",
      [] {
        py::list out;
        for (const FinishInfo& f : finishes()) out.append(py::make_tuple(f.name, f.description));
        return out;
      },
      "The finishing marks Camera.warp(finish=...) and artcam warp --finish apply: (name, "
      "description) pairs.");
  m.def("read_image", &readImageFile, py::arg("path"), R"doc(
Reads a photo as `artcam warp` does (every format OpenImageIO reads; movies refused): the stored
numbers, upright. Raises FileNotFoundError for a missing file and ValueError naming the file and
the cause for one artcam cannot read.)doc");
  m.def("write_image", &writeImageFile, py::arg("path"), py::arg("pixels"), py::kw_only(),
        py::arg("like") = py::none(), R"doc(
Writes `pixels` (H×W×C uint8, uint16 or float32, alpha premultiplied) to `path` in the format its
extension names, atomically (written aside, checked, renamed: a failed write leaves no file).

like: an artcam.Image whose metadata, ICC profile, JPEG quality and subsampling to keep.
Keywords are the CLI's write options: quality=N, subsampling='444'|'422'|'420',
bit_depth='8'|'16'|'half'|'float', colourspace='input'|'srgb', colourspace_out=NAME.
Raises ValueError for a bad option (the CLI's message) and OSError when the write fails.)doc");
}

}  // namespace artcam::python
