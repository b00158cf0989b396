// SPDX-License-Identifier: Apache-2.0
#include "core/mapping/coordinates.h"

#include "core/mapping/inverse_seed.h"
#include "core/mapping/projective_kernel.h"
#include "core/mapping/rational_kernel.h"
#include "core/model/frames.h"

#include <optional>
#include <string>
#include <utility>

namespace artcam {
namespace {

Eigen::Matrix3d pixelHomography(const CameraStructure& structure, FrameSize source_px,
                                FrameSize target_px) {
  // The homography is stored normalised (frames.h); in pixels it is P_out · H · N_source.
  return pixelFromNormalizedMatrix(target_px) * Eigen::Matrix3d(structure.homography) *
         normalizedFromPixelMatrix(source_px);
}

}  // namespace

KernelChoice makeCoordinateKernel(const Camera& camera, const CameraStructure& structure,
                                  FrameSize source_px, FrameSize target_px,
                                  const CoordinateOptions& options, int threads) {
  KernelChoice choice;
  if (!options.force_rational && structure.geometry != GeometryClass::Rational) {
    const bool same_size = source_px == target_px;
    // An identity between frames of different pixel sizes is an axis-aligned scaling.
    choice.name = structure.geometry == GeometryClass::Identity
                      ? (same_size ? "identity" : "affine")
                      : std::string(geometryClassName(structure.geometry));
    choice.kernel =
        makeProjectiveKernel(pixelHomography(structure, source_px, target_px), source_px, options.scalar_only);
    return choice;
  }
  choice.name = "rational";
  RationalMap forward(camera, source_px, target_px);
  std::optional<RationalMap> seed;
  if (options.fit_inverse_seed) {
    Result<RationalMap> fitted = fitInverseSeed(forward, source_px, target_px);
    if (fitted) seed = std::move(*fitted);
    else choice.note = "inverse seed not used: " + fitted.status.message;
  }
  choice.kernel =
      makeRationalKernel(std::move(forward), std::move(seed), source_px, target_px, options, threads);
  return choice;
}

std::unique_ptr<InverseMap> makeReferenceInverse(const Camera& camera,
                                                 const CameraStructure& structure,
                                                 FrameSize source_px, FrameSize target_px,
                                                 bool force_rational) {
  if (!force_rational && structure.geometry != GeometryClass::Rational)
    return makeHomographyInverse(pixelHomography(structure, source_px, target_px), source_px);
  // The pre-fusion production path: Newton at every pixel to ~1e-7 px, from the fitted seed,
  // the neighbours and the centre (validated against closed forms in test_kernels).
  RationalMap forward(camera, source_px, target_px);
  std::optional<RationalMap> seed;
  if (Result<RationalMap> fitted = fitInverseSeed(forward, source_px, target_px)) seed = std::move(*fitted);
  RationalInverseOptions ro;
  return makeRationalInverse(std::move(forward), std::move(seed), source_px, ro);
}

}  // namespace artcam
