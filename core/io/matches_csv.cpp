// SPDX-License-Identifier: Apache-2.0
// Strict CSV for match and point lists: numbers parse with std::from_chars (correctly rounded,
// locale-free, the whole field or nothing), so a typo is reported instead of read as 0. Blank
// lines and lines starting with '#' are skipped; CRLF and a UTF-8 BOM are tolerated.
#include "core/io/matches_csv.h"

#include "core/colour/transfer.h"
#include "core/io/atomic_file.h"
#include "core/io/text_input.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <string_view>
#include <unordered_map>

namespace artcam {

namespace {

struct Line {
  int number = 0;  // 1-based line in the file
  std::string_view text;
};

std::string_view trim(std::string_view s) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> splitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    fields.push_back(
        trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

// The lines that carry data: blank lines and '#' comments dropped, line numbers kept.
std::vector<Line> contentLines(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  std::vector<Line> lines;
  int number = 0;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = std::min(text.find('\n', start), text.size());
    ++number;
    const std::string_view line = trim(text.substr(start, end - start));
    if (!line.empty() && line.front() != '#') lines.push_back({number, line});
    start = end + 1;
  }
  return lines;
}

// The whole field must be a number. std::from_chars leaves the value untouched on overflow
// and underflow (1e999, 1e-999), so those are reported as out of range rather than guessed.
enum class Parsed { Number, NotNumber, OutOfRange };

Parsed parseNumber(std::string_view field, double& value) {
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  if (field.empty()) return Parsed::NotNumber;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (end != field.data() + field.size()) return Parsed::NotNumber;
  if (error == std::errc::result_out_of_range) return Parsed::OutOfRange;
  return error == std::errc() ? Parsed::Number : Parsed::NotNumber;
}

bool isNumber(std::string_view field) {
  double ignored = 0.0;
  return parseNumber(field, ignored) != Parsed::NotNumber;
}

std::string quoted(std::string_view s) { return "\"" + std::string(s) + "\""; }

// Parses one number per name from the leading fields; the message names the column.
std::optional<std::string> parseNumbers(const std::vector<std::string_view>& fields,
                                        const std::vector<std::string>& names, double* out) {
  for (size_t k = 0; k < names.size(); ++k) {
    const std::string where = "column " + std::to_string(k + 1) + " (" + names[k] + ")";
    if (fields[k].empty()) return where + ": empty";
    const Parsed parsed = parseNumber(fields[k], out[k]);
    if (parsed == Parsed::NotNumber) return where + ": not a number: " + quoted(fields[k]);
    if (parsed == Parsed::OutOfRange)
      return where + ": out of range for a double: " + quoted(fields[k]);
    if (!std::isfinite(out[k])) return where + ": not a finite number: " + quoted(fields[k]);
    // A value no photo, frame or colour can have: refused here, where the row can be named,
    // rather than later as an overflowing residual or a fit record that cannot be written.
    if (std::abs(out[k]) > kMaxMatchValue)
      return where + ": " + quoted(fields[k]) + " is beyond any coordinate or colour (|value| > 1e9)";
  }
  return std::nullopt;
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) {
    return static_cast<char>(c >= 'A' && c <= 'Z' ? c + 32 : c);
  });
  return out;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ",") + n;
  return out;
}

