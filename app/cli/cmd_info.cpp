// artcam info: what a camera file holds: blocks, structure, frames, tensors, fit report.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "core/io/artcam_file.h"
#include "core/fit/poles.h"
#include "core/model/structure.h"

#include <cstdio>

namespace artcam::cli {

const char* const kInfoUsage =
    "usage: artcam info CAM.artcam\n\n"
    "Prints the camera's blocks, its structure (which parts are zero; geometry identity,\n"
    "translation, affine, homography or rational), its frames, its tensors (normalised\n"
    "frame) and the fit report it came from, if any. No options.\n\n"
    "Example:\n"
    "  artcam info lens.artcam\n";

int infoCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {});
  args.expectPositional(1, "CAM.artcam");
  const auto doc = readArtcamFile(args.positional()[0]);
  if (!doc) throw CommandError(doc.status.message);
  const Camera& camera = doc->camera;
  const CameraStructure structure = analyseStructure(camera);

  std::printf("file:      %s\n", args.positional()[0].c_str());
  std::printf("blocks:   ");
  for (const Block& b : camera.blocks())
    std::printf(" %s(%d)", std::string(blockKindName(b.kind)).c_str(), b.size);
  std::printf("\nstructure: %s\n", structure.summary.c_str());
  std::printf("frames:    source %dx%d, target %dx%d (tensors in the normalised frames)\n",
              camera.sourceSize().width, camera.sourceSize().height, camera.targetSize().width,
              camera.targetSize().height);
  std::printf("poles:     %s\n", checkPoles(camera).describe().c_str());
  if (structure.geometry != GeometryClass::Rational && structure.homography.size() > 0) {
    std::printf("homography (target_from_source, normalised, column form):\n");
    for (Eigen::Index r = 0; r < structure.homography.rows(); ++r) {
      std::printf("  ");
      for (Eigen::Index c = 0; c < structure.homography.cols(); ++c)
        std::printf(" %14.8g", structure.homography(r, c));
      std::printf("\n");
    }
  }
  for (size_t s = 0; s < camera.stages().size(); ++s)
    for (size_t i = 0; i < camera.stages()[s].q.size(); ++i) {
      const Eigen::MatrixXd& q = camera.stages()[s].q[i];
      std::printf("stage %zu Q_%zu:\n", s + 1, i + 1);
      for (Eigen::Index r = 0; r < q.rows(); ++r) {
        std::printf("  ");
        for (Eigen::Index c = 0; c < q.cols(); ++c) std::printf(" %14.8g", q(r, c));
        std::printf("\n");
      }
    }
  if (doc->fit) {
    const FitRecord& f = *doc->fit;
    std::printf("fit:       %s, %d matches, RMS %.4g px, max %.4g px\n", f.model.c_str(), f.matches,
                f.rms_px, f.max_px);
    if (!f.reason.empty()) std::printf("           %s\n", f.reason.c_str());
  }
  std::printf("matches:   %zu stored\n", doc->matches.size());
  return 0;
}

}  // namespace artcam::cli
