// SPDX-License-Identifier: Apache-2.0
// artcam.fit, fit_lines, fit_stmap, fit_colour: core's fits on numpy arrays (or the CLI's files),
// each returning the camera and the report `artcam fit --json` prints. Arrays are read through
// the CSV readers' own parser (written as %.17g rows under the header, exact), so an array is
// checked as a file is: the same bounds, the same refusal of NaN and inf, the same messages
// (row k, from 0, is line k + 2).
#include "app/cli/reports.h"
#include "core/colour/colour_map.h"
#include "core/fit/fit_colour.h"
#include "core/fit/fit_image.h"
#include "core/fit/fit_lines.h"
#include "core/io/matches_csv.h"
#include "core/io/stmap_file.h"
#include "core/project/document_camera.h"
#include "python/src/common.h"

#include <cstdio>

namespace artcam::python {
namespace {

using Rows = py::array_t<double, py::array::c_style | py::array::forcecast>;

Rows rowsOf(const py::handle& a, py::ssize_t columns, const std::string& what) {
  const Rows rows = Rows::ensure(a);
  if (!rows || rows.ndim() != 2 || rows.shape(1) != columns)
    raiseValueError(what + ": expected an N×" + std::to_string(columns) + " array");
  return rows;
}

// `a` and `b` side by side as CSV rows (no header), with an enabled column when given.
std::string csvRows(const Rows& a, const Rows& b, const py::object& enabled,
                    const std::string& what, const std::string& header) {
  if (a.shape(0) != b.shape(0))
    raiseValueError(what + ": " + std::to_string(a.shape(0)) + " sources but " +
                    std::to_string(b.shape(0)) + " targets");
  std::vector<bool> on(static_cast<size_t>(a.shape(0)), true);
  if (!enabled.is_none()) {
    on = enabled.cast<std::vector<bool>>();
    if (on.size() != static_cast<size_t>(a.shape(0)))
      raiseValueError(what + ": enabled has " + std::to_string(on.size()) + " entries for " +
                      std::to_string(a.shape(0)) + " rows");
  }
  std::string text = header + ",enabled\n";
  char number[40];
  for (py::ssize_t r = 0; r < a.shape(0); ++r) {
    for (py::ssize_t c = 0; c < a.shape(1) + b.shape(1); ++c) {
      const double v = c < a.shape(1) ? a.at(r, c) : b.at(r, c - a.shape(1));
      std::snprintf(number, sizeof number, "%s%.17g", c ? "," : "", v);
      text += number;
    }
    text += on[static_cast<size_t>(r)] ? ",1\n" : ",0\n";
  }
  return text;
}

std::vector<PointMatch> matchesFrom(const py::object& src, const py::object& dst,
                                    const py::object& enabled, int* dimension) {
  if (isPathLike(src)) {
    if (!dst.is_none()) raiseValueError("fit: give a matches CSV alone, or src and dst arrays");
    const std::string path = pathOf(src);
    auto read = readMatchesCsv(path, *dimension);
    if (!read) raiseReadError(path, read.status.message);
    return std::move(*read);
  }
  if (dst.is_none()) raiseValueError("fit: dst (the target points) is missing");
  const Rows probe = Rows::ensure(src);
  if (probe && probe.ndim() == 2 && probe.shape(1) == 3) *dimension = 3;
  const Rows a = rowsOf(src, *dimension, "src"), b = rowsOf(dst, *dimension, "dst");
  const char* header =
      *dimension == 2 ? "src_x,src_y,dst_x,dst_y" : "src_x,src_y,src_z,dst_x,dst_y,dst_z";
  auto parsed = parseMatchesCsv(csvRows(a, b, enabled, "fit", header), "<matches>", *dimension);
  if (!parsed) raiseValueError(parsed.status.message);
  return std::move(*parsed);
}

PyCamera cameraOf(Artcam doc, const std::string& name) {
  return {std::make_shared<const Artcam>(std::move(doc)), name};
}

void checked(const Status& s) {
  if (!s) raiseValueError(s.message);
}

// The CLI's --json report with its summary line beside it.
py::object reportOf(nlohmann::json report, const std::string& line) {
  report["report"] = line;
  return fromJson(report);
}

py::tuple fit(const py::object& src, const py::object& dst, const py::object& size,
              const py::object& target_size, const std::string& model, bool robust,
              const py::object& threshold, bool refine, bool allow_poles,
              const py::object& enabled) {
  FitOptions options;
  const auto m = modelClassFromName(model);
  if (!m) raiseValueError("unknown model \"" + model + "\"");
  options.model = *m;
  options.robust = robust;
  if (!threshold.is_none()) {
    if (!robust) raiseValueError("threshold goes with robust=True");
    options.robust_threshold_px = threshold.cast<double>();
  }
  options.refine = refine;
  options.require_pole_free = !allow_poles;
  checked(options.check());
  int dimension = 2;
  const std::vector<PointMatch> matches = matchesFrom(src, dst, enabled, &dimension);
  FrameSize source, target;
  if (dimension == 2) {
    if (size.is_none()) raiseValueError("fit: size=(width, height) of the source image is missing");
    source = sizeArgument(size, "size");
    target = target_size.is_none() ? source : sizeArgument(target_size, "target_size");
  }
  FitSummary summary;
  {
    py::gil_scoped_release release;
    summary = dimension == 2 ? fitImageCamera(matches, source, target, options)
                             : fitObjectCamera(matches, options);
  }
  if (!summary.status) raiseValueError(summary.status.message);
  Artcam doc(summary.camera);
  doc.matches = matches;
  doc.fit = summary.record;
  nlohmann::json report = cli::fitReportJson(summary.record, options.robust);
  const std::vector<std::string> warnings = cameraWarnings(doc);
  if (!warnings.empty()) report["warning"] = warnings.back();
  return py::make_tuple(cameraOf(std::move(doc), "fit " + summary.record.model),
                        reportOf(std::move(report), summary.report()));
}

py::tuple fitLines(const py::object& lines_in, const py::object& size, const py::object& pairs_src,
                   const py::object& pairs_dst, const py::object& target_size,
                   const std::string& model) {
  const auto m = lineModelFromName(model);
  if (!m)
    raiseValueError("model with lines expects auto, radial or quadratic, not \"" + model + "\"");
  LinesFitOptions options;
  options.model = *m;
  checked(options.check());
  // Lines: a CSV path, or a list of N×2 arrays (labelled 1, 2, …), or a {label: N×2} dict.
  std::vector<LineTrace> lines;
  if (isPathLike(lines_in)) {
    const std::string path = pathOf(lines_in);
    auto read = readLinesCsv(path);
    if (!read) raiseReadError(path, read.status.message);
    lines = std::move(*read);
  } else {
    std::vector<std::pair<std::string, py::object>> labelled;
    if (py::isinstance<py::dict>(lines_in)) {
      for (const auto& [label, points] : lines_in.cast<py::dict>())
        labelled.emplace_back(py::str(label).cast<std::string>(),
                              py::reinterpret_borrow<py::object>(points));
    } else {
      int k = 0;
      for (const py::handle points : lines_in.cast<py::sequence>())
        labelled.emplace_back(std::to_string(++k), py::reinterpret_borrow<py::object>(points));
    }
    std::string text = "line,x,y\n";
    char row[96];
    for (const auto& [label, points] : labelled) {
      if (label.find_first_of(",\n\r\"") != std::string::npos)
        raiseValueError("line label \"" + label + "\": no commas, quotes or line breaks");
      const Rows p = rowsOf(points, 2, "line " + label);
      for (py::ssize_t r = 0; r < p.shape(0); ++r) {
        std::snprintf(row, sizeof row, ",%.17g,%.17g\n", p.at(r, 0), p.at(r, 1));
        text += label + row;
      }
    }
    auto parsed = parseLinesCsv(text, "<lines>");
    if (!parsed) raiseValueError(parsed.status.message);
    lines = std::move(*parsed);
  }
  std::vector<PointMatch> pairs;
  if (!pairs_src.is_none()) {
    int dimension = 2;
    pairs = matchesFrom(pairs_src, pairs_dst, py::none(), &dimension);
    if (dimension != 2) raiseValueError("fit_lines: pairs are 2D (N×2)");
  }
  const FrameSize source = sizeArgument(size, "size");
  const FrameSize target =
      target_size.is_none() ? source : sizeArgument(target_size, "target_size");
  LinesFitSummary summary;
  {
    py::gil_scoped_release release;
    summary = target == source ? fitDocumentLines(lines, pairs, source, options.model)
                               : fitLinesCamera(lines, pairs, source, target, options);
  }
  if (!summary.status) raiseValueError(summary.status.message);
  Artcam doc(summary.camera);
  doc.matches = pairs;
  doc.fit = summary.record();
  return py::make_tuple(
      cameraOf(std::move(doc), "fit_lines " + std::string(lineModelName(summary.model))),
      reportOf(cli::linesFitJson(summary), summary.report()));
}

py::tuple fitStmap(const std::string& path, const py::object& size, const std::string& layer,
                   const std::string& model, bool robust) {
  StmapSampleOptions options;
  if (!size.is_none()) options.source_px = sizeArgument(size, "size");
  options.layer = layer;
  Result<StmapSamples> samples;
  {
    py::gil_scoped_release release;
    samples = readStmapSamples(path, options);
  }
  if (!samples) raiseReadError(path, samples.status.message);
  FitOptions fit_options;
  const auto m = modelClassFromName(model);
  if (!m) raiseValueError("unknown model \"" + model + "\"");
  fit_options.model = *m;
  fit_options.robust = robust;
  FitSummary summary;
  {
    py::gil_scoped_release release;
    summary = fitImageCamera(samples->matches, samples->source_px, samples->map_px, fit_options);
  }
  if (!summary.status) raiseValueError(path + ": " + summary.status.message);
  Artcam doc(summary.camera);
  doc.matches = samples->matches;
  doc.fit = summary.record;
  nlohmann::json report = cli::fitReportJson(summary.record, robust);
  report["samples"] = samples->matches.size();
  report["step_px"] = samples->step;
  report["convention"] = std::string(stmapConventionName(samples->convention));
  return py::make_tuple(cameraOf(std::move(doc), "fit_stmap " + path),
                        reportOf(std::move(report), summary.report()));
}

py::tuple fitColour(const py::object& src, const py::object& dst, const py::object& size,
                    const std::string& model, bool robust, const py::object& threshold, bool srgb,
                    const py::object& enabled) {
  ColourFitOptions options;
  const auto m = colourModelFromName(model);
  if (!m) raiseValueError("unknown colour model \"" + model + "\"");
  if (*m == ColourModel::RootPolynomial)
    raiseValueError(
        "a root-polynomial colour map is not a quadratic form, so no ARTcam can hold "
        "it; use model='auto' to compare it with the models that can be stored");
  options.model = *m;
  options.robust = robust;
  if (!threshold.is_none()) {
    if (!robust) raiseValueError("threshold goes with robust=True");
    options.robust_threshold_de = threshold.cast<double>();
  }
  checked(options.check());
  const FrameSize frame = sizeArgument(size, "size");
  const Rows a = rowsOf(src, 3, "src"), b = rowsOf(dst, 3, "dst");
  auto samples = parseColourSamplesCsv(
      csvRows(a, b, enabled, "fit_colour", "src_r,src_g,src_b,dst_r,dst_g,dst_b"), "<samples>",
      srgb ? ColourEncoding::Srgb : ColourEncoding::Linear);
  if (!samples) raiseValueError(samples.status.message);
  ColourFitSummary summary;
  {
    py::gil_scoped_release release;
    summary = fitColourSamples(*samples, options);
  }
  if (!summary.status) raiseValueError(summary.status.message);
  Artcam doc(colourCamera(summary.map, frame));
  doc.matches = *samples;
  doc.fit = summary.record();
  return py::make_tuple(
      cameraOf(std::move(doc), "fit_colour " + std::string(colourModelName(summary.map.model))),
      reportOf(cli::colourFitJson(summary, robust), summary.report()));
}

}  // namespace

void registerFitting(py::module_& m) {
  m.def("fit", &fit, py::arg("src"), py::arg("dst") = py::none(), py::arg("size") = py::none(),
        py::kw_only(), py::arg("target_size") = py::none(), py::arg("model") = "auto",
        py::arg("robust") = false, py::arg("threshold") = py::none(), py::arg("refine") = true,
        py::arg("allow_poles") = false, py::arg("enabled") = py::none(), R"doc(
Fits a camera to point matches, as `artcam fit MATCHES.csv --size WxH` does.

src, dst: N×2 arrays of source and target pixels (N×3 object points for a 3D camera, no size),
  or src a matches CSV path and dst None.
size: (width, height) of the source image; target_size: of the target (default size).
model: 'auto' (the ladder, chosen by held-out error), 'translation', 'similarity', 'affine',
  'homography' or 'quadratic'. robust: MSAC/LO-RANSAC first (threshold in target px, default 3).
refine: Levenberg–Marquardt after the DLT; allow_poles: keep a camera with a pole in the frame.
enabled: N booleans (False leaves a match out, as the CSV's enabled column).

Returns (camera, report): report is the dict `artcam fit --json` prints (model, matches, rms_px,
max_px, residuals_px, reason, held_out_rms_px, models, …) plus 'report', the CLI's summary line.
Raises ValueError with the CLI's message: too few matches, degenerate ones (row k, from 0, is
line k + 2 of the CSV it would be),
NaN or inf, a camera with a pole.)doc");
  m.def("fit_lines", &fitLines, py::arg("lines"), py::arg("size"), py::kw_only(),
        py::arg("pairs_src") = py::none(), py::arg("pairs_dst") = py::none(),
        py::arg("target_size") = py::none(), py::arg("model") = "auto", R"doc(
Fits a lens camera that straightens traced lines, as `artcam fit --lines LINES.csv` (and the
studio's line tool) does.

lines: a list of N×2 arrays of source pixels (one per straight edge, at least 3 points), a dict
  {label: N×2 array}, or a lines CSV path (line,x,y). size: (width, height) of the photo.
pairs_src, pairs_dst: optional N×2 point pairs fitted with the lines.
model: 'auto', 'radial' or 'quadratic'.

Returns (camera, report): report as `artcam fit --lines --json` (lines with each bow before and
after, rms_bow_px, max_bow_px, radial_k, reason, …) plus 'report'.)doc");
  m.def("fit_stmap", &fitStmap, py::arg("path"), py::kw_only(), py::arg("size") = py::none(),
        py::arg("layer") = "", py::arg("model") = "auto", py::arg("robust") = false, R"doc(
Fits a camera to an ST map (Nuke's STMap or OpenCV's maps, as export_map writes them), as
`artcam fit --stmap MAP.exr` does. size: the photo's (width, height) when the map's header
does not say; layer: one layer of a layered map. Returns (camera, report) with the fit's report
plus samples, step_px and convention.)doc");
  m.def("fit_colour", &fitColour, py::arg("src"), py::arg("dst"), py::arg("size"), py::kw_only(),
        py::arg("model") = "auto", py::arg("robust") = false, py::arg("threshold") = py::none(),
        py::arg("srgb") = false, py::arg("enabled") = py::none(), R"doc(
Fits a colour camera (the paper's colour block) to colour samples, as `artcam fit --block colour`
does: src, dst N×3 arrays of linear Rec.709 RGB (srgb=True: sRGB-encoded 0..1, decoded first);
size: (width, height) of the photos it will recolour. model: 'auto', 'linear', 'affine',
'quadratic' (those an ARTcam holds). robust: threshold in ΔE00 (default 3).
Returns (camera, report): report as `artcam fit --block colour --json` (delta_e, mean_de,
median_de, max_de, candidates' choice, reason) plus 'report'.)doc");
}

}  // namespace artcam::python
