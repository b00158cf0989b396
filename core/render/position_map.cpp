// SPDX-License-Identifier: Apache-2.0
#include "core/render/position_map.h"

#include "core/model/structure.h"
#include "core/render/attributed.h"
#include "core/util/parallel.h"

#include <algorithm>
#include <stdexcept>

namespace artcam {

PositionMap emptyPositionMap(FrameSize source_px, FrameSize target_px) {
  if (source_px.width <= 0 || source_px.height <= 0 || target_px.width <= 0 ||
      target_px.height <= 0)
    throw std::invalid_argument("a position map needs positive source and target sizes");
  PositionMap map;
  map.source_px = source_px;
  map.target_px = target_px;
  const size_t n = static_cast<size_t>(target_px.width) * static_cast<size_t>(target_px.height);
  map.x_px.assign(n, 0.0f);
  map.y_px.assign(n, 0.0f);
  map.preimage.assign(n, Preimage::None);
  map.invalid_pixels = static_cast<long long>(n);
  return map;
}

void countPreimages(PositionMap& map) {
  map.invalid_pixels = 0;
  map.outside_pixels = 0;
  for (const Preimage p : map.preimage) {
    map.invalid_pixels += p == Preimage::None;
    map.outside_pixels += p == Preimage::OutsidePhoto;
  }
}

PositionMap sourcePositionMap(const Camera& input, FrameSize source_px, FrameSize target_px,
                              const PositionMapOptions& options) {
  input.validate();
  const BlockLayout& layout = input.layout();
  const int p = layout.find(BlockKind::Position);
  if (p < 0 || layout.blocks[static_cast<size_t>(p)].size != 3)
    throw std::invalid_argument("a position map needs a camera with a 2D image position block");
  const CameraStructure input_structure = analyseStructure(input);
  if (input_structure.geometry_depends_on_attributes)
    throw std::invalid_argument(
        "this camera's geometry depends on colour or depth, so where a pixel comes from depends "
        "on the photo; no position map can hold it");
  // Only positions are asked: a colour or depth part does not move pixels.
  const Camera camera = layout.blocks.size() == 1 ? input : positionPart(input);
  const CameraStructure structure = analyseStructure(camera);
  PositionMap map = emptyPositionMap(source_px, target_px);  // checks the sizes
  if (structure.degenerate) {
    map.kernel = "degenerate";
    return map;
  }
  const KernelChoice choice = makeCoordinateKernel(camera, structure, source_px, target_px,
                                                   options.coordinates, options.threads);
  map.kernel = choice.name;
  const CoordinateKernel& kernel = *choice.kernel;
  ParallelOptions po;
  po.threads = options.threads;
  parallelForRows(target_px.height, po, [&](int y0, int y1) {
    alignas(32) float sx[kSpanPixels], sy[kSpanPixels];
    unsigned char valid[kSpanPixels];
    for (int y = y0; y < y1; ++y) {
      RowState state;  // each row's spans left to right, as the warp asks (coordinates.h)
      for (int x0 = 0; x0 < target_px.width; x0 += kSpanPixels) {
        const int count = std::min(kSpanPixels, target_px.width - x0);
        kernel.span(y, x0, count, sx, sy, valid, state);
        for (int i = 0; i < count; ++i) {
          if (valid[i]) storePreimage(map, map.index(x0 + i, y), sx[i], sy[i]);
        }
      }
    }
  });
  countPreimages(map);
  return map;
}

}  // namespace artcam
