// SPDX-License-Identifier: Apache-2.0
// Why the fit chose its model, for people: the per-model scores of the fit record as a compact
// table, and the record's one-line reason. Shared by the Pairs panel and the status tooltip so
// both say the same thing.
#pragma once

#include "core/model/fit_record.h"

#include <QString>

namespace artcam::ui {

// A small HTML table: model, RMS px, held-out px, criterion; the chosen model in bold, models
// that were not eligible greyed with their note. Empty when the record has no scores.
QString modelScoresHtml(const FitRecord& record);

// The reason, plain text (empty when there is none).
QString fitReasonText(const FitRecord& record);

}  // namespace artcam::ui
