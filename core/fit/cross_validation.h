// SPDX-License-Identifier: Apache-2.0
// K-fold cross-validation, the one the model choices share (the geometry ladder, fit_image.cpp;
// the colour ladder, fit_colour.cpp). Fold f of K holds out the items k with k % K == f and
// trains on the others: interleaved, so every fold spans the whole input (matches clicked or
// tracked in order would otherwise leave one fold to extrapolate), and fixed, so the same
// input always gives the same held-out error.
#pragma once

#include <functional>
#include <optional>
#include <vector>

namespace artcam {

// Items in the smallest training set of K folds: items − ceil(items / K).
int smallestTrainingSet(int items, int folds);

// One fold: the held-out items' errors (one per item of `held`, in its order) of a model fitted
// to `train`; nullopt when that fit failed.
using FoldErrors = std::function<std::optional<std::vector<double>>(const std::vector<int>& train,
                                                                    const std::vector<int>& held)>;

// The sum of every held-out error over the K folds, taken in fold order; nullopt when K < 2,
// when a training set would hold fewer than `min_train` items, or at the first fold whose fit
// failed (the folds after it are not fitted).
std::optional<double> crossValidatedSum(int items, int folds, int min_train,
                                        const FoldErrors& errors);

}  // namespace artcam
