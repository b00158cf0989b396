// SPDX-License-Identifier: Apache-2.0
#include "core/project/studio_project.h"

#include "core/effects/finish.h"
#include "core/io/artcam_file.h"
#include "core/io/atomic_file.h"
#include "core/io/io_text.h"
#include "core/io/text_input.h"
#include "core/util/base64.h"
#include "core/util/memory_budget.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace artcam {
namespace {

using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

// Unwinds from deep inside the reader; becomes a Result at the API boundary.
struct Refusal {
  std::string message;  // "<json path>: <cause>"
};

[[noreturn]] void refuse(const std::string& path, const std::string& cause) {
  throw Refusal{path + ": " + cause};
}

// A value quoted for a one-line message: JSON-escaped and cut, so a "\n" in a string cannot
// split the message.
std::string describe(const Json& j) {
  if (j.is_object()) return "an object";
  if (j.is_array()) return "an array";
  std::string text = j.dump(-1, ' ', false, Json::error_handler_t::replace);
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return text;
}

double finiteNumber(const Json& j, const std::string& path, const char* what = "a number") {
  if (!j.is_number()) refuse(path, std::string("expected ") + what + ", found " + describe(j));
  const double v = j.get<double>();
  if (!std::isfinite(v)) refuse(path, "not a finite number");
  return v;
}

// Pairs, line points and depth anchors: pixels, held to the bound every match reader keeps.
Eigen::Vector2d pointAt(const Json& j, const std::string& path) {
  if (!j.is_array() || j.size() != 2 || !j[0].is_number() || !j[1].is_number())
    refuse(path, "expected [x, y]");
  const Eigen::Vector2d p{finiteNumber(j[0], path), finiteNumber(j[1], path)};
  for (int k = 0; k < 2; ++k)
    if (std::abs(p[k]) > kMaxMatchValue)
      refuse(path + "/" + std::to_string(k),
             describe(j[k]) + " is beyond any pixel coordinate (|value| > 1e9)");
  return p;
}

std::string stringAt(const Json& j, const std::string& path) {
  if (!j.is_string()) refuse(path, "expected a string, found " + describe(j));
  return j.get<std::string>();
}

const Json& objectAt(const Json& j, const std::string& path) {
  if (!j.is_object()) refuse(path, "expected an object, found " + describe(j));
  return j;
}

const Json& arrayAt(const Json& j, const std::string& path) {
  if (!j.is_array()) refuse(path, "expected an array, found " + describe(j));
  return j;
}

// A depth mask larger than this is refused before it is allocated: 2^30 pixels is beyond any
// photo the studio edits, and a few bytes of runs must not be able to ask for gigabytes.
constexpr std::uint64_t kMaxMaskPixels = std::uint64_t{1} << 30;

// Pixels the run bytes cover, read with region_mask.h's grammar (a value byte, then the run
// length as a little-endian base-128 varint) without allocating; nullopt when malformed.
std::optional<std::uint64_t> pixelsCoveredByRuns(const std::vector<uint8_t>& runs) {
  std::uint64_t covered = 0;
  size_t i = 0;
  while (i < runs.size()) {
    ++i;  // the value byte
    std::uint64_t run = 0;
    for (int shift = 0;; shift += 7) {
      if (i >= runs.size() || shift > 35) return std::nullopt;
      const uint8_t b = runs[i++];
      run |= static_cast<std::uint64_t>(b & 0x7f) << shift;
      if (!(b & 0x80)) break;
    }
    covered += run;  // at most 2^42 per run: no overflow for any file that fits in memory
  }
  return covered;
}

// What a document of these masks (pixels each) and a photo of `photo_pixels` pixels of
// `channels` channels holds at its peak: the masks, one more for the mask being decoded
// (decodeMaskRuns builds it beside the result) and the photo with its depth raster (the float
// copy as image_checks::claimedSize counts it: at least the 4 channels of a render).
double documentBytes(const std::vector<std::uint64_t>& mask_pixels, double photo_pixels,
                     int channels) {
  double masks = 0.0, largest = 0.0;
  for (const std::uint64_t n : mask_pixels) {
    masks += static_cast<double>(n);
    largest = std::max(largest, static_cast<double>(n));
  }
  const double photo_bytes_per_pixel =
      kProjectPhotoBytesPerPixel - 16.0 + 4.0 * std::max(4, channels);
  return masks + largest + photo_pixels * photo_bytes_per_pixel;
}

std::string budgetRefusal(const std::vector<std::uint64_t>& mask_pixels, double photo_pixels,
                          const std::string& photo_what, double bytes) {
  double masks = 0.0;
  for (const std::uint64_t n : mask_pixels) masks += static_cast<double>(n);
  std::string text = std::to_string(mask_pixels.size()) + " depth mask" +
                     (mask_pixels.size() == 1 ? "" : "s") + " (" + describeBytes(masks) + ")";
  if (photo_pixels > 0.0) text += " and " + photo_what;
  return text + " need " + describeBytes(bytes) + ", more than " + describeMemoryBudget();
}

// The masks' sizes as the JSON states them, against the budget before any is decoded: the
// photo they were painted on is their size, so the largest stands for it until its header is
// read (checkProjectMemory). Malformed sizes are left to depthLayerAt's refusal.
void checkMaskMemory(const Json& layers) {
  std::vector<std::uint64_t> pixels;
  std::uint64_t largest = 0;
  for (const Json& o : layers) {
    if (!o.is_object() || !o.contains("size")) continue;
    const Json& size = o["size"];
    if (!size.is_array() || size.size() != 2 || !size[0].is_number_unsigned() ||
        !size[1].is_number_unsigned())
      continue;
    const std::uint64_t w = size[0].get<std::uint64_t>(), h = size[1].get<std::uint64_t>();
    // Beyond one mask's limit: depthLayerAt's refusal names that layer's size.
    if (w > (1u << 30) || h > (1u << 30) || w * h > kMaxMaskPixels) continue;
    pixels.push_back(w * h);
    largest = std::max(largest, w * h);
  }
  const double bytes = documentBytes(pixels, static_cast<double>(largest), 4);
  if (bytes > memoryBudgetBytes())
    refuse("/depth/layers",
           budgetRefusal(pixels, static_cast<double>(largest),
                         std::string("the photo ") + (pixels.size() == 1 ? "it was" : "they were") +
                             " painted on (float, with its depth)",
                         bytes));
}

std::string pathForFile(const std::string& path, const std::string& project_path) {
  std::error_code ec;
  const fs::path base = fs::absolute(fs::path(project_path), ec).parent_path();
  const fs::path relative = fs::path(path).lexically_relative(base);
  if (relative.empty() || *relative.begin() == "..") return path;
  return relative.generic_string();
}

std::string pathFromFile(const std::string& path, const std::string& project_path) {
  const fs::path p(path);
  if (p.is_absolute()) return path;
  std::error_code ec;
  const fs::path base = fs::absolute(fs::path(project_path), ec).parent_path();
  return (base / p).lexically_normal().string();
}

ProjectDepthLayer depthLayerAt(const Json& o, const std::string& where) {
  objectAt(o, where);
  ProjectDepthLayer l;
  if (o.contains("name")) l.name = stringAt(o["name"], where + "/name");
  const Json& size = o.contains("size") ? o["size"] : Json();
  if (!size.is_array() || size.size() != 2 || !size[0].is_number_integer() ||
      !size[1].is_number_integer())
    refuse(where + "/size", "expected [width, height]");
  const long long width = size[0].get<long long>(), height = size[1].get<long long>();
  if (width < 0 || height < 0 || width > (1 << 30) || height > (1 << 30))
    refuse(where + "/size", "expected [width, height] of whole numbers ≥ 0");
  const auto pixels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  if (pixels > kMaxMaskPixels)
    refuse(where + "/size", std::to_string(width) + "x" + std::to_string(height) +
                                " is larger than the 2^30-pixel limit of a mask");
  const std::string text = o.contains("mask") ? stringAt(o["mask"], where + "/mask") : "";
  const auto runs = decodeBase64(text);
  if (!runs) refuse(where + "/mask", "not base64");
  const auto covered = pixelsCoveredByRuns(*runs);
  if (!covered) refuse(where + "/mask", "truncated or malformed run lengths");
  if (pixels > 0 && *covered != pixels)
    refuse(where + "/mask", "runs cover " + std::to_string(*covered) + " of " +
                                std::to_string(pixels) + " pixels");
  Result<RegionMask> mask = decodeMaskRuns(*runs, static_cast<int>(width),
                                           static_cast<int>(height), where + "/mask");
  if (!mask) throw Refusal{mask.status.message};
  l.mask = std::move(*mask.value);
  if (o.contains("anchors")) {
    const Json& anchors = arrayAt(o["anchors"], where + "/anchors");
    if (anchors.size() > static_cast<size_t>(kMaxDepthAnchors))
      refuse(where + "/anchors", "at most 3 depth points");
    for (size_t k = 0; k < anchors.size(); ++k) {
      const std::string at = where + "/anchors/" + std::to_string(k);
      const Json& a = objectAt(anchors[k], at);
      const Eigen::Vector2d pixel = pointAt(a.contains("pixel") ? a["pixel"] : Json(), at + "/pixel");
      const double z = a.contains("depth") && a["depth"].is_number() ? a["depth"].get<double>() : -1;
      if (!(z > 0.0) || !std::isfinite(z))
        refuse(at + "/depth", "expected a number greater than 0");
      l.anchors.push_back({pixel, z});
    }
  }
  return l;
}

EffectStep effectStepAt(const Json& o, const std::string& where) {
  objectAt(o, where);
  EffectStep step;
  step.effect = stringAt(o.contains("effect") ? o["effect"] : Json(), where + "/effect");
  const EffectSpec* spec = findEffect(step.effect);
  if (!spec) refuse(where + "/effect", "unknown effect " + describe(o["effect"]));
  if (!o.contains("params")) return step;
  const Json& params = objectAt(o["params"], where + "/params");
  for (const auto& [name, value] : params.items()) {
    const std::string at = where + "/params/" + name;
    const EffectParam* param = findParam(*spec, name);
    if (!param) refuse(at, "not a parameter of " + step.effect);
    std::vector<double> numbers;
    if (value.is_number()) {
      numbers.push_back(finiteNumber(value, at));
    } else {
      const Json& array = arrayAt(value, at);
      for (size_t k = 0; k < array.size(); ++k)
        numbers.push_back(finiteNumber(array[k], at + "/" + std::to_string(k)));
    }
    if (const std::string problem = checkEffectValue(*param, numbers); !problem.empty())
      refuse(at, problem);
    step.values[name] = std::move(numbers);
  }
  return step;
}

Artcam cameraAt(const Json& j, const std::string& file, const std::string& where) {
  objectAt(j, where);
  Result<Artcam> camera = parseArtcam(j.dump(), file + ": " + where);
  if (!camera) throw Refusal{camera.status.message.substr(file.size() + 2)};
  return std::move(*camera.value);
}

StudioProject projectAt(const Json& root, const std::string& file,
                        const std::string& project_path) {
  objectAt(root, "/");
  if (!root.contains("format") || root["format"] != "artcam-studio-project")
    refuse("/format", "not an ARTcam Studio project");
  if (!root.contains("version") || !root["version"].is_number_integer())
    refuse("/version", "missing or not a number");
  const long long version = root["version"].get<long long>();
  if (version < 1) refuse("/version", "missing or not a number");
  if (version > kProjectFormatVersion)
    throw Refusal{"written by a newer ARTcam Studio (project version " + std::to_string(version) +
                  "; this one reads up to " + std::to_string(kProjectFormatVersion) + ")"};
  StudioProject p;
  const std::string photo = root.contains("photo") ? stringAt(root["photo"], "/photo") : "";
  if (photo.empty()) refuse("/photo", "missing photo path");
  p.photo_path = pathFromFile(photo, project_path);
  if (root.contains("photo_size")) {
    const Json& size = root["photo_size"];
    if (!size.is_array() || size.size() != 2 || !size[0].is_number_integer() ||
        !size[1].is_number_integer() || size[0].get<long long>() < 1 ||
        size[1].get<long long>() < 1 || size[0].get<long long>() > (1 << 30) ||
        size[1].get<long long>() > (1 << 30))
      refuse("/photo_size", "expected [width, height] of whole numbers ≥ 1");
    p.photo_size = FrameSize{static_cast<int>(size[0].get<long long>()),
                             static_cast<int>(size[1].get<long long>())};
  }
  if (root.contains("model")) {
    const std::string name = stringAt(root["model"], "/model");
    const auto model = modelClassFromName(name);
    if (!model) refuse("/model", "unknown model " + describe(root["model"]));
    p.model = *model;
  }
  if (root.contains("line_model")) {
    const auto line_model = lineModelFromName(stringAt(root["line_model"], "/line_model"));
    if (!line_model)
      refuse("/line_model",
             "unknown line model " + describe(root["line_model"]) + " (auto, radial or quadratic)");
    p.line_model = *line_model;
  }
  if (root.contains("pairs")) {
    const Json& pairs = arrayAt(root["pairs"], "/pairs");
    for (size_t i = 0; i < pairs.size(); ++i) {
      const std::string where = "/pairs/" + std::to_string(i);
      const Json& o = objectAt(pairs[i], where);
      PointMatch m;
      m.source = pointAt(o.contains("source") ? o["source"] : Json(), where + "/source");
      m.target = pointAt(o.contains("target") ? o["target"] : Json(), where + "/target");
      if (o.contains("enabled")) {
        if (!o["enabled"].is_boolean()) refuse(where + "/enabled", "expected true or false");
        m.enabled = o["enabled"].get<bool>();
      }
      p.pairs.push_back(std::move(m));
    }
  }
  if (root.contains("lines")) {
    const Json& lines = arrayAt(root["lines"], "/lines");
    for (size_t i = 0; i < lines.size(); ++i) {
      const std::string where = "/lines/" + std::to_string(i);
      const Json& o = objectAt(lines[i], where);
      LineTrace line;
      line.label = o.contains("label") ? stringAt(o["label"], where + "/label") : std::to_string(i + 1);
      if (!o.contains("points")) refuse(where + "/points", "missing");
      const Json& points = arrayAt(o["points"], where + "/points");
      for (size_t k = 0; k < points.size(); ++k)
        line.points.push_back(pointAt(points[k], where + "/points/" + std::to_string(k)));
      if (o.contains("enabled")) {
        if (!o["enabled"].is_boolean()) refuse(where + "/enabled", "expected true or false");
        line.enabled = o["enabled"].get<bool>();
      }
      if (o.contains("role")) {
        const std::string role = stringAt(o["role"], where + "/role");
        if (role == "horizontal")
          line.role = LineRole::Horizontal;
        else if (role == "vertical")
          line.role = LineRole::Vertical;
        else if (role != "none")
          refuse(where + "/role",
                 "unknown role " + describe(o["role"]) + " (horizontal, vertical or none)");
      }
      p.lines.push_back(std::move(line));
    }
  }
  if (root.contains("camera")) p.manual_camera = cameraAt(root["camera"], file, "/camera");
  if (root.contains("effects")) {
    const Json& effects = arrayAt(root["effects"], "/effects");
    if (effects.size() > kMaxProjectEffects)
      refuse("/effects", std::to_string(effects.size()) + " effects, more than the " +
                             std::to_string(kMaxProjectEffects) + " a stack may hold");
    for (size_t i = 0; i < effects.size(); ++i)
      p.effects.push_back(effectStepAt(effects[i], "/effects/" + std::to_string(i)));
  }
  if (root.contains("second")) {
    const Json& second = objectAt(root["second"], "/second");
    const std::string path =
        second.contains("path") ? stringAt(second["path"], "/second/path") : "";
    if (path.empty()) refuse("/second/path", "missing");
    p.second_path = pathFromFile(path, project_path);
  }
  if (root.contains("finish")) {
    p.finish = stringAt(root["finish"], "/finish");
    if (!finishByName(p.finish)) {
      std::string names;
      for (const FinishInfo& f : finishes()) names += (names.empty() ? "" : ", ") + f.name;
      refuse("/finish", "unknown finish " + describe(root["finish"]) + " (" + names + ")");
    }
  }
  if (root.contains("view")) p.view_json = objectAt(root["view"], "/view").dump();
  if (root.contains("parts")) p.parts_json = objectAt(root["parts"], "/parts").dump();
  if (root.contains("depth")) {
    const Json& depth = objectAt(root["depth"], "/depth");
    if (depth.contains("layers")) {
      const Json& layers = arrayAt(depth["layers"], "/depth/layers");
      checkMaskMemory(layers);
      for (size_t i = 0; i < layers.size(); ++i)
        p.depth_layers.push_back(depthLayerAt(layers[i], "/depth/layers/" + std::to_string(i)));
    }
    if (depth.contains("map")) {
      const Json& m = objectAt(depth["map"], "/depth/map");
      ProjectDepthMap ref;
      const std::string path = m.contains("path") ? stringAt(m["path"], "/depth/map/path") : "";
      if (path.empty()) refuse("/depth/map/path", "missing");
      ref.path = pathFromFile(path, project_path);
      if (m.contains("scale")) {
        ref.options.scale = finiteNumber(m["scale"], "/depth/map/scale");
        if (!(ref.options.scale > 0.0))
          refuse("/depth/map/scale", "expected a number greater than 0");
      }
      if (m.contains("inverse")) {
        if (!m["inverse"].is_boolean()) refuse("/depth/map/inverse", "expected true or false");
        ref.options.inverse = m["inverse"].get<bool>();
      }
      p.depth_map = ref;
    }
  }
  return p;
}

Json pointJson(const Eigen::VectorXd& p) { return Json::array({p.x(), p.y()}); }

}  // namespace

