// SPDX-License-Identifier: Apache-2.0
#include "ui/matting/insertion_model.h"

#include "ui/document.h"
#include "ui/matting/insertion_commands.h"

#include <algorithm>
#include <cmath>

namespace artcam::ui {

InsertionModel::InsertionModel(Document* document, QObject* parent)
    : QObject(parent), document_(document) {
  connect(document_, &Document::photoChanged, this, [this] {
    // Matches and region are photo pixels of the old photo; board, threshold and graphic stay.
    InsertionState next = state_;
    next.matches.clear();
    next.region.clear();
    next.other_media.clear();
    next.current_medium = 0;
    selected_match_ = -1;
    setState(std::move(next));
  });
}

void InsertionModel::setState(InsertionState state) {
  state_ = std::move(state);
  if (selected_match_ >= static_cast<int>(state_.matches.size())) selected_match_ = -1;
  if (selected_corner_ >= cornerCount()) selected_corner_ = 0;
  emit stateChanged();
}

void InsertionModel::edit(const InsertionState& next, const QString& text) {
  if (next == state_) return;
  document_->undoStack()->push(new SetInsertionStateCommand(this, state_, next, text));
}

std::vector<InsertionMedium> InsertionModel::media(const InsertionState& state) {
  std::vector<InsertionMedium> all = state.other_media;
  const int at = std::clamp(state.current_medium, 0, static_cast<int>(all.size()));
  all.insert(all.begin() + at, InsertionMedium{state.matches, state.region});
  return all;
}

InsertionState InsertionModel::editing(const InsertionState& state, int index) {
  std::vector<InsertionMedium> all = media(state);
  index = std::clamp(index, 0, static_cast<int>(all.size()) - 1);
  InsertionState next = state;
  next.matches = all[static_cast<size_t>(index)].matches;
  next.region = all[static_cast<size_t>(index)].region;
  all.erase(all.begin() + index);
  next.other_media = std::move(all);
  next.current_medium = index;
  return next;
}

void InsertionModel::addMedium() {
  if (state_.matches.empty() && state_.region.empty()) return;  // the edited one is still empty
  if (mediumCount() >= kMaxInsertionMedia) return;
  InsertionState next = state_;
  next.other_media = media(state_);
  next.current_medium = static_cast<int>(next.other_media.size());
  next.matches.clear();
  next.region.clear();
  selected_match_ = -1;
  edit(next, tr("New Medium"));
}

void InsertionModel::editMedium(int index) {
  if (index == state_.current_medium) return;
  selected_match_ = -1;
  edit(editing(state_, index), tr("Edit Medium %1").arg(index + 1));
}

namespace {

std::vector<PointMatch> matchesOfKind(const std::vector<GridMatch>& matches, bool on_table) {
  std::vector<PointMatch> out;
  for (const GridMatch& m : matches) {
    if (m.on_table != on_table) continue;
    PointMatch p;
    p.source = m.board;
    p.target = m.photo;
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace

std::vector<PointMatch> InsertionModel::pointMatches() const {
  return matchesOfKind(state_.matches, false);
}

std::vector<PointMatch> InsertionModel::tableMatches() const {
  return matchesOfKind(state_.matches, true);
}

Eigen::Vector2d InsertionModel::cornerPosition(int corner) const {
  const int n = cornersPerRow();
  if (n <= 0) return Eigen::Vector2d::Zero();
  const int i = corner % n + 1, j = corner / n + 1;
  return {static_cast<double>(i) * state_.board_size.width / state_.squares,
          static_cast<double>(j) * state_.board_size.height / state_.squares};
}

int InsertionModel::cornerAt(const Eigen::Vector2d& board_px, double tolerance_px) const {
  const int n = cornersPerRow();
  if (n <= 0) return -1;
  const double sx = static_cast<double>(state_.board_size.width) / state_.squares;
  const double sy = static_cast<double>(state_.board_size.height) / state_.squares;
  const int i = static_cast<int>(std::lround(board_px.x() / sx));
  const int j = static_cast<int>(std::lround(board_px.y() / sy));
  if (i < 1 || j < 1 || i > n || j > n) return -1;
  const int corner = (j - 1) * n + (i - 1);
  return (cornerPosition(corner) - board_px).norm() <= tolerance_px ? corner : -1;
}

int InsertionModel::matchOfCorner(int corner) const {
  const Eigen::Vector2d c = cornerPosition(corner);
  for (size_t k = 0; k < state_.matches.size(); ++k)
    if (state_.matches[k].on_table == clicking_table_ && (state_.matches[k].board - c).norm() < 1e-6)
      return static_cast<int>(k);
  return -1;
}

void InsertionModel::setSelectedCorner(int corner) {
  corner = std::clamp(corner, 0, std::max(0, cornerCount() - 1));
  if (corner == selected_corner_) return;
  selected_corner_ = corner;
  emit selectionChanged();
}

void InsertionModel::setSelectedMatch(int match) {
  if (match >= static_cast<int>(state_.matches.size())) match = -1;
  if (match == selected_match_) return;
  selected_match_ = match;
  emit selectionChanged();
}

void InsertionModel::setClickingTable(bool on_table) {
  if (on_table == clicking_table_) return;
  clicking_table_ = on_table;
  emit selectionChanged();
}

void InsertionModel::setErrorMapVisible(bool visible) {
  if (visible == error_map_visible_) return;
  error_map_visible_ = visible;
  emit errorMapVisibilityChanged(visible);
}

}  // namespace artcam::ui
