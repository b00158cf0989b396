// SPDX-License-Identifier: Apache-2.0
#include "ui/fit_explanation.h"

#include <QCoreApplication>

namespace artcam::ui {

namespace {

QString number(double v) {
  return v < 0 ? QStringLiteral("–") : QString::number(v, 'g', 3);
}

}  // namespace

QString modelScoresHtml(const FitRecord& record) {
  if (record.models.empty()) return {};
  const QString score =
      record.criterion == "aic" ? QCoreApplication::translate("fit", "AIC") : QString();
  QString html = QStringLiteral("<table cellspacing=\"0\" cellpadding=\"1\"><tr><th align=\"left\">%1</th>"
                                "<th align=\"right\">%2</th><th align=\"right\">%3</th>"
                                "<th align=\"right\">%4</th></tr>")
                     .arg(QCoreApplication::translate("fit", "model"),
                          QCoreApplication::translate("fit", "RMS px"),
                          QCoreApplication::translate("fit", "held-out"), score);
  for (const ModelScore& m : record.models) {
    const bool chosen = m.model == record.model;
    const bool eligible = m.rms_px >= 0 && m.note.empty();
    const auto cell = [chosen](const QString& text, bool right) {
      return QStringLiteral("<td%1>%2%3%4</td>")
          .arg(right ? QStringLiteral(" align=\"right\"") : QString(),
               chosen ? QStringLiteral("<b>") : QString(), text,
               chosen ? QStringLiteral("</b>") : QString());
    };
    // The held-out column is the criterion under "held-out"; the AIC column otherwise.
    const QString row = cell(QString::fromStdString(m.model), false) + cell(number(m.rms_px), true) +
                        cell(number(m.held_out_rms_px), true) +
                        cell(record.criterion == "aic" ? number(m.criterion) : QString(), true);
    // Qt's rich text has no row tooltips: a model that was not eligible is grey, its note after.
    const QString note = m.note.empty() ? QString()
                                        : QStringLiteral("<td>%1</td>").arg(
                                              QString::fromStdString(m.note).toHtmlEscaped());
    html += QStringLiteral("<tr%1>%2%3</tr>")
                .arg(eligible ? QString() : QStringLiteral(" style=\"color:gray\""), row, note);
  }
  return html + QStringLiteral("</table>");
}

QString fitReasonText(const FitRecord& record) { return QString::fromStdString(record.reason); }

}  // namespace artcam::ui
