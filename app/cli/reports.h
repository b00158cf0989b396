// SPDX-License-Identifier: Apache-2.0
// The JSON reports of artcam's fits and lens cameras (`fit --json`, `fit --lines --json`,
// `fit --block colour --json`, `lens search/camera --json`), one builder each, so the CLI and the
// Python module (python/src: the same dict) say the same thing. The caller adds what only it
// knows (the output file's name).
#pragma once

#include "core/fit/fit_colour.h"
#include "core/fit/fit_image.h"
#include "core/fit/fit_lines.h"
#include "core/lens/lens_camera.h"
#include "core/lens/lens_database.h"
#include "core/lens/photo_lens.h"

#include <nlohmann/json.hpp>

#include <string>

namespace artcam::cli {

// A position fit: model, matches, rms_px, max_px, residuals_px, singular_values, reason,
// held_out_rms_px, algebraic_rms_px, pole_free/pole_margin, criterion, models; inliers when
// `robust`.
nlohmann::json fitReportJson(const FitRecord& record, bool robust);
// A colour fit: block, model, selected, samples, delta_e, mean/median/max_de, rms_rgb, reason,
// held_out_de, candidates; inliers when `robust`.
nlohmann::json colourFitJson(const ColourFitSummary& fit, bool robust);
// A line fit: model, lines (each bow before and after), rms_bow_px, max_bow_px, pairs, reason,
// radial_k, the pairs' residuals.
nlohmann::json linesFitJson(const LinesFitSummary& fit);
// One lens of the database.
nlohmann::json lensEntryJson(const LensEntry& lens);
// A lens camera against lensfun; with `choice` (made from `photo`'s EXIF) its camera, lens match
// and size too.
nlohmann::json lensCameraJson(const LensCameraSummary& summary, const LensCameraOptions& options,
                              const PhotoLensChoice* choice = nullptr,
                              const std::string& photo = "");

}  // namespace artcam::cli
