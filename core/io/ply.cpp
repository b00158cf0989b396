// SPDX-License-Identifier: Apache-2.0
// PLY reading (see ply.h for the decisions; writing is in ply_write.cpp). The reader works on the
// whole file in memory: one read, then a header pass that checks every count against the bytes that
// follow, then one pass over the vertices. Numbers parse with std::from_chars (locale-free, exact).
#include "core/io/ply.h"

#include "core/colour/transfer.h"
#include "core/io/text_input.h"
#include "core/util/memory_budget.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace artcam {

namespace {

enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<Scalar> scalarFromName(std::string_view n) {
  if (n == "char" || n == "int8") return Scalar::Int8;
  if (n == "uchar" || n == "uint8") return Scalar::UInt8;
  if (n == "short" || n == "int16") return Scalar::Int16;
  if (n == "ushort" || n == "uint16") return Scalar::UInt16;
  if (n == "int" || n == "int32") return Scalar::Int32;
  if (n == "uint" || n == "uint32") return Scalar::UInt32;
  if (n == "float" || n == "float32") return Scalar::Float32;
  if (n == "double" || n == "float64") return Scalar::Float64;
  return std::nullopt;
}

const char* scalarName(Scalar s) {
  constexpr const char* names[] = {"char", "uchar", "short", "ushort",
                                   "int",  "uint",  "float", "double"};
  return names[static_cast<int>(s)];
}

size_t scalarSize(Scalar s) {
  constexpr size_t sizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
  return sizes[static_cast<int>(s)];
}

bool isInteger(Scalar s) { return s != Scalar::Float32 && s != Scalar::Float64; }

struct Property {
  std::string name;
  Scalar type = Scalar::Float32;
  bool is_list = false;
  Scalar count_type = Scalar::UInt8;
  int line = 0;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  int line = 0;
};

struct Header {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<Element> elements;
  size_t data_offset = 0;
  int line_count = 0;  // lines in the header, so ASCII data lines can be numbered
};

std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

std::string quoted(std::string_view s) { return "\"" + std::string(s.substr(0, 40)) + "\""; }

Result<Header> parseHeader(std::string_view bytes, const std::string& name) {
  Header h;
  const auto fail = [&](int line, const std::string& why) {
    return Result<Header>::failure(name + ": header line " + std::to_string(line) + ": " + why);
  };
  size_t pos = 0;
  int line_no = 0;
  bool have_format = false;
  while (true) {
    const size_t nl = bytes.find('\n', pos);
    ++line_no;
    if (nl == std::string_view::npos) {
      if (line_no == 1)
        return Result<Header>::failure(name + ": not a PLY file (empty or no header)");
      return Result<Header>::failure(name + ": header has no end_header line (file ends at line " +
                                     std::to_string(line_no) + ")");
    }
    const std::string_view line = bytes.substr(pos, nl - pos);
    pos = nl + 1;
    const std::vector<std::string_view> t = tokens(line);
    if (line_no == 1) {
      if (t.size() != 1 || t[0] != "ply")
        return Result<Header>::failure(name + ": not a PLY file (the first line is not \"ply\")");
      continue;
    }
    if (t.empty()) return fail(line_no, "empty line in the header");
    const std::string_view key = t[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "format") {
      if (have_format) return fail(line_no, "second format line");
      if (t.size() != 3)
        return fail(line_no,
                    "expected \"format <ascii|binary_little_endian|binary_big_endian> 1.0\"");
      if (t[1] == "ascii")
        h.format = PlyFormat::Ascii;
      else if (t[1] == "binary_little_endian")
        h.format = PlyFormat::BinaryLittleEndian;
      else if (t[1] == "binary_big_endian")
        h.format = PlyFormat::BinaryBigEndian;
      else
        return fail(line_no, "unknown format " + quoted(t[1]));
      if (t[2] != "1.0" && t[2] != "1")
        return fail(line_no, "unsupported PLY version " + quoted(t[2]) + " (1.0 is read)");
      have_format = true;
    } else if (key == "element") {
      if (!have_format) return fail(line_no, "element before the format line");
      if (t.size() != 3) return fail(line_no, "expected \"element <name> <count>\"");
      Element e;
      e.name = std::string(t[1]);
      e.line = line_no;
      const auto r = std::from_chars(t[2].data(), t[2].data() + t[2].size(), e.count);
      if (r.ec != std::errc() || r.ptr != t[2].data() + t[2].size())
        return fail(line_no, "bad element count " + quoted(t[2]));
      for (const Element& other : h.elements)
        if (other.name == e.name)
          return fail(line_no, "element " + quoted(e.name) + " declared twice");
      h.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (h.elements.empty()) return fail(line_no, "property before any element");
      Property p;
      p.line = line_no;
      if (t.size() >= 2 && t[1] == "list") {
        if (t.size() != 5)
          return fail(line_no, "expected \"property list <count type> <item type> <name>\"");
        const auto count_type = scalarFromName(t[2]);
        const auto item_type = scalarFromName(t[3]);
        if (!count_type || !isInteger(*count_type))
          return fail(line_no, "unsupported list count type " + quoted(t[2]) +
                                   " (an integer type is needed)");
        if (!item_type) return fail(line_no, "unsupported property type " + quoted(t[3]));
        p.is_list = true;
        p.count_type = *count_type;
        p.type = *item_type;
        p.name = std::string(t[4]);
      } else {
        if (t.size() != 3) return fail(line_no, "expected \"property <type> <name>\"");
        const auto type = scalarFromName(t[1]);
        if (!type) return fail(line_no, "unsupported property type " + quoted(t[1]));
        p.type = *type;
        p.name = std::string(t[2]);
      }
      Element& e = h.elements.back();
      for (const Property& other : e.properties)
        if (other.name == p.name)
          return fail(line_no,
                      "property " + quoted(p.name) + " declared twice in element " + e.name);
      e.properties.push_back(std::move(p));
    } else if (key == "end_header") {
      if (!have_format) return fail(line_no, "end_header before the format line");
      h.data_offset = pos;
      h.line_count = line_no;
      return Result<Header>::success(std::move(h));
    } else {
      return fail(line_no, "unknown header keyword " + quoted(key));
    }
  }
}

// Where each vertex property goes.
enum class Role { Skip, X, Y, Z, Red, Green, Blue, Alpha };

Role roleOf(std::string_view n) {
  if (n == "x") return Role::X;
  if (n == "y") return Role::Y;
  if (n == "z") return Role::Z;
  if (n == "red" || n == "diffuse_red") return Role::Red;
  if (n == "green" || n == "diffuse_green") return Role::Green;
  if (n == "blue" || n == "diffuse_blue") return Role::Blue;
  if (n == "alpha") return Role::Alpha;
  return Role::Skip;
}

double readBinary(const char* p, Scalar type, bool swap) {
  std::array<unsigned char, 8> b{};
  const size_t n = scalarSize(type);
  std::memcpy(b.data(), p, n);
  if (swap) std::reverse(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(n));
  const auto as = [&b]<class T>(T) {
    T v;
    std::memcpy(&v, b.data(), sizeof(T));
    return static_cast<double>(v);
  };
  switch (type) {
    case Scalar::Int8:
      return as(std::int8_t{});
    case Scalar::UInt8:
      return as(std::uint8_t{});
    case Scalar::Int16:
      return as(std::int16_t{});
    case Scalar::UInt16:
      return as(std::uint16_t{});
    case Scalar::Int32:
      return as(std::int32_t{});
    case Scalar::UInt32:
      return as(std::uint32_t{});
    case Scalar::Float32:
      return as(float{});
    case Scalar::Float64:
      return as(double{});
  }
  return 0.0;
}

// Minimum bytes one entry of `e` occupies: fixed sizes in binary, "v " per value in ASCII.
std::uint64_t minimumEntryBytes(const Element& e, PlyFormat format) {
  std::uint64_t bytes = 0;
  for (const Property& p : e.properties) {
    if (format == PlyFormat::Ascii)
      bytes += 2;
    else
      bytes += p.is_list ? scalarSize(p.count_type) : scalarSize(p.type);
  }
  return bytes;
}

struct Cursor {
  std::string_view bytes;
  size_t pos = 0;
  int line = 0;  // ASCII: the current line number in the file