Status checkProjectMemory(const StudioProject& project, FrameSize photo, int photo_channels,
                          const std::string& where) {
  std::vector<std::uint64_t> pixels;
  for (const ProjectDepthLayer& l : project.depth_layers)
    pixels.push_back(static_cast<std::uint64_t>(l.mask.width()) *
                     static_cast<std::uint64_t>(l.mask.height()));
  const double photo_pixels = static_cast<double>(std::max(0, photo.width)) *
                              static_cast<double>(std::max(0, photo.height));
  const double bytes = documentBytes(pixels, photo_pixels, photo_channels);
  if (bytes <= memoryBudgetBytes()) return Status::success();
  return Status::failure(where + ": photo: " +
                         budgetRefusal(pixels, photo_pixels,
                                       "the " + std::to_string(photo.width) + "x" +
                                           std::to_string(photo.height) +
                                           " photo (float, with its depth)",
                                       bytes));
}

std::optional<FrameSize> projectPhotoSize(const StudioProject& project) {
  if (project.photo_size) return project.photo_size;
  if (!project.depth_layers.empty())
    return FrameSize{project.depth_layers.front().mask.width(),
                     project.depth_layers.front().mask.height()};
  if (project.manual_camera && project.manual_camera->main().sourceSize().isImage())
    return project.manual_camera->main().sourceSize();
  return std::nullopt;
}

