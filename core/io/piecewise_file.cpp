// Piecewise .artcam files; see piecewise_file.h.
#include "core/io/piecewise_file.h"

#include "core/io/atomic_file.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace artcam {
namespace {

using Json = nlohmann::ordered_json;

Result<PiecewiseDocument> fail(const std::string& m) { return Result<PiecewiseDocument>::failure(m); }

bool finiteNumber(const Json& j) { return j.is_number() && std::isfinite(j.get<double>()); }

}  // namespace

Result<PiecewiseDocument> readPiecewiseFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail(path + ": cannot read: no such file or not readable");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) return fail(path + ": cannot read: I/O error");
  return parsePiecewiseJson(buffer.str(), path);
}

Result<PiecewiseDocument> parsePiecewiseJson(std::string_view text, const std::string& path) {
  // Names syntax errors by line and column, and refuses nesting deep enough to overflow the
  // stack when a patch's camera is re-serialised below.
  auto whole = parseArtcamJson(text, path);
  if (!whole) return fail(whole.status.message);

  PiecewiseDocument doc{*whole, std::nullopt};
  const Json root = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!root.is_object() || !root.contains("patches")) return Result<PiecewiseDocument>::success(doc);
  const Json& patches = root["patches"];
  if (!patches.is_array() || patches.empty())
    return fail(path + ": /patches: expected a non-empty list of patches");

  PiecewiseCamera pieces;
  if (root.contains("support_margin_px")) {
    if (!finiteNumber(root["support_margin_px"]) || root["support_margin_px"].get<double>() < 0.0)
      return fail(path + ": /support_margin_px: expected a number ≥ 0");
    pieces.support_margin_px = root["support_margin_px"].get<double>();
  }
  pieces.source_size = whole->camera.sourceSize();
  pieces.target_size = whole->camera.targetSize();
  for (size_t i = 0; i < patches.size(); ++i) {
    const std::string where = path + ": /patches/" + std::to_string(i);
    const Json& p = patches[i];
    if (!p.is_object()) return fail(where + ": expected an object");
    const Json* rect = p.contains("rect") ? &p["rect"] : nullptr;
    if (!rect || !rect->is_array() || rect->size() != 4 ||
        !std::all_of(rect->begin(), rect->end(), finiteNumber))
      return fail(where + "/rect: expected [x0, y0, x1, y1]");
    CameraPatch patch;
    patch.rect = {(*rect)[0].get<double>(), (*rect)[1].get<double>(), (*rect)[2].get<double>(),
                  (*rect)[3].get<double>()};
    if (!(patch.rect.x1 > patch.rect.x0 && patch.rect.y1 > patch.rect.y0))
      return fail(where + "/rect: x1 must exceed x0 and y1 must exceed y0");
    if (!p.contains("camera") || !p["camera"].is_object())
      return fail(where + "/camera: expected an embedded .artcam document");
    auto camera = parseArtcamJson(p["camera"].dump(), where + "/camera");
    if (!camera) return fail(camera.status.message);
    if (camera->camera.blocks() != whole->camera.blocks() ||
        camera->camera.sourceSize() != pieces.source_size ||
        camera->camera.targetSize() != pieces.target_size)
      return fail(where + "/camera: blocks and frames must match the top-level camera's");
    patch.camera = camera->camera;
    if (p.contains("support")) {
      const Json& hull = p["support"];
      if (!hull.is_array()) return fail(where + "/support: expected a list of [x, y] points");
      for (size_t k = 0; k < hull.size(); ++k) {
        const Json& v = hull[k];
        if (!v.is_array() || v.size() != 2 || !finiteNumber(v[0]) || !finiteNumber(v[1]))
          return fail(where + "/support/" + std::to_string(k) + ": expected [x, y]");
        patch.support.emplace_back(v[0].get<double>(), v[1].get<double>());
      }
    }
    if (p.contains("model") && !p["model"].is_string())
      return fail(where + "/model: expected a string");
    patch.model = p.value("model", std::string());
    patch.matches = p.contains("matches") && p["matches"].is_number_integer() ? p["matches"].get<int>() : 0;
    if (p.contains("rms_px") && finiteNumber(p["rms_px"])) patch.rms_px = p["rms_px"].get<double>();
    if (p.contains("max_px") && finiteNumber(p["max_px"])) patch.max_px = p["max_px"].get<double>();
    pieces.patches.push_back(std::move(patch));
  }
  doc.pieces = std::move(pieces);
  return Result<PiecewiseDocument>::success(std::move(doc));
}

Status writePiecewiseFile(const std::string& path, const PiecewiseDocument& document) {
  std::string text;
  try {
    Json root = Json::parse(toArtcamJson(document.whole));
    if (document.pieces) {
      Json patches = Json::array();
      for (const CameraPatch& p : document.pieces->patches) {
        p.camera.validate();
        Json j;
        j["rect"] = {p.rect.x0, p.rect.y0, p.rect.x1, p.rect.y1};
        j["model"] = p.model;
        j["matches"] = p.matches;
        j["rms_px"] = std::isfinite(p.rms_px) ? p.rms_px : -1.0;
        j["max_px"] = std::isfinite(p.max_px) ? p.max_px : -1.0;
        Json hull = Json::array();
        for (const Eigen::Vector2d& v : p.support) hull.push_back({v.x(), v.y()});
        j["support"] = std::move(hull);
        j["camera"] = Json::parse(toArtcamJson(ArtcamDocument{p.camera, {}, std::nullopt}));
        patches.push_back(std::move(j));
      }
      root["support_margin_px"] = document.pieces->support_margin_px;
      root["patches"] = std::move(patches);
    }
    text = root.dump(1) + "\n";
  } catch (const std::exception& e) {
    return Status::failure(path + ": cannot write: " + e.what());
  }
  return writeTextAtomically(path, text);
}

}  // namespace artcam
