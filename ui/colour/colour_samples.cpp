// SPDX-License-Identifier: Apache-2.0
#include "ui/colour/colour_samples.h"

#include "ui/document.h"

#include <algorithm>
#include <cmath>

namespace artcam::ui {

std::optional<Eigen::Vector3d> patchMean(const ImageF& image, const Eigen::Vector2d& pixel,
                                         int radius) {
  if (image.empty() || !pixel.allFinite()) return std::nullopt;
  const double px = std::floor(pixel.x()), py = std::floor(pixel.y());
  if (px < 0 || py < 0 || px >= image.width || py >= image.height) return std::nullopt;
  radius = std::clamp(radius, 0, kMaxPatchRadius);
  const int cx = static_cast<int>(px), cy = static_cast<int>(py);
  const int x0 = std::max(0, cx - radius), x1 = std::min(image.width - 1, cx + radius);
  const int y0 = std::max(0, cy - radius), y1 = std::min(image.height - 1, cy + radius);
  const int colour_channels = image.alpha_channel >= 0 ? image.channels - 1 : image.channels;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double weight = 0.0;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const float* p = image.pixel(x, y);
      // Colour channels are those that are not alpha, in order (grey, or R, G, B).
      double c[3] = {0, 0, 0};
      int k = 0;
      for (int ch = 0; ch < image.channels && k < 3; ++ch)
        if (ch != image.alpha_channel) c[k++] = p[ch];
      if (colour_channels == 1) c[1] = c[2] = c[0];
      sum += Eigen::Vector3d(c[0], c[1], c[2]);
      weight += image.alpha_channel >= 0 ? p[image.alpha_channel] : 1.0;
    }
  if (!(weight > 0.0)) return std::nullopt;
  const Eigen::Vector3d mean = sum / weight;  // premultiplied sum over alpha sum
  if (!mean.allFinite()) return std::nullopt;
  return mean;
}

ColourSampleModel::ColourSampleModel(Document* document, QObject* parent)
    : QObject(parent), document_(document) {
  // A first look has no full pixels to average (patchMean gives none); the full photo does.
  connect(document_, &Document::photoRefined, this, &ColourSampleModel::changed);
  connect(document_, &Document::photoChanged, this, [this] {
    if (state_.samples.empty()) {
      emit changed();  // the source colours change with the photo
      return;
    }
    ColourSampleState s = state_;
    s.samples.clear();
    setState(std::move(s));
  });
}

void ColourSampleModel::setState(ColourSampleState state) {
  state_ = std::move(state);
  std::erase_if(selection_, [&](int i) { return i >= static_cast<int>(state_.samples.size()); });
  emit changed();
  emit selectionChanged();
}

std::optional<PointMatch> ColourSampleModel::colourPair(int index) const {
  if (index < 0 || index >= static_cast<int>(state_.samples.size())) return std::nullopt;
  const PhotoPtr& source = document_->photo();
  if (!source || !state_.reference) return std::nullopt;
  const ColourSample& s = state_.samples[static_cast<size_t>(index)];
  const auto a = patchMean(source->full.image, s.source, state_.radius);
  const auto b = patchMean(state_.reference->full.image, s.reference, state_.radius);
  if (!a || !b) return std::nullopt;
  PointMatch m;
  m.source = *a;
  m.target = *b;
  m.enabled = s.enabled;
  return m;
}

std::vector<PointMatch> ColourSampleModel::colourPairs(std::vector<int>* indices) const {
  std::vector<PointMatch> out;
  if (indices) indices->clear();
  for (int i = 0; i < static_cast<int>(state_.samples.size()); ++i)
    if (auto m = colourPair(i)) {
      out.push_back(std::move(*m));
      if (indices) indices->push_back(i);
    }
  return out;
}

void ColourSampleModel::setSelection(std::vector<int> indices) {
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  std::erase_if(indices,
                [&](int i) { return i < 0 || i >= static_cast<int>(state_.samples.size()); });
  if (indices == selection_) return;
  selection_ = std::move(indices);
  emit selectionChanged();
}

}  // namespace artcam::ui
