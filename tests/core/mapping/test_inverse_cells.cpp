// SPDX-License-Identifier: Apache-2.0
// The rational kernel's certified cells and subcells on a strong barrel, u' = u / (1 + 0.6 r²),
// whose fold circle r' = 1/√2.4 cuts the frame's corners: every pixel against the closed-form
// inverse, and the subdivision of open cells against the same cells left whole. On a mild
// barrel, the cells certified in pairs: each the pair's patch over its quarter.
#include "core/effects/image_warps.h"
#include "core/model/frames.h"
#include "core/model/structure.h"
#include "core/mapping/coordinates.h"
#include "core/mapping/inverse.h"
#include "core/mapping/inverse_cells.h"
#include "core/mapping/rational_map.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cmath>
#include <optional>
#include <vector>

using namespace artcam;

namespace {

constexpr double kK = -0.6;

// The inverse on the source centre's side of the fold: r' = r / (1 − k r²) gives
// −k r' r² − r + r' = 0, whose smaller root is r = (1 − √(1 + 4 k r'²)) / (−2 k r'); beyond the
// fold circle (negative discriminant) there is no preimage.
std::optional<Eigen::Vector2d> exactInverse(FrameSize size, const Eigen::Vector2d& t_px, double k = kK) {
  const Eigen::Vector2d t = normalizedFromPixel(size, t_px);
  const double rt = t.norm();
  if (rt == 0.0) return pixelFromNormalized(size, t);
  const double disc = 1.0 + 4.0 * k * rt * rt;
  if (disc < 0.0) return std::nullopt;
  const double r = (1.0 - std::sqrt(disc)) / (-2.0 * k * rt);
  return pixelFromNormalized(size, t * (r / rt));
}

}  // namespace

class TestInverseCells : public QObject {
  Q_OBJECT

 private slots:
  // Every output pixel of the fused kernel: within 1/256 px of the closed form wherever it has
  // a preimage within the filters' reach, transparent wherever it has none (never NaN). The
  // kernel's own closed form (central_inverse.h) and, without it, the cells' quadtree and the
  // per-pixel Newton that every non-central map relies on.
  void strongBarrelEveryPixelAgreesWithClosedForm_data() {
    QTest::addColumn<bool>("central");
    QTest::newRow("central inverse") << true;
    QTest::newRow("general path") << false;
  }
  void strongBarrelEveryPixelAgreesWithClosedForm() {
    QFETCH(bool, central);
    const FrameSize size{3000, 2000};
    const Camera camera = radialLensCamera(kK, size);
    const CameraStructure structure = analyseStructure(camera);
    CoordinateOptions options;
    options.central_inverse = central;
    const KernelChoice choice = makeCoordinateKernel(camera, structure, size, size, options, 2);
    QCOMPARE(choice.name, std::string("rational"));
    float sx[kSpanPixels], sy[kSpanPixels];
    unsigned char ok[kSpanPixels];
    double worst = 0.0;
    long long missing = 0, spurious = 0, without_preimage = 0;
    for (int y = 0; y < size.height; ++y) {
      RowState state;
      for (int x0 = 0; x0 < size.width; x0 += kSpanPixels) {
        const int n = std::min(kSpanPixels, size.width - x0);
        choice.kernel->span(y, x0, n, sx, sy, ok, state);
        for (int i = 0; i < n; ++i) {
          const std::optional<Eigen::Vector2d> exact = exactInverse(size, {x0 + i + 0.5, y + 0.5});
          if (!exact) ++without_preimage;
          if (ok[i] && !(std::isfinite(sx[i]) && std::isfinite(sy[i]))) ++spurious;
          if (ok[i] && !exact) ++spurious;
          if (!exact) continue;
          // A preimage beyond the filters' reach may render transparent either way.
          const bool reachable = exact->x() > -2 && exact->y() > -2 &&
                                 exact->x() < size.width + 2 && exact->y() < size.height + 2;
          if (!ok[i]) {
            missing += reachable ? 1 : 0;
            continue;
          }
          if (reachable)
            worst = std::max(worst, std::hypot(sx[i] - exact->x(), sy[i] - exact->y()));
        }
      }
    }
    qInfo("strong barrel: worst %.3g px, %lld pixels without preimage", worst, without_preimage);
    QVERIFY(without_preimage > 0);  // the fold circle is in the frame
    QCOMPARE(missing, 0LL);
    QCOMPARE(spurious, 0LL);
    QVERIFY2(worst <= 1.0 / 256.0, qPrintable(QString("worst %1 px").arg(worst)));
  }

