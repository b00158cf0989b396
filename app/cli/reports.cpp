// SPDX-License-Identifier: Apache-2.0
#include "app/cli/reports.h"

#include "core/colour/colour_map.h"

namespace artcam::cli {

nlohmann::json fitReportJson(const FitRecord& record, bool robust) {
  nlohmann::json j = {{"model", record.model},
                      {"matches", record.matches},
                      {"rms_px", record.rms_px},
                      {"max_px", record.max_px},
                      {"residuals_px", record.residuals_px},
                      {"singular_values", record.singular_values},
                      {"reason", record.reason}};
  if (record.held_out_rms_px >= 0) j["held_out_rms_px"] = record.held_out_rms_px;
  if (record.algebraic_rms_px >= 0) j["algebraic_rms_px"] = record.algebraic_rms_px;
  if (record.pole_checked) {
    j["pole_free"] = record.pole_free;
    j["pole_margin"] = record.pole_margin;
  }
  if (robust) j["inliers"] = record.inliers;
  // Each rung of the ladder as the choice scored it (-1: not computable).
  if (!record.criterion.empty()) j["criterion"] = record.criterion;
  for (const ModelScore& m : record.models)
    j["models"].push_back({{"model", m.model},
                           {"rms_px", m.rms_px},
                           {"held_out_rms_px", m.held_out_rms_px},
                           {"criterion", m.criterion},
                           {"note", m.note}});
  return j;
}

nlohmann::json colourFitJson(const ColourFitSummary& fit, bool robust) {
  nlohmann::json j = {{"block", "colour"},
                      {"model", std::string(colourModelName(fit.map.model))},
                      {"selected", std::string(colourModelName(fit.selected))},
                      {"samples", fit.delta_e.size()},
                      {"delta_e", fit.delta_e},
                      {"mean_de", fit.mean_de},
                      {"median_de", fit.median_de},
                      {"max_de", fit.max_de},
                      {"rms_rgb", fit.rms_rgb},
                      {"reason", fit.reason}};
  if (fit.held_out_de >= 0) j["held_out_de"] = fit.held_out_de;
  nlohmann::json candidates = nlohmann::json::array();
  for (const ColourCandidate& c : fit.candidates) {
    nlohmann::json jc = {{"model", std::string(colourModelName(c.model))}, {"fitted", c.fitted}};
    if (c.fitted) jc["mean_de"] = c.mean_de;
    if (c.held_out_de >= 0) jc["held_out_de"] = c.held_out_de;
    if (!c.fitted) jc["failure"] = c.failure;
    candidates.push_back(jc);
  }
  j["candidates"] = candidates;
  if (robust) j["inliers"] = fit.inliers;
  return j;
}

nlohmann::json linesFitJson(const LinesFitSummary& fit) {
  nlohmann::json per_line = nlohmann::json::array();
  for (size_t k = 0; k < fit.bows.size(); ++k)
    per_line.push_back({{"line", fit.bows[k].label},
                        {"points", fit.bows[k].points},
                        {"bow_px", fit.bows[k].max_px},
                        {"rms_px", fit.bows[k].rms_px},
                        {"bow_before_px", fit.bows_before[k].max_px}});
  const FitRecord record = fit.record();
  nlohmann::json j = {{"model", std::string(lineModelName(fit.model))},
                      {"lines", per_line},
                      {"rms_bow_px", fit.rms_bow_px},
                      {"max_bow_px", fit.max_bow_px},
                      {"pairs", record.matches},
                      {"reason", fit.reason}};
  if (fit.model == LineModel::Radial) j["radial_k"] = fit.radial_k;
  if (record.matches > 0) {
    j["pair_rms_px"] = record.rms_px;
    j["pair_max_px"] = record.max_px;
    j["pair_residuals_px"] = record.residuals_px;
  }
  return j;
}

nlohmann::json lensEntryJson(const LensEntry& e) {
  return {{"maker", e.maker},
          {"model", e.model},
          {"min_focal_mm", e.min_focal_mm},
          {"max_focal_mm", e.max_focal_mm},
          {"crop_factor", e.crop_factor},
          {"type", e.type},
          {"distortion", e.distortion},
          {"tca", e.tca},
          {"vignetting", e.vignetting}};
}

nlohmann::json lensCameraJson(const LensCameraSummary& s, const LensCameraOptions& options,
                              const PhotoLensChoice* choice, const std::string& photo) {
  nlohmann::json j = {
      {"lens", lensEntryJson(s.lens)},
      {"crop", s.crop},
      {"focal_mm", s.focal_mm},
      {"distort", options.distort},
      {"piecewise", s.piecewise},
      {"patches", s.patches},
      {"single_max_px", s.single_max_px},
      {"single_rms_px", s.single_rms_px},
      {"max_px", s.max_px},
      {"rms_px", s.rms_px},
      {"checked", s.checked},
      {"unmapped", s.unmapped},
      {"max_error_px", options.max_error_px},
      {"within_tolerance", s.within_tolerance},
      {"tca", s.tca},
      {"tca_max_px", s.tca_max_px},
      {"aperture", options.aperture},
      {"distance_m", options.distance_m},
      {"vignetting", s.vignetting},
      {"vignetting_max_percent", s.vignetting ? s.vignetting_fit.max_percent : -1.0},
      {"vignetting_rms_percent", s.vignetting ? s.vignetting_fit.rms_percent : -1.0},
      {"notes", s.notes}};
  if (choice) {
    j["photo"] = photo;
    j["camera"] = choice->lookup.camera;
    j["lens_match"] = choice->lookup.lens_match;
    j["size"] = {options.size.width, options.size.height};
  }
  return j;
}

}  // namespace artcam::cli
