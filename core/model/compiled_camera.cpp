// SPDX-License-Identifier: Apache-2.0
#include "core/model/compiled_camera.h"

#include <algorithm>
#include <stdexcept>

namespace artcam {

CompiledCamera::CompiledCamera(const Camera& camera) : layout_(camera.layout()) {
  const int n = layout_.dimension;
  if (n > kMaxDimension)
    throw std::invalid_argument("camera has " + std::to_string(n) + " elements; at most " +
                                std::to_string(kMaxDimension) + " can be compiled");
  for (const Stage& stage : camera.stages()) {
    std::vector<Output> outputs;
    for (int i = 0; i < n; ++i) {
      const Eigen::MatrixXd& q = stage.q[i];
      Output out{i, false, {}};
      const int position = layout_.find(BlockKind::Position);
      out.position = position >= 0 && i >= layout_.offsets[position] &&
                     i < layout_.offsets[position] + layout_.blocks[position].size;
      for (int a = 0; a < n; ++a)
        for (int b = a; b < n; ++b) {
          // x Q xᵀ counts an off-diagonal pair twice (eq 10): merge it into one term.
          const double c = a == b ? q(a, a) : q(a, b) + q(b, a);
          if (c != 0.0) out.terms.push_back({a, b, c});
        }
      if (!out.terms.empty()) outputs.push_back(std::move(out));
    }
    stages_.push_back(std::move(outputs));
  }
  const Camera id = Camera::identity(layout_.blocks, camera.sourceSize(), camera.targetSize());
  identity_ = true;
  for (const Stage& stage : camera.stages())
    for (int i = 0; i < n; ++i) {
      const Eigen::MatrixXd& q = stage.q[i];
      if ((0.5 * (q + q.transpose()) - id.stages()[0].q[i]).cwiseAbs().maxCoeff() != 0.0)
        identity_ = false;
    }
}

void CompiledCamera::evaluateStage(size_t stage, const Vector& x, Vector& z,
                                   bool position_only) const {
  z.fill(0.0);
  for (const Output& out : stages_[stage]) {
    if (position_only && !out.position) continue;
    double sum = 0.0;
    for (const Term& t : out.terms) sum += t.q * x[t.a] * x[t.b];  // eq 3
    z[out.index] = sum;
  }
}

void CompiledCamera::divide(const Vector& z, Vector& y) const {
  y = z;
  divideBlocks(layout_, z.data(), y.data());
}

void CompiledCamera::rehomogenise(const Vector& z, Vector& x) const {
  divide(z, x);
  for (size_t b = 0; b < layout_.blocks.size(); ++b) {
    if (!weightIsAlpha(layout_.blocks[b].kind)) continue;
    const int h = layout_.homogeneousIndex(static_cast<int>(b));
    for (int k = layout_.offsets[b]; k < h; ++k) x[k] *= x[h];
  }
}

void CompiledCamera::evaluateHomogeneous(const Vector& x, Vector& z, bool position_only) const {
  const size_t last = stages_.size() - 1;
  evaluateStage(0, x, z, position_only && last == 0);
  Vector next;
  for (size_t s = 1; s <= last; ++s) {
    rehomogenise(z, next);
    evaluateStage(s, next, z, position_only && s == last);
  }
}

}  // namespace artcam
