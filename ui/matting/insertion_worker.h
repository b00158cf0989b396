// SPDX-License-Identifier: Apache-2.0
// The Insertion worker (a newest-request worker, newest_request_worker.h: one thread, one
// pending request slot where the newest request wins, std::atomic restart/abort flags, results
// by queued signals stamped with the request's generation). A request carries the grid
// matches, the graphic, the photo and the region; the worker fits the piecewise camera
// (core/piecewise/piecewise_fit.h) and, from four or more table clicks, the board's homography
// (Fig 7b), emits the fit, then puts the graphic on the table and in the object through core's
// insertGraphic (the same call as `artcam insert`; core/pipeline/insert_graphic.h), and emits
// the preview.
//
// The fit and the render have no cancel hook: a newer request makes the worker drop the
// current one between the fit and the render, and the last fit is reused when only the
// graphic, the photo or the region changed. A request whose fit or render throws is a `failed`
// signal, and the next request is served.
#pragma once

#include "core/model/fit_record.h"
#include "core/model/image.h"
#include "core/model/piecewise_camera.h"
#include "core/piecewise/piecewise_fit.h"
#include "ui/matting/graphic_placement.h"
#include "ui/newest_request_worker.h"

#include <QImage>
#include <QMetaType>
#include <QPolygonF>
#include <QString>
#include <QVector>

#include <memory>
#include <optional>
#include <vector>

namespace artcam::ui {

struct InsertionRequest {
  quint64 generation = 0;
  std::vector<PointMatch> matches;        // board pixels → photo pixels, through the object
  std::vector<PointMatch> table_matches;  // board pixels → photo pixels, seen on the table
  FrameSize board_size;
  PiecewiseOptions options;
  FrameSize photo_size;                   // the fit's target frame (full resolution)
  std::shared_ptr<const ImageF> photo;    // linear; the preview copy (any size: see retarget)
  std::shared_ptr<const ImageF> graphic;  // linear premultiplied; null: fit only
  std::vector<Eigen::Vector2d> region;    // photo pixels; < 3 points: no limit
  GraphicPlacement placement;
  // The other media (InsertionState::other_media), each fitted as its own camera; the graphic
  // goes through all of them in the panel's order, the edited one at `current_medium`.
  struct Medium {
    std::vector<PointMatch> matches, table_matches;
    std::vector<Eigen::Vector2d> region;
  };
  std::vector<Medium> other_media;
  int current_medium = 0;
};

// What the panel and the error map show of a fit.
struct InsertionFit {
  bool ok = false;
  QString message;  // why there is no camera, when !ok
  QString report;   // PiecewiseSummary::report()
  int matches = 0;
  int patches = 0;
  double rms_px = 0.0, max_px = 0.0, seam_gap_px = 0.0;
  double single_rms_px = -1.0, single_max_px = -1.0;
  bool converged = false;
  double fit_ms = 0.0;
  std::shared_ptr<const PiecewiseCamera> camera;
  // The board → photo homography from the table clicks (null: fewer than 4, or refused) and
  // what to say about it ("table: homography, 4 matches …", or why there is none).
  std::shared_ptr<const Camera> table;
  QString table_report;
  // Per patch: its support hull mapped through its own camera (photo pixels) and its max error.
  QVector<QPolygonF> patch_outlines;
  QVector<double> patch_max_px;
  // The other media's fits (the request's other_media, in order; their own fields above, no
  // outlines) and where the edited one stands among them.
  struct Medium {
    bool ok = false;
    QString message;
    int patches = 0;
    double max_px = 0.0;
    std::shared_ptr<const PiecewiseCamera> camera;
    std::shared_ptr<const Camera> table;
    std::vector<Eigen::Vector2d> region;
  };
  std::vector<Medium> other_media;
  int current_medium = 0;
  // Some medium has a camera: the graphic will be drawn.
  bool rendersAny() const {
    bool any = ok && camera;
    for (const Medium& m : other_media) any = any || (m.ok && m.camera);
    return any;
  }
};

class InsertionWorker : public NewestRequestWorker<InsertionRequest> {
  Q_OBJECT

 public:
  // request() (GUI thread) replaces the pending request; shutdown() stops the thread
  // (idempotent; the destructor calls it).
  explicit InsertionWorker(QObject* parent = nullptr);
  ~InsertionWorker() override;  // aborts and joins (waits for a fit in flight)

  // The same camera onto a target frame of another size (the preview copy of the photo):
  // cameras live in normalised frames, so only the recorded sizes change.
  static PiecewiseCamera retarget(const PiecewiseCamera& camera, FrameSize target_size);
  // The preview (and export) a request gives for a fit: the placed graphic through core's
  // insertGraphic with the fit's cameras and the region, over the photo at its size (a copy).
  // `table` may be null (the object's copy only). Public so tests can compare with core calls.
  static ImageF composite(const ImageF& photo, const ImageF& graphic, const PiecewiseCamera& camera,
                          const std::vector<Eigen::Vector2d>& region,
                          const GraphicPlacement& placement = {}, const Camera* table = nullptr);
  // The graphic through every fitted medium of `fit` in turn, each on the last one's output
  // (the edited medium with `region`, the others with their own).
  static ImageF compositeMedia(const ImageF& photo, const ImageF& graphic, const InsertionFit& fit,
                               const std::vector<Eigen::Vector2d>& region,
                               const GraphicPlacement& placement = {});
  static InsertionFit describe(const PiecewiseSummary& summary);

 signals:
  void fitted(const artcam::ui::InsertionFit& fit, quint64 generation);
  void rendered(const QImage& composite, quint64 generation);

 protected:
  void serve(InsertionRequest& job) override;

 private:
  // Worker thread only: the inputs of the last fit and its result.
  std::optional<InsertionRequest> last_fit_inputs_;
  InsertionFit last_fit_;
  // The other media's last fits and their inputs (reused while their matches stay).
  std::vector<std::pair<InsertionRequest, InsertionFit>> other_fits_;
};

}  // namespace artcam::ui

Q_DECLARE_METATYPE(artcam::ui::InsertionFit)