Status checkProjectPhotoSize(const StudioProject& project, FrameSize photo,
                             const std::string& photo_path, const std::string& where) {
  const std::optional<FrameSize> made_on = projectPhotoSize(project);
  if (!made_on || (made_on->width == photo.width && made_on->height == photo.height))
    return Status::success();
  const auto size = [](FrameSize f) {
    return std::to_string(f.width) + "x" + std::to_string(f.height);
  };
  return Status::failure(where + ": " + photo_path + " is " + size(photo) +
                         " but the project was made on a " + size(*made_on) +
                         " photo (its pairs and masks are that photo's pixels)");
}

Result<std::optional<Camera>> projectColourBlock(const StudioProject& project,
                                                 const std::string& where) {
  using R = Result<std::optional<Camera>>;
  if (project.parts_json.empty()) return R::success(std::nullopt);
  const Json parts = Json::parse(project.parts_json, nullptr, false);
  if (!parts.is_object() || !parts.contains("colour") || !parts["colour"].is_object() ||
      !parts["colour"].contains("colour_block"))
    return R::success(std::nullopt);
  try {
    const Artcam block = cameraAt(parts["colour"]["colour_block"], where,
                                  "/parts/colour/colour_block");
    if (block.layers.size() != 1 || block.pieces)
      return R::failure(where + ": /parts/colour/colour_block: expected one camera, found a " +
                        std::string(artcamKindName(block.kind())) + " camera");
    return R::success(block.main());
  } catch (const Refusal& refusal) {
    return R::failure(where + ": " + refusal.message);
  }
}

