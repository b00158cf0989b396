// SPDX-License-Identifier: Apache-2.0
// CSV inputs of the CLI: match lists with the header `src_x,src_y,dst_x,dst_y`
// (pixels; 3D: src_x,src_y,src_z,dst_x,dst_y,dst_z), colour samples with the header
// `src_r,src_g,src_b,dst_r,dst_g,dst_b`, and point lists `x,y` (a header line is allowed).
//
// Colour samples: one pair of RGB colours per row, the source colour (a patch in the photo to
// recolour) and the colour it should become. Values are LINEAR-LIGHT RGB with sRGB (Rec. 709)
// primaries and D65 white, 1 = diffuse white (the engine's working space): values
// above 1 or below 0 are kept. ColourEncoding::Srgb reads values that are sRGB-ENCODED
// (0…1, e.g. 8-bit codes divided by 255) and decodes them to linear light on read. Opaque:
// there is no alpha column. Errors name the file, the line and the cause ("matches.csv:7: expected 4 numbers,
// found 3").
//
// Strict on purpose (a typo must not become a 0): numbers are the whole field, parsed with
// std::from_chars (correctly rounded, locale-free; a leading '+' is allowed); NaN, inf and
// out-of-range literals are refused. Blank lines and lines starting with '#' are skipped;
// CRLF, spaces around fields and a UTF-8 BOM are tolerated. A match list may end with an
// `enabled` column (0/1/true/false); writeMatchesCsv adds it when a match is disabled.
#pragma once

#include "core/model/fit_record.h"
#include "core/model/line_trace.h"
#include "core/model/status.h"

#include <Eigen/Core>

#include <string>
#include <string_view>
#include <vector>

namespace artcam {

// dimension 2 or 3: coordinates per side.
Result<std::vector<PointMatch>> readMatchesCsv(const std::string& path, int dimension = 2);
// Colour samples as 3D matches (source = src_r,src_g,src_b; target = dst_r,dst_g,dst_b), in
// linear light whatever the file's encoding; the optional `enabled` column as for matches.
enum class ColourEncoding { Linear, Srgb };
Result<std::vector<PointMatch>> readColourSamplesCsv(const std::string& path,
                                                     ColourEncoding encoding = ColourEncoding::Linear);
Result<std::vector<Eigen::Vector2d>> readPointsCsv(const std::string& path);
// The same readers on text already in memory; `name` stands for the file in messages (the
// fuzz targets in fuzz/ call these).
Result<std::vector<PointMatch>> parseMatchesCsv(std::string_view text, const std::string& name,
                                                int dimension = 2);
Result<std::vector<PointMatch>> parseColourSamplesCsv(
    std::string_view text, const std::string& name, ColourEncoding encoding = ColourEncoding::Linear);
// Points grouped by a label, the header `LABEL,x,y` (lines: `line`, walls: `wall`), one point
// per row; the rows with one label, in file order, are one group, the groups in the order their
// labels first appear. `first_line` is where a group starts, for the callers' messages.
struct LabelledPoints {
  std::string label;
  std::vector<Eigen::Vector2d> points;
  int first_line = 0;
};
Result<std::vector<LabelledPoints>> parseLabelledPointsCsv(std::string_view text,
                                                           const std::string& name,
                                                           const std::string& label_column);
// Straight lines traced in a photo: the header `line,x,y`, one point per row (source pixels);
// `line` is any non-empty label, and the rows with one label, in file order, are one line.
Result<std::vector<LineTrace>> readLinesCsv(const std::string& path);
Result<std::vector<LineTrace>> parseLinesCsv(std::string_view text, const std::string& name);
// Writes the header and rows with %.17g numbers (locale-free, round-trip exact; atomic).
Status writeMatchesCsv(const std::string& path, const std::vector<PointMatch>& matches);
// Colour samples in the columns parseColourSamplesCsv reads (linear light, as given).
Status writeColourSamplesCsv(const std::string& path, const std::vector<PointMatch>& samples);
// Points under the header `x,y`, as readPointsCsv reads them.
Status writePointsCsv(const std::string& path, const std::vector<Eigen::Vector2d>& points);

}  // namespace artcam
