// SPDX-License-Identifier: Apache-2.0
// Opening a JPEG: the first look (a DCT-scaled decode) comes first, the full photo after, with
// the same size and exactly readImage's pixels; an edit made between the two survives the swap
// (and its undo); an export asked for during the first look waits and renders the full photo.
#include "core/io/image_io.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/export_job.h"
#include "ui/image_loader.h"
#include "ui/photo.h"
#include "ui/session.h"

#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <cmath>
#include <cstdint>

using namespace artcam;
using namespace artcam::ui;

namespace {

// 4000×400: the live preview is 1920×192, which libjpeg's 1/2 decode (2000×200) covers.
constexpr int kWidth = 4000;
constexpr int kHeight = 400;

// Noise over checks: a reduced decode, scaled back up, is far from these pixels.
ImageF noisePhoto() {
  ImageF image(kWidth, kHeight, 3);
  std::uint32_t seed = 99;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int c = 0; c < 3; ++c) {
        seed = seed * 1664525u + 1013904223u;
        image.pixel(x, y)[c] =
            ((x / 4 + y / 4) % 2 ? 0.5f : 0.1f) + 0.4f * static_cast<float>(seed >> 24) / 255.0f;
      }
  return image;
}

Pair somePair() { return {{1000.5, 100.5}, {1010.5, 104.5}, true}; }

}  // namespace

