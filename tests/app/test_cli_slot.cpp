// SPDX-License-Identifier: Apache-2.0
// The CLI keeps to the CPUs its slot gives it: under `taskset -c 0` (an affinity mask of one
// CPU, set by util-linux, not by us) warp's --stats reports one thread, and an explicit
// --threads still wins. The cgroup files' parsing is tested in
// tests/core/util/test_slot_limits.cpp.
#include "tests/app/cli_files.h"
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QProcess>
#include <QRegularExpression>
#include <QStandardPaths>
#include <QTemporaryDir>

using artcam::test::artcamCli;

class TestCliSlot : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

  // warp --stats under `taskset -c CPUS`: the threads it reports (-1: none reported).
  int reportedThreads(const QString& cpus, const QStringList& extra = {}) {
    QProcess p;
    p.start("taskset",
            QStringList{"-c", cpus, ARTCAM_CLI_PATH, "warp", path("in.png"), path("c.artcam"), "-o",
                        path("o.png"), "--overwrite", "--stats", "--quiet"} +
                extra);
    if (!p.waitForFinished(60000) || p.exitCode() != 0) return -1;
    const auto match = QRegularExpression("threads=([0-9]+)").match(p.readAllStandardError());
    return match.hasMatch() ? match.captured(1).toInt() : -1;
  }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(artcam::test::writeNoisePhoto(path("in.png"), 64, 48));
    const auto preset = artcamCli({"preset", "barrel", "--size", "64x48", "-o", path("c.artcam")});
    QVERIFY2(preset.exit_code == 0, qPrintable(preset.err));
  }

  void oneCpuOfAffinityIsOneThread() {
    if (QStandardPaths::findExecutable("taskset").isEmpty()) QFAIL("taskset is not installed (packaging/install-deps.sh installs it; a missing peer is a failed check, not a pass)");
    QCOMPARE(reportedThreads("0"), 1);
    QCOMPARE(reportedThreads("0", {"--threads", "3"}), 3);  // asked for: kept
  }
};

QTEST_GUILESS_MAIN(TestCliSlot)
#include "test_cli_slot.moc"
