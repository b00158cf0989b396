// SPDX-License-Identifier: Apache-2.0
// The state of the studio's Insertion mode (the paper's §5, Figs 7 and 8):
// calibration-grid matches from the canonical board to the photo, the marked reflecting or
// refracting region, the board's canonical size and squares, the fit's max error and the
// graphic to insert. Panels and tools read it and change it only through
// SetInsertionStateCommand (insertion_commands.h) on the document's undo stack; selection and
// the error-map toggle are view state (not undoable).
//
// Frames: a match's `board` point is in canonical board PIXELS (the board's canonical view,
// default 512×512; the graphic is drawn over the same frame, scaled to it), its `photo` point
// in photo PIXELS (centres at i + 0.5). The fit maps board → photo (source → target).
//
// A match is seen either through the object (the reflection or refraction; the piecewise
// camera's matches) or directly on the table the board lies on (Fig 7b: at least four such
// clicks fix the board → photo homography that puts the graphic on the table too). The grid
// tool makes whichever kind the model's click mode says; a corner may have one of each.
#pragma once

#include "core/model/camera.h"
#include "core/model/fit_record.h"
#include "core/model/image.h"
#include "ui/matting/graphic_placement.h"

#include <QObject>
#include <QString>

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace artcam::ui {

class Document;

struct GridMatch {
  Eigen::Vector2d board{0.0, 0.0};  // canonical board pixels (source)
  Eigen::Vector2d photo{0.0, 0.0};  // photo pixels (target)
  bool on_table = false;            // seen directly on the table, not through the object
  bool operator==(const GridMatch&) const = default;
};

// One refracting or reflecting medium the graphic is seen through (Fig 8: the water, and the
// air above it): its grid matches and its region, fitted as its own piecewise camera.
inline constexpr int kMaxInsertionMedia = 16;  // a project's bound

struct InsertionMedium {
  std::vector<GridMatch> matches;
  std::vector<Eigen::Vector2d> region;
  bool operator==(const InsertionMedium&) const = default;
};

// Everything an undoable Insertion edit may change; commands store whole old and new values.
struct InsertionState {
  // The medium being edited (the grid and region tools work on it).
  std::vector<GridMatch> matches;
  std::vector<Eigen::Vector2d> region;  // photo pixels; fewer than 3 points: no region
  // The other media, in the order the panel lists them, the edited one standing at
  // `current_medium` among them; the graphic goes through each in that order (as chained
  // `artcam insert` runs do, each on the last one's output).
  std::vector<InsertionMedium> other_media;
  int current_medium = 0;
  FrameSize board_size{512, 512};
  int squares = 24;
  double max_error_px = 0.5;
  std::shared_ptr<const ImageF> graphic;  // linear premultiplied; null: none
  QString graphic_path;
  GraphicPlacement placement;  // default: the graphic fills the board

  bool operator==(const InsertionState& o) const {
    return matches == o.matches && region == o.region && other_media == o.other_media &&
           current_medium == o.current_medium && board_size == o.board_size &&
           squares == o.squares && max_error_px == o.max_error_px && graphic == o.graphic &&
           graphic_path == o.graphic_path && placement == o.placement;
  }
};

class InsertionModel : public QObject {
  Q_OBJECT

 public:
  // A new photo in the document starts over (its undo stack is cleared too).
  explicit InsertionModel(Document* document, QObject* parent = nullptr);

  Document* document() const { return document_; }
  const InsertionState& state() const { return state_; }
  // Raw mutator for SetInsertionStateCommand.
  void setState(InsertionState state);

  // Convenience: the edit as one undo step on the document's stack (no step when unchanged).
  void edit(const InsertionState& next, const QString& text);

  // Every medium in the panel's order, the edited one at state().current_medium.
  static std::vector<InsertionMedium> media(const InsertionState& state);
  // The state with medium `index` (of media()) the edited one; the others keep their order.
  static InsertionState editing(const InsertionState& state, int index);
  // One undo step each: a new, empty medium after the others, edited from now on (the edited
  // one, when it has matches or a region, stays as it is); and editing medium `index`.
  void addMedium();  // none past kMaxInsertionMedia
  void editMedium(int index);
  int mediumCount() const { return static_cast<int>(state_.other_media.size()) + 1; }

  // The matches through the object as core point matches (board → photo).
  std::vector<PointMatch> pointMatches() const;
  // The matches seen directly on the table (board → photo), for the table's homography.
  std::vector<PointMatch> tableMatches() const;
  // Interior corners of the board, row-major: (squares - 1)² points, corner (i, j) at
  // (i · w / squares, j · h / squares) for i, j in 1 … squares - 1.
  int cornersPerRow() const { return state_.squares - 1; }
  int cornerCount() const { return cornersPerRow() * cornersPerRow(); }
  Eigen::Vector2d cornerPosition(int corner) const;
  // Index of the corner within `tolerance_px` of a board point, or -1.
  int cornerAt(const Eigen::Vector2d& board_px, double tolerance_px) const;
  // Index of the match of the click mode's kind whose board point is this corner, or -1.
  int matchOfCorner(int corner) const;

  // --- view state ---
  int selectedCorner() const { return selected_corner_; }
  void setSelectedCorner(int corner);
  int selectedMatch() const { return selected_match_; }
  void setSelectedMatch(int match);
  // Whether grid clicks place matches on the table (true) or through the object.
  bool clickingTable() const { return clicking_table_; }
  void setClickingTable(bool on_table);
  bool errorMapVisible() const { return error_map_visible_; }
  void setErrorMapVisible(bool visible);

 signals:
  void stateChanged();  // any undoable part
  void selectionChanged();
  void errorMapVisibilityChanged(bool visible);

 private:
  Document* document_;
  InsertionState state_;
  int selected_corner_ = 0;
  int selected_match_ = -1;
  bool error_map_visible_ = true;
  bool clicking_table_ = false;
};

}  // namespace artcam::ui
