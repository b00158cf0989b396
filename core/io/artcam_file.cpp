// SPDX-License-Identifier: Apache-2.0
// .artcam reading and writing. Reading walks the JSON with its path in hand so every refusal
// names the field (RFC 6901 pointer); the Camera constructor then checks the model itself.
// Doubles survive bit-exactly: nlohmann writes the shortest string that reads back to the same
// double and reads with correct rounding, which the tests check on random and edge values.
#include "core/io/artcam_file.h"

#include "core/io/atomic_file.h"
#include "core/io/io_text.h"
#include "core/io/text_input.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace artcam {

namespace {

using Json = nlohmann::ordered_json;

// Internal unwinding from deep inside the reader; turned into a Status at the API boundary.
struct Refusal {
  std::string message;  // "<path>: <cause>" or a cause that needs no path
};

[[noreturn]] void refuse(const std::string& path, const std::string& cause) {
  throw Refusal{path + ": " + cause};
}

// A value quoted for a one-line message: strings JSON-escaped (a "\n" in a file's string must not
// split the message), long values cut.
std::string describe(const Json& j) {
  if (j.is_string() || j.is_number() || j.is_boolean() || j.is_null()) {
    std::string text = j.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return j.is_null() ? "null" : text;
  }
  return std::string("an ") + (j.is_array() ? "array" : "object");
}

const Json& field(const Json& object, const std::string& path, const char* key) {
  const auto it = object.find(key);
  if (it == object.end()) refuse(path + "/" + key, "missing");
  return *it;
}

const Json& objectAt(const Json& j, const std::string& path) {
  if (!j.is_object()) refuse(path, "expected an object, found " + describe(j));
  return j;
}

const Json& arrayAt(const Json& j, const std::string& path, const std::string& of) {
  if (!j.is_array()) refuse(path, "expected an array of " + of + ", found " + describe(j));
  return j;
}

double numberAt(const Json& j, const std::string& path) {
  if (!j.is_number()) refuse(path, "expected a number, found " + describe(j));
  const double value = j.get<double>();
  // JSON has no NaN/inf, but an overflowing literal such as 1e999 reads as inf.
  if (!std::isfinite(value)) refuse(path, "not a finite number");
  return value;
}

// Whole numbers end up in ints: 2^31 and above would wrap (to a negative frame size).
long long wholeNumberAt(const Json& j, const std::string& path, long long min,
                        long long max = (1LL << 31) - 1) {
  if (!j.is_number_integer()) refuse(path, "expected a whole number, found " + describe(j));
  if (j.is_number_unsigned() && j.get<unsigned long long>() > static_cast<unsigned long long>(max))
    refuse(path, "number out of range: " + describe(j) + " (at most " + std::to_string(max) + ")");
  const long long value = j.get<long long>();
  if (value < min)
    refuse(path, "expected a whole number of at least " + std::to_string(min) + ", found " +
                     std::to_string(value));
  if (value > max)
    refuse(path, "expected a whole number of at most " + std::to_string(max) + ", found " +
                     std::to_string(value));
  return value;
}

std::vector<double> numbersAt(const Json& j, const std::string& path, size_t count) {
  const std::string expected = std::to_string(count) + " numbers";
  if (!j.is_array()) refuse(path, "expected " + expected + ", found " + describe(j));
  if (j.size() != count)
    refuse(path, "expected " + expected + ", found " + std::to_string(j.size()));
  std::vector<double> values;
  for (size_t k = 0; k < count; ++k)
    values.push_back(numberAt(j[k], path + "/" + std::to_string(k)));
  return values;
}

Eigen::VectorXd pointAt(const Json& j, const std::string& path, size_t expected_size) {
  if (!j.is_array()) refuse(path, "expected 2 or 3 numbers, found " + describe(j));
  if (expected_size == 0 && j.size() != 2 && j.size() != 3)
    refuse(path, "expected 2 or 3 numbers, found " + std::to_string(j.size()));
  const std::vector<double> v = numbersAt(j, path, expected_size ? expected_size : j.size());
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

std::string stringAt(const Json& j, const std::string& path) {
  if (!j.is_string()) refuse(path, "expected a string, found " + describe(j));
  return j.get<std::string>();
}

// kMaxFrameSide (artcam.h) is checked here, by path, before anything renders the camera.
FrameSize frameAt(const Json& j, const std::string& path) {
  if (!j.is_array() || j.size() != 2) refuse(path, "expected [w, h], found " + describe(j));
  return {static_cast<int>(wholeNumberAt(j[0], path + "/0", 0, kMaxFrameSide)),
          static_cast<int>(wholeNumberAt(j[1], path + "/1", 0, kMaxFrameSide))};
}

std::vector<Block> blocksAt(const Json& j, const std::string& path) {
  arrayAt(j, path, "blocks");
  if (j.empty()) refuse(path, "expected at least one block");
  std::vector<Block> blocks;
  for (size_t b = 0; b < j.size(); ++b) {
    const std::string here = path + "/" + std::to_string(b);
    const Json& block = objectAt(j[b], here);
    const std::string kind_name = stringAt(field(block, here, "kind"), here + "/kind");
    const std::optional<BlockKind> kind = blockKindFromName(kind_name);
    if (!kind)
      refuse(here + "/kind",
             "unknown block kind " + describe(Json(kind_name)) +
                 " (expected position, colour or depth)");
    const Block parsed{
        *kind, static_cast<int>(wholeNumberAt(field(block, here, "size"), here + "/size", 1))};
    if (!isValidBlock(parsed))
      refuse(here + "/size",
             std::to_string(parsed.size) + " elements is not a valid " + kind_name + " block");
    blocks.push_back(parsed);
  }
  return blocks;
}

Stage stageAt(const Json& j, const std::string& path, int n) {
  const Json& tensors_json = field(objectAt(j, path), path, "tensors");
  const std::string tensors_path = path + "/tensors";
  const size_t count = static_cast<size_t>(n);
  arrayAt(tensors_json, tensors_path, "tensors");
  if (tensors_json.size() != count)
    refuse(tensors_path, "expected " + std::to_string(n) + " tensors (one per element), found " +
                             std::to_string(tensors_json.size()));
  Stage stage;
  for (size_t i = 0; i < count; ++i) {
    const std::string tensor_path = tensors_path + "/" + std::to_string(i);
    const Json& rows = tensors_json[i];
    arrayAt(rows, tensor_path, "rows");
    if (rows.size() != count)
      refuse(tensor_path,
             "expected " + std::to_string(n) + " rows, found " + std::to_string(rows.size()));
    // Every row is read before the n×n matrix is allocated: a file listing n empty rows must
    // not make us allocate n² doubles (30 000 empty rows, 90 kB, would ask for 7 GB).
    std::vector<std::vector<double>> values;
    for (size_t r = 0; r < count; ++r)
      values.push_back(numbersAt(rows[r], tensor_path + "/" + std::to_string(r), count));
    Eigen::MatrixXd q(n, n);
    for (size_t r = 0; r < count; ++r)
      for (size_t c = 0; c < count; ++c)
        q(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = values[r][c];
    stage.q.push_back(std::move(q));
  }
  return stage;
}

std::vector<PointMatch> matchesAt(const Json& j, const std::string& path) {
  arrayAt(j, path, "matches");
  std::vector<PointMatch> matches;
  size_t source_size = 0, target_size = 0;  // fixed by the first match
  for (size_t m = 0; m < j.size(); ++m) {
    const std::string here = path + "/" + std::to_string(m);
    const Json& match = objectAt(j[m], here);
    PointMatch parsed;
    parsed.source = pointAt(field(match, here, "source"), here + "/source", source_size);
    parsed.target = pointAt(field(match, here, "target"), here + "/target", target_size);
    source_size = static_cast<size_t>(parsed.source.size());
    target_size = static_cast<size_t>(parsed.target.size());
    if (const auto it = match.find("enabled"); it != match.end()) {
      if (!it->is_boolean())
        refuse(here + "/enabled", "expected true or false, found " + describe(*it));
      parsed.enabled = it->get<bool>();
    }
    matches.push_back(std::move(parsed));
  }
  return matches;
}

std::vector<double> numberListAt(const Json& j, const std::string& path) {
  arrayAt(j, path, "numbers");
  return numbersAt(j, path, j.size());
}

FitRecord fitAt(const Json& j, const std::string& path) {
  objectAt(j, path);
  FitRecord fit;
  fit.model = stringAt(field(j, path, "model"), path + "/model");
  fit.matches = static_cast<int>(wholeNumberAt(field(j, path, "matches"), path + "/matches", 0));
  fit.rms_px = numberAt(field(j, path, "rms_px"), path + "/rms_px");
  fit.max_px = numberAt(field(j, path, "max_px"), path + "/max_px");
  if (j.contains("residuals_px"))
    fit.residuals_px = numberListAt(j["residuals_px"], path + "/residuals_px");
  if (j.contains("singular_values"))
    fit.singular_values = numberListAt(j["singular_values"], path + "/singular_values");
  if (j.contains("reason")) fit.reason = stringAt(j["reason"], path + "/reason");
  if (j.contains("held_out_rms_px"))
    fit.held_out_rms_px = numberAt(j["held_out_rms_px"], path + "/held_out_rms_px");
  if (j.contains("algebraic_rms_px"))
    fit.algebraic_rms_px = numberAt(j["algebraic_rms_px"], path + "/algebraic_rms_px");
  if (j.contains("pole_free")) {
    if (!j["pole_free"].is_boolean())
      refuse(path + "/pole_free", "expected true or false, found " + describe(j["pole_free"]));
    fit.pole_checked = true;
    fit.pole_free = j["pole_free"].get<bool>();
  }
  if (j.contains("pole_margin")) fit.pole_margin = numberAt(j["pole_margin"], path + "/pole_margin");
  if (j.contains("inliers"))
    for (const double v : numberListAt(j["inliers"], path + "/inliers")) {
      if (v < 0 || v != std::floor(v) || v > 1e9)
        refuse(path + "/inliers", "expected whole numbers ≥ 0");
      fit.inliers.push_back(static_cast<int>(v));
    }
  // The scored ladder (files before it was written lack it).
  if (j.contains("criterion")) fit.criterion = stringAt(j["criterion"], path + "/criterion");
  if (j.contains("models")) {
    arrayAt(j["models"], path + "/models", "model scores");
    for (size_t k = 0; k < j["models"].size(); ++k) {
      const Json& e = j["models"][k];
      const std::string at = path + "/models/" + std::to_string(k);
      objectAt(e, at);
      ModelScore score;
      score.model = stringAt(field(e, at, "model"), at + "/model");
      if (e.contains("rms_px")) score.rms_px = numberAt(e["rms_px"], at + "/rms_px");
      if (e.contains("held_out_rms_px"))
        score.held_out_rms_px = numberAt(e["held_out_rms_px"], at + "/held_out_rms_px");
      if (e.contains("criterion")) score.criterion = numberAt(e["criterion"], at + "/criterion");
      if (e.contains("note")) score.note = stringAt(e["note"], at + "/note");
      fit.models.push_back(std::move(score));
    }
  }
  return fit;
}

// The geometry of one camera: blocks, frames, stages. `prefix` is the JSON path of the object
// holding them ("" at the top level, "/patches/3/camera" for a patch's embedded camera).
Camera cameraAt(const Json& root, const std::string& prefix) {
  objectAt(root, prefix.empty() ? "/" : prefix);
  std::vector<Block> blocks = blocksAt(field(root, prefix, "blocks"), prefix + "/blocks");
  const int n = BlockLayout(blocks).dimension;
  const std::string frames_path = prefix + "/frames";
  const Json& frames = objectAt(field(root, prefix, "frames"), frames_path);
  const FrameSize source = frameAt(field(frames, frames_path, "source"), frames_path + "/source");
  const FrameSize target = frameAt(field(frames, frames_path, "target"), frames_path + "/target");
  const Json& stages_json = arrayAt(field(root, prefix, "stages"), prefix + "/stages", "stages");
  if (stages_json.empty()) refuse(prefix + "/stages", "expected at least one stage");
  std::vector<Stage> stages;
  for (size_t s = 0; s < stages_json.size(); ++s)
    stages.push_back(stageAt(stages_json[s], prefix + "/stages/" + std::to_string(s), n));
  try {
    return Camera(std::move(blocks), std::move(stages), source, target);
  } catch (const std::invalid_argument& e) {
    throw Refusal{(prefix.empty() ? std::string() : prefix + ": ") + "invalid camera: " + e.what()};
  }
}

std::vector<Camera> layersAt(const Json& j, const Camera& main) {
  const Json& layers = arrayAt(j, "/layers", "layers");
  std::vector<Camera> out;
  for (size_t l = 0; l < layers.size(); ++l) {
    const std::string path = "/layers/" + std::to_string(l);
    objectAt(layers[l], path);
    const Json& stages_json = arrayAt(field(layers[l], path, "stages"), path + "/stages", "stages");
    if (stages_json.empty()) refuse(path + "/stages", "expected at least one stage");
    std::vector<Stage> stages;
    for (size_t s = 0; s < stages_json.size(); ++s)
      stages.push_back(stageAt(stages_json[s], path + "/stages/" + std::to_string(s), main.dimension()));
    try {
      out.emplace_back(main.blocks(), std::move(stages), main.sourceSize(), main.targetSize());
    } catch (const std::invalid_argument& e) {
      throw Refusal{path + ": invalid camera: " + e.what()};
    }
  }
  return out;
}

// Read before anything is allocated per patch: a list longer than kMaxPatches is refused by its
// size alone.
PiecewiseCamera piecesAt(const Json& root, const Camera& main) {
  const Json& patches = arrayAt(root["patches"], "/patches", "patches");
  if (patches.empty()) refuse("/patches", "expected at least one patch");
  if (patches.size() > static_cast<size_t>(kMaxPatches))
    refuse("/patches", std::to_string(patches.size()) + " patches, more than the " +
                           std::to_string(kMaxPatches) + " allowed");
  PiecewiseCamera pieces;
  pieces.source_size = main.sourceSize();
  pieces.target_size = main.targetSize();
  if (root.contains("support_margin_px")) {
    pieces.support_margin_px = numberAt(root["support_margin_px"], "/support_margin_px");
    if (pieces.support_margin_px < 0.0) refuse("/support_margin_px", "expected a number ≥ 0");
  }
  if (root.contains("patch_frame")) {
    // A homography composed before the patches (piecewise_camera.h, PatchFrame).
    const Json& frame = objectAt(root["patch_frame"], "/patch_frame");
    PatchFrame pf;
    pf.size = frameAt(field(frame, "/patch_frame", "size"), "/patch_frame/size");
    if (!pf.size.isImage()) refuse("/patch_frame/size", "expected an image frame");
    const std::vector<double> h =
        numbersAt(field(frame, "/patch_frame", "patch_from_source_px"), "/patch_frame/patch_from_source_px", 9);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) pf.patch_from_source(r, c) = h[static_cast<size_t>(3 * r + c)];
    pieces.patch_frame = pf;
  }
  for (size_t i = 0; i < patches.size(); ++i) {
    const std::string where = "/patches/" + std::to_string(i);
    const Json& p = objectAt(patches[i], where);
    CameraPatch patch;
    const std::vector<double> r = numbersAt(field(p, where, "rect"), where + "/rect", 4);
    patch.rect = {r[0], r[1], r[2], r[3]};
    if (!(patch.rect.x1 > patch.rect.x0 && patch.rect.y1 > patch.rect.y0))
      refuse(where + "/rect", "x1 must exceed x0 and y1 must exceed y0");
    patch.camera = cameraAt(objectAt(field(p, where, "camera"), where + "/camera"), where + "/camera");
    if (p.contains("support")) {
      const Json& hull = arrayAt(p["support"], where + "/support", "[x, y] points");
      for (size_t k = 0; k < hull.size(); ++k) {
        const std::vector<double> v = numbersAt(hull[k], where + "/support/" + std::to_string(k), 2);
        patch.support.emplace_back(v[0], v[1]);
      }
    }
    if (p.contains("model")) patch.model = stringAt(p["model"], where + "/model");
    if (p.contains("matches"))
      patch.matches = static_cast<int>(wholeNumberAt(p["matches"], where + "/matches", 0));
    // -1 marks an error that could not be measured (written so by the fitter).
    if (p.contains("rms_px")) patch.rms_px = numberAt(p["rms_px"], where + "/rms_px");
    if (p.contains("max_px")) patch.max_px = numberAt(p["max_px"], where + "/max_px");
    if (p.contains("held_out_max_px"))
      patch.held_out_max_px = numberAt(p["held_out_max_px"], where + "/held_out_max_px");
    pieces.patches.push_back(std::move(patch));
  }
  return pieces;
}

Artcam artcamAt(const Json& root) {
  if (!root.is_object())
    throw Refusal{"expected a JSON object at the top level, found " + describe(root)};
  const auto format = root.find("format");
  if (format == root.end()) throw Refusal{"/format: missing (not an ARTcam file)"};
  if (!format->is_string() || format->get<std::string>() != "artcam")
    refuse("/format", "expected \"artcam\", found " + describe(*format) + " (not an ARTcam file)");
  const long long version = wholeNumberAt(field(root, "", "version"), "/version", 1);
  if (version > kArtcamFormatVersion)
    throw Refusal{"written by a newer ARTcam (version " + std::to_string(version) +
                  "; this build reads up to " + std::to_string(kArtcamFormatVersion) + ")"};

  Artcam camera(cameraAt(root, ""));
  if (root.contains("layers")) {
    std::vector<Camera> more = layersAt(root["layers"], camera.main());
    camera.layers.insert(camera.layers.end(), more.begin(), more.end());
  }
  if (root.contains("depth_output")) {
    const std::string name = stringAt(root["depth_output"], "/depth_output");
    const std::optional<DepthOutput> output = depthOutputFromName(name);
    if (!output)
      refuse("/depth_output",
             "expected \"depth\" or \"blur-variance\", found " + describe(Json(name)));
    camera.depth_output = *output;
  }
  if (root.contains("frame")) {
    const std::string name = stringAt(root["frame"], "/frame");
    const std::optional<CameraFrame> frame = cameraFrameFromName(name);
    if (!frame)
      refuse("/frame", "expected \"sensor\" or \"upright\", found " + describe(Json(name)));
    camera.frame = *frame;
  }
  if (root.contains("patches")) camera.pieces = piecesAt(root, camera.main());
  if (root.contains("matches")) camera.matches = matchesAt(root["matches"], "/matches");
  if (root.contains("fit")) camera.fit = fitAt(root["fit"], "/fit");
  // What a well-formed file can still get wrong: zero stages, patches that overlap or leave
  // the frame, layers of other frames.
  if (const Status s = validateArtcam(camera); !s) throw Refusal{s.message};
  return camera;
}

// ---- writing ----

// Builds the JSON and remembers the first non-finite number (JSON cannot hold it; nlohmann
// would silently write null).
struct Builder {
  std::string bad_path;

  Json number(double v, const std::string& path) {
    if (!std::isfinite(v) && bad_path.empty()) bad_path = path;
    return v;
  }
  Json numbers(const double* v, size_t count, const std::string& path) {
    Json array = Json::array();
    for (size_t k = 0; k < count; ++k)
      array.push_back(number(v[k], path + "/" + std::to_string(k)));
    return array;
  }
  Json vector(const Eigen::VectorXd& v, const std::string& path) {
    return numbers(v.data(), static_cast<size_t>(v.size()), path);
  }

  Json stagesOf(const Camera& camera, const std::string& prefix) {
    Json stages = Json::array();
    for (size_t s = 0; s < camera.stages().size(); ++s) {
      Json tensors = Json::array();
      const auto& q = camera.stages()[s].q;
      for (size_t i = 0; i < q.size(); ++i) {
        const std::string path =
            prefix + "/stages/" + std::to_string(s) + "/tensors/" + std::to_string(i);
        Json rows = Json::array();
        for (Eigen::Index r = 0; r < q[i].rows(); ++r) {
          const Eigen::VectorXd row = q[i].row(r).transpose();
          rows.push_back(vector(row, path + "/" + std::to_string(r)));
        }
        tensors.push_back(std::move(rows));
      }
      stages.push_back({{"tensors", std::move(tensors)}});
    }
    return stages;
  }

  // The geometry of one camera (a patch embeds it as a complete camera-only document).
  Json cameraJson(const Camera& camera, const std::string& prefix) {
    Json root;
    root["format"] = "artcam";
    root["version"] = kArtcamFormatVersion;
    Json blocks = Json::array();
    for (const Block& b : camera.blocks())
      blocks.push_back({{"kind", std::string(blockKindName(b.kind))}, {"size", b.size}});
    root["blocks"] = blocks;
    root["frames"] = {{"source", {camera.sourceSize().width, camera.sourceSize().height}},
                      {"target", {camera.targetSize().width, camera.targetSize().height}}};
    root["stages"] = stagesOf(camera, prefix);
    return root;
  }

  Json patchesJson(const PiecewiseCamera& pieces) {
    Json patches = Json::array();
    for (size_t i = 0; i < pieces.patches.size(); ++i) {
      const CameraPatch& p = pieces.patches[i];
      const std::string where = "/patches/" + std::to_string(i);
      Json j;
      j["rect"] = {number(p.rect.x0, where + "/rect"), number(p.rect.y0, where + "/rect"),
                   number(p.rect.x1, where + "/rect"), number(p.rect.y1, where + "/rect")};
      j["model"] = p.model;
      j["matches"] = p.matches;
      j["rms_px"] = std::isfinite(p.rms_px) ? p.rms_px : -1.0;
      j["max_px"] = std::isfinite(p.max_px) ? p.max_px : -1.0;
      if (p.held_out_max_px >= 0)  // infinite (no fold could be fitted) is written as -1
        j["held_out_max_px"] = std::isfinite(p.held_out_max_px) ? p.held_out_max_px : -1.0;
      Json hull = Json::array();
      for (const Eigen::Vector2d& v : p.support)
        hull.push_back({number(v.x(), where + "/support"), number(v.y(), where + "/support")});
      j["support"] = std::move(hull);
      j["camera"] = cameraJson(p.camera, where + "/camera");
      patches.push_back(std::move(j));
    }
    return patches;
  }

  Json document(const Artcam& d) {
    Json root = cameraJson(d.main(), "");
    if (d.layers.size() > 1) {
      Json layers = Json::array();
      for (size_t l = 1; l < d.layers.size(); ++l)
        layers.push_back({{"stages", stagesOf(d.layers[l], "/layers/" + std::to_string(l - 1))}});
      root["layers"] = std::move(layers);
    }
    if (d.depth_output != DepthOutput::Depth)
      root["depth_output"] = std::string(depthOutputName(d.depth_output));
    if (d.frame) root["frame"] = std::string(cameraFrameName(*d.frame));
    if (!d.matches.empty()) {
      Json matches = Json::array();
      for (size_t m = 0; m < d.matches.size(); ++m) {
        const std::string path = "/matches/" + std::to_string(m);
        matches.push_back({{"source", vector(d.matches[m].source, path + "/source")},
                           {"target", vector(d.matches[m].target, path + "/target")},
                           {"enabled", d.matches[m].enabled}});
      }
      root["matches"] = std::move(matches);
    }
    if (d.fit) {
      const FitRecord& f = *d.fit;
      root["fit"] = {{"model", f.model},
                     {"matches", f.matches},
                     {"rms_px", number(f.rms_px, "/fit/rms_px")},
                     {"max_px", number(f.max_px, "/fit/max_px")},
                     {"residuals_px",
                      numbers(f.residuals_px.data(), f.residuals_px.size(), "/fit/residuals_px")},
                     {"singular_values", numbers(f.singular_values.data(), f.singular_values.size(),
                                                 "/fit/singular_values")},
                     {"reason", f.reason}};
      if (f.held_out_rms_px >= 0)
        root["fit"]["held_out_rms_px"] = number(f.held_out_rms_px, "/fit/held_out_rms_px");
      if (f.algebraic_rms_px >= 0)
        root["fit"]["algebraic_rms_px"] = number(f.algebraic_rms_px, "/fit/algebraic_rms_px");
      if (f.pole_checked) {
        root["fit"]["pole_free"] = f.pole_free;
        root["fit"]["pole_margin"] = number(f.pole_margin, "/fit/pole_margin");
      }
      if (!f.inliers.empty()) root["fit"]["inliers"] = f.inliers;
      if (!f.criterion.empty()) root["fit"]["criterion"] = f.criterion;
      if (!f.models.empty()) {
        Json models = Json::array();
        for (size_t k = 0; k < f.models.size(); ++k) {
          const ModelScore& score = f.models[k];
          const std::string at = "/fit/models/" + std::to_string(k);
          Json e = {{"model", score.model}};
          if (score.rms_px >= 0) e["rms_px"] = number(score.rms_px, at + "/rms_px");
          if (score.held_out_rms_px >= 0)
            e["held_out_rms_px"] = number(score.held_out_rms_px, at + "/held_out_rms_px");
          if (score.criterion >= 0) e["criterion"] = number(score.criterion, at + "/criterion");
          if (!score.note.empty()) e["note"] = score.note;
          models.push_back(std::move(e));
        }
        root["fit"]["models"] = std::move(models);
      }
    }
    if (d.pieces) {
      root["support_margin_px"] = number(d.pieces->support_margin_px, "/support_margin_px");
      root["patches"] = patchesJson(*d.pieces);
      if (d.pieces->patch_frame) {
        const PatchFrame& pf = *d.pieces->patch_frame;
        Json h = Json::array();
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) h.push_back(number(pf.patch_from_source(r, c), "/patch_frame/patch_from_source_px"));
        root["patch_frame"] = {{"size", {pf.size.width, pf.size.height}}, {"patch_from_source_px", std::move(h)}};
      }
    }
    return root;
  }
};

std::string oneLine(const Json& j) {
  if (j.is_array()) {
    std::string out = "[";
    for (size_t k = 0; k < j.size(); ++k) out += (k ? ", " : "") + oneLine(j[k]);
    return out + "]";
  }
  if (j.is_object()) {
    std::string out = "{";
    bool first = true;
    for (const auto& [key, value] : j.items()) {
      out += (first ? "" : ", ") + Json(key).dump() + ": " + oneLine(value);
      first = false;
    }
    return out + "}";
  }
  return j.dump();
}

// Pretty JSON (indent 2) that keeps rows of numbers and short objects on one line, so a
// tensor reads as a matrix and a match list as one match per line.
void emit(const Json& j, int indent, std::string& out) {
  constexpr size_t kLineWidth = 100;
  const bool container = j.is_array() || j.is_object();
  const bool flat = j.is_array() && std::none_of(j.begin(), j.end(), [](const Json& e) {
                      return e.is_array() || e.is_object();
                    });
  const std::string line = oneLine(j);
  if (!container || j.empty() || flat || static_cast<size_t>(indent) + line.size() <= kLineWidth) {
    out += line;
    return;
  }
  const std::string pad(static_cast<size_t>(indent + 2), ' ');
  out += j.is_array() ? "[\n" : "{\n";
  size_t k = 0;
  for (const auto& [key, value] : j.items()) {
    out += pad;
    if (j.is_object()) out += Json(key).dump() + ": ";
    emit(value, indent + 2, out);
    out += ++k < j.size() ? ",\n" : "\n";
  }
  out += std::string(static_cast<size_t>(indent), ' ') + (j.is_array() ? "]" : "}");
}

// Deeper nesting than any .artcam needs is refused before parsing: readers that embed a
// document (piecewise patches, projects) re-serialise parts of the tree recursively, and a
// few hundred kilobytes of "[[[[" would overflow the stack there.
constexpr int kMaxJsonDepth = 64;

}  // namespace

