// SPDX-License-Identifier: Apache-2.0
// A camera that is written can be read back: validateArtcam holds every limit the reader holds
// (frame sides of kMaxFrameSide), so writeArtcam refuses what readArtcam would; and requests
// that would make such a camera are refused where they are made: an ST map whose header
// claims a source frame beyond the limit (naming --size), and a map that reads one point or
// one line, which no camera's inverse does.
#include "core/io/artcam_file.h"
#include "core/io/stmap_file.h"
#include "core/model/artcam.h"

#include <QtTest/QtTest>

#include <filesystem>
#include <string>

using namespace artcam;

namespace {

Artcam identityOf(FrameSize source, FrameSize target) {
  return Artcam(Camera::identity({{BlockKind::Position, 3}}, source, target));
}

// A w×h map of a `source` frame: every pixel reads position(i, j) inside the photo.
template <class Position>
PositionMap mapOf(int w, int h, FrameSize source, Position position) {
  PositionMap map;
  map.source_px = source;
  map.target_px = {w, h};
  const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
  map.x_px.resize(n);
  map.y_px.resize(n);
  map.preimage.assign(n, Preimage::InPhoto);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const Eigen::Vector2d p = position(i, j);
      map.x_px[map.index(i, j)] = static_cast<float>(p.x());
      map.y_px[map.index(i, j)] = static_cast<float>(p.y());
    }
  return map;
}

bool contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return true;
  qWarning("\"%s\" lacks \"%s\"", text.c_str(), part.c_str());
  return false;
}

}  // namespace

class TestCameraRequests : public QObject {
  Q_OBJECT
  QTemporaryDir dir_;
  std::string path(const char* name) const { return dir_.filePath(name).toStdString(); }

 private slots:
  void frameSidesBeyondTheReadersLimitAreNotWritten() {
    const int side = kMaxFrameSide;
    const Artcam largest = identityOf({side, 48}, {64, side});
    QVERIFY2(validateArtcam(largest).ok, validateArtcam(largest).message.c_str());
    QVERIFY(writeArtcam(path("largest.artcam"), largest).ok);
    QVERIFY(readArtcam(path("largest.artcam")).ok());  // what is written reads back

    const Artcam wide = identityOf({side + 1, 48}, {64, 48});
    const Status s = validateArtcam(wide);
    QVERIFY(!s.ok);
    QVERIFY(contains(s.message, "/frames/source: 1048577x48 has a side beyond the 1048576"));
    const Status w = writeArtcam(path("wide.artcam"), wide);
    QVERIFY(!w.ok);
    QVERIFY(contains(w.message, "wide.artcam: cannot write: /frames/source"));
    QVERIFY(!std::filesystem::exists(path("wide.artcam")));
    QVERIFY(contains(validateArtcam(identityOf({64, 48}, {64, 2147483647})).message,
                     "/frames/target: 64x2147483647"));
  }

  void anStmapHeaderClaimingAGiantSourceIsRefusedNamingSize() {
    const FrameSize giant{2147483647, 48};
    const PositionMap map = mapOf(
        64, 48, giant, [](int i, int j) { return Eigen::Vector2d(1000.0 * i + 0.5, j + 0.5); });
    QVERIFY(writeStmap(path("giant.exr"), {{"", &map}}, StmapConvention::StMap).ok);
    const auto refused = readStmapSamples(path("giant.exr"));
    QVERIFY(!refused.ok());
    QVERIFY(contains(refused.status.message,
                     "giant.exr: artcam:source_width/artcam:source_height "
                     "2147483647x48 has a side beyond the 1048576"));
    QVERIFY(contains(refused.status.message, "--size WxH"));
    StmapSampleOptions sized;  // the photo's size given: the header's claim is not used
    sized.source_px = FrameSize{64000, 48};
    QVERIFY(readStmapSamples(path("giant.exr"), sized).ok());
  }

  void aMapThatReadsOnePointOrOneLineIsNoCamera() {
    const FrameSize frame{64, 48};
    const PositionMap constant =
        mapOf(64, 48, frame, [](int, int) { return Eigen::Vector2d(32.0, 24.0); });
    QVERIFY(writeStmap(path("constant.exr"), {{"", &constant}}, StmapConvention::StMap).ok);
    const auto one = readStmapSamples(path("constant.exr"));
    QVERIFY(!one.ok());
    QVERIFY(contains(one.status.message,
                     "constant.exr: every sample of the map reads the same "
                     "source point (a constant map)"));

    const PositionMap line =
        mapOf(64, 48, frame, [](int i, int) { return Eigen::Vector2d(i + 0.5, 24.0); });
    QVERIFY(writeStmap(path("line.exr"), {{"", &line}}, StmapConvention::StMap).ok);
    const auto on_line = readStmapSamples(path("line.exr"));
    QVERIFY(!on_line.ok());
    QVERIFY(contains(on_line.status.message, "source points on one line"));

    const PositionMap shift =
        mapOf(64, 48, frame, [](int i, int j) { return Eigen::Vector2d(i + 3.5, j + 0.5); });
    QVERIFY(writeStmap(path("shift.exr"), {{"", &shift}}, StmapConvention::StMap).ok);
    QVERIFY(readStmapSamples(path("shift.exr")).ok());
  }
};

QTEST_GUILESS_MAIN(TestCameraRequests)
#include "test_camera_requests.moc"
