// SPDX-License-Identifier: Apache-2.0
// The lensfun lens database (Debian's liblensfun-data-v1, read by liblensfun): finding a lens
// by the words of its name, and suggesting lenses for a photo from its EXIF make, model, lens
// name and focal length.
//
// lensfun's types stay inside lens_database.cpp and lens_camera.cpp: callers see LensEntry, a
// plain description, and name a lens by its model string (which lensfun's own tools show and
// which already holds the maker, "Canon EF-S 10-22mm f/3.5-4.5 USM"). A model calibrated on
// several crop factors appears once per calibration; `crop_factor` tells them apart.
#pragma once

#include "core/io/photo_metadata.h"
#include "core/model/status.h"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

struct lfLens;
struct lfDatabase;

namespace artcam {

struct LensEntry {
  std::string maker;
  std::string model;          // the name `artcam lens camera --lens` takes
  double min_focal_mm = 0.0;  // the focal range the lens covers
  double max_focal_mm = 0.0;
  double crop_factor = 1.0;   // of the camera it was calibrated on
  std::string type;           // "rectilinear", "fisheye (equisolid)", … (lensfun's projection)
  bool distortion = false;    // the database has a distortion calibration
  bool tca = false;           // … transverse chromatic aberration
  bool vignetting = false;    // … vignetting
  int index = -1;             // position in the database (LensDatabase::lens)

  // "Canon EF-S 10-22mm f/3.5-4.5 USM (10-22 mm, crop 1.613; distortion, TCA)"
  std::string describe() const;
};

// What a photo says about the lens: its EXIF make, model, lens model and focal length.
using LensHint = PhotoLensTags;

// How search() found its lenses: every word beginning a word of the name; else lensfun's own
// name match (FindLenses: every word of the text in the name, words split at punctuation too,
// so "1.4" finds "f/1.4G"); else lensfun's loose match (FindLenses with LF_SEARCH_LOOSE: some
// words, ranked by lensfun's score).
enum class LensSearchMatch { None, Words, Lensfun, LensfunLoose };
const char* lensSearchMatchName(LensSearchMatch match);  // "words", "lensfun", "lensfun-loose"

// The lensfun entries a photo's EXIF leads to (LensDatabase::lookUp): the camera lensfun knows
// by the EXIF make and model, and the lenses for the EXIF lens name on that camera (else, with
// no lens name or none matching, the lenses lensfun lists for the camera: a compact's fixed
// lens), those that cover the focal length first. Without a camera only strict name matches
// count: a loose one is narrowed to the camera's mount or not taken.
struct PhotoLensLookup {
  LensHint hint;
  std::string camera;             // lensfun's model name of the camera; empty: none matched
  double camera_crop = 0.0;       // that camera's crop factor; 0 when none matched
  bool camera_loose = false;      // the camera was found only by lensfun's loose match
  std::vector<LensEntry> lenses;  // best first
  // How they were found: "exact name", "lensfun", "lensfun loose", "words" (the name alone, no
  // camera matched) or "the camera's lenses" (no lens name, or none matched); empty: none.
  std::string lens_match;
  // What was looked for, for a refusal: "lens "X" with camera "Make Model" (lensfun: …)".
  std::string searched() const;
};

class LensDatabase {
 public:
  // lensfun's system database (/usr/share/lensfun); a failure names the directory and the cause.
  static Result<std::shared_ptr<const LensDatabase>> load();
  ~LensDatabase();
  LensDatabase(const LensDatabase&) = delete;
  LensDatabase& operator=(const LensDatabase&) = delete;

  int size() const { return static_cast<int>(entries_.size()); }
  const std::vector<LensEntry>& entries() const { return entries_; }
  const lfLens* lens(int index) const;

  // Lenses whose "maker model" has, for every word of `text`, a word beginning with it
  // (case-insensitive; words split at spaces, so "10-22" finds "10-22mm" and "8mm" does not
  // find "18mm"); an exact model name first, then by maker and model. Empty text: none.
  // When that finds nothing, lensfun's own match and then its loose match (LensSearchMatch);
  // `how` says which found the lenses.
  std::vector<LensEntry> search(std::string_view text, int limit = 50,
                                LensSearchMatch* how = nullptr) const;
  // The lens named exactly (case-insensitive) by its model, or by "maker model"; of several
  // calibrations the one whose crop factor is nearest to `crop` (0: the first). Not found: a
  // message naming the text and up to three near names from search().
  Result<LensEntry> find(std::string_view name, double crop = 0.0) const;
  // For a photo: the camera and lenses its EXIF leads to (PhotoLensTags). The one lookup the
  // studio's lens dialog and `artcam lens camera --from`/`batch --lens-from-exif` share.
  PhotoLensLookup lookUp(const LensHint& hint) const;
  // lookUp's lenses, at most `limit` (0: all).
  std::vector<LensEntry> suggest(const LensHint& hint, int limit = 20) const;

 private:
  LensDatabase() = default;
  lfDatabase* db_ = nullptr;
  std::vector<const lfLens*> lenses_;
  std::vector<LensEntry> entries_;

  // The entries of lensfun's FindLenses answer (freed here), in its order.
  std::vector<LensEntry> entriesOf(const lfLens** found) const;
};

}  // namespace artcam
