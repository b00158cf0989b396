// SPDX-License-Identifier: Apache-2.0
// The live preview renderer (after Qt's Mandelbrot example): one thread, one pending
// request slot where the newest request wins, std::atomic restart/abort flags polled between
// tiles through WarpOptions::progress, a coarse pass (1/4 size) before the full preview while
// full passes are slow (kCoarseAboveMs), and
// results delivered by queued signals carrying a QImage and the request's generation stamp.
// The loop and its exception boundary are NewestRequestWorker's (newest_request_worker.h): a
// throwing pass becomes a `failed` signal, and the next request is served.
//
// Cameras that change colour or depth (a fitted colour block) render through core's
// render front door (core/pipeline/render.h) from the float preview copy: the colour-only
// path when the geometry is the identity, else gather (or splat). Geometry-only cameras keep
// the 8-bit pyramid path, which is what makes a drag's preview fast.
#pragma once

#include "core/colour/stored_encoding.h"
#include "core/model/artcam.h"
#include "core/model/image.h"
#include "core/sampling/mip_pyramid.h"
#include "core/render/warp.h"
#include "ui/newest_request_worker.h"

#include <QImage>
#include <QString>

#include <functional>
#include <memory>
#include <optional>

namespace artcam::ui {

struct RenderRequest {
  // When set, the 8-bit path: warpPreview from the photo's mip pyramid straight into an RGBA8
  // QImage (the preview path); else the float path from `source`.
  std::shared_ptr<const StoredMipPyramid> pyramid;
  std::shared_ptr<const ImageF> source;  // the downscaled preview source
  // How `source` was decoded from the photo's stored values: the float path resamples in that
  // domain, as the export and `artcam warp` do (core/colour/stored_encoding.h). Null: linear.
  std::shared_ptr<const StoredEncoding> encoding;
  // Depth block input for cameras that read depth (core/depth/depth_raster.h form, any size).
  std::shared_ptr<const ImageF> depth;
  // The second image compositing cameras read (RenderInputs::second), any size.
  std::shared_ptr<const ImageF> second;
  // Marks after the render (core/effects/finish.h), by name; empty: none. Drawn on the pass's
  // own pixels, as the export draws them on its own (so at another scale on a bigger photo).
  std::string finish;
  Artcam camera;  // the document's whole camera
  // The photo's EXIF orientation (ImageInfo::stored_orientation): a camera made for the stored
  // raster is applied before the turn (core/pipeline/camera_frame.h).
  int stored_orientation = 1;
  int width = 0;  // full-pass output size (the coarse pass is a quarter of it)
  int height = 0;
  quint64 generation = 0;
};

class RenderWorker : public NewestRequestWorker<RenderRequest> {
  Q_OBJECT

 public:
  static constexpr int kCoarseFactor = 4;
  // The coarse pass comes first only while final passes take longer than this: each pass pays
  // the camera's setup (inverse seed, correction grid), so for fast finals it only adds delay.
  static constexpr double kCoarseAboveMs = 30.0;

  // The warp options of a preview pass (no progress hook): one place, so a direct render with
  // them reproduces the worker's image exactly.
  static WarpOptions passOptions(int width, int height);
  // One pass of a request with those options (plus a progress hook): what the worker emits,
  // rendered by core's front door (core/pipeline/render.h). A camera that needs the linear
  // photo (needsLinearPhoto: colour, depth, layers) renders from `source`, never the pyramid.
  // With a finish, `before_marks` (when given) gets the picture before the marks are drawn on
  // it and the render's time; returning false stops there (summary->cancelled, an empty image).
  static QImage renderPass(const RenderRequest& job, const WarpOptions& options,
                           WarpSummary* summary,
                           const std::function<bool(const QImage&, double)>& before_marks = {});

  // request() replaces the pending request and cancels the one in flight at its next tile;
  // shutdown() stops the thread (idempotent; the destructor calls it). A pass that throws is
  // `failed(message, generation)`.
  explicit RenderWorker(QObject* parent = nullptr);
  ~RenderWorker() override;  // aborts any render and joins the thread

 signals:
  // `final_pass` is false for the coarse pass. render_ms is the warp time of that pass.
  void rendered(const QImage& image, quint64 generation, bool final_pass, double render_ms);

 protected:
  void serve(RenderRequest& job) override;

 private:
  double last_final_ms_ = 1e300;  // worker thread only: the last final pass's render time
};

}  // namespace artcam::ui
