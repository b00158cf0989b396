// SPDX-License-Identifier: Apache-2.0
// `artcam warp - CAM -o - --format EXT`: the photo from standard input, the image to standard
// output. The truth is the file route: the same photo and camera through named files must give
// the same pixels, read back by the engine's reader. Standard output must carry the image's
// bytes and nothing else, and a failure must leave it empty.
#include "core/io/image_io.h"
#include "tests/app/cli_files.h"
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QProcess>

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>

#include <algorithm>

using namespace artcam;
using artcam::test::artcamCli;
using artcam::test::artcamCliPiped;
using artcam::test::fileBytes;
using Piped = artcam::test::CliBytesRun;

namespace {

const QString kResources = QStringLiteral(ARTCAM_RESOURCES_DIR);

bool writeBytes(const QString& path, const QByteArray& bytes) {
  QFile f(path);
  return f.open(QIODevice::WriteOnly) && f.write(bytes) == bytes.size();
}

ImageF readBack(const QString& path) {
  auto loaded = readImage(path.toStdString());
  return loaded ? std::move(loaded->image) : ImageF();
}

// Our lines on stderr: libpng prints its own "libpng error: ..." line, as for a named file.
QStringList errorLines(const QString& err) {
  QStringList lines;
  for (const QString& line : err.split('\n', Qt::SkipEmptyParts))
    if (!line.startsWith("libpng ")) lines << line;
  return lines;
}

}  // namespace

