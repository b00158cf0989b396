// SPDX-License-Identifier: Apache-2.0
#include "ui/colour/colour_project.h"

#include "core/io/artcam_file.h"
#include "ui/json_points.h"

#include <QJsonArray>
#include <QJsonDocument>

#include <cmath>

namespace artcam::ui {

QJsonObject colourPartToJson(const ColourSampleState& s, const std::optional<Camera>& block) {
  if (s.samples.empty() && s.reference_path.isEmpty() && !block) return {};
  QJsonObject o;
  o["radius"] = s.radius;
  if (!s.reference_path.isEmpty()) o["reference"] = s.reference_path;
  QJsonArray samples;
  for (const ColourSample& c : s.samples)
    samples.append(QJsonObject{{"source", jsonFromPoint(c.source)},
                               {"reference", jsonFromPoint(c.reference)},
                               {"enabled", c.enabled}});
  o["samples"] = samples;
  if (block) {
    o["colour_block"] =
        QJsonDocument::fromJson(QByteArray::fromStdString(toArtcamJson(Artcam(*block)))).object();
  }
  return o;
}

Result<ColourProjectPart> colourPartFromJson(const QJsonObject& o, const std::string& where) {
  const auto fail = [&](const std::string& m) {
    return Result<ColourProjectPart>::failure(where + m);
  };
  ColourProjectPart part;
  if (o.isEmpty()) return Result<ColourProjectPart>::success(std::move(part));
  const QJsonValue radius = o["radius"];
  if (!radius.isDouble() || radius.toDouble() != std::floor(radius.toDouble()) ||
      radius.toInt(-1) < 0 || radius.toInt() > kMaxPatchRadius)
    return fail("/radius: expected a whole number of pixels from 0 to " +
                std::to_string(kMaxPatchRadius));
  part.state.radius = radius.toInt();
  part.state.reference_path = o["reference"].toString();
  const QJsonArray samples = o["samples"].toArray();
  for (qsizetype i = 0; i < samples.size(); ++i) {
    const QJsonObject m = samples[i].toObject();
    const auto a = pointFromJson(m["source"]), b = pointFromJson(m["reference"]);
    if (!a || !b)
      return fail("/samples/" + std::to_string(i) + ": expected source and reference [x, y]");
    part.state.samples.push_back({*a, *b, m["enabled"].toBool(true)});
  }
  if (o.contains("colour_block")) {
    const QByteArray text =
        QJsonDocument(o["colour_block"].toObject()).toJson(QJsonDocument::Compact);
    Result<Artcam> cam = parseArtcam(text.toStdString(), where + "/colour_block");
    if (!cam) return Result<ColourProjectPart>::failure(cam.status.message);
    if (cam->kind() != ArtcamKind::Attributed && cam->kind() != ArtcamKind::Single &&
        cam->kind() != ArtcamKind::Chained)
      return Result<ColourProjectPart>::failure(where + "/colour_block: expected one camera, found a " +
                                                std::string(artcamKindName(cam->kind())) + " camera");
    part.colour_block = cam->main();
  }
  return Result<ColourProjectPart>::success(std::move(part));
}

}  // namespace artcam::ui