// Pairs of `names.size() / 2` numbers per side under the header `names` (+ optional enabled).
// `path` names the file in messages.
Result<std::vector<PointMatch>> parsePairsCsv(std::string_view text, const std::string& path,
                                              const std::vector<std::string>& names) {
  using R = Result<std::vector<PointMatch>>;
  const int dimension = static_cast<int>(names.size() / 2);
  const size_t numbers = names.size();
  const std::vector<Line> lines = contentLines(text);
  if (lines.empty()) return R::failure(path + ": empty, expected the header " + joined(names));

  // Header: the coordinate columns, optionally followed by "enabled" (0/1, true/false).
  const std::vector<std::string_view> header = splitFields(lines.front().text);
  std::vector<std::string> header_names;
  for (std::string_view h : header) header_names.push_back(lower(h));
  bool has_enabled = false;
  std::vector<std::string> with_enabled = names;
  with_enabled.push_back("enabled");
  if (header_names == with_enabled) {
    has_enabled = true;
  } else if (header_names != names) {
    return R::failure(path + ":" + std::to_string(lines.front().number) + ": expected the header " +
                      joined(names) + ", found " + quoted(lines.front().text));
  }

  std::vector<PointMatch> matches;
  for (size_t l = 1; l < lines.size(); ++l) {
    const std::string where = textInputName(path) + ":" + std::to_string(lines[l].number) + ": ";
    const std::vector<std::string_view> fields = splitFields(lines[l].text);
    const size_t expected = numbers + (has_enabled ? 1 : 0);
    if (fields.size() != expected)
      return R::failure(where + "expected " + std::to_string(numbers) + " numbers" +
                        (has_enabled ? " and enabled" : "") + ", found " +
                        std::to_string(fields.size()) + (has_enabled ? " fields" : ""));
    double values[6] = {};
    if (const auto error = parseNumbers(fields, names, values)) return R::failure(where + *error);
    PointMatch match;
    const int d = dimension;
    match.source = Eigen::Map<const Eigen::VectorXd>(values, d);
    match.target = Eigen::Map<const Eigen::VectorXd>(values + d, d);
    if (has_enabled) {
      const std::string flag = lower(fields[numbers]);
      if (flag == "1" || flag == "true") {
        match.enabled = true;
      } else if (flag == "0" || flag == "false") {
        match.enabled = false;
      } else {
        return R::failure(where + "column " + std::to_string(numbers + 1) +
                          " (enabled): expected 0, 1, true or false, found " +
                          quoted(fields[numbers]));
      }
    }
    matches.push_back(std::move(match));
  }
  return R::success(std::move(matches));
}

}  // namespace

Result<std::vector<PointMatch>> parseMatchesCsv(std::string_view text, const std::string& name,
                                                int dimension) {
  using R = Result<std::vector<PointMatch>>;
  if (dimension != 2 && dimension != 3)
    return R::failure(name + ": matches must have 2 or 3 coordinates per side, not " +
                      std::to_string(dimension));
  return parsePairsCsv(text, name,
                       dimension == 2 ? std::vector<std::string>{"src_x", "src_y", "dst_x", "dst_y"}
                                      : std::vector<std::string>{"src_x", "src_y", "src_z",
                                                                 "dst_x", "dst_y", "dst_z"});
}

Result<std::vector<PointMatch>> readMatchesCsv(const std::string& path, int dimension) {
  const Result<std::string> text = readTextInput(path);
  if (!text) return Result<std::vector<PointMatch>>::failure(text.status.message);
  return parseMatchesCsv(*text, textInputName(path), dimension);
}

Result<std::vector<PointMatch>> readColourSamplesCsv(const std::string& path,
                                                     ColourEncoding encoding) {
  const Result<std::string> text = readTextInput(path);
  if (!text) return Result<std::vector<PointMatch>>::failure(text.status.message);
  return parseColourSamplesCsv(*text, textInputName(path), encoding);
}

Result<std::vector<PointMatch>> parseColourSamplesCsv(std::string_view text,
                                                      const std::string& name,
                                                      ColourEncoding encoding) {
  auto samples =
      parsePairsCsv(text, name, {"src_r", "src_g", "src_b", "dst_r", "dst_g", "dst_b"});
  if (samples && encoding == ColourEncoding::Srgb) {
    const Transfer srgb = Transfer::srgb();
    const char* const names[] = {"src_r", "src_g", "src_b", "dst_r", "dst_g", "dst_b"};
    for (size_t s = 0; s < samples->size(); ++s) {
      PointMatch& sample = (*samples)[s];
      for (int k = 0; k < 6; ++k) {
        double& value = k < 3 ? sample.source[k] : sample.target[k - 3];
        const double encoded = value;
        value = srgb.decode(encoded);
        // The decode raises to the power 2.4: a huge encoded value (1e308) overflows to inf.
        if (!std::isfinite(value))
          return Result<std::vector<PointMatch>>::failure(
              name + ": sample " + std::to_string(s + 1) + ", column " + std::to_string(k + 1) +
              " (" + names[k] + "): sRGB value " + std::to_string(encoded) +
              " decodes to a non-finite linear value (sRGB-encoded values are 0…1)");
      }
    }
  }
  return samples;
}

