// SPDX-License-Identifier: Apache-2.0
#include "core/lens/lens_database.h"

#include <lensfun/lensfun.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <tuple>

namespace artcam {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::vector<std::string> words(std::string_view text) {
  std::vector<std::string> out;
  std::istringstream in{lower(text)};
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// An lfMLstr's first string is the untranslated one: names stay the same in every locale.
std::string text(const char* s) { return s ? std::string(s) : std::string(); }

std::string typeName(lfLensType type) {
  switch (type) {
    case LF_RECTILINEAR: return "rectilinear";
    case LF_FISHEYE: return "fisheye (equidistant)";
    case LF_PANORAMIC: return "panoramic";
    case LF_EQUIRECTANGULAR: return "equirectangular";
    case LF_FISHEYE_ORTHOGRAPHIC: return "fisheye (orthographic)";
    case LF_FISHEYE_STEREOGRAPHIC: return "fisheye (stereographic)";
    case LF_FISHEYE_EQUISOLID: return "fisheye (equisolid)";
    case LF_FISHEYE_THOBY: return "fisheye (Thoby)";
    default: return "unknown";
  }
}

template <typename T>
bool hasAny(T* const* calib) {
  return calib && calib[0];
}

std::string haystack(const LensEntry& e) { return lower(e.maker + " " + e.model); }

// Every query word begins a word of the name: "8mm" finds "Samyang 8mm" but not "18mm", and
// "10-22" finds "10-22mm".
bool holdsAll(const LensEntry& e, const std::vector<std::string>& ws) {
  const std::vector<std::string> name = words(e.maker + " " + e.model);
  return std::all_of(ws.begin(), ws.end(), [&](const std::string& w) {
    return std::any_of(name.begin(), name.end(),
                       [&](const std::string& n) { return n.compare(0, w.size(), w) == 0; });
  });
}

bool namedExactly(const LensEntry& e, std::string_view name) {
  const std::string n = lower(name);
  return lower(e.model) == n || haystack(e) == n;
}

}  // namespace

std::string LensEntry::describe() const {
  char range[64];
  if (min_focal_mm == max_focal_mm)
    std::snprintf(range, sizeof range, "%g mm", min_focal_mm);
  else
    std::snprintf(range, sizeof range, "%g-%g mm", min_focal_mm, max_focal_mm);
  char crop[32];
  std::snprintf(crop, sizeof crop, "%g", crop_factor);
  std::string has;
  for (const auto& [on, name] :
       {std::pair{distortion, "distortion"}, std::pair{tca, "TCA"}, std::pair{vignetting, "vignetting"}})
    if (on) has += std::string(has.empty() ? "" : ", ") + name;
  return model + " (" + range + ", crop " + crop + ", " + type + (has.empty() ? "" : "; " + has) +
         ")";
}

Result<std::shared_ptr<const LensDatabase>> LensDatabase::load() {
  std::shared_ptr<LensDatabase> out(new LensDatabase());
  out->db_ = new lfDatabase();
  const lfError e = out->db_->Load();
  // lensfun reports LF_NO_DATABASE when no file was found and a negative errno otherwise.
  if (e != LF_NO_ERROR)
    return Result<std::shared_ptr<const LensDatabase>>::failure(
        std::string("the lensfun database (/usr/share/lensfun) could not be read: ") +
        (e == LF_NO_DATABASE ? "no database files (install liblensfun-data-v1)"
                             : "a file in it is malformed"));
  const lfLens* const* all = out->db_->GetLenses();
  for (int i = 0; all && all[i]; ++i) {
    const lfLens* l = all[i];
    LensEntry entry;
    entry.maker = text(l->Maker);
    entry.model = text(l->Model);
    entry.min_focal_mm = l->MinFocal;
    entry.max_focal_mm = l->MaxFocal;
    entry.crop_factor = l->CropFactor;
    entry.type = typeName(l->Type);
    entry.distortion = hasAny(l->CalibDistortion);
    entry.tca = hasAny(l->CalibTCA);
    entry.vignetting = hasAny(l->CalibVignetting);
    entry.index = i;
    out->lenses_.push_back(l);
    out->entries_.push_back(std::move(entry));
  }
  if (out->entries_.empty())
    return Result<std::shared_ptr<const LensDatabase>>::failure(
        "the lensfun database (/usr/share/lensfun) holds no lenses (install liblensfun-data-v1)");
  return Result<std::shared_ptr<const LensDatabase>>::success(std::move(out));
}

LensDatabase::~LensDatabase() { delete db_; }

const lfLens* LensDatabase::lens(int index) const {
  return lenses_.at(static_cast<size_t>(index));
}

const char* lensSearchMatchName(LensSearchMatch match) {
  switch (match) {
    case LensSearchMatch::Words:
      return "words";
    case LensSearchMatch::Lensfun:
      return "lensfun";
    case LensSearchMatch::LensfunLoose:
      return "lensfun-loose";
    default:
      return "none";
  }
}

std::vector<LensEntry> LensDatabase::entriesOf(const lfLens** found) const {
  std::vector<LensEntry> out;
  for (int i = 0; found && found[i]; ++i) {
    const auto at = std::find(lenses_.begin(), lenses_.end(), found[i]);
    if (at != lenses_.end()) out.push_back(entries_[static_cast<size_t>(at - lenses_.begin())]);
  }
  lf_free(found);
  return out;
}

std::vector<LensEntry> LensDatabase::search(std::string_view query, int limit,
                                            LensSearchMatch* how) const {
  const std::vector<std::string> ws = words(query);
  std::vector<LensEntry> hits;
  if (how) *how = LensSearchMatch::None;
  if (ws.empty()) return hits;
  for (const LensEntry& e : entries_)
    if (holdsAll(e, ws)) hits.push_back(e);
  std::stable_sort(hits.begin(), hits.end(), [&](const LensEntry& a, const LensEntry& b) {
    const bool ea = namedExactly(a, query), eb = namedExactly(b, query);
    if (ea != eb) return ea;
    return std::tie(a.maker, a.model) < std::tie(b.maker, b.model);
  });
  LensSearchMatch match = hits.empty() ? LensSearchMatch::None : LensSearchMatch::Words;
  // Words split at spaces miss "nikon 50mm 1.4" for "Nikon AF-S Nikkor 50mm f/1.4G"; lensfun's
  // own matcher splits at punctuation as well and ranks by its score, so it is the fallback,
  // its strict form before the loose one (which needs only some of the words).
  const std::string pattern(query);
  for (const auto& [flags, kind] :
       {std::pair{0, LensSearchMatch::Lensfun},
        std::pair{int{LF_SEARCH_LOOSE}, LensSearchMatch::LensfunLoose}}) {
    if (!hits.empty()) break;
    hits = entriesOf(db_->FindLenses(nullptr, nullptr, pattern.c_str(), flags));
    if (!hits.empty()) match = kind;
  }
  if (how) *how = match;
  if (limit > 0 && static_cast<int>(hits.size()) > limit) hits.resize(static_cast<size_t>(limit));
  return hits;
}

Result<LensEntry> LensDatabase::find(std::string_view name, double crop) const {
  const LensEntry* best = nullptr;
  for (const LensEntry& e : entries_) {
    if (!namedExactly(e, name)) continue;
    if (!best || (crop > 0 && std::abs(e.crop_factor - crop) < std::abs(best->crop_factor - crop)))
      best = &e;
  }
  if (best) return Result<LensEntry>::success(*best);
  std::string message = "no lens named \"" + std::string(name) + "\" in the lensfun database";
  const std::vector<LensEntry> near = search(name, 3);
  if (!near.empty()) {
    message += "; did you mean";
    for (size_t i = 0; i < near.size(); ++i)
      message += (i ? ", \"" : " \"") + near[i].model + "\"";
    message += "?";
  } else {
    message += " (artcam lens search WORDS lists names)";
  }
  return Result<LensEntry>::failure(message);
}

std::string PhotoLensLookup::searched() const {
  std::string out;
  // Cameras mostly repeat the make in the model ("Canon", "Canon PowerShot G11").
  const bool make_in_model = lower(hint.camera_model).rfind(lower(hint.camera_maker), 0) == 0;
  const std::string camera_tags =
      make_in_model ? hint.camera_model : hint.camera_maker + " " + hint.camera_model;
  if (!hint.lens_model.empty()) out = "lens \"" + hint.lens_model + "\"";
  if (!camera_tags.empty()) {
    out += (out.empty() ? "camera \"" : " with camera \"") + camera_tags + "\"";
    out += camera.empty() ? std::string(" (not in lensfun)")
                          : " (lensfun: " + camera + (camera_loose ? ", loose match)" : ")");
  }
  return out.empty() ? "no lens or camera" : out;
}

PhotoLensLookup LensDatabase::lookUp(const LensHint& hint) const {
  PhotoLensLookup out;
  out.hint = hint;
  const lfCamera* camera = nullptr;
  const lfCamera** cameras = nullptr;
  if (!hint.camera_model.empty()) {
    // lensfun normalises makers ("NIKON CORPORATION" is "Nikon"); its loose match is the fallback
    // for a model it spells otherwise, and the camera chosen is said in every report.
    const char* maker = hint.camera_maker.empty() ? nullptr : hint.camera_maker.c_str();
    cameras = db_->FindCamerasExt(maker, hint.camera_model.c_str(), 0);
    if (!cameras || !cameras[0]) {
      lf_free(cameras);
      cameras = db_->FindCamerasExt(maker, hint.camera_model.c_str(), LF_SEARCH_LOOSE);
      out.camera_loose = cameras && cameras[0];
    }
    if (cameras && cameras[0]) {
      camera = cameras[0];
      out.camera = text(camera->Model);  // lensfun's models hold the brand: "Nikon D750"
      out.camera_crop = camera->CropFactor;
    }
  }
  if (!hint.lens_model.empty()) {
    // An exact model name first; else lensfun's match of the EXIF name among the lenses that fit
    // the camera (its mount and crop), strict before loose; else the name searched alone.
    for (const LensEntry& e : entries_)
      if (namedExactly(e, hint.lens_model)) out.lenses.push_back(e);
    if (!out.lenses.empty()) out.lens_match = "exact name";
    const std::string model = hint.lens_model;
    for (const auto& [flags, how] :
         {std::pair{0, "lensfun"}, std::pair{int{LF_SEARCH_LOOSE}, "lensfun loose"}}) {
      if (!out.lenses.empty() || !camera) break;
      out.lenses = entriesOf(db_->FindLenses(camera, nullptr, model.c_str(), flags));
      if (!out.lenses.empty()) out.lens_match = how;
    }
    if (out.lenses.empty() && !camera) {
      // No camera to narrow the lenses to a mount: only the strict matches, since lensfun's
      // loose one would take any lens sharing a word ("50mm") for the photo's.
      LensSearchMatch how = LensSearchMatch::None;
      out.lenses = search(hint.lens_model, 0, &how);
      if (how == LensSearchMatch::LensfunLoose) out.lenses.clear();
      out.lens_match = lensSearchMatchName(how);
    }
  }
  if (out.lenses.empty() && camera) {
    // lensfun lists the lenses that fit a camera's mount; a compact's fixed lens is on a mount
    // of its own, so this finds exactly it (its EXIF lens name is often only "6.1-30.5 mm").
    out.lenses = entriesOf(db_->FindLenses(camera, nullptr, nullptr, 0));
    if (!out.lenses.empty()) out.lens_match = "the camera's lenses";
  }
  if (out.lenses.empty()) out.lens_match.clear();
  lf_free(cameras);
  if (hint.focal_mm > 0) {
    const auto covers = [&](const LensEntry& e) {
      return hint.focal_mm >= e.min_focal_mm - 0.05 && hint.focal_mm <= e.max_focal_mm + 0.05;
    };
    std::stable_partition(out.lenses.begin(), out.lenses.end(), covers);
  }
  return out;
}

std::vector<LensEntry> LensDatabase::suggest(const LensHint& hint, int limit) const {
  std::vector<LensEntry> found = lookUp(hint).lenses;
  if (limit > 0 && static_cast<int>(found.size()) > limit) found.resize(static_cast<size_t>(limit));
  return found;
}

}  // namespace artcam
