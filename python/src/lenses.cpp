// SPDX-License-Identifier: Apache-2.0
// artcam.lens_search and artcam.lens_camera: the lensfun database (core/lens), as `artcam lens
// search` and `artcam lens camera` use it.
#include "app/cli/reports.h"
#include "core/lens/lens_camera.h"
#include "core/lens/lens_database.h"
#include "core/lens/photo_lens.h"
#include "python/src/common.h"

#include <mutex>

namespace artcam::python {
namespace {

// Loaded once per process: the database is read-only once loaded.
std::shared_ptr<const LensDatabase> database() {
  static std::mutex mutex;
  static std::shared_ptr<const LensDatabase> db;
  std::lock_guard lock(mutex);
  if (!db) {
    auto loaded = LensDatabase::load();
    if (!loaded) raiseOSError(loaded.status.message);
    db = *loaded.value;
  }
  return db;
}

py::list lensSearch(const std::string& text, int limit) {
  if (limit < 0) raiseValueError("limit must be 0 (all) or more");
  const auto db = database();
  LensSearchMatch match = LensSearchMatch::None;
  std::vector<LensEntry> hits;
  {
    py::gil_scoped_release release;
    hits = db->search(text, 0, &match);
  }
  py::list out;
  for (size_t i = 0; i < hits.size() && (limit == 0 || i < static_cast<size_t>(limit)); ++i) {
    nlohmann::json lens = cli::lensEntryJson(hits[i]);
    lens["match"] = lensSearchMatchName(match);
    out.append(fromJson(lens));
  }
  return out;
}

py::tuple lensCamera(const py::object& lens, const py::object& focal, const py::object& size,
                     const py::object& photo, const py::object& crop, bool distort, bool tca,
                     const py::object& max_error) {
  LensCameraOptions options;
  if (!photo.is_none()) {
    if (!lens.is_none() || !focal.is_none() || !size.is_none())
      raiseValueError("lens, focal and size cannot go with photo= (the photo gives them)");
  } else {
    if (lens.is_none()) raiseValueError("missing lens= or photo= (artcam.lens_search lists names)");
    if (focal.is_none()) raiseValueError("missing focal= (the focal length in mm)");
    if (size.is_none()) raiseValueError("missing size=(width, height) (the photo's size)");
    options.lens = lens.cast<std::string>();
    options.focal_mm = focal.cast<double>();
    if (!(options.focal_mm > 0)) raiseValueError("focal must be above 0 mm");
    options.size = sizeArgument(size, "size");
  }
  if (!crop.is_none()) {
    options.crop = crop.cast<double>();
    if (!(options.crop > 0)) raiseValueError("crop must be above 0");
  }
  if (!max_error.is_none()) {
    options.max_error_px = max_error.cast<double>();
    if (!(options.max_error_px > 0)) raiseValueError("max_error must be above 0 px");
  }
  options.distort = distort;
  options.tca = tca;
  const auto db = database();
  std::optional<PhotoLensChoice> choice;
  std::string photo_path;
  if (!photo.is_none()) {
    photo_path = pathOf(photo);
    Result<PhotoLensChoice> chosen;
    {
      py::gil_scoped_release release;
      chosen = lensForPhoto(*db, photo_path, options);
    }
    if (!chosen) raiseReadError(photo_path, chosen.status.message);
    choice = std::move(*chosen.value);
    options = choice->options;
  }
  LensCameraSummary s;
  {
    py::gil_scoped_release release;
    s = lensCamera(*db, options);
  }
  if (!s.status)
    raiseValueError(choice ? photo_path + ": " + choice->describe() + ": " + s.status.message
                           : s.status.message);
  nlohmann::json report = cli::lensCameraJson(s, options, choice ? &*choice : nullptr, photo_path);
  report["report"] = s.report();
  const std::string name = "lens " + s.lens.model + " at " +
                           py::repr(py::float_(s.focal_mm)).cast<std::string>() + " mm";
  return py::make_tuple(PyCamera{std::make_shared<const Artcam>(std::move(s.camera)), name},
                        fromJson(report));
}

}  // namespace

void registerLenses(py::module_& m) {
  m.def("lens_search", &lensSearch, py::arg("text"), py::kw_only(), py::arg("limit") = 50, R"doc(
Lenses of the lensfun database whose name holds every word of `text` (as `artcam lens search`;
lensfun's own and loose matches when no name holds them all). Returns a list of dicts: maker,
model, min_focal_mm, max_focal_mm, crop_factor, type, distortion, tca, vignetting, and match
('words', 'lensfun' or 'lensfun-loose'). limit=0 returns all.)doc");
  m.def("lens_camera", &lensCamera, py::arg("lens") = py::none(), py::arg("focal") = py::none(),
        py::arg("size") = py::none(), py::kw_only(), py::arg("photo") = py::none(),
        py::arg("crop") = py::none(), py::arg("distort") = false, py::arg("tca") = true,
        py::arg("max_error") = py::none(), R"doc(
The camera that corrects (distort=True: simulates) a lens of the lensfun database, as
`artcam lens camera` makes it: lens (a model name), focal (mm) and size=(width, height), or
photo= a photo whose EXIF names its camera, lens and focal length (`--from PHOTO`: made for its
stored raster). crop: the camera's crop factor (default the lens's); tca: one layer per colour
channel where the database has TCA; max_error: single camera up to this (px), piecewise beyond.
Returns (camera, report): report as `artcam lens camera --json` (single and final rms/max
against lensfun over the check grid, patches, tca_max_px, notes) plus 'report'.)doc");
}

}  // namespace artcam::python