Result<std::vector<Eigen::Vector2d>> readPointsCsv(const std::string& path) {
  using R = Result<std::vector<Eigen::Vector2d>>;
  const Result<std::string> text = readTextInput(path);
  if (!text) return R::failure(text.status.message);
  const std::vector<std::string> names{"x", "y"};
  std::vector<Eigen::Vector2d> points;
  const std::vector<Line> lines = contentLines(*text);
  for (size_t l = 0; l < lines.size(); ++l) {
    const std::string where = textInputName(path) + ":" + std::to_string(lines[l].number) + ": ";
    const std::vector<std::string_view> fields = splitFields(lines[l].text);
    if (fields.size() != 2)
      return R::failure(where + "expected 2 numbers, found " + std::to_string(fields.size()));
    // The first line may be a header: two names, neither a number.
    if (l == 0 && !isNumber(fields[0]) && !isNumber(fields[1])) continue;
    double values[2] = {};
    if (const auto error = parseNumbers(fields, names, values)) return R::failure(where + *error);
    points.emplace_back(values[0], values[1]);
  }
  return R::success(std::move(points));
}

namespace {

// The rows of both CSV kinds: `columns` names the 2·d values; an `enabled` column is added when
// a row is disabled. `what` names a row in messages ("match", "sample").
Status writeRows(const std::string& path, const std::vector<PointMatch>& rows, Eigen::Index d,
                 const char* columns, const char* what) {
  bool any_disabled = false;
  for (size_t m = 0; m < rows.size(); ++m) {
    const PointMatch& row = rows[m];
    if (row.source.size() != d || row.target.size() != d)
      return Status::failure(path + ": cannot write: " + what + " " + std::to_string(m) +
                             " has " + std::to_string(row.source.size()) + " and " +
                             std::to_string(row.target.size()) + " values per side, not " +
                             std::to_string(d));
    if (!row.source.allFinite() || !row.target.allFinite())
      return Status::failure(path + ": cannot write: " + what + " " + std::to_string(m) +
                             " has a non-finite value");
    any_disabled = any_disabled || !row.enabled;
  }
  std::string text = columns;
  if (any_disabled) text += ",enabled";
  text += "\n";
  char buffer[32];
  for (const PointMatch& row : rows) {
    for (Eigen::Index k = 0; k < 2 * d; ++k) {
      const double v = k < d ? row.source[k] : row.target[k - d];
      // %.17g, but locale-free: a GUI process runs under the user's locale (decimal commas).
      const auto result =
          std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::general, 17);
      text += (k ? "," : "") + std::string(buffer, result.ptr);
    }
    if (any_disabled) text += row.enabled ? ",1" : ",0";
    text += "\n";
  }
  return writeTextAtomically(path, text);
}

}  // namespace

Status writeMatchesCsv(const std::string& path, const std::vector<PointMatch>& matches) {
  const Eigen::Index d = matches.empty() ? 2 : matches.front().source.size();
  if (d != 2 && d != 3)
    return Status::failure(path + ": cannot write: matches must have 2 or 3 coordinates per side");
  return writeRows(path, matches, d,
                   d == 2 ? "src_x,src_y,dst_x,dst_y" : "src_x,src_y,src_z,dst_x,dst_y,dst_z",
                   "match");
}

Status writeColourSamplesCsv(const std::string& path, const std::vector<PointMatch>& samples) {
  return writeRows(path, samples, 3, "src_r,src_g,src_b,dst_r,dst_g,dst_b", "sample");
}

