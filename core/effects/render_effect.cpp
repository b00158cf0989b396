#include "core/effects/render_effect.h"

#include <stdexcept>

namespace artcam {

AttributedImage renderEffect(const ImageF& source, const ImageF* depth, const Artcam& camera,
                             const AttributedOptions& options, AttributedSummary* summary) {
  if (camera.isPiecewise())
    throw std::invalid_argument("a piecewise camera is not an image effect (patches are not layers)");
  AttributedSummary local;
  AttributedSummary& report = summary ? *summary : local;
  AttributedImage out = renderLayers(source, depth, camera.layers, options, &report);
  if (report.cancelled || camera.depth_output != DepthOutput::BlurVariance) return out;
  BlurOptions blur;
  blur.threads = options.threads;
  blur.progress = options.progress;
  out.colour = stackBlur(out.colour, sigmaPixelsFromVariance(out.depth), blur);
  if (out.colour.empty()) {
    report.cancelled = true;
    return {};
  }
  return out;
}

}  // namespace artcam