  // Open cells split into subcells certified by the same rule: the area left to the per-pixel
  // path shrinks to a fraction of what whole cells leave, and every pixel of a certified
  // subcell's patch is within the certification tolerance's budget of the closed form.
  void subdivisionShrinksPerPixelPath() {
    const FrameSize size{6000, 4000};
    const Camera camera = radialLensCamera(kK, size);
    const NewtonInverse newton(RationalMap(camera, size, size), size, 1e-3);
    InverseCellsOptions whole_options;
    whole_options.subdivide = false;
    const InverseCells whole(newton, nullptr, size, size, whole_options);
    const InverseCells split(newton, nullptr, size, size, InverseCellsOptions{});
    const double whole_open = 1.0 - whole.certifiedShare() - whole.emptyShare();
    const double split_open = 1.0 - split.certifiedShare() - split.emptyShare();
    qInfo("per-pixel share: whole cells %.4f, subdivided %.4f", whole_open, split_open);
    QVERIFY(whole_open > 0.0);  // the fold leaves cells uncertified
    QVERIFY2(split_open < 0.5 * whole_open,
             qPrintable(QString("%1 of %2").arg(split_open).arg(whole_open)));

    double worst = 0.0;
    long long checked = 0;
    for (int cy = 0; cy < split.cellsHigh(); ++cy)
      for (int cx = 0; cx < split.cellsWide(); ++cx) {
        if (split.kind(cx, cy) != InverseCells::kOpen || !split.refined(cx, cy)) continue;
        for (int sy = 0; sy < InverseCells::kSubs; ++sy)
          for (int sx = 0; sx < InverseCells::kSubs; ++sx) {
            if (split.subKind(cx, cy, sx, sy) != InverseCells::kCertified) continue;
            for (int j = 0; j < InverseCells::kSub; ++j) {
              const int y = cy * InverseCells::kCell + sy * InverseCells::kSub + j;
              InverseCells::SubRow r;
              split.subRow(cx, sx, y, r);
              for (int i = 0; i < InverseCells::kSub; ++i) {
                const int x = cx * InverseCells::kCell + sx * InverseCells::kSub + i;
                if (x >= size.width || y >= size.height) continue;
                const std::optional<Eigen::Vector2d> exact = exactInverse(size, {x + 0.5, y + 0.5});
                QVERIFY2(
                    exact.has_value(),
                    qPrintable(QString("certified pixel %1,%2 has no preimage").arg(x).arg(y)));
                const double u = (x + 0.5 - r.x0) / r.size;
                const Eigen::Vector2d s(
                    r.cubic.x[0] + u * (r.cubic.x[1] + u * (r.cubic.x[2] + u * r.cubic.x[3])),
                    r.cubic.y[0] + u * (r.cubic.y[1] + u * (r.cubic.y[2] + u * r.cubic.y[3])));
                worst = std::max(worst, (s - *exact).norm());
                ++checked;
              }
            }
          }
      }
    qInfo("certified subcell pixels: %lld, worst %.3g px", checked, worst);
    QVERIFY(checked > 0);
    // Certified to 1/8192 px by one Newton step at the patch's error peaks; the budget is 1/256.
    QVERIFY2(worst <= 1.0 / 1024.0, qPrintable(QString("worst %1 px").arg(worst)));
  }

  // A mild barrel's cells certify in pairs (2 × 2 cells as one square), and each cell of a pair
  // then takes its nodes between the pair's corners from the pair's patch, not from Newton:
  // its patch is the pair's over its quarter, as exact as the pair's. Against the closed form at
  // every pixel of every tenth row, the double patches stay far inside the certification
  // tolerance (1/4096 px), where a slip in the derived nodes (a cross derivative off by a fifth)
  // would show; the float positions the kernel renders round these to ~5e-4 px anyway.
  void pairedCellsFollowTheInverse() {
    const FrameSize size{6000, 4000};
    constexpr double k = -0.08;
    const NewtonInverse newton(RationalMap(radialLensCamera(k, size), size, size), size, 1e-3);
    const InverseCells cells(newton, nullptr, size, size, InverseCellsOptions{});
    qInfo("certified %.4f, empty %.4f", cells.certifiedShare(), cells.emptyShare());
    QVERIFY(cells.certifiedShare() > 0.85);  // the corners see beyond the photo: empty
    QCOMPARE(cells.certifiedShare() + cells.emptyShare(), 1.0);
    double worst = 0.0;
    long long checked = 0;
    for (int y = 5; y < size.height; y += 10) {
      const int cy = std::min(y / InverseCells::kCell, cells.cellsHigh() - 1);
      for (int cx = 0; cx < cells.cellsWide(); ++cx) {
        if (cells.kind(cx, cy) != InverseCells::kCertified) continue;
        CellRow r;
        cells.row(cx, y, r);
        for (int i = 0; i < InverseCells::kCell && cx * InverseCells::kCell + i < size.width; ++i) {
          const int x = cx * InverseCells::kCell + i;
          const std::optional<Eigen::Vector2d> exact = exactInverse(size, {x + 0.5, y + 0.5}, k);
          QVERIFY(exact.has_value());
          const double u = (i + 0.5) / InverseCells::kCell;
          const Eigen::Vector2d s(r.x[0] + u * (r.x[1] + u * (r.x[2] + u * r.x[3])),
                                  r.y[0] + u * (r.y[1] + u * (r.y[2] + u * r.y[3])));
          worst = std::max(worst, (s - *exact).norm());
          ++checked;
        }
      }
    }
    qInfo("%lld pixels, worst %.3g px", checked, worst);
    QVERIFY(checked > 2000000);
    QVERIFY2(worst < 1.0 / 4096.0, qPrintable(QString::number(worst)));
  }

