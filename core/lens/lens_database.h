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
  std::vector<LensEntry> search(std::string_view text, int limit = 50) const;
  // The lens named exactly (case-insensitive) by its model, or by "maker model"; of several
  // calibrations the one whose crop factor is nearest to `crop` (0: the first). Not found: a
  // message naming the text and up to three near names from search().
  Result<LensEntry> find(std::string_view name, double crop = 0.0) const;
  // For a photo: the lenses its EXIF lens name finds, else the lenses lensfun lists for its
  // camera; those covering the focal length first.
  std::vector<LensEntry> suggest(const LensHint& hint, int limit = 20) const;

 private:
  LensDatabase() = default;
  lfDatabase* db_ = nullptr;
  std::vector<const lfLens*> lenses_;
  std::vector<LensEntry> entries_;
};

}  // namespace artcam
