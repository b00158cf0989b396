// SPDX-License-Identifier: Apache-2.0
#include "core/project/project_render.h"

#include "core/effects/finish.h"

#include "core/depth/depth_raster.h"
#include "core/io/stored_image.h"
#include "core/pipeline/camera_frame.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <exception>
#include <stdexcept>
#include <vector>

namespace artcam {

ValidRect largestValidRect(const ImageF& image) {
  ValidRect best;
  if (image.empty()) return best;
  const int w = image.width, h = image.height, a = image.channels - 1;
  // Maximal rectangle in a binary matrix: per row, the heights of valid columns ending there,
  // then the largest rectangle under that histogram with a stack. O(w·h).
  std::vector<int> heights(static_cast<size_t>(w), 0);
  std::vector<int> stack;
  long long best_area = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x)
      heights[static_cast<size_t>(x)] =
          image.pixel(x, y)[a] >= 0.999f ? heights[static_cast<size_t>(x)] + 1 : 0;
    stack.clear();
    for (int x = 0; x <= w; ++x) {
      const int cur = x < w ? heights[static_cast<size_t>(x)] : 0;
      while (!stack.empty() && heights[static_cast<size_t>(stack.back())] >= cur) {
        const int top = heights[static_cast<size_t>(stack.back())];
        stack.pop_back();
        const int left = stack.empty() ? 0 : stack.back() + 1;
        const long long area = static_cast<long long>(top) * (x - left);
        if (area > best_area) {
          best_area = area;
          best = {left, y - top + 1, x, y + 1};
        }
      }
      stack.push_back(x);
    }
  }
  return best;
}

namespace {

ImageF crop(const ImageF& image, const ValidRect& r) {
  ImageF out(r.width(), r.height(), image.channels, image.alpha_channel);
  for (int y = 0; y < r.height(); ++y)
    for (int x = 0; x < r.width(); ++x) {
      const float* s = image.pixel(r.x0 + x, r.y0 + y);
      float* d = out.pixel(x, y);
      for (int c = 0; c < image.channels; ++c) d[c] = s[c];
    }
  return out;
}

// Premultiplied "over": the picture over the fill colour. Returns the pixels that were not
// opaque (the fill shows through them).
long long fillUnder(ImageF& image, const std::array<float, 4>& fill) {
  const int a = image.channels - 1;
  long long filled = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      float* p = image.pixel(x, y);
      const float rest = 1.0f - p[a];
      if (rest > 0.0f) ++filled;
      for (int c = 0; c < a; ++c) p[c] += rest * fill[static_cast<size_t>(std::min(c, 2))] * fill[3];
      p[a] += rest * fill[3];
    }
  return filled;
}

}  // namespace

bool outputHoldsAlpha(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return true;
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext != "jpg" && ext != "jpeg";
}

ExportOptions exportOptionsForOutput(ExportOptions options, const std::string& path) {
  if (!outputHoldsAlpha(path) && !options.fill && !options.crop_to_valid)
    options.fill = kFlattenFill;
  return options;
}

ImageF renderExport(const LoadedImage& loaded, const ImageF* depth, const Artcam& camera,
                    const ExportOptions& options, const std::function<bool(double)>& progress,
                    RenderSummary* summary, const ImageF* second) {
  const ImageF& photo = loaded.image;
  const StoredEncoding encoding = storedEncodingOf(loaded.info);
  RenderOptions render_options;
  render_options.warp.filter = options.filter;
  render_options.warp.edge = options.edge;
  render_options.warp.width = options.width;
  render_options.warp.height = options.height;
  render_options.warp.progress = progress;
  RenderSummary local;
  RenderSummary* s = summary ? summary : &local;
  // In the camera's frame (camera_frame.h): a lens camera corrects the stored raster, then the
  // result is turned upright.
  const int turn =
      turnAfterCamera(camera, {photo.width, photo.height}, loaded.info.stored_orientation);
  RenderInputs inputs = RenderInputs::of(photo, depth, &encoding);
  inputs.second = second && !second->empty() ? second : nullptr;
  ImageF out = renderTurned(inputs, camera, render_options, turn, s);
  if (s->cancelled || out.empty()) return out;
  if (!options.finish.empty())
    if (const Status marked = applyFinishLinear(out, encoding, options.finish); !marked)
      throw std::invalid_argument(marked.message);
  if (options.crop_to_valid) {
    const ValidRect r = largestValidRect(out);
    if (r.width() <= 0 || r.height() <= 0)
      throw std::invalid_argument("crop to the valid area: no pixel of the result is valid");
    if (r.width() != out.width || r.height() != out.height) {
      out = crop(out, r);
      s->note += std::string(s->note.empty() ? "" : "; ") + "cropped to the valid " +
                 std::to_string(r.width()) + "x" + std::to_string(r.height()) + " at (" +
                 std::to_string(r.x0) + ", " + std::to_string(r.y0) + ")";
      s->size = {r.width(), r.height()};
    }
    s->transparent_pixels = 0;  // every pixel of the valid rectangle has a preimage
  }
  if (options.fill) {
    // The summary speaks of the file written: a filled pixel is no longer transparent.
    const long long filled = fillUnder(out, *options.fill);
    if (filled > 0)
      s->note += std::string(s->note.empty() ? "" : "; ") + std::to_string(filled) +
                 " pixels without a preimage filled";
    if ((*options.fill)[3] >= 1.0f) s->transparent_pixels = 0;
  }
  // As every render of a photo without alpha: the added alpha goes again when it is opaque.
  if (photo.alpha_channel < 0) dropOpaqueAlpha(out);
  return out;
}