class TestCliStdio : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }
  QString spoolDir() const { return dir_.filePath("tmp"); }

  // Runs the stdin/stdout route with TMPDIR inside the test folder, so its spools can be seen.
  Piped piped(const QStringList& args, const QByteArray& input) const {
    return artcamCliPiped(args, input, {"TMPDIR=" + spoolDir()});
  }

  // The stdin → stdout route and the file route over one photo and camera: same pixels.
  void expectSameAsFiles(const QString& photo, const QString& camera, const QString& extension) {
    const QString file_out = path("file-" + QFileInfo(photo).fileName() + "-" +
                                  QFileInfo(camera).baseName() + "." + extension);
    const auto files = artcamCli({"warp", photo, camera, "-o", file_out, "--quiet"});
    QVERIFY2(files.exit_code == 0, qPrintable(files.err));
    const Piped run = piped({"warp", "-", camera, "-o", "-", "--format", extension, "--quiet"},
                            fileBytes(photo));
    QVERIFY2(run.exit_code == 0, qPrintable(run.err));
    QVERIFY(!run.out.isEmpty());
    // The report goes to stderr, naming the stream.
    QVERIFY2(run.err.contains("wrote <stdout>"), qPrintable(run.err));
    QVERIFY(!run.out.contains("wrote"));
    const QString piped_out = path("piped." + extension);
    QVERIFY(writeBytes(piped_out, run.out));
    const ImageF expected = readBack(file_out);
    const ImageF got = readBack(piped_out);
    QVERIFY(!expected.empty());
    QCOMPARE(got.width, expected.width);
    QCOMPARE(got.height, expected.height);
    QCOMPARE(got.channels, expected.channels);
    QVERIFY(got.data == expected.data);
    // No spool left behind.
    QCOMPARE(QDir(spoolDir()).entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot),
             QStringList());
  }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(QDir().mkpath(spoolDir()));
    QVERIFY(artcam::test::writeNoisePhoto(path("in.png"), 96, 64));
    QVERIFY(artcam::test::writeNoisePhoto(path("in.jpg"), 96, 64));
    // The identity of the image plane as quadratic forms (X = xw, Y = yw, W = ww), photo-sized.
    QVERIFY(writeBytes(path("id.artcam"),
                       R"({"format": "artcam", "version": 1,
                           "blocks": [{"kind": "position", "size": 3}],
                           "frames": {"source": [96, 64], "target": [96, 64]},
                           "stages": [{"tensors": [[[0, 0, 0.5], [0, 0, 0], [0.5, 0, 0]],
                                                   [[0, 0, 0], [0, 0, 0.5], [0, 0.5, 0]],
                                                   [[0, 0, 0], [0, 0, 0], [0, 0, 1]]]}]})"));
    // Inputs read while the request is parsed: a depth map (2 units everywhere) for a camera
    // that reads depth, and a second image for a compositing camera, both of the photo's size.
    ImageF depth(96, 64, 1);
    std::fill(depth.data.begin(), depth.data.end(), 2.0f);
    QVERIFY(writeImage(path("depth.exr").toStdString(), depth).ok);
    QVERIFY(artcam::test::writeNoisePhoto(path("second.png"), 96, 64));
    QCOMPARE(artcamCli({"preset", "aerial-perspective", "--size", "96x64", "-o", path("ap.artcam")})
                 .exit_code,
             0);
    QCOMPARE(
        artcamCli({"preset", "composite", "--size", "96x64", "-o", path("over.artcam")}).exit_code,
        0);
  }

  void pngThroughThePipeEqualsTheFileRoute() {
    expectSameAsFiles(path("in.png"), path("id.artcam"), "png");
    // A camera that moves pixels: the pipe still takes the file's route.
    expectSameAsFiles(path("in.png"), kResources + "/sample.artcam", "png");
  }

  // Standard output holds one PNG from its signature to its IEND chunk: not a byte of text
  // before or after it.
  void stdoutCarriesOnlyTheImage() {
    const Piped run = piped({"warp", "-", path("id.artcam"), "-o", "-", "--format", "png"},
                            fileBytes(path("in.png")));
    QVERIFY2(run.exit_code == 0, qPrintable(run.err));
    QVERIFY(run.out.startsWith(QByteArray("\x89PNG\r\n\x1a\n", 8)));
    QVERIFY(run.out.endsWith(QByteArray("IEND\xae\x42\x60\x82", 8)));
  }

  // --depth and --second are read before the render: what the command says about them goes to
  // stderr with -o -, so standard output is still one PNG and nothing else.
  void depthAndSecondKeepStdoutTheImage() {
    const QStringList runs[] = {
        {"warp", path("in.png"), path("ap.artcam"), "--depth", path("depth.exr")},
        {"warp", "-", path("ap.artcam"), "--depth", path("depth.exr")},
        {"warp", path("in.png"), path("over.artcam"), "--second", path("second.png")},
        {"warp", "-", path("over.artcam"), "--second", path("second.png")},
    };
    for (const QStringList& args : runs) {
      const Piped run =
          piped(args + QStringList{"-o", "-", "--format", "png"}, fileBytes(path("in.png")));
      const QString call = args.join(' ') + ": " + run.err;
      QVERIFY2(run.exit_code == 0, qPrintable(call));
      QVERIFY2(run.out.startsWith(QByteArray("\x89PNG\r\n\x1a\n", 8)),
               qPrintable(call + "\nstdout starts: " + QString::fromLatin1(run.out.left(40))));
      QVERIFY2(run.out.endsWith(QByteArray("IEND\xae\x42\x60\x82", 8)), qPrintable(call));
      QVERIFY(writeBytes(path("depth-second.png"), run.out));
      QCOMPARE(readBack(path("depth-second.png")).width, 96);
      // Said, on stderr: the input read and its size.
      const QString input = args.contains("--depth") ? path("depth.exr") : path("second.png");
      QVERIFY2(run.err.contains(input + ": 96x64"), qPrintable(call));
    }
  }

  // With --json, standard output is one JSON object, and the inputs read are in it: the depth
  // map's size and range (2 everywhere, no holes) and the second image's size.
  void depthAndSecondKeepJsonTheOnlyStdout() {
    const struct {
      QStringList args;
      const char* key;
    } runs[] = {
        {{"warp", path("in.png"), path("ap.artcam"), "--depth", path("depth.exr")}, "depth"},
        {{"warp", path("in.png"), path("over.artcam"), "--second", path("second.png")}, "second"},
    };
    for (const auto& [args, key] : runs) {
      const QString out = path(QStringLiteral("json-%1.png").arg(key));
      const auto run = artcamCli(args + QStringList{"-o", out, "--json", "--quiet"});
      const QString call = args.join(' ') + ": " + run.err;
      QVERIFY2(run.exit_code == 0, qPrintable(call));
      QJsonParseError error;
      const QJsonDocument doc = QJsonDocument::fromJson(run.out.toUtf8(), &error);
      QVERIFY2(error.error == QJsonParseError::NoError && doc.isObject(),
               qPrintable(call + "\nstdout: " + run.out));
      const QJsonObject o = doc.object();
      QCOMPARE(o["output"].toString(), out);
      const QJsonObject input = o[key].toObject();
      QCOMPARE(input["file"].toString(), args.last());
      QCOMPARE(input["width"].toInt(), 96);
      QCOMPARE(input["height"].toInt(), 64);
      if (QString(key) == "depth") {
        QCOMPARE(input["min"].toDouble(), 2.0);
        QCOMPARE(input["max"].toDouble(), 2.0);
        QCOMPARE(input["holes"].toInt(), 0);
      }
    }
  }

  void jpegFromStdin() { expectSameAsFiles(path("in.jpg"), path("id.artcam"), "png"); }

  void exrToStdout() {
    expectSameAsFiles(path("in.png"), path("id.artcam"), "exr");
    const Piped run = piped({"warp", "-", path("id.artcam"), "-o", "-", "--format", "EXR", "-q"},
                            fileBytes(path("in.png")));
    QVERIFY2(run.exit_code == 0, qPrintable(run.err));
    QVERIFY(run.out.startsWith(QByteArray("\x76\x2f\x31\x01", 4)));  // OpenEXR's magic
  }

  // A file output from piped input, and a piped output from a file: each side alone.
  void oneStreamAtATime() {
    const Piped in_only = piped({"warp", "-", path("id.artcam"), "-o", path("from-stdin.png")},
                                fileBytes(path("in.png")));
    QVERIFY2(in_only.exit_code == 0, qPrintable(in_only.err));
    QVERIFY(in_only.out.startsWith("wrote " + path("from-stdin.png").toUtf8()));
    QVERIFY(readBack(path("from-stdin.png")).data == readBack(path("in.png")).data);
    const Piped out_only =
        piped({"warp", path("in.png"), path("id.artcam"), "-o", "-", "--format", "png"}, {});
    QVERIFY2(out_only.exit_code == 0, qPrintable(out_only.err));
    QVERIFY(writeBytes(path("to-stdout.png"), out_only.out));
    QVERIFY(readBack(path("to-stdout.png")).data == readBack(path("in.png")).data);
  }

  void badStdinIsOneLineNamingIt() {
    const Piped run = piped({"warp", "-", path("id.artcam"), "-o", "-", "--format", "png"},
                            QByteArray("this is not an image, just some text\n"));
    QCOMPARE(run.exit_code, 1);
    QVERIFY(run.out.isEmpty());
    QCOMPARE(errorLines(run.err).size(), 1);
    QVERIFY2(run.err.startsWith("artcam warp: <stdin>: cannot read") ||
                 run.err.contains("<stdin>: cannot read"),
             qPrintable(run.err));
    QVERIFY2(!run.err.contains("/proc/"), qPrintable(run.err));

    const Piped empty = piped({"warp", "-", path("id.artcam"), "-o", "-", "--format", "png"}, {});
    QCOMPARE(empty.exit_code, 1);
    QVERIFY(empty.out.isEmpty());
    QCOMPARE(errorLines(empty.err).size(), 1);
    QVERIFY2(empty.err.contains("<stdin>: cannot read: standard input is empty"),
             qPrintable(empty.err));

    // Cut short: the first half of a PNG.
    const QByteArray png = fileBytes(path("in.png"));
    const Piped cut = piped({"warp", "-", path("id.artcam"), "-o", "-", "--format", "png"},
                            png.left(png.size() / 2));
    QCOMPARE(cut.exit_code, 1);
    QVERIFY(cut.out.isEmpty());
    QCOMPARE(errorLines(cut.err).size(), 1);
    QVERIFY2(cut.err.contains("<stdin>"), qPrintable(cut.err));
  }

  // An encode that fails puts nothing on stdout: JPEG stores at most 65500 pixels a side.
  void failedEncodeSendsNothing() {
    const Piped run = piped({"warp", "-", path("id.artcam"), "-o", "-", "--format", "jpg",
                             "--size", "70000x2", "-q"},
                            fileBytes(path("in.png")));
    QCOMPARE(run.exit_code, 1);
    QVERIFY(run.out.isEmpty());
    QCOMPARE(errorLines(run.err).size(), 1);
    QVERIFY2(run.err.contains("<stdout>: cannot write"), qPrintable(run.err));
    QVERIFY2(!run.err.contains(spoolDir()), qPrintable(run.err));
    QCOMPARE(QDir(spoolDir()).entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot),
             QStringList());
  }

  void aReaderClosingThePipeEarlyIsOneLine() {
    // 2400×1600 uncompressed TIFF (11.5 MB, far beyond a pipe's buffer) into `true`, which reads
    // nothing and exits: the write meets a closed pipe. The command must say so on stderr and
    // exit 1, not die of SIGPIPE.
    QProcess shell;
    shell.start(QStringLiteral("/bin/bash"),
                {QStringLiteral("-c"),
                 QStringLiteral("\"$0\" warp \"$1\" \"$2\" --size 2400x1600 -o - --format tif "
                                "| true; exit ${PIPESTATUS[0]}"),
                 QStringLiteral(ARTCAM_CLI_PATH), path("in.png"), path("id.artcam")});
    QVERIFY(shell.waitForFinished(120000));
    const QString err = QString::fromUtf8(shell.readAllStandardError());
    QCOMPARE(shell.exitCode(), 1);
    QVERIFY2(err.contains("<stdout>") && err.contains("closed the pipe"), qPrintable(err));
    QCOMPARE(err.trimmed().count('\n'), 0);
  }

  void usageMistakesExitTwo() {
    const QByteArray png = fileBytes(path("in.png"));
    const QList<QStringList> mistakes = {
        {"warp", "-", path("id.artcam"), "-o", "-"},  // no format to write
        {"warp", "-", path("id.artcam"), "-o", path("u.png"), "--format", "png"},  // two formats
        {"warp", "-", path("id.artcam"), "-o", "-", "--format", "nosuchformat"},
        {"warp", "-", path("id.artcam"), "-o", "-", "--format", "png", "--json"},
    };
    for (const QStringList& args : mistakes) {
      const Piped run = piped(args, png);
      QVERIFY2(run.exit_code == 2, qPrintable(args.join(' ') + ": " + run.err));
      QVERIFY(run.out.isEmpty());
      QVERIFY(run.err.contains("see 'artcam warp --help'"));
    }
    QVERIFY(!QFile::exists(path("u.png")));
  }
};

QTEST_GUILESS_MAIN(TestCliStdio)
#include "test_cli_stdio.moc"