Result<StudioProject> parseStudioProject(std::string_view text, const std::string& project_path) {
  const std::string file = fs::path(project_path).filename().string();
  // A little deeper than a camera may nest, so an embedded camera's own check names its place.
  constexpr int kMaxProjectDepth = 64 + 4;
  if (const size_t deep = io_text::jsonTooDeepAt(text, kMaxProjectDepth);
      deep != std::string_view::npos)
    return Result<StudioProject>::failure(
        file + ": " + io_text::jsonPositionOf(text, deep + 1) + ": nested deeper than " +
        std::to_string(kMaxProjectDepth) + " levels (not an ARTcam Studio project)");
  Json root;
  try {
    root = Json::parse(text.begin(), text.end());
  } catch (const Json::exception& e) {
    std::string cause = e.what();
    // Drop nlohmann's "[json.exception.parse_error.101] " prefix; keep its line and column.
    if (const size_t at = cause.find("] "); at != std::string::npos) cause = cause.substr(at + 2);
    return Result<StudioProject>::failure(file + ": not valid JSON: " + cause);
  }
  try {
    return Result<StudioProject>::success(projectAt(root, file, project_path));
  } catch (const Refusal& refusal) {
    return Result<StudioProject>::failure(file + ": " + refusal.message);
  } catch (const Json::exception& e) {
    return Result<StudioProject>::failure(file + ": unreadable: " + e.what());
  }
}