ImageF rasteriseProjectDepth(const std::vector<ProjectDepthLayer>& layers, FrameSize photo,
                             const ImageF* map, bool* has_depth) {
  bool any = map != nullptr && !map->empty();
  std::vector<DepthLayer> raster_layers;
  for (const ProjectDepthLayer& l : layers) {
    DepthLayer d{&l.mask, std::nullopt};
    if (l.anchors.size() == static_cast<size_t>(kMaxDepthAnchors)) {
      const Result<InverseDepthPlane> plane =
          planeFromAnchors({l.anchors[0], l.anchors[1], l.anchors[2]});
      if (plane) d.plane = *plane;
    }
    if (d.plane && l.mask.coveredCount() > 0) any = true;
    // A mask not of the photo's size (the photo changed since it was painted) is left out, as
    // the studio does when it opens the project.
    if (l.mask.width() == photo.width && l.mask.height() == photo.height)
      raster_layers.push_back(d);
  }
  if (has_depth) *has_depth = any;
  if (!any || !photo.isImage()) return {};
  return rasteriseDepth(raster_layers, photo.width, photo.height, map);
}

ImageF depthMapImage(const ImageF& raster) {
  ImageF out(raster.width, raster.height, 1, -1);
  for (int y = 0; y < raster.height; ++y)
    for (int x = 0; x < raster.width; ++x) {
      const std::optional<double> z = depthAt(raster, x, y);
      out.pixel(x, y)[0] = z ? static_cast<float>(*z) : 0.0f;
    }
  return out;
}

Status writeDepthMapFile(const std::string& path, const ImageF& raster,
                         const std::function<bool(double)>& progress) {
  WriteImageOptions options;
  options.pixel_type = "float";
  options.channel_names = {"Z"};
  options.progress = progress;
  return writeImage(path, depthMapImage(raster), nullptr, options);
}

Result<ProjectScene> loadProjectScene(const StudioProject& project, const std::string& where,
                                      const ReadImageOptions& photo_read) {
  using R = Result<ProjectScene>;
  ProjectScene scene;
  // The whole document against the budget from the photo's header, before it is decoded.
  {
    Result<StoredShape> shape = readStoredShape(project.photo_path);
    if (!shape) return R::failure(where + ": photo: " + shape.status.message);
    if (const Status fits =
            checkProjectMemory(project, {shape->width, shape->height}, shape->channels, where);
        !fits)
      return R::failure(fits.message);
  }
  Result<LoadedImage> photo = readImage(project.photo_path, photo_read);
  if (!photo) return R::failure(where + ": photo: " + photo.status.message);
  scene.photo = std::move(*photo.value);
  const FrameSize frame{scene.photo.image.width, scene.photo.image.height};
  ImageF map;
  if (project.depth_map) {
    Result<ImageF> read = readDepthFile(project.depth_map->path, project.depth_map->options);
    if (!read) return R::failure(where + ": depth map: " + read.status.message);
    map = std::move(*read.value);
  }
  bool has_depth = false;
  scene.depth = rasteriseProjectDepth(project.depth_layers, frame, map.empty() ? nullptr : &map,
                                      &has_depth);
  Result<std::optional<Camera>> colour = projectColourBlock(project, where);
  if (!colour) return R::failure(colour.status.message);
  DocumentFitInputs in;
  in.frame = frame;
  in.matches = project.pairs;
  in.lines = project.lines;
  in.model = project.model;
  in.line_model = project.line_model;
  if (project.manual_camera) in.manual_camera = project.manual_camera->main();
  in.colour_block = *colour.value;
  scene.fit = fitDocumentGeometry(in);
  std::string base_note;
  Artcam base;
  try {
    base = documentBase(project.manual_camera, scene.fit.camera, *colour.value, &base_note);
  } catch (const std::exception& e) {
    return R::failure(where + ": /camera: " + e.what());
  }
  if (project.second_path) {
    Result<LoadedImage> second = readImage(*project.second_path);
    if (!second) return R::failure(where + ": second image: " + second.status.message);
    scene.second = std::move(second->image);
  }
  scene.camera =
      assembleDocumentArtcam(base, project.effects, frame, has_depth, !scene.second.empty());
  if (!base_note.empty())
    scene.camera.note = base_note + (scene.camera.note.empty() ? "" : "; " + scene.camera.note);
  // As the render front door says of `warp --depth`: a map of another aspect is stretched.
  if (const std::string stretched = depthMapAspectNote({map.width, map.height}, frame);
      !map.empty() && !stretched.empty())
    scene.camera.note = (scene.camera.note.empty() ? "" : scene.camera.note + "; ") +
                        project.depth_map->path + ": " + stretched;
  // The second image lies over the photo's frame: another size is stretched to it, and said.
  if (const std::string stretched =
          scene.second.empty()
              ? std::string()
              : secondImageSizeNote({scene.second.width, scene.second.height}, frame);
      !stretched.empty())
    scene.camera.note = (scene.camera.note.empty() ? "" : scene.camera.note + "; ") +
                        *project.second_path + ": " + stretched;
  return R::success(std::move(scene));
}

}  // namespace artcam
