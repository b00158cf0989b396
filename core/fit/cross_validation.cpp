// SPDX-License-Identifier: Apache-2.0
#include "core/fit/cross_validation.h"

namespace artcam {

int smallestTrainingSet(int items, int folds) { return items - (items + folds - 1) / folds; }

std::optional<double> crossValidatedSum(int items, int folds, int min_train,
                                        const FoldErrors& errors) {
  if (folds < 2 || smallestTrainingSet(items, folds) < min_train) return std::nullopt;
  double sum = 0.0;
  for (int f = 0; f < folds; ++f) {
    std::vector<int> train, held;
    for (int k = 0; k < items; ++k) (k % folds == f ? held : train).push_back(k);
    const std::optional<std::vector<double>> e = errors(train, held);
    if (!e) return std::nullopt;
    for (double v : *e) sum += v;
  }
  return sum;
}

}  // namespace artcam
