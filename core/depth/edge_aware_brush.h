// SPDX-License-Identifier: Apache-2.0
// An edge-aware mask brush: a dab paints only the pixels of its disc that are connected to
// the pixel under the dab's centre through pixels of similar colour — a flood fill clipped to
// the brush disc — so painting along an object's border does not spill across it.
//
// Decisions:
// - Similar means within `tolerance` of a REFERENCE colour, Euclidean in linear RGB (the
//   engine's colour space; alpha ignored, grey photos compared as grey). The reference is
//   sampled once per stroke, under its first dab, and kept: a stroke that wanders across an
//   edge keeps painting the side it began on, and painting the other side takes a new stroke.
//   A dab whose centre pixel is not similar paints nothing.
// - Connected is 4-connected among pixels whose centres lie within the radius; the dab's
//   soft falloff (region_mask.h) then applies to the flooded pixels as usual.
// - The photo must be the mask's size (masks are photo pixels; centres at i + 0.5).
#pragma once

#include "core/depth/region_mask.h"
#include "core/model/image.h"

#include <Eigen/Core>

namespace artcam {

struct EdgeAwareOptions {
  Eigen::Vector3f reference = Eigen::Vector3f::Zero();  // linear RGB the stroke paints
  double tolerance = 0.12;                              // linear RGB distance
};

// Linear RGB of photo pixel (x, y) (alpha skipped; one colour channel is replicated).
Eigen::Vector3f photoColourAt(const ImageF& photo, int x, int y);

// The pixels one edge-aware dab may paint (see the header comment).
DabLimit edgeAwareLimit(const RegionMask& mask, const ImageF& photo, const Eigen::Vector2d& centre,
                        double radius, const EdgeAwareOptions& options);

// RegionMask::stamp and ::segment (same dab spacing), each dab limited by edgeAwareLimit.
// Throws std::invalid_argument when the photo is not the mask's size.
PixelRect stampEdgeAware(RegionMask& mask, const ImageF& photo, const Eigen::Vector2d& centre,
                         const BrushOptions& brush, const EdgeAwareOptions& options);
PixelRect segmentEdgeAware(RegionMask& mask, const ImageF& photo, const Eigen::Vector2d& from,
                           const Eigen::Vector2d& to, const BrushOptions& brush,
                           const EdgeAwareOptions& options);

}  // namespace artcam