Status writePointsCsv(const std::string& path, const std::vector<Eigen::Vector2d>& points) {
  std::string text = "x,y\n";
  char buffer[32];
  for (size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())
      return Status::failure(path + ": cannot write: point " + std::to_string(i) +
                             " has a non-finite value");
    for (int k = 0; k < 2; ++k) {
      // Locale-free %.17g, as for the match rows.
      const auto result =
          std::to_chars(buffer, buffer + sizeof buffer, points[i][k], std::chars_format::general, 17);
      text += (k ? "," : "") + std::string(buffer, result.ptr);
    }
    text += "\n";
  }
  return writeTextAtomically(path, text);
}

// Lines: rows `line,x,y`, one traced point per row; the rows of one line need not be
// adjacent (a line is every row with its label, in file order), and lines keep the order in
// which their labels first appear.
Result<std::vector<LabelledPoints>> parseLabelledPointsCsv(std::string_view text,
                                                           const std::string& name,
                                                           const std::string& label_column) {
  using R = Result<std::vector<LabelledPoints>>;
  const std::string header_text = label_column + ",x,y";
  const std::vector<Line> lines = contentLines(text);
  if (lines.empty()) return R::failure(name + ": empty, expected the header " + header_text);
  std::vector<std::string> header;
  for (std::string_view h : splitFields(lines.front().text)) header.push_back(lower(h));
  if (header != std::vector<std::string>{label_column, "x", "y"})
    return R::failure(name + ":" + std::to_string(lines.front().number) + ": expected the header " +
                      header_text + ", found " + quoted(lines.front().text));
  std::vector<LabelledPoints> out;
  // Each label's place in `out`: one hash look-up per row keeps the parse linear in the rows
  // (a search of `out` per row made 200 000 one-point lines a quadratic half minute).
  std::unordered_map<std::string, size_t> index_of_label;
  for (size_t l = 1; l < lines.size(); ++l) {
    const std::string where = name + ":" + std::to_string(lines[l].number) + ": ";
    const std::vector<std::string_view> fields = splitFields(lines[l].text);
    if (fields.size() != 3)
      return R::failure(where + "expected a " + label_column + " label and 2 numbers, found " +
                        std::to_string(fields.size()) + " fields");
    if (fields[0].empty()) return R::failure(where + "column 1 (" + label_column + "): empty");
    double xy[2] = {};
    for (int k = 0; k < 2; ++k) {
      const std::string column = k == 0 ? "x" : "y";
      // parseNumbers names the column of its own list ("column 1 (x)..."); keep the cause.
      if (const auto error = parseNumbers({fields[static_cast<size_t>(k) + 1]}, {column}, &xy[k]))
        return R::failure(where + "column " + std::to_string(k + 2) + " (" + column + ")" +
                          error->substr(error->find(')') + 1));
    }
    const auto [at, added] = index_of_label.try_emplace(std::string(fields[0]), out.size());
    if (added) out.push_back(LabelledPoints{at->first, {}, lines[l].number});
    out[at->second].points.emplace_back(xy[0], xy[1]);
  }
  if (out.empty()) return R::failure(name + ": no rows after the header " + header_text);
  return R::success(std::move(out));
}

Result<std::vector<LineTrace>> parseLinesCsv(std::string_view text, const std::string& name) {
  auto labelled = parseLabelledPointsCsv(text, name, "line");
  if (!labelled) return Result<std::vector<LineTrace>>::failure(labelled.status.message);
  std::vector<LineTrace> out;
  for (LabelledPoints& l : *labelled)
    out.push_back(LineTrace{std::move(l.label), std::move(l.points), true});
  return Result<std::vector<LineTrace>>::success(std::move(out));
}

Result<std::vector<LineTrace>> readLinesCsv(const std::string& path) {
  const Result<std::string> text = readTextInput(path);
  if (!text) return Result<std::vector<LineTrace>>::failure(text.status.message);
  return parseLinesCsv(*text, textInputName(path));
}

}  // namespace artcam
