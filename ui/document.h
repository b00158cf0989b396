// SPDX-License-Identifier: Apache-2.0
// The model every panel shares: the photo, the point pairs, the straight lines, the model
// class, the camera and its fit. Panels read it and listen to its signals; they change it only through the
// QUndoCommands of commands.h (every document edit is a command), which call the
// mutators below. Selection is view state: not undoable, not saved.
//
// Frames: pairs and line points are in PIXELS of the photo (centres at i + 0.5); source and
// target frames are both the photo's size. The camera is in normalised frames (core/model/frames.h).
#pragma once

#include "core/fit/fit_image.h"
#include "core/fit/fit_lines.h"
#include "core/model/camera.h"
#include "core/model/image.h"
#include "core/model/line_trace.h"
#include "ui/depth_model.h"
#include "ui/document_fit.h"
#include "ui/photo.h"

#include <QObject>
#include <QUndoStack>

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace artcam::ui {

class FitWorker;

struct Pair {
  Eigen::Vector2d source{0.0, 0.0};  // where a feature is in the photo
  Eigen::Vector2d target{0.0, 0.0};  // where the camera should send it
  bool enabled = true;

  bool operator==(const Pair& o) const {
    return source == o.source && target == o.target && enabled == o.enabled;
  }
};

enum class Endpoint { Source, Target };

// The straight edges traced in the photo (core/model/line_trace.h), and the one being traced.
// The open line is part of the document so that each clicked point is an undo step, but it is
// not fitted (a line needs 3 points, and a half-traced edge would pull the camera on every
// click) and not saved: Enter ends it into `lines`.
struct LineSet {
  std::vector<LineTrace> lines;
  std::vector<Eigen::Vector2d> open;
  bool operator==(const LineSet& o) const;
};

class Document : public QObject {
  Q_OBJECT

 public:
  explicit Document(QObject* parent = nullptr);
  ~Document() override;

  QUndoStack* undoStack() { return &undo_stack_; }
  // Depth planes and map (depth_model.h); reset() empties it for the new photo.
  DepthModel* depth() { return &depth_; }
  const DepthModel* depth() const { return &depth_; }

  // --- photo (not undoable: a new photo starts a new session) ---
  const PhotoPtr& photo() const { return photo_; }
  FrameSize frame() const;
  // Replaces everything: photo, pairs, model; clears the colour block and the undo stack and
  // marks clean.
  void reset(PhotoPtr photo, std::vector<Pair> pairs = {}, ModelClass model = ModelClass::Auto,
             std::optional<Artcam> manual_camera = std::nullopt,
             std::vector<EffectStep> effects = {}, std::vector<LineTrace> lines = {},
             LineModel line_model = LineModel::Auto);
  // The full photo of a quick first look (Photo::reduced_by, image_loader.h) replaces it: same
  // path and size(), so pairs, lines, effects, the camera, the selection and the undo stack stay
  // as they are (nothing refits). Emits photoRefined, not photoChanged. Ignored (false) when
  // the current photo is not that first look (another photo was opened meanwhile).
  bool refinePhoto(PhotoPtr full);
  // The full decode of the first look failed: the photo stays the first look, and what waits
  // for the full image (whenFullImage) is told so. Emits photoRefineFailed.
  void failRefine(const QString& message);
  // Runs `then(true)` once the photo has its full image: at once when it has (or there is no
  // photo), else when refinePhoto brings it. `then(false)` when the full decode failed or
  // another photo replaced this one first. Nothing runs once `context` is destroyed.
  void whenFullImage(QObject* context, std::function<void(bool ready)> then);

  // --- pairs: raw mutators for commands.h ---
  const std::vector<Pair>& pairs() const { return pairs_; }
  void insertPair(int index, const Pair& pair);
  void removePair(int index);
  // How an edit refits. Now: before the call returns (discrete edits, undo, redo), so camera()
  // and fit() are exact at once. InWorker (a drag's mouse moves): the GUI thread only records
  // the pairs and emits pairsChanged; the FitWorker fits the newest pairs and its result
  // arrives later as pairsChanged + cameraChanged, unless a newer edit superseded it.
  enum class Refit { Now, InWorker };
  // Sets several pairs at once and refits once (drags of a multi-selection).
  void setPairs(const std::vector<int>& indices, const std::vector<Pair>& values,
                Refit refit = Refit::Now);
  // Every edit of the fit's inputs bumps editRevision(); camera(), fit() and residual() are
  // those of cameraRevision(). fitPending(): a worker fit of a newer edit is still on its way.
  quint64 editRevision() const { return edit_revision_; }
  quint64 cameraRevision() const { return camera_revision_; }
  bool fitPending() const { return camera_revision_ != edit_revision_; }
  // false: Refit::InWorker fits on the GUI thread too (artcam-studio-bench's comparison).
  void setFitsInWorker(bool in_worker) { fits_in_worker_ = in_worker; }
  int enabledPairCount() const;
  std::vector<PointMatch> matches() const;  // all pairs, with their enabled flags

  // --- straight lines: the raw mutator for line_commands.h ---
  // With an enabled line the geometry is the line fit with the pairs (document_camera.h).
  const std::vector<LineTrace>& lines() const { return lines_.lines; }
  const std::vector<Eigen::Vector2d>& openLine() const { return lines_.open; }
  const LineSet& lineSet() const { return lines_; }
  // Refits only when the finished lines changed (a point added to the open line does not).
  void setLineSet(LineSet lines, Refit refit = Refit::Now);
  // The remaining bow of line `index` under the current fit; none when the geometry is not a
  // line fit (a hand-set camera, a failed fit) or the line is disabled.
  std::optional<LineBow> lineBow(int index) const;
  // The enabled lines' bows, in order; empty when the geometry is not a line fit.
  const std::vector<LineBow>& lineBows() const { return line_bows_; }

  // --- model and camera ---
  ModelClass model() const { return model_; }
  void setModel(ModelClass model);
  // The model chosen for the lines (auto, radial, quadratic); the line fit uses
  // documentLineModel(model(), lineModel()) (core/project/document_camera.h).
  LineModel lineModel() const { return line_model_; }
  // Both at once, one refit (the model row's choice with lines: SetModelChoiceCommand).
  void setModels(ModelClass model, LineModel line_model);
  // True when an enabled finished line makes the geometry a line fit (no camera set by hand).
  bool linesDriveFit() const;
  // A camera set by hand (tensor edits, .artcam import of any kind) replaces the fitted one
  // until cleared. Its first layer is the geometry camera() shows and the tensor panel edits;
  // its other layers, patches and depth output are kept (core/project/document_camera.h).
  const std::optional<Artcam>& manualCamera() const { return manual_camera_; }
  void setManualCamera(std::optional<Artcam> camera);
  const FitSummary& fit() const { return fit_; }
  // The fitted colour block (ui/colour: a colourCamera, identity geometry) or none. When set,
  // camera() carries it in its last stage's colour outputs (core/colour/colour_stage.h), so the
  // preview, the export and .artcam files show the colour change.
  const std::optional<Camera>& colourBlock() const { return colour_block_; }
  void setColourBlock(std::optional<Camera> colour);
  // Manual camera, else the fitted one, else identity (too few or degenerate pairs); with the
  // colour block when there is one.
  const Camera& camera() const { return camera_; }
  // The effect stack: effects of the effects table applied in order after the geometry and
  // colour, reading the depth of depth() (SetEffectsCommand edits it).
  const std::vector<EffectStep>& effects() const { return effects_; }
  void setEffects(std::vector<EffectStep> effects);
  // The second image the compositing effects read (over, in, atop, xor, multiply, screen, …:
  // core/colour/composite.h), laid over the photo's frame; none: those effects are left out
  // (SetSecondImageCommand edits it; Document::reset clears it).
  struct SecondImage {
    QString path;                         // absolute
    std::shared_ptr<const ImageF> image;  // linear, premultiplied RGBA, as core reads it
  };
  const std::optional<SecondImage>& secondImage() const { return second_; }
  void setSecondImage(std::optional<SecondImage> second);
  // Marks after the render (core/effects/finish.h: pencil, charcoal, painting, cartoon) by
  // name, "" for none: the preview, the export and the project draw them (SetFinishCommand).
  const std::string& finish() const { return finish_; }
  void setFinish(std::string finish);
  // The whole camera the preview, the export, Export Camera and the project render: camera()
  // (or the whole camera set by hand), then the effects that could be applied.
  // core/project/document_camera.h makes it, the same function `artcam export` calls.
  const Artcam& artcam() const { return whole_.camera; }
  // Why an effect is left out of artcam() (it reads depth and there is none, …); "" if none.
  const std::string& artcamNote() const { return whole_.note; }
  // Enabled pairs still missing before the chosen model is determined (0 when enough, and when
  // an enabled line makes the geometry a line fit).
  int pairsNeeded() const;
  // Residual (target px) of pair `index` under the current fit; negative if unknown.
  double residual(int index) const;

  // --- selection (view state) ---
  const std::vector<int>& selection() const { return selection_; }
  bool isSelected(int index) const;
  void setSelection(std::vector<int> indices);

  bool isModified() const { return !undo_stack_.isClean(); }

 signals:
  void photoChanged();
  // The first look's full photo arrived (refinePhoto): pictures and pixel readers refresh;
  // nothing else changed.
  void photoRefined();
  void photoRefineFailed(const QString& message);
  void pairsChanged();      // any pair added, removed or changed
  void pairCountChanged();  // rows added or removed (tables reset)
  void linesChanged();      // a line or the open line changed, or their bows after a refit
  void modelChanged();
  void cameraChanged();  // after every refit, even if the camera came out equal
  void effectsChanged();  // the effect stack changed (cameraChanged follows)
  void secondImageChanged();  // a second image set or removed (cameraChanged follows)
  void finishChanged();       // the finish changed (the camera did not)
  void selectionChanged();

 private:
  void refit();
  void refitInWorker();  // a drag's move: record the edit, fit the newest inputs off-thread
  FitInputs fitInputs() const;
  void applyFit(FittedCamera fitted);
  void onWorkerFit(FittedCamera fitted, quint64 revision);
  void assemble();  // whole_ from camera_, the manual camera, the colour block and stack_
  void composeStack();  // stack_ from effects_, the frame and has_depth_ (the costly part)
  void onDepthChanged();

  QUndoStack undo_stack_;
  DepthModel depth_;
  PhotoPtr photo_;
  std::vector<Pair> pairs_;
  LineSet lines_;
  ModelClass model_ = ModelClass::Auto;
  LineModel line_model_ = LineModel::Auto;
  std::optional<Artcam> manual_camera_;
  std::optional<Camera> colour_block_;
  std::vector<EffectStep> effects_;
  std::optional<SecondImage> second_;
  std::string finish_;
  EffectStack stack_;  // effects_ composed; remade only when they or has_depth_ change
  DocumentArtcam whole_;
  bool has_depth_ = false;  // depth_.hasDepth() when whole_ was assembled
  FitSummary fit_;
  Camera camera_;
  std::vector<double> residual_by_pair_;
  std::vector<LineBow> line_bows_;  // enabled lines, in order, when the geometry is a line fit
  std::vector<int> selection_;
  quint64 edit_revision_ = 0;
  quint64 camera_revision_ = 0;
  bool fits_in_worker_ = true;
  std::unique_ptr<FitWorker> fit_worker_;  // started by the first Refit::InWorker edit
};

}  // namespace artcam::ui
