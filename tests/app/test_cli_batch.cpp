// SPDX-License-Identifier: Apache-2.0
// artcam batch, run as a process: every input warped as artcam warp warps it, a failed file
// does not stop the rest, inputs are never overwritten by default, frame patterns, and
// Ctrl-C (SIGINT) leaves only finished outputs and exit status 130.
#include "core/io/image_io.h"
#include "tests/app/cli_files.h"
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>

#include <signal.h>

#include <memory>
#include <vector>

using namespace artcam;
using namespace artcam::test;
using Run = artcam::test::CliRun;

namespace {

const QString kCamera = QStringLiteral(ARTCAM_RESOURCES_DIR "/sample.artcam");  // 600x400 frames

bool samePixels(const QString& a, const QString& b) {
  const auto x = readImage(a.toStdString());
  const auto y = readImage(b.toStdString());
  return x && y && x->image.width == y->image.width && x->image.height == y->image.height &&
         x->image.channels == y->image.channels && x->image.data == y->image.data;
}

}  // namespace

class TestCliBatch : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(QDir().mkpath(path("in")));
    QVERIFY(writeNoisePhoto(path("in/a.png"), 300, 200));
    QVERIFY(writeNoisePhoto(path("in/b.png"), 450, 300));
    QVERIFY(writeNoisePhoto(path("in/c.jpg"), 150, 100));
  }

  // The batch runs the same stages as artcam warp: outputs equal warp's, sized from each input
  // (the camera's 600x400 target frame scaled by input width / 600), named IN + suffix + format.
  void everyInputWarpedAsWarpDoes() {
    const Run r = artcamCli({"batch", kCamera, path("in/a.png"), path("in/b.png"), path("in/c.jpg"),
                             "-o", path("out1"), "--suffix", "_w", "--format", "tif"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("3 of 3 written"), qPrintable(r.out));
    QCOMPARE(visibleFiles(path("out1")), QStringList({"a_w.tif", "b_w.tif", "c_w.tif"}));
    QVERIFY(hiddenFiles(path("out1")).isEmpty());
    const struct {
      const char* in;
      const char* out;
      int width, height;
    } expected[] = {{"a.png", "a_w.tif", 300, 200},
                    {"b.png", "b_w.tif", 450, 300},
                    {"c.jpg", "c_w.tif", 150, 100}};
    for (const auto& e : expected) {
      const QString single = path(QStringLiteral("single-%1.tif").arg(e.in));
      const Run w = artcamCli({"warp", path(QStringLiteral("in/") + e.in), kCamera, "-o", single});
      QVERIFY2(w.exit_code == 0, qPrintable(w.err));
      const auto out = readImage(path(QStringLiteral("out1/") + e.out).toStdString());
      QVERIFY(out);
      QCOMPARE(out->image.width, e.width);
      QCOMPARE(out->image.height, e.height);
      QVERIFY2(samePixels(single, path(QStringLiteral("out1/") + e.out)), e.out);
    }
  }

  void aFailedFileDoesNotStopTheRest() {
    QFile bad(path("in/broken.png"));
    QVERIFY(bad.open(QIODevice::WriteOnly));
    bad.write(fileBytes(path("in/a.png")).left(200));  // a truncated PNG
    bad.close();
    const Run r = artcamCli({"batch", kCamera, path("in/broken.png"), path("in/missing.png"),
                             path("in/a.png"), "-o", path("out2"), "--quiet"});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains("broken.png") && r.err.contains("missing.png"), qPrintable(r.err));
    QVERIFY2(r.out.contains("1 of 3 written") && r.out.contains("2 failed"), qPrintable(r.out));
    QCOMPARE(visibleFiles(path("out2")), QStringList({"a.png"}));
    QVERIFY(hiddenFiles(path("out2")).isEmpty());
  }

  // Outputs that would replace an input are refused before anything is written, however the
  // path is spelled (equivalent files, not equal strings), even with --overwrite.
  void inputsAreNeverOverwrittenByDefault() {
    QVERIFY(QDir().mkpath(path("own")));
    QVERIFY(QFile::copy(path("in/a.png"), path("own/a.png")));
    const QByteArray before = fileBytes(path("own/a.png"));
    const QString detour = path("own/../own/.");
    const Run r = artcamCli({"batch", kCamera, path("own/a.png"), "-o", detour});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains("refusing to overwrite the input"), qPrintable(r.err));
    QCOMPARE(fileBytes(path("own/a.png")), before);

    const Run w = artcamCli({"warp", path("own/a.png"), kCamera, "-o", detour + "/a.png"});
    QCOMPARE(w.exit_code, 1);
    QVERIFY2(w.err.contains("refusing to overwrite the input"), qPrintable(w.err));
    // A hard link is the same file under another name.
    QVERIFY(::link(path("own/a.png").toLocal8Bit().constData(),
                   path("own/link.png").toLocal8Bit().constData()) == 0);
    const Run l = artcamCli({"warp", path("own/a.png"), kCamera, "-o", path("own/link.png")});
    QCOMPARE(l.exit_code, 1);
    QCOMPARE(fileBytes(path("own/a.png")), before);

    for (const char* flag : {"--overwrite", "--force"}) {
      const Run o = artcamCli({"batch", kCamera, path("own/a.png"), "-o", path("own"), flag});
      QCOMPARE(o.exit_code, 1);
      QVERIFY2(o.err.contains("refusing to overwrite the input"), qPrintable(o.err));
      QCOMPARE(fileBytes(path("own/a.png")), before);
    }
  }

  void twoInputsForOneOutputAreRefused() {
    QVERIFY(QFile::copy(path("in/c.jpg"), path("in/a.jpg")));
    const Run r = artcamCli({"batch", kCamera, path("in/a.png"), path("in/a.jpg"), "-o",
                             path("out3"), "--format", "tif"});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains("a.png") && r.err.contains("a.jpg"), qPrintable(r.err));
    QVERIFY(visibleFiles(path("out3")).isEmpty());
  }

  // f_%03d.png from frame 1 (there is no frame 0) up to the first gap.
  void framePatternIsASequence() {
    QVERIFY(QDir().mkpath(path("seq")));
    for (int k : {1, 2, 3, 5})
      QVERIFY(
          writeNoisePhoto(path(QStringLiteral("seq/f_%1.png").arg(k, 3, 10, QChar('0'))), 60, 40));
    const Run r = artcamCli({"batch", kCamera, path("seq/f_%03d.png"), "-o", path("seq-out")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QCOMPARE(visibleFiles(path("seq-out")), QStringList({"f_001.png", "f_002.png", "f_003.png"}));
    const Run from = artcamCli(
        {"batch", kCamera, path("seq/f_%03d.png"), "-o", path("seq-out5"), "--first", "5"});
    QVERIFY2(from.exit_code == 0, qPrintable(from.err));
    QCOMPARE(visibleFiles(path("seq-out5")), QStringList({"f_005.png"}));
    // The pattern is parsed, never handed to printf: anything but one %d / %0Nd is refused.
    for (const char* bad : {"seq/f_%s.png", "seq/f_%d_%d.png", "seq/f_%n.png"}) {
      const Run refused = artcamCli({"batch", kCamera, path(bad), "-o", path("seq-bad")});
      QCOMPARE(refused.exit_code, 2);
      QVERIFY2(refused.err.contains("frame pattern"), qPrintable(refused.err));
    }
    QVERIFY(visibleFiles(path("seq-bad")).isEmpty());
  }

  // A farm's split of one shot: four --chunk K/4 tasks, run at once, write exactly the whole
  // run's files, byte for byte, each frame by one task; a retried task is harmless
  // (--skip-existing, --overwrite); --frames picks frames by number, with steps, and a listed
  // frame that is missing fails as that frame.
  void framesAndChunksForAFarm() {
    QVERIFY(QDir().mkpath(path("shot")));
    for (int k = 1001; k <= 1010; ++k)
      QVERIFY(writeNoisePhoto(path(QStringLiteral("shot/p.%1.png").arg(k)), 60 + k % 3, 40));
    const QString pattern = path("shot/p.%04d.png");
    auto json = [](const Run& r) { return QJsonDocument::fromJson(r.out.toUtf8()).object(); };
    auto numbers = [](const QJsonValue& v) {
      QList<int> n;
      for (const QJsonValue& x : v.toArray()) n.append(x.toInt());
      return n;
    };
    QList<int> all;
    for (int k = 1001; k <= 1010; ++k) all.append(k);

    const Run whole = artcamCli(
        {"batch", kCamera, pattern, "-o", path("whole"), "--frames", "1001-1010", "--json"});
    QVERIFY2(whole.exit_code == 0, qPrintable(whole.err));
    QCOMPARE(numbers(json(whole)["frames"].toObject()["done"]), all);
    QCOMPARE(json(whole)["files"].toArray()[0].toObject()["frame"].toInt(), 1001);

    std::vector<std::unique_ptr<QProcess>> tasks;
    for (int k = 1; k <= 4; ++k) {
      auto p = std::make_unique<QProcess>();
      p->start(QStringLiteral(ARTCAM_CLI_PATH),
               {"batch", kCamera, pattern, "-o", path("farm"), "--frames", "1001-1010", "--chunk",
                QStringLiteral("%1/4").arg(k), "--json", "--threads", "1"});
      tasks.push_back(std::move(p));
    }
    QList<int> done;
    for (auto& p : tasks) {
      QVERIFY(p->waitForFinished(120000));
      QCOMPARE(p->exitCode(), 0);
      const QJsonObject report = QJsonDocument::fromJson(p->readAllStandardOutput()).object();
      const QList<int> mine = numbers(report["frames"].toObject()["done"]);
      QVERIFY2(mine.size() == 2 || mine.size() == 3, qPrintable(QString::number(mine.size())));
      done += mine;
    }
    QCOMPARE(done, all);  // in order, each frame once
    QCOMPARE(visibleFiles(path("farm")), visibleFiles(path("whole")));
    QCOMPARE(visibleFiles(path("farm")).size(), 10);
    for (const QString& name : visibleFiles(path("whole")))
      QVERIFY2(fileBytes(path("farm/") + name) == fileBytes(path("whole/") + name),
               qPrintable(name));
    QVERIFY(hiddenFiles(path("farm")).isEmpty());

    // The same task again: refused without a choice, skipped or replaced with one.
    const QStringList task2 = {"batch",    kCamera,     pattern,   "-o",  path("farm"),
                               "--frames", "1001-1010", "--chunk", "2/4", "--json"};
    QCOMPARE(artcamCli(task2).exit_code, 1);
    const Run again = artcamCli(task2 + QStringList{"--skip-existing"});
    QVERIFY2(again.exit_code == 0, qPrintable(again.err));
    QCOMPARE(json(again)["totals"].toObject()["written"].toInt(), 0);
    QCOMPARE(numbers(json(again)["frames"].toObject()["skipped"]), QList<int>({1003, 1004, 1005}));
    QCOMPARE(json(again)["files"].toArray()[0].toObject()["status"].toString(), QString("skipped"));
    const Run text = artcamCli({"batch", kCamera, pattern, "-o", path("farm"), "--frames",
                                "1001-1010", "--chunk", "2/4", "--skip-existing"});
    QVERIFY2(text.out.contains("0 of 3 written") && text.out.contains("3 skipped"),
             qPrintable(text.out));
    const QByteArray before = fileBytes(path("farm/p.1004.png"));
    QVERIFY(QFile::remove(path("farm/p.1004.png")));
    const Run redo = artcamCli(task2 + QStringList{"--skip-existing"});
    QCOMPARE(numbers(json(redo)["frames"].toObject()["done"]), QList<int>({1004}));
    QCOMPARE(fileBytes(path("farm/p.1004.png")), before);
    QCOMPARE(artcamCli(task2 + QStringList{"--overwrite"}).exit_code, 0);
    QCOMPARE(fileBytes(path("farm/p.1004.png")), before);

    // Steps and lists; a listed frame with no file fails alone, as that frame.
    const Run stepped = artcamCli(
        {"batch", kCamera, pattern, "-o", path("step"), "--frames", "1001-1010x3", "--json"});
    QVERIFY2(stepped.exit_code == 0, qPrintable(stepped.err));
    QCOMPARE(numbers(json(stepped)["frames"].toObject()["done"]),
             QList<int>({1001, 1004, 1007, 1010}));
    const Run gaps = artcamCli(
        {"batch", kCamera, pattern, "-o", path("gaps"), "--frames", "1009-1012,1002", "--json"});
    QCOMPARE(gaps.exit_code, 1);
    QCOMPARE(numbers(json(gaps)["frames"].toObject()["done"]), QList<int>({1009, 1010, 1002}));
    QCOMPARE(numbers(json(gaps)["frames"].toObject()["failed"]), QList<int>({1011, 1012}));
    QVERIFY2(gaps.err.contains("p.1011.png"), qPrintable(gaps.err));

    // More slices than frames: the empty ones succeed with nothing to do.
    const Run empty = artcamCli(
        {"batch", kCamera, pattern, "-o", path("thin"), "--frames", "1001-1003", "--chunk", "1/5"});
    QVERIFY2(empty.exit_code == 0 && empty.out.contains("0 of 0 written"), qPrintable(empty.out));

    // Refusals name the option, in one line, before any work.
    const QList<QStringList> refused = {{"--frames", "1010-1001"},
                                        {"--frames", "abc"},
                                        {"--frames", "1001x2"},
                                        {"--frames", "1001-1010x0"},
                                        {"--frames", "1001,"},
                                        {"--frames", "-3-4"},
                                        {"--frames", "10x2-20"},
                                        {"--frames", "0-2000000000"},
                                        {"--chunk", "0/4"},
                                        {"--chunk", "5/4"},
                                        {"--chunk", "2"},
                                        {"--chunk", "a/b"},
                                        {"--frames", "1-2", "--first", "1"},
                                        {"--skip-existing", "--overwrite"}};
    for (const QStringList& extra : refused) {
      const Run r =
          artcamCli(QStringList{"batch", kCamera, pattern, "-o", path("refused")} + extra);
      QVERIFY2(r.exit_code == 2, qPrintable(extra.join(' ') + ": " + r.err));
      QVERIFY2(r.err.contains(extra[0]) || r.err.contains("--first"),
               qPrintable(extra.join(' ') + ": " + r.err));
    }
    const Run plain =
        artcamCli({"batch", kCamera, path("in/a.png"), "-o", path("refused"), "--frames", "1-2"});
    QCOMPARE(plain.exit_code, 2);
    QVERIFY2(plain.err.contains("not one"), qPrintable(plain.err));
    QVERIFY(visibleFiles(path("refused")).isEmpty());
  }

  // SIGINT once the first output is finished: exit 130, the finished outputs complete, no
  // temporary and no partial output left.
  void interruptKeepsFinishedOutputsOnly() {
    QVERIFY(QDir().mkpath(path("many")));
    QStringList args{"batch", kCamera};
    constexpr int kCount = 24;
    for (int k = 0; k < kCount; ++k) {
      const QString in = path(QStringLiteral("many/p%1.png").arg(k, 2, 10, QChar('0')));
      QVERIFY(QFile::copy(path("in/a.png"), in));
      args << in;
    }
    const QString out = path("many-out");
    // Large outputs (PNG encoding takes a while) from small inputs.
    args << "-o" << out << "--size"
         << "2400x1600";
    QProcess p;
    p.start(QStringLiteral(ARTCAM_CLI_PATH), args);
    QVERIFY(p.waitForStarted());
    QVERIFY(waitUntil(
        [&] { return !visibleFiles(out).isEmpty() || p.state() == QProcess::NotRunning; }));
    QCOMPARE(p.state(), QProcess::Running);
    QCOMPARE(::kill(static_cast<pid_t>(p.processId()), SIGINT), 0);
    QVERIFY(p.waitForFinished(120000));
    QCOMPARE(p.exitStatus(), QProcess::NormalExit);
    QCOMPARE(p.exitCode(), 130);
    const QString summary = QString::fromUtf8(p.readAllStandardOutput());
    QVERIFY2(summary.contains("interrupted"), qPrintable(summary));
    QVERIFY2(hiddenFiles(out).isEmpty(), qPrintable(hiddenFiles(out).join(", ")));
    const QStringList done = visibleFiles(out);
    QVERIFY(!done.isEmpty());
    QVERIFY(done.size() < kCount);
    for (const QString& f : done) {
      const auto image = readImage(path("many-out/" + f).toStdString());
      QVERIFY2(image, qPrintable(f));
      QCOMPARE(image->image.width, 2400);
      QCOMPARE(image->image.height, 1600);
    }
  }

  // A single warp interrupted while it writes: no temporary, no output.
  void interruptedWarpLeavesNoFile() {
    QVERIFY(QDir().mkpath(path("one")));
    QProcess p;
    p.start(QStringLiteral(ARTCAM_CLI_PATH),
            {"warp", path("in/a.png"), kCamera, "-o", path("one/big.png"), "--size", "6000x4000"});
    QVERIFY(p.waitForStarted());
    QVERIFY(waitUntil(
        [&] { return !hiddenFiles(path("one")).isEmpty() || p.state() == QProcess::NotRunning; }));
    QCOMPARE(p.state(), QProcess::Running);
    QCOMPARE(::kill(static_cast<pid_t>(p.processId()), SIGTERM), 0);
    QVERIFY(p.waitForFinished(120000));
    QCOMPARE(p.exitCode(), 128 + SIGTERM);
    QVERIFY2(QDir(path("one")).entryList(QDir::Files | QDir::Hidden).isEmpty(),
             qPrintable(QDir(path("one")).entryList(QDir::Files | QDir::Hidden).join(", ")));
  }

  // Commands that do not poll for Ctrl-C (here render) are stopped by the handler itself,
  // which removes the temporary of the save in flight: exit 130, an empty folder.
  void anyCommandInterruptedLeavesNoTemporary() {
    QVERIFY(QDir().mkpath(path("render/out")));
    const QString camera = path("render/twist.artcam");
    QCOMPARE(artcamCli({"preset", "twist-3d", "-o", camera}).exit_code, 0);
    QProcess p;
    p.start(QStringLiteral(ARTCAM_CLI_PATH),
            {"render", QStringLiteral(ARTCAM_RESOURCES_DIR "/cube.ply"), camera, "-o",
             path("render/out/big.png"), "--size", "12000x12000"});
    QVERIFY(p.waitForStarted());
    QVERIFY(waitUntil([&] {
      return !hiddenFiles(path("render/out")).isEmpty() || p.state() == QProcess::NotRunning;
    }));
    QCOMPARE(p.state(), QProcess::Running);
    QCOMPARE(::kill(static_cast<pid_t>(p.processId()), SIGINT), 0);
    QVERIFY(p.waitForFinished(120000));
    QCOMPARE(p.exitCode(), 130);
    QVERIFY2(QDir(path("render/out")).entryList(QDir::Files | QDir::Hidden).isEmpty(),
             qPrintable(QDir(path("render/out")).entryList(QDir::Files | QDir::Hidden).join(", ")));
  }
};

QTEST_GUILESS_MAIN(TestCliBatch)
#include "test_cli_batch.moc"