Result<Artcam> parseArtcam(std::string_view text, const std::string& name) {
  if (const size_t deep = io_text::jsonTooDeepAt(text, kMaxJsonDepth); deep != std::string_view::npos)
    return Result<Artcam>::failure(name + ": " + io_text::jsonPositionOf(text, deep + 1) +
                                           ": nested deeper than " + std::to_string(kMaxJsonDepth) +
                                           " levels (not an ARTcam file)");
  Json root;
  try {
    root = Json::parse(text.begin(), text.end());
  } catch (const Json::parse_error& e) {
    std::string cause = e.what();
    // Drop nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 2: ".
    if (const size_t at = cause.find("syntax error"); at != std::string::npos)
      cause = cause.substr(at);
    else if (const size_t colon = cause.find(": "); colon != std::string::npos)
      cause = cause.substr(colon + 2);
    return Result<Artcam>::failure(name + ": " + io_text::jsonPositionOf(text, e.byte) +
                                           ": invalid JSON: " + cause);
  } catch (const Json::out_of_range& e) {
    // An overflowing literal ("number overflow parsing '1e999'"): nlohmann gives no position,
    // so find the literal it quotes.
    const std::string what = e.what();
    const size_t open = what.find('\'');
    const size_t close = what.rfind('\'');
    const std::string literal = open < close ? what.substr(open + 1, close - open - 1) : "";
    const size_t at = literal.empty() ? std::string_view::npos : text.find(literal);
    return Result<Artcam>::failure(
        name + ": " + (at == std::string_view::npos ? "" : io_text::jsonPositionOf(text, at + 1) + ": ") +
        "not a finite number: " + (literal.empty() ? what : literal));
  } catch (const Json::exception& e) {
    return Result<Artcam>::failure(name + ": invalid JSON: " + e.what());
  }
  try {
    return Result<Artcam>::success(artcamAt(root));
  } catch (const Refusal& refusal) {
    return Result<Artcam>::failure(name + ": " + refusal.message);
  }
}

Result<Artcam> readArtcam(const std::string& path) {
  Result<std::string> text = readTextInput(path);
  if (!text) return Result<Artcam>::failure(text.status.message);
  return parseArtcam(*text.value, textInputName(path));
}

std::string toArtcamJson(const Artcam& camera) {
  Builder builder;
  const Json root = builder.document(camera);
  if (!builder.bad_path.empty())
    throw std::invalid_argument("cannot write .artcam: " + builder.bad_path +
                                " is not a finite number");
  std::string out;
  emit(root, 0, out);
  return out + "\n";
}

Status writeArtcam(const std::string& path, const Artcam& camera) {
  if (const Status s = validateArtcam(camera); !s)
    return Status::failure(path + ": cannot write: " + s.message);
  Builder builder;
  builder.document(camera);
  if (!builder.bad_path.empty())
    return Status::failure(path + ": cannot write: " + builder.bad_path + " is not a finite number");
  return writeTextAtomically(path, toArtcamJson(camera));
}

}  // namespace artcam
