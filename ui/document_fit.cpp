// SPDX-License-Identifier: Apache-2.0
#include "ui/document_fit.h"

#include "ui/colour/colour_stage.h"

#include <QCoreApplication>
#include <QThread>

#include <algorithm>
#include <atomic>
#include <exception>
#include <string>

namespace artcam::ui {
namespace {

std::atomic<long> g_fits_on_gui{0};
std::atomic<long> g_fits_elsewhere{0};

void countFit() {
  const QCoreApplication* app = QCoreApplication::instance();
  if (app && QThread::currentThread() == app->thread())
    ++g_fits_on_gui;
  else
    ++g_fits_elsewhere;
}

}  // namespace

Camera identityImageCamera(FrameSize f) {
  if (!f.isImage()) f = {1, 1};
  return Camera::identity({Block{BlockKind::Position, 3}}, f, f);
}

int pairsNeededFor(ModelClass model, int enabled_pairs) {
  const ModelClass m = model == ModelClass::Auto ? ModelClass::Translation : model;
  return std::max(0, minimumMatches(m) - enabled_pairs);
}

FitThreadCounts fitThreadCounts() { return {g_fits_on_gui.load(), g_fits_elsewhere.load()}; }

// The camera is a pure function of the inputs, which is what makes undo restore it exactly
// and lets a worker compute it for the GUI thread.
FittedCamera fitDocumentCamera(const FitInputs& in) {
  countFit();
  const FrameSize f = in.frame;
  FittedCamera out;
  out.residual_by_pair.assign(in.matches.size(), -1.0);
  out.camera = identityImageCamera(f);
  if (!f.isImage()) return out;
  try {
    const int enabled = static_cast<int>(std::count_if(
        in.matches.begin(), in.matches.end(), [](const PointMatch& m) { return m.enabled; }));
    if (in.manual_camera) {
      out.camera = *in.manual_camera;
    } else if (enabled == 0) {
      out.fit.status =
          Status::failure("No point pairs yet: click a source point, then its target.");
    } else if (const int need = pairsNeededFor(in.model, enabled); need > 0) {
      out.fit.status =
          Status::failure("Need " + std::to_string(need) + " more pair" + (need == 1 ? "" : "s") +
                          " for the " + std::string(modelClassName(in.model)) + " model.");
    } else {
      FitOptions options;
      options.model = in.model;
      out.fit = fitImageCamera(in.matches, f, f, options);
      if (out.fit.status.ok) out.camera = out.fit.camera;
    }
    if (!in.matches.empty()) {
      // Residuals of every pair, disabled ones too: they show how far an outlier is off.
      std::vector<PointMatch> all = in.matches;
      for (PointMatch& m : all) m.enabled = true;
      const std::vector<double> r = reprojectionResiduals(out.camera, all);
      for (size_t i = 0; i < r.size() && i < out.residual_by_pair.size(); ++i)
        out.residual_by_pair[i] = r[i];
    }
    // After the residuals: they are a property of the geometry (a position-only camera).
    if (in.colour_block) out.camera = withColourBlock(out.camera, *in.colour_block);
  } catch (const std::exception& e) {
    // A broken contract in the engine must not take the GUI down: report it as a failed fit.
    out.fit = FitSummary{};
    out.fit.status = Status::failure(std::string("Fit failed: ") + e.what());
    out.camera = identityImageCamera(f);
  }
  return out;
}

}  // namespace artcam::ui