Result<StudioProject> readStudioProject(const std::string& path) {
  Result<std::string> text = readTextInput(path);
  if (!text) return Result<StudioProject>::failure(text.status.message);
  return parseStudioProject(*text.value, path);
}

std::string studioProjectToJson(const StudioProject& project, const std::string& project_path) {
  Json root;
  root["format"] = "artcam-studio-project";
  const bool has_depth = !project.depth_layers.empty() || project.depth_map.has_value();
  const int version = project.second_path || !project.finish.empty()                    ? 5
                      : !project.lines.empty() || project.line_model != LineModel::Auto ? 4
                      : !project.effects.empty()                                        ? 3
                      : has_depth || !project.parts_json.empty()                        ? 2
                                                                                        : 1;
  root["version"] = version;
  if (!project.parts_json.empty()) root["parts"] = Json::parse(project.parts_json);
  root["photo"] = pathForFile(project.photo_path, project_path);
  if (project.photo_size)
    root["photo_size"] = Json::array({project.photo_size->width, project.photo_size->height});
  root["model"] = std::string(modelClassName(project.model));
  if (project.line_model != LineModel::Auto)
    root["line_model"] = std::string(lineModelName(project.line_model));
  Json pairs = Json::array();
  for (const PointMatch& m : project.pairs)
    pairs.push_back({{"source", pointJson(m.source)},
                     {"target", pointJson(m.target)},
                     {"enabled", m.enabled}});
  root["pairs"] = pairs;
  if (!project.lines.empty()) {
    Json lines = Json::array();
    for (const LineTrace& line : project.lines) {
      Json points = Json::array();
      for (const Eigen::Vector2d& q : line.points) points.push_back(pointJson(q));
      Json entry = {{"label", line.label}, {"points", points}, {"enabled", line.enabled}};
      if (line.role != LineRole::None)
        entry["role"] = line.role == LineRole::Horizontal ? "horizontal" : "vertical";
      lines.push_back(std::move(entry));
    }
    root["lines"] = lines;
  }
  if (project.manual_camera) root["camera"] = Json::parse(toArtcamJson(*project.manual_camera));
  if (!project.effects.empty()) {
    Json effects = Json::array();
    for (const EffectStep& step : project.effects) {
      Json params = Json::object();
      for (const auto& [name, values] : step.values) params[name] = values;
      effects.push_back({{"effect", step.effect}, {"params", params}});
    }
    root["effects"] = effects;
  }
  if (project.second_path)
    root["second"] = {{"path", pathForFile(*project.second_path, project_path)}};
  if (!project.finish.empty()) root["finish"] = project.finish;
  if (!project.view_json.empty()) root["view"] = Json::parse(project.view_json);
  if (has_depth) {
    Json depth;
    Json layers = Json::array();
    for (const ProjectDepthLayer& l : project.depth_layers) {
      Json anchors = Json::array();
      for (const DepthAnchor& a : l.anchors)
        anchors.push_back({{"pixel", Json::array({a.pixel.x(), a.pixel.y()})}, {"depth", a.depth}});
      layers.push_back({{"name", l.name},
                        {"size", Json::array({l.mask.width(), l.mask.height()})},
                        {"mask", encodeBase64(encodeMaskRuns(l.mask))},
                        {"anchors", anchors}});
    }
    depth["layers"] = layers;
    if (project.depth_map)
      depth["map"] = {{"path", pathForFile(project.depth_map->path, project_path)},
                      {"scale", project.depth_map->options.scale},
                      {"inverse", project.depth_map->options.inverse}};
    root["depth"] = depth;
  }
  // nlohmann writes the shortest decimal that reads back to the same double.
  return root.dump(2) + "\n";
}

Status writeStudioProject(const std::string& path, const StudioProject& project) {
  std::string text;
  try {
    text = studioProjectToJson(project, path);
  } catch (const std::exception& e) {
    return Status::failure(path + ": cannot write: " + e.what());
  }
  return writeTextAtomically(path, text);
}

}  // namespace artcam
