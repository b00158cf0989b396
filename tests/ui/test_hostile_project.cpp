// SPDX-License-Identifier: Apache-2.0
// Replays the project-file fuzz corpus (fuzz/corpus/project/: seeds and nasty inputs, see
// fuzz/fuzz_project.cpp) through readProject: every file parses or is refused with one line
// naming the file and the cause; the nasty ones for the reason they were kept. The depth masks
// of the nasty files claim up to 2^31 pixels: they must be refused before allocation.
#include "ui/project_file.h"

#include <QDir>
#include <QFileInfo>
#include <QtTest/QtTest>

using namespace artcam;

namespace {

QString corpusDir() { return QStringLiteral(ARTCAM_SOURCE_DIR "/fuzz/corpus/project"); }

QStringList corpusFiles() { return QDir(corpusDir()).entryList(QDir::Files, QDir::Name); }

}  // namespace

class TestHostileProject : public QObject {
  Q_OBJECT

 private slots:
  void corpus_data() {
    QTest::addColumn<QString>("file");
    const QStringList files = corpusFiles();
    QVERIFY2(files.size() >= 3, "fuzz/corpus/project has fewer than 3 inputs");
    for (const QString& f : files) QTest::newRow(f.toUtf8().constData()) << f;
  }

  void corpus() {
    QFETCH(QString, file);
    const Result<ui::Project> read = ui::readProject(corpusDir() + "/" + file);
    if (file.startsWith("seed-")) {
      QVERIFY2(read.ok(), read.status.message.c_str());
      return;
    }
    if (read.ok()) return;
    const std::string& m = read.status.message;
    QVERIFY2(m.rfind(file.toStdString() + ": ", 0) == 0, m.c_str());
    QVERIFY2(m.size() > static_cast<size_t>(file.size()) + 4, m.c_str());
    QVERIFY2(m.find('\n') == std::string::npos, m.c_str());
  }

  void nastyRefusedForTheirReason_data() {
    QTest::addColumn<QString>("file");
    QTest::addColumn<QString>("cause");
    QTest::newRow("giant mask")
        << "nasty-giant-mask.artcamproj"
        << "/depth/layers/0/size: 46340x46340 is larger than the 2^30-pixel limit";
    // The whole-document budget refuses this before its mask is decoded.
    QTest::newRow("lying mask") << "nasty-lying-mask.artcamproj"
                                << "/depth/layers: 1 depth mask";
    // Twelve 32768^2 masks in 2 KB of JSON: the document budget, before any is decoded.
    QTest::newRow("mask bomb") << "nasty-mask-bomb.artcamproj"
                               << "/depth/layers: 12 depth masks";
    QTest::newRow("effects over the limit")
        << "nasty-effects-over-limit.artcamproj"
        << "/effects: 300 effects, more than the 256 a stack may hold";
    QTest::newRow("match beyond any pixel")
        << "nasty-huge-match.artcamproj"
        << "/pairs/0/source/0: 1e+300 is beyond any pixel coordinate";
    QTest::newRow("preview mode") << "nasty-preview-mode.artcamproj"
                                  << "/view/preview_mode: expected 0 to 3";
    // Found by fuzz_project: a raw newline inside the model name split the message in two.
    // Raw control characters are not JSON: the reader refuses them where they are.
    QTest::newRow("newline in model") << "found-model-newline.artcamproj"
                                      << "line 1, column 73: syntax error while parsing value - "
                                         "invalid string: control character U+0000";
    QTest::newRow("deep nesting") << "nasty-deep-nesting.artcamproj"
                                  << ": nested deeper than 68 levels";
    QTest::newRow("deep camera") << "nasty-deep-camera.artcamproj"
                                 << "line 1, column 508: nested deeper than 68 levels";
  }

  void nastyRefusedForTheirReason() {
    QFETCH(QString, file);
    QFETCH(QString, cause);
    const Result<ui::Project> read = ui::readProject(corpusDir() + "/" + file);
    QVERIFY2(!read.ok(), file.toUtf8().constData());
    QVERIFY2(read.status.message.find(cause.toStdString()) != std::string::npos,
             read.status.message.c_str());
  }
};

QTEST_GUILESS_MAIN(TestHostileProject)
#include "test_hostile_project.moc"