  // Coverage is skipped only where it would mark every block: a pin-cushion's frame lies inside
  // the image of the source (every cell certifies, nothing is empty), a mild barrel's corners
  // see beyond the photo (coverage is built and empties them), and so does the strong barrel's
  // fold.
  void coverageSkippedOnlyWhereFrameIsCovered() {
    const FrameSize size{3000, 2000};
    const struct {
      double k;
      bool covered;
    } cases[] = {{0.15, true}, {-0.15, false}, {kK, false}};
    for (const auto& c : cases) {
      const NewtonInverse newton(RationalMap(radialLensCamera(c.k, size), size, size), size, 1e-3);
      const InverseCells cells(newton, nullptr, size, size, InverseCellsOptions{});
      qInfo("k %.2f: coverage %s, certified %.4f, empty %.4f", c.k, cells.coverageKnown() ? "built" : "skipped",
            cells.certifiedShare(), cells.emptyShare());
      QCOMPARE(cells.coverageKnown(), !c.covered);
      if (c.covered) QCOMPARE(cells.certifiedShare(), 1.0);
      else QVERIFY(cells.emptyShare() > 0.0);
    }
  }

  // Pixels beyond the fold circle in open subcells: the per-pixel path's coverage test must
  // turn them away, or every Newton start fails on each in turn. Coverage is a bound (it may
  // not miss a pixel with a preimage: the test above), so a thin band just beyond the circle
  // stays; the mapped quads' bounding boxes, before their polygons, let 5.9k pixels through,
  // in a band up to 7 px wide along the diagonals.
  void coverageHugsTheFold() {
    const FrameSize size{6000, 4000};
    const Camera camera = radialLensCamera(kK, size);
    const NewtonInverse newton(RationalMap(camera, size, size), size, 1e-3);
    const InverseCells cells(newton, nullptr, size, size, InverseCellsOptions{});
    long long let_through = 0, open_pixels = 0;
    double widest = 0.0;  // beyond the circle, in output pixels
    const double fold_radius = std::sqrt(-1.0 / (4.0 * kK));  // where the discriminant vanishes
    unsigned char covered[InverseCells::kCell];
    for (int y = 0; y < size.height; ++y) {
      const int cy = std::min(y / InverseCells::kCell, cells.cellsHigh() - 1);
      const int sub_y = std::min((y - cy * InverseCells::kCell) / InverseCells::kSub, InverseCells::kSubs - 1);
      for (int cx = 0; cx < cells.cellsWide(); ++cx) {
        if (cells.kind(cx, cy) != InverseCells::kOpen) continue;
        const int x0 = cx * InverseCells::kCell, n = std::min(InverseCells::kCell, size.width - x0);
        cells.coveredRun(x0, y, n, covered);
        for (int i = 0; i < n; ++i) {
          const int sub_x = i / InverseCells::kSub;
          if (cells.refined(cx, cy) && cells.subKind(cx, cy, sub_x, sub_y) != InverseCells::kOpen) continue;
          ++open_pixels;
          const Eigen::Vector2d t(x0 + i + 0.5, y + 0.5);
          if (!covered[i] || exactInverse(size, t)) continue;
          ++let_through;
          const double r = normalizedFromPixel(size, t).norm();
          widest = std::max(widest, (r - fold_radius) / (r / (t - pixelFromNormalized(size, {0, 0})).norm()));
        }
      }
    }
    qInfo("open pixels %lld, beyond the fold but covered %lld, up to %.2f px beyond", open_pixels,
          let_through, widest);
    QVERIFY(open_pixels > 0);
    QVERIFY2(let_through < 1500, qPrintable(QString::number(let_through)));
    QVERIFY2(widest < 3.0, qPrintable(QString::number(widest)));
  }
};

QTEST_GUILESS_MAIN(TestInverseCells)
#include "test_inverse_cells.moc"
