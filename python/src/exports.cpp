// SPDX-License-Identifier: Apache-2.0
// artcam.export_map (the ST maps of `artcam export-map`, as arrays or a file) and
// artcam.export_project (a saved studio project rendered as `artcam export` renders it).
#include "app/cli/project_export.h"
#include "core/io/stmap_file.h"
#include "core/pipeline/source_maps.h"
#include "python/src/common.h"

namespace artcam::python {
namespace {

py::array_t<float> exportMap(const PyCamera& camera, const py::object& size_in,
                             const std::string& convention_name, const py::object& source_size,
                             const py::object& path) {
  const FrameSize size = sizeArgument(size_in, "size");
  const auto convention = stmapConventionFromName(convention_name);
  if (!convention)
    raiseValueError("convention expects stmap or opencv, not \"" + convention_name + "\"");
  // As export-map: the maps are held whole (9 bytes a pixel a layer), at most 2^27 pixels.
  const long long pixels = static_cast<long long>(size.width) * size.height *
                           static_cast<long long>(camera.camera->layers.size());
  if (pixels > kMaxSourceMapPixels)
    raiseValueError("size is too large for a map (at most 2^27 pixels in all layers)");
  SourceMapsOptions options;
  if (!source_size.is_none()) options.source_px = sizeArgument(source_size, "source_size");
  Result<SourceMaps> maps;
  {
    py::gil_scoped_release release;
    maps = sourceMaps(*camera.camera, size, options);
  }
  if (!maps) raiseValueError(camera.name + ": " + maps.status.message);
  const int per_layer = stmapChannelCount(*convention);
  const size_t layers = maps->layers.size();
  py::array_t<float> out(std::vector<py::ssize_t>{size.height, size.width,
                                                  static_cast<py::ssize_t>(per_layer * layers)});
  float* p = out.mutable_data();
  {
    py::gil_scoped_release release;
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x)
        for (const SourceMapLayer& layer : maps->layers) {
          stmapPixel(layer.map, layer.map.index(x, y), *convention, p);
          p += per_layer;
        }
  }
  if (!path.is_none()) {
    const std::string file = pathOf(path);
    std::vector<StmapLayer> files;
    for (const SourceMapLayer& layer : maps->layers) files.push_back({layer.name, &layer.map});
    Status s;
    {
      py::gil_scoped_release release;
      s = writeStmap(file, files, *convention);
    }
    if (!s) raiseOSError(s.message);
  }
  return out;
}

py::dict exportProject(const std::string& project_path, const std::string& output,
                       const py::kwargs& keywords) {
  const cli::Args args = argsFromKeywords(keywords, cli::projectExportOptions(), {project_path});
  cli::ProjectExport done;
  {
    py::gil_scoped_release release;
    done = cli::exportProject(args, output, {}, {}, {});
  }
  // export --json's object, with the camera itself under "camera" and its kind under "kind".
  py::dict report = fromJson(cli::projectExportJson(done));
  report["kind"] = report["camera"];
  report["camera"] = PyCamera{std::make_shared<const Artcam>(std::move(done.camera)), project_path};
  return report;
}

}  // namespace

void registerExports(py::module_& m) {
  m.def("export_map", &exportMap, py::arg("camera"), py::arg("size"), py::kw_only(),
        py::arg("convention") = "stmap", py::arg("source_size") = py::none(),
        py::arg("path") = py::none(), R"doc(
The camera's inverse map for a `size` = (width, height) output, as `artcam export-map` writes it:
for each output pixel where `artcam warp` reads the photo.

convention: 'stmap' (Nuke/Fusion/Resolve STMap: channels R = x / W, G = 1 - y / H, B = 0,
  A = 1 where the pixel reads the photo) or 'opencv' (cv::remap's map_x, map_y; -1 where there
  is no preimage).
source_size: the photo the map will warp (default the camera's source frame).
path: also write the map there (.exr, atomically, with the header export-map writes).

Returns an H×W×C float32 array (C = 4 or 2; a per-channel camera, e.g. chromatic aberration,
holds one map per colour channel side by side: C = 12 or 6, in R, G, B order). With the opencv
convention `cv2.remap(photo, m[..., 0], m[..., 1], cv2.INTER_LINEAR)` warps as the camera does.
Raises ValueError for a camera no map can carry (positions that read colour or depth, 3D).)doc");
  m.def("export_project", &exportProject, py::arg("project"), py::arg("out"), R"doc(
Renders a saved studio project (.artcamproj) into `out`, as `artcam export PROJECT -o OUT` does
(the studio's File > Export: the same pixels). Keywords are export's options: photo (the photo's
new place if it moved), size ((w, h), one side 0 for the aspect), filter, edge, quality,
subsampling, bit_depth, colourspace, colourspace_in, colourspace_out, crop_valid, fill
("r,g,b[,a]"), finish (marks over the project's own finish; 'none' without), camera_out and
depth_out (also write the project's camera and depth), overwrite.

Returns `artcam export --json`'s object as a dict (output, width, height, description,
render_ms, effects, effects_applied, warning, camera_out, depth_out) with the camera's kind under
'kind' and 'camera' the project's camera as an artcam.Camera. Raises OSError for a missing or
unreadable file or an output that exists, ValueError for a bad option or project.)doc");
}

}  // namespace artcam::python
