// SPDX-License-Identifier: Apache-2.0
// PLY point clouds (Stanford polygon format), read and written without a library: Debian has
// no small, well-kept PLY reader that fits, and the subset a point cloud needs is small.
//
// Read:
// - ASCII, binary_little_endian and binary_big_endian, version 1.0.
// - The `vertex` element's x, y, z (any scalar type: char…double) and optional red, green,
//   blue [alpha] (also diffuse_red/…): uchar is sRGB-encoded like an 8-bit image and decoded to
//   linear light; float/double colours are linear already (like EXR); alpha is never encoded.
//   Colours are premultiplied by alpha on the way in (core/cloud/point_cloud.h).
// - Other vertex properties (normals, confidence…) and other elements (faces…) are skipped,
//   lists included, except that a list property on `vertex` is refused.
// - Every refusal is one line naming the file, the header line or vertex index, and the cause:
//   malformed header, truncated data, unsupported property type, absurd counts. A header's
//   counts are checked against the bytes that follow it BEFORE anything is allocated, so a
//   lying header cannot ask for gigabytes.
// - Positions that are NaN (scanners mark missing points so) are kept; renderers skip them.
//
// Write: binary little endian by default (ASCII or big endian on request), float x y z
// (double on request), uchar sRGB red green blue, plus alpha when the cloud has it. Atomic
// (core/io/atomic_file.h): readers never see a partial file.
#pragma once

#include "core/cloud/point_cloud.h"
#include "core/model/status.h"

#include <string>
#include <string_view>

namespace artcam {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyWriteOptions {
  PlyFormat format = PlyFormat::BinaryLittleEndian;
  bool double_positions = false;  // float is what most viewers expect; double round-trips
  std::string comment = "written by ARTcam Studio";
};

// `name` is used in messages ("cube.ply: header line 4: …").
Result<PointCloud> parsePly(std::string_view bytes, const std::string& name);
Result<PointCloud> readPly(const std::string& path);

std::string plyBytes(const PointCloud& cloud, const PlyWriteOptions& options = {});
Status writePly(const std::string& path, const PointCloud& cloud,
                const PlyWriteOptions& options = {});

}  // namespace artcam