class TestFirstLook : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString jpeg_;
  LoadedImage truth_;  // readImage of jpeg_

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    QVERIFY(dir_.isValid());
    jpeg_ = dir_.filePath("wide.jpg");
    const Status written = writeImage(jpeg_.toStdString(), noisePhoto());
    QVERIFY2(written, written.message.c_str());
    auto read = readImage(jpeg_.toStdString());
    QVERIFY2(read, read.status.message.c_str());
    truth_ = std::move(*read.value);
  }

  void loaderBringsFirstLookThenFullPhoto() {
    ImageLoader loader(jpeg_);
    loader.setFirstLook(true);
    QSignalSpy loaded(&loader, &ImageLoader::loaded);
    QSignalSpy refined(&loader, &ImageLoader::refined);
    QSignalSpy finished(&loader, &ImageLoader::finished);
    loader.start();
    QTRY_COMPARE_WITH_TIMEOUT(finished.size(), 1, 60000);
    QCOMPARE(loaded.size(), 1);
    QCOMPARE(refined.size(), 1);
    const PhotoPtr first = loaded.front().front().value<PhotoPtr>();
    const PhotoPtr full = refined.front().front().value<PhotoPtr>();
    QVERIFY(!first->hasFullImage());
    QCOMPARE(first->reduced_by, 2);
    QVERIFY(first->full.image.empty());  // no reduced pixels pass for the photo's
    QCOMPARE(first->size().width, kWidth);
    QCOMPARE(first->size().height, kHeight);
    QCOMPARE(first->full.info.format_name, std::string("jpeg"));
    // The first look's picture covers 7/8 of the live preview it feeds, or more
    // (firstLookReduction): here 1/2, 2000×200 for 1920×192.
    const FrameSize live = livePreviewSize(*first);
    QCOMPARE(live.width, 1920);
    QVERIFY(first->display.width() >= live.width && first->display.height() >= live.height);
    QVERIFY(first->pyramid);
    QCOMPARE(qAlpha(first->display.pixel(17, 3)), 255);  // libjpeg-turbo's RGBA is opaque
    QCOMPARE(first->preview.width, full->preview.width);  // the float copy: 1000×100 both
    QCOMPARE(first->preview.channels, full->preview.channels);

    QVERIFY(full->hasFullImage());
    QCOMPARE(full->size().width, kWidth);
    QCOMPARE(full->size().height, kHeight);
    QCOMPARE(full->full.image.width, kWidth);
    QVERIFY(full->full.image.data == truth_.image.data);
  }

  // Held, the whole read waits for releaseWholeRead(): nothing of it comes while the first look
  // is up (its own limit set far out of reach), then the full photo follows the release. Held
  // and never released, it starts at its limit.
  void heldWholeReadWaitsForTheRelease() {
    ImageLoader loader(jpeg_);
    loader.setFirstLook(true);
    loader.setHoldWholeRead(true, 600000);
    QSignalSpy loaded(&loader, &ImageLoader::loaded);
    QSignalSpy refined(&loader, &ImageLoader::refined);
    QSignalSpy finished(&loader, &ImageLoader::finished);
    loader.start();
    QTRY_COMPARE_WITH_TIMEOUT(loaded.size(), 1, 60000);
    QTest::qWait(300);  // the whole read of this small photo takes a few ms, once begun
    QCOMPARE(refined.size(), 0);
    QCOMPARE(finished.size(), 0);
    loader.releaseWholeRead();
    QTRY_COMPARE_WITH_TIMEOUT(finished.size(), 1, 60000);
    QCOMPARE(refined.size(), 1);
    loader.releaseWholeRead();  // nothing waits any more: no second read
    QTest::qWait(50);
    QCOMPARE(refined.size(), 1);

    ImageLoader unreleased(jpeg_);
    unreleased.setFirstLook(true);
    unreleased.setHoldWholeRead(true, 20);
    QSignalSpy refined_anyway(&unreleased, &ImageLoader::refined);
    unreleased.start();
    QTRY_COMPARE_WITH_TIMEOUT(refined_anyway.size(), 1, 60000);
  }

  // Cancelled while held: finished() and nothing else.
  void cancelWhileHeldFinishes() {
    ImageLoader loader(jpeg_);
    loader.setFirstLook(true);
    loader.setHoldWholeRead(true, 50);
    QSignalSpy loaded(&loader, &ImageLoader::loaded);
    QSignalSpy refined(&loader, &ImageLoader::refined);
    QSignalSpy finished(&loader, &ImageLoader::finished);
    loader.start();
    QTRY_COMPARE_WITH_TIMEOUT(loaded.size(), 1, 60000);
    loader.cancel();
    QTRY_COMPARE_WITH_TIMEOUT(finished.size(), 1, 60000);
    QTest::qWait(50);
    QCOMPARE(refined.size(), 0);
    QCOMPARE(finished.size(), 1);
  }

  // A PNG has no DCT scaling: read whole, loaded() only.
  void otherFormatsAreReadWhole() {
    const QString png = dir_.filePath("wide.png");
    QVERIFY(writeImage(png.toStdString(), truth_.image).ok);
    ImageLoader loader(png);
    loader.setFirstLook(true);
    QSignalSpy loaded(&loader, &ImageLoader::loaded);
    QSignalSpy refined(&loader, &ImageLoader::refined);
    QSignalSpy finished(&loader, &ImageLoader::finished);
    loader.start();
    QTRY_COMPARE_WITH_TIMEOUT(finished.size(), 1, 60000);
    QCOMPARE(loaded.size(), 1);
    QCOMPARE(refined.size(), 0);
    QVERIFY(loaded.front().front().value<PhotoPtr>()->hasFullImage());
  }

  // The edit lands while the first look is up (queued behind its delivery, so before the
  // full photo's, which the first look's delivery only starts).
  void editBetweenLooksSurvivesSwap() {
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    QSignalSpy swapped(&doc, &Document::photoRefined);
    bool edited_on_first_look = false;
    connect(
        &doc, &Document::photoChanged, this,
        [&] {
          edited_on_first_look = doc.photo() && !doc.photo()->hasFullImage();
          doc.undoStack()->push(new AddPairCommand(&doc, somePair()));
        },
        Qt::QueuedConnection);
    session.openPhoto(jpeg_);
    QTRY_COMPARE_WITH_TIMEOUT(swapped.size(), 1, 60000);
    QVERIFY(edited_on_first_look);
    QVERIFY(doc.photo()->hasFullImage());
    QCOMPARE(doc.photo()->size().width, kWidth);
    QVERIFY(doc.photo()->full.image.data == truth_.image.data);
    QCOMPARE(doc.pairs().size(), size_t{1});
    QCOMPARE(doc.pairs()[0].target, somePair().target);
    QCOMPARE(doc.undoStack()->count(), 1);
    QVERIFY(doc.isModified());
    doc.undoStack()->undo();
    QCOMPARE(doc.pairs().size(), size_t{0});
  }

  // Asked for during the first look, the export waits, then renders the full photo: the
  // identity camera gives the photo back, which a reduced render could not.
  void exportDuringFirstLookUsesFullPhoto() {
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    const QString out = dir_.filePath("exported.png");
    QSignalSpy finished(&session, &Session::exportFinished);
    QSignalSpy status(&session, &Session::statusMessage);
    bool asked_on_first_look = false;
    connect(
        &doc, &Document::photoChanged, this,
        [&] {
          asked_on_first_look = doc.photo() && !doc.photo()->hasFullImage();
          session.exportImage(out);
        },
        Qt::QueuedConnection);
    session.openPhoto(jpeg_);
    QTRY_COMPARE_WITH_TIMEOUT(finished.size(), 1, 60000);
    QVERIFY2(finished.front().at(0).toBool(), qPrintable(finished.front().at(1).toString()));
    QVERIFY(asked_on_first_look);
    bool waited = false;
    for (const QList<QVariant>& s : status)
      waited = waited || s.front().toString().contains(QStringLiteral("waits for the full photo"));
    QVERIFY(waited);
    const auto back = readImage(out.toStdString());
    QVERIFY2(back, back.status.message.c_str());
    QCOMPARE(back->image.width, kWidth);
    QCOMPARE(back->image.height, kHeight);
    QCOMPARE(back->image.channels, truth_.image.channels);
    double worst = 0.0;
    for (size_t k = 0; k < back->image.data.size(); ++k)
      worst = std::max(worst, std::abs(static_cast<double>(back->image.data[k]) -
                                       truth_.image.data[k]));
    QVERIFY2(worst < 0.01, qPrintable(QString::number(worst)));
  }

  // The job itself refuses a first look rather than render nothing.
  void exportJobRefusesFirstLook() {
    ImageLoader loader(jpeg_);
    loader.setFirstLook(true);
    QSignalSpy loaded(&loader, &ImageLoader::loaded);
    loader.start();
    QTRY_COMPARE_WITH_TIMEOUT(loaded.size(), 1, 60000);
    loader.cancel();
    const PhotoPtr first = loaded.front().front().value<PhotoPtr>();
    QVERIFY(!first->hasFullImage());
    Document doc;
    doc.reset(first);
    ExportJob job(first, doc.artcam(), dir_.filePath("never.png"));
    QSignalSpy done(&job, &ExportJob::done);
    job.start();
    QTRY_COMPARE_WITH_TIMEOUT(done.size(), 1, 10000);
    QVERIFY(!done.front().at(0).toBool());
    QVERIFY(!QFileInfo::exists(dir_.filePath("never.png")));
  }
};

QTEST_MAIN(TestFirstLook)
#include "test_first_look.moc"
