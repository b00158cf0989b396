// SPDX-License-Identifier: Apache-2.0
// Colour samples picked on two photos: a patch of the SOURCE photo
// (the document's photo, the one the camera recolours) and the matching patch of a REFERENCE
// photo (how that surface should look). A patch's colour is the mean over a square of side
// 2·radius + 1 pixels centred on the pixel under the picked point, in LINEAR light
// (premultiplied pixels averaged, then divided by the mean alpha: the correct mean of
// premultiplied data). Those colour pairs feed core's fitColourSamples (fit_colour.h).
//
// Frames: a sample's `source` point is in source photo PIXELS, `reference` in reference photo
// PIXELS (centres at i + 0.5).
//
// State and undo: everything an edit may change is one ColourSampleState; every edit is a
// SetColourSamplesCommand (colour_commands.h) holding the whole state before and after. The
// selection is view state (not undoable, not saved).
#pragma once

#include "core/model/fit_record.h"
#include "core/model/image.h"
#include "ui/photo.h"

#include <QObject>
#include <QString>

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace artcam::ui {

class Document;

struct ColourSample {
  Eigen::Vector2d source{0.0, 0.0};     // source photo pixels
  Eigen::Vector2d reference{0.0, 0.0};  // reference photo pixels
  bool enabled = true;
  bool operator==(const ColourSample&) const = default;
};

struct ColourSampleState {
  std::vector<ColourSample> samples;
  int radius = 4;      // patch half-side in pixels (side 2·radius + 1)
  PhotoPtr reference;  // null: none opened
  QString reference_path;

  bool operator==(const ColourSampleState& o) const {
    return samples == o.samples && radius == o.radius && reference == o.reference &&
           reference_path == o.reference_path;
  }
};

inline constexpr int kMaxPatchRadius = 64;

// The mean linear RGB over the square patch around `pixel` (clipped to the image); empty when
// the point is outside the image or the patch has no coverage (alpha 0). Grey is replicated.
std::optional<Eigen::Vector3d> patchMean(const ImageF& image, const Eigen::Vector2d& pixel,
                                         int radius);

class ColourSampleModel : public QObject {
  Q_OBJECT

 public:
  // A new photo in the document clears the samples (their source points are its pixels); the
  // reference photo stays.
  explicit ColourSampleModel(Document* document, QObject* parent = nullptr);

  Document* document() const { return document_; }
  const ColourSampleState& state() const { return state_; }
  // Raw mutator for the command and for project loading (no undo step).
  void setState(ColourSampleState state);

  // The colour pairs (source patch → reference patch) of every sample, with their enabled
  // flags: what fitColourSamples and the CSV export take. A sample whose patch has no colour
  // (a photo missing, a point outside) is left out; `indices` then maps back.
  std::vector<PointMatch> colourPairs(std::vector<int>* indices = nullptr) const;
  // One sample's colours; empty when either patch has none.
  std::optional<PointMatch> colourPair(int index) const;

  const std::vector<int>& selection() const { return selection_; }
  void setSelection(std::vector<int> indices);

 signals:
  void changed();  // the state changed (samples, radius or reference)
  void selectionChanged();

 private:
  Document* document_;
  ColourSampleState state_;
  std::vector<int> selection_;
};

}  // namespace artcam::ui
