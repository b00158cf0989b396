// SPDX-License-Identifier: Apache-2.0
// artcam.Camera: one camera value (core/model/artcam.h) read, written, mapped and rendered.
#include "core/io/artcam_file.h"
#include "core/pipeline/point_map.h"
#include "python/src/common.h"

#include <cmath>
#include <limits>

namespace artcam::python {
namespace {

py::tuple sizeTuple(FrameSize size) { return py::make_tuple(size.width, size.height); }

PyCamera readCamera(const std::string& path) {
  Result<Artcam> camera;
  {
    py::gil_scoped_release release;
    camera = readArtcam(path);
  }
  if (!camera) raiseReadError(path, camera.status.message);
  return {std::make_shared<const Artcam>(std::move(*camera.value)), path};
}

PyCamera cameraFromJson(const std::string& text, const std::string& name) {
  auto camera = parseArtcam(text, name);
  if (!camera) raiseValueError(camera.status.message);
  return {std::make_shared<const Artcam>(std::move(*camera.value)), name};
}

// N×2 source pixels → N×2 target pixels (N×L×2 for L layers); NaN where a point has no image.
py::array_t<double> mapPoints(const PyCamera& self, const py::array& points_in) {
  const auto points =
      py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points_in);
  if (!points || points.ndim() != 2 || points.shape(1) != 2)
    raiseValueError(self.name + ": map expects an N×2 array of source pixels (x, y)");
  const auto mapper = PointMapper::of(*self.camera, self.name);
  if (!mapper) raiseValueError(mapper.status.message);
  const py::ssize_t n = points.shape(0);
  const py::ssize_t layers = static_cast<py::ssize_t>(mapper->layers());
  std::vector<py::ssize_t> shape =
      layers == 1 ? std::vector<py::ssize_t>{n, 2} : std::vector<py::ssize_t>{n, layers, 2};
  py::array_t<double> out(shape);
  const double* in = points.data();
  double* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    for (py::ssize_t k = 0; k < n; ++k)
      for (py::ssize_t l = 0; l < layers; ++l) {
        const auto y = mapper->map(static_cast<size_t>(l), {in[2 * k], in[2 * k + 1]});
        const double nan = std::numeric_limits<double>::quiet_NaN();
        o[(k * layers + l) * 2] = y ? y->x() : nan;
        o[(k * layers + l) * 2 + 1] = y ? y->y() : nan;
      }
  }
  return out;
}

}  // namespace