  // ASCII: the next non-blank line, or nullopt at the end of the file.
  std::optional<std::string_view> nextLine() {
    while (pos < bytes.size()) {
      size_t nl = bytes.find('\n', pos);
      if (nl == std::string_view::npos) nl = bytes.size();
      const std::string_view line_text = bytes.substr(pos, nl - pos);
      pos = nl + 1;
      ++line;
      if (line_text.find_first_not_of(" \t\r") != std::string_view::npos) return line_text;
    }
    return std::nullopt;
  }
};

}  // namespace

Result<PointCloud> parsePly(std::string_view bytes, const std::string& name) {
  auto header = parseHeader(bytes, name);
  if (!header) return Result<PointCloud>::failure(header.status.message);
  const Header& h = *header;
  using R = Result<PointCloud>;

  int vertex_index = -1;
  for (size_t i = 0; i < h.elements.size(); ++i)
    if (h.elements[i].name == "vertex") vertex_index = static_cast<int>(i);
  if (vertex_index < 0) return R::failure(name + ": no vertex element in the header");
  const Element& vertex = h.elements[vertex_index];
  // A cloud of no points renders an empty picture: nothing a user asked for.
  if (vertex.count == 0)
    return R::failure(name + ": header line " + std::to_string(vertex.line) +
                      ": element vertex 0: the cloud has no points");
  std::vector<Role> roles;
  std::array<int, 8> where{};
  where.fill(-1);
  for (size_t k = 0; k < vertex.properties.size(); ++k) {
    const Property& p = vertex.properties[k];
    const auto fail = [&](const std::string& why) {
      return R::failure(name + ": header line " + std::to_string(p.line) + ": " + why);
    };
    if (p.is_list)
      return fail("list property " + quoted(p.name) +
                  " on vertex is not supported (a point has "
                  "one value per property)");
    const Role role = roleOf(p.name);
    if (role != Role::Skip && where[static_cast<int>(role)] >= 0)
      return fail("vertex property " + quoted(p.name) + " repeats a colour channel");
    if (role >= Role::Red && p.type != Scalar::UInt8 && p.type != Scalar::Float32 &&
        p.type != Scalar::Float64)
      return fail("unsupported type " + std::string(scalarName(p.type)) + " for colour property " +
                  quoted(p.name) + " (uchar, float or double are read)");
    where[static_cast<int>(role)] = static_cast<int>(k);
    roles.push_back(role);
  }
  const auto has = [&](Role r) { return where[static_cast<int>(r)] >= 0; };
  if (!has(Role::X) || !has(Role::Y) || !has(Role::Z))
    return R::failure(name + ": header line " + std::to_string(vertex.line) +
                      ": vertex element lacks an x, y or z property");
  const int colour_channels = has(Role::Red) + has(Role::Green) + has(Role::Blue);
  if (colour_channels != 0 && colour_channels != 3)
    return R::failure(name + ": header line " + std::to_string(vertex.line) +
                      ": vertex colour needs all of red, green and blue");
  if (has(Role::Alpha) && colour_channels == 0)
    return R::failure(name + ": header line " + std::to_string(vertex.line) +
                      ": vertex alpha without red, green and blue");

  // Every count up to the vertex element against the bytes that follow, before allocating.
  std::uint64_t available = bytes.size() - h.data_offset;
  if (h.format == PlyFormat::Ascii) available += 1;  // the last line may lack its newline
  for (int i = 0; i <= vertex_index; ++i) {
    const Element& e = h.elements[i];
    const std::uint64_t entry = minimumEntryBytes(e, h.format);
    if (entry == 0) {
      if (e.count > 0)
        return R::failure(name + ": header line " + std::to_string(e.line) + ": element " + e.name +
                          " has no properties");
      continue;
    }
    if (e.count > available / entry)
      return R::failure(
          name + ": header line " + std::to_string(e.line) + ": element " + e.name + " claims " +
          std::to_string(e.count) + " entries (at least " +
          (e.count > UINT64_MAX / entry ? std::string("2^64") : std::to_string(e.count * entry)) +
          " bytes) but only " + std::to_string(available) +
          " bytes of data remain (truncated file or corrupt header)");
    available -= e.count * entry;
  }

  // uchar colours are sRGB like 8-bit images; a table keeps the decode exact and cheap.
  std::array<float, 256> srgb_lut{};
  const Transfer srgb = Transfer::srgb();
  for (int v = 0; v < 256; ++v) srgb_lut[v] = static_cast<float>(srgb.decode(v / 255.0));
  const auto colourValue = [&](double v, Scalar type, bool is_alpha) {
    if (type != Scalar::UInt8) return static_cast<float>(v);
    const int byte = static_cast<int>(v);
    return is_alpha ? static_cast<float>(byte / 255.0) : srgb_lut[byte];
  };

  PointCloud cloud;
  const size_t n = static_cast<size_t>(vertex.count);  // checked against the file size above
  cloud.positions.resize(n);
  if (colour_channels == 3) cloud.colours.resize(n);
  cloud.has_alpha = has(Role::Alpha);

  std::array<double, 8> value{};
  const auto store = [&](size_t i) {
    cloud.positions[i] = Eigen::Vector3d(value[1], value[2], value[3]);
    if (colour_channels != 3) return;
    const Property* const props = vertex.properties.data();
    const auto channel = [&](Role r) {
      return colourValue(value[static_cast<int>(r)], props[where[static_cast<int>(r)]].type,
                         r == Role::Alpha);
    };
    const float a = has(Role::Alpha) ? channel(Role::Alpha) : 1.0f;
    cloud.colours[i] = Eigen::Vector4f(channel(Role::Red) * a, channel(Role::Green) * a,
                                       channel(Role::Blue) * a, a);
  };

  if (h.format == PlyFormat::Ascii) {
    Cursor cur{bytes, h.data_offset, h.line_count};
    for (int e = 0; e < vertex_index; ++e)
      for (std::uint64_t k = 0; k < h.elements[e].count; ++k)
        if (!cur.nextLine())
          return R::failure(name + ": element " + h.elements[e].name + " " + std::to_string(k) +
                            ": file ends early (truncated data)");
    for (size_t i = 0; i < n; ++i) {
      const auto line = cur.nextLine();
      const std::string where_text = name + ": vertex " + std::to_string(i);
      if (!line)
        return R::failure(where_text + ": file ends early (truncated data; the header promised " +
                          std::to_string(n) + " vertices)");
      const std::vector<std::string_view> t = tokens(*line);
      const std::string at = where_text + " (line " + std::to_string(cur.line) + ")";
      if (t.size() != roles.size())
        return R::failure(at + ": expected " + std::to_string(roles.size()) + " values, found " +
                          std::to_string(t.size()));
      for (size_t k = 0; k < roles.size(); ++k) {
        if (roles[k] == Role::Skip) continue;
        double v = 0.0;
        const auto r = std::from_chars(t[k].data(), t[k].data() + t[k].size(), v);
        if (r.ec != std::errc() || r.ptr != t[k].data() + t[k].size())
          return R::failure(at + ": " + quoted(t[k]) + " is not a number (property " +
                            vertex.properties[k].name + ")");
        if (vertex.properties[k].type == Scalar::UInt8 && roles[k] >= Role::Red &&
            !(v >= 0 && v <= 255 && v == std::floor(v)))
          return R::failure(at + ": " + quoted(t[k]) + " is not a uchar 0…255 (property " +
                            vertex.properties[k].name + ")");
        // A float property holds the float nearest to its text, as a binary file would.
        value[static_cast<int>(roles[k])] =
            vertex.properties[k].type == Scalar::Float32 ? static_cast<float>(v) : v;
      }
      store(i);
    }
    return R::success(std::move(cloud));
  }

  const bool swap =
      (h.format == PlyFormat::BinaryLittleEndian) != (std::endian::native == std::endian::little);
  size_t pos = h.data_offset;
  for (int e = 0; e < vertex_index; ++e) {
    const Element& el = h.elements[e];
    for (std::uint64_t k = 0; k < el.count; ++k)
      for (const Property& p : el.properties) {
        const size_t head = p.is_list ? scalarSize(p.count_type) : scalarSize(p.type);
        if (bytes.size() - pos < head)
          return R::failure(name + ": element " + el.name + " " + std::to_string(k) +
                            ": file ends early (truncated data)");
        if (!p.is_list) {
          pos += head;
          continue;
        }
        const double count = readBinary(bytes.data() + pos, p.count_type, swap);
        pos += head;
        if (count < 0 || count * static_cast<double>(scalarSize(p.type)) >
                             static_cast<double>(bytes.size() - pos))
          return R::failure(name + ": element " + el.name + " " + std::to_string(k) + ": list " +
                            p.name + " of " + std::to_string(static_cast<long long>(count)) +
                            " items runs past the end of the file (truncated or corrupt)");
        pos += static_cast<size_t>(count) * scalarSize(p.type);
      }
  }
  std::vector<size_t> offsets;
  size_t stride = 0;
  for (const Property& p : vertex.properties) {
    offsets.push_back(stride);
    stride += scalarSize(p.type);
  }
  if ((bytes.size() - pos) / stride < n)
    return R::failure(name + ": vertex " + std::to_string((bytes.size() - pos) / stride) +
                      ": file ends early (truncated data; the header promised " +
                      std::to_string(n) + " vertices)");
  for (size_t i = 0; i < n; ++i) {
    const char* base = bytes.data() + pos + i * stride;
    for (size_t k = 0; k < roles.size(); ++k)
      if (roles[k] != Role::Skip)
        value[static_cast<int>(roles[k])] =
            readBinary(base + offsets[k], vertex.properties[k].type, swap);
    store(i);
  }
  return R::success(std::move(cloud));
}

Result<PointCloud> readPly(const std::string& path) {
  // A binary cloud of tens of millions of points is a large but honest file: its cap is the
  // memory budget's quarter (the points it decodes to take about as much again), not the
  // text inputs' 64 MiB.
  TextInputOptions options;
  options.max_bytes = static_cast<std::size_t>(memoryBudgetBytes() / 4.0);
  Result<std::string> bytes = readTextInput(path, options);
  if (!bytes) return Result<PointCloud>::failure(bytes.status.message);
  return parsePly(*bytes.value, textInputName(path));
}

}  // namespace artcam