void registerCameras(py::module_& m) {
  py::class_<PyCamera>(m, "Camera", R"doc(
An ARTcam: every output coordinate (position, colour, depth) a ratio of quadratic forms of the
input point. A value: read it from a .artcam file (artcam.read), make it (artcam.preset,
artcam.fit, artcam.compose, artcam.lens_camera), map points and warp images through it, write it.
Pickles as its .artcam text, so it ships to Dask workers as one small string.)doc")
      .def_property_readonly(
          "kind", [](const PyCamera& c) { return std::string(artcamKindName(c.camera->kind())); },
          "'single', 'chained', 'attributed', 'layered' or 'piecewise'.")
      .def_property_readonly(
          "layers", [](const PyCamera& c) { return c.camera->layers.size(); },
          "How many layers (3 for a chromatic-aberration camera, one per colour channel).")
      .def_property_readonly(
          "patches",
          [](const PyCamera& c) {
            return c.camera->pieces ? c.camera->pieces->patches.size() : size_t{0};
          },
          "How many patches a piecewise camera has (0 for any other).")
      .def_property_readonly(
          "source_size", [](const PyCamera& c) { return sizeTuple(c.camera->sourceSize()); },
          "(width, height) of the source frame the camera's source pixels are in.")
      .def_property_readonly(
          "target_size", [](const PyCamera& c) { return sizeTuple(c.camera->targetSize()); },
          "(width, height) of the target frame (the output's size for a photo of source_size).")
      .def_property_readonly(
          "frames",
          [](const PyCamera& c) {
            py::dict d;
            d["source"] = sizeTuple(c.camera->sourceSize());
            d["target"] = sizeTuple(c.camera->targetSize());
            return d;
          },
          "{'source': (w, h), 'target': (w, h)}: the frames of the .artcam file's \"frames\".")
      .def_property_readonly(
          "frame",
          [](const PyCamera& c) -> py::object {
            if (!c.camera->frame) return py::none();
            return py::str(std::string(cameraFrameName(*c.camera->frame)));
          },
          "'sensor' (made for the stored raster, e.g. a lens camera: applied before the EXIF "
          "turn), 'upright', or None when the file does not say.")
      .def_property_readonly(
          "name", [](const PyCamera& c) { return c.name; },
          "The file it was read from, or what made it.")
      .def(
          "to_json", [](const PyCamera& c) { return toArtcamJson(*c.camera); },
          "The camera as .artcam JSON text (what write() writes).")
      .def(
          "write",
          [](const PyCamera& c, const std::string& path) {
            Status s;
            {
              py::gil_scoped_release release;
              s = writeArtcam(path, *c.camera);
            }
            if (!s) raiseOSError(s.message);
          },
          py::arg("path"),
          "Writes the camera to `path` as a .artcam file (atomically: written aside, checked, "
          "renamed). Raises OSError naming the file and the cause.")
      .def("map", &mapPoints, py::arg("points"), R"doc(
Maps source pixels to target pixels, as `artcam map` does.

points: an N×2 array of (x, y) source pixels. Returns an N×2 float64 array of target pixels
(N×L×2 for a camera of L layers, one pair per layer). A point with no image (on the camera's
pole curve, or outside every patch of a piecewise camera, where warp renders nothing) is NaN.
Raises ValueError for a camera whose positions depend on colour or depth.)doc")
      .def("warp", &warpArray, py::arg("image"), py::kw_only(), py::arg("depth") = py::none(),
           py::arg("size") = py::none(), py::arg("filter") = "bilinear",
           py::arg("edge") = "transparent", py::arg("alpha") = false, py::arg("threads") = 0,
           py::arg("out") = py::none(), py::arg("finish") = py::none(),
           R"doc(
Renders `image` through the camera, as `artcam warp` renders a photo (same pixels).

image: an H×W or H×W×C array (C = 1..4; 2 and 4 have alpha last, premultiplied) of uint8,
  uint16 or float32, read in place (no copy) for cameras of position alone. Its rows may be
  strided (a crop of a bigger array) but each row's pixels must be packed: a non-contiguous
  array is refused (numpy.ascontiguousarray makes one).
depth: an H'×W' float32 depth map for cameras that read depth (stretched to the image's frame).
size: (width, height) of the output; default the output-frame rule: the image scaled by the
  camera's target frame / source frame (a warning when the image's aspect is not the camera's).
filter: 'nearest', 'bilinear' or 'bicubic'.
edge: 'transparent' (the last half pixel fades out), 'extend' (Hugin's nona and fulla) or 'black'.
alpha: add an alpha channel (pixels with no preimage transparent) when the image has none;
  without it such pixels are black (composited over black).
threads: render threads, 0 for all cores. The GIL is released while it renders.
out: an array to render into (its shape and dtype the output's), for cameras of position
  alone: a loop over frames that reuses one output array allocates nothing.
finish: marks after the render, as `artcam warp --finish`: 'pencil', 'charcoal', 'painting' or
  'cartoon' (artcam.finishes()).

Returns the output array (`out`, or a new one of the image's dtype). Raises ValueError for a wrong dtype or shape.)doc")
      .def("__repr__",
           [](const PyCamera& c) {
             const FrameSize s = c.camera->sourceSize(), t = c.camera->targetSize();
             return "<artcam.Camera " + std::string(artcamKindName(c.camera->kind())) + " " +
                    std::to_string(s.width) + "x" + std::to_string(s.height) + " -> " +
                    std::to_string(t.width) + "x" + std::to_string(t.height) + " (" + c.name + ")>";
           })
      .def(py::pickle(
          [](const PyCamera& c) { return py::make_tuple(toArtcamJson(*c.camera), c.name); },
          [](const py::tuple& t) {
            if (t.size() != 2) raiseValueError("artcam.Camera: bad pickle");
            return cameraFromJson(t[0].cast<std::string>(), t[1].cast<std::string>());
          }));

  m.def("read", &readCamera, py::arg("path"), R"doc(
Reads a .artcam camera file. Raises FileNotFoundError for a missing file and ValueError naming
the file and the place for a malformed one (the messages `artcam info` prints).)doc");
  m.def("from_json", &cameraFromJson, py::arg("text"), py::arg("name") = "<camera>",
        "A camera from .artcam JSON text; `name` is what its messages call it.");
}

}  // namespace artcam::python
