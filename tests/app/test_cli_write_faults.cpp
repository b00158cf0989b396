// SPDX-License-Identifier: Apache-2.0
// A failing machine under the writers: a full disk (a file-size limit, RLIMIT_FSIZE, which any
// user may lower and which gives EFBIG exactly as a full disk gives ENOSPC), a full and a
// closed standard output, two runs racing for one output name, metadata no JPEG segment holds
// or no parser reads. Every save either writes all it says or fails with one line naming the
// file and the cause, leaving the previous file byte for byte and no temporary behind.
#include "core/io/image_io.h"
#include "tests/app/cli_files.h"
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QDir>
#include <QFile>
#include <QProcess>
#include <QTemporaryDir>

#include <cstdint>

using namespace artcam;
using artcam::test::artcamCli;
using artcam::test::CliRun;
using artcam::test::fileBytes;
using artcam::test::hiddenFiles;
using artcam::test::writeNoisePhoto;

namespace {

// Runs artcam through /bin/sh with `prelude` before it (a ulimit, a redirection), the
// arguments passed as "$@" so nothing is re-quoted.
CliRun artcamInShell(const QString& prelude, const QStringList& args, const QString& after = {}) {
  QProcess p;
  p.start("/bin/sh", QStringList{"-c", prelude + "; exec \"$0\" \"$@\" " + after,
                                 QStringLiteral(ARTCAM_CLI_PATH)} +
                         args);
  p.waitForFinished(300000);
  return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1,
          QString::fromUtf8(p.readAllStandardOutput()),
          QString::fromUtf8(p.readAllStandardError())};
}

// The prelude of a run whose files may grow to `kib` KiB: SIGXFSZ ignored (an ignored signal
// stays ignored across exec), so a write past the limit fails with EFBIG instead of killing.
QString fileSizeLimit(int kib) { return QString("trap '' XFSZ; ulimit -f %1").arg(kib); }

std::uint32_t crc32(const QByteArray& bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (const char byte : bytes) {
    crc ^= static_cast<unsigned char>(byte);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

QByteArray bigEndian32(std::uint32_t v) {
  QByteArray b(4, '\0');
  for (int k = 0; k < 4; ++k) b[k] = static_cast<char>((v >> (24 - 8 * k)) & 0xFF);
  return b;
}

// `png` with one more chunk right after IHDR (where every reader sees it, before the pixels).
QByteArray withChunk(const QByteArray& png, const QByteArray& type, const QByteArray& data) {
  const QByteArray body = type + data;
  const QByteArray chunk =
      bigEndian32(static_cast<std::uint32_t>(data.size())) + body + bigEndian32(crc32(body));
  constexpr int kAfterIhdr = 8 + 25;  // signature, then IHDR's length, type, 13 bytes and CRC
  return png.left(kAfterIhdr) + chunk + png.mid(kAfterIhdr);
}

QByteArray xmpPacket(const QByteArray& body) {
  return "<?xpacket begin=\"\" id=\"W5M0MpCehiHzreSzNTczkc9d\"?><x:xmpmeta "
         "xmlns:x=\"adobe:ns:meta/\">"
         "<rdf:RDF xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\"><rdf:Description "
         "rdf:about=\"\" xmlns:dc=\"http://purl.org/dc/elements/1.1/\">" +
         body + "</rdf:Description></rdf:RDF></x:xmpmeta><?xpacket end=\"w\"?>";
}

bool writeBytes(const QString& path, const QByteArray& bytes) {
  QFile f(path);
  return f.open(QIODevice::WriteOnly) && f.write(bytes) == bytes.size();
}

QStringList ourLines(const QString& err) {
  QStringList lines;
  for (const QString& line : err.split('\n', Qt::SkipEmptyParts))
    if (!line.startsWith("libpng ")) lines << line;
  return lines;
}

}  // namespace

class TestCliWriteFaults : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

  // The photo's metadata variants: PNG text chunks the readers carry to the output.
  QString photoWith(const QString& name, const QByteArray& type, const QByteArray& data) {
    const QString out = path(name);
    if (!writeBytes(out, withChunk(fileBytes(path("photo.png")), type, data))) return {};
    return out;
  }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(writeNoisePhoto(path("photo.png"), 400, 300));
    QVERIFY(writeNoisePhoto(path("big.png"), 1500, 1000));
    for (const auto& [name, size] :
         {std::pair{"lens.artcam", "400x300"}, {"big.artcam", "1500x1000"}}) {
      const CliRun preset = artcamCli({"preset", "barrel", "--size", size, "-o", path(name)});
      QVERIFY2(preset.exit_code == 0, qPrintable(preset.err));
    }
    // A JPEG input takes the libjpeg path (jpeg_file.h), a PNG input to JPEG OpenImageIO's.
    const CliRun jpeg =
        artcamCli({"warp", path("big.png"), path("big.artcam"), "-o", path("big.jpg")});
    QVERIFY2(jpeg.exit_code == 0, qPrintable(jpeg.err));
    // The limit is set in the shell. Lowering a soft limit is always allowed (POSIX
    // setrlimit), so a refusal means the harness is broken: a failed check, not a skip.
    const CliRun probe = artcamInShell(fileSizeLimit(64), {"--version"});
    QVERIFY2(probe.exit_code == 0,
             qPrintable("cannot lower the file-size limit (ulimit -f): " + probe.err));
  }

  // A full disk in the middle of the pixels: the save fails naming the file and errno's text,
  // the previous output stays as it was, no temporary is left.
  void fullDiskKeepsThePreviousFile_data() {
    QTest::addColumn<QString>("input");
    QTest::addColumn<QString>("extension");
    QTest::newRow("png") << "big.png"
                         << "png";
    QTest::newRow("jpeg from jpeg (libjpeg path)") << "big.jpg"
                                                   << "jpg";
    QTest::newRow("jpeg from png (image library)") << "big.png"
                                                   << "jpg";
    QTest::newRow("openexr") << "big.png"
                             << "exr";
    QTest::newRow("tiff") << "big.png"
                          << "tif";
    QTest::newRow("gif") << "big.png"
                         << "gif";
    QTest::newRow("sgi (no proxy: read back)") << "big.png"
                                               << "sgi";
  }
  void fullDiskKeepsThePreviousFile() {
    QFETCH(QString, input);
    QFETCH(QString, extension);
    const QString folder = path("full-" + extension + "-" + QFileInfo(input).suffix());
    QVERIFY(QDir().mkpath(folder));
    const QString out = folder + "/out." + extension;
    const CliRun first = artcamCli({"warp", path(input), path("big.artcam"), "-o", out});
    QVERIFY2(first.exit_code == 0, qPrintable(first.err));
    const QByteArray previous = fileBytes(out);
    QVERIFY(previous.size() > 16 * 1024);

    const CliRun full = artcamInShell(
        fileSizeLimit(8), {"warp", path(input), path("big.artcam"), "-o", out, "--overwrite"});
    QCOMPARE(full.exit_code, 1);
    const QStringList lines = ourLines(full.err);
    QVERIFY2(lines.size() == 1, qPrintable(full.err));
    QVERIFY2(lines[0].contains(out + ": cannot write"), qPrintable(full.err));
    // errno's text, where the writer's own words do not carry it (libtiff names the scanline).
    if (extension != "tif")
      QVERIFY2(lines[0].contains("File too large") || lines[0].contains("does not read back"),
               qPrintable(full.err));
    QVERIFY(!full.err.contains(".tmp-"));
    QVERIFY(fileBytes(out) == previous);
    QVERIFY2(hiddenFiles(folder).isEmpty(), qPrintable(hiddenFiles(folder).join(", ")));
  }

  // batch on a full disk: every file failed, none counted as written, none left cut.
  void fullDiskBatchWritesNothingCut() {
    const QString folder = path("batch-full");
    const CliRun run = artcamInShell(
        fileSizeLimit(8),
        {"batch", path("big.artcam"), path("big.png"), path("big.jpg"), "-o", folder, "--quiet"});
    QCOMPARE(run.exit_code, 1);
    QVERIFY2(run.err.contains("File too large"), qPrintable(run.err));
    QVERIFY2(artcam::test::visibleFiles(folder).isEmpty(),
             qPrintable(artcam::test::visibleFiles(folder).join(", ")));
    QVERIFY(hiddenFiles(folder).isEmpty());
  }

  // What a command prints on standard output must arrive, else it fails.
  void fullStandardOutputFails_data() {
    QTest::addColumn<QStringList>("args");
    QTest::newRow("info") << QStringList{"info", "LENS"};
    QTest::newRow("info --json") << QStringList{"info", "LENS", "--json"};
    QTest::newRow("map") << QStringList{"map", "LENS", "POINTS"};
    QTest::newRow("lens search") << QStringList{"lens", "search", "nikon"};
    QTest::newRow("--help") << QStringList{"--help"};
  }
  void fullStandardOutputFails() {
    QFETCH(QStringList, args);
    QVERIFY(writeBytes(path("points.csv"), "x,y\n10,10\n200,150\n"));
    args.replaceInStrings("LENS", path("lens.artcam"))
        .replaceInStrings("POINTS", path("points.csv"));
    QProcess p;
    p.setStandardOutputFile("/dev/full");
    p.start(QStringLiteral(ARTCAM_CLI_PATH), args);
    QVERIFY(p.waitForFinished(60000));
    const QString err = QString::fromUtf8(p.readAllStandardError());
    QCOMPARE(p.exitCode(), 1);
    QVERIFY2(err.contains("<stdout>: cannot write: No space left on device"), qPrintable(err));

    const CliRun closed = artcamInShell(":", args, ">&-");
    QCOMPARE(closed.exit_code, 1);
    QVERIFY2(closed.err.contains("<stdout>: cannot write: standard output is closed"),
             qPrintable(closed.err));
  }

  // `-o -` with standard output closed: refused before standard input is read, so the stdin
  // spool (which would have become descriptor 1) never receives the image.
  void closedStandardOutputRefusesImageStream() {
    const CliRun run =
        artcamInShell(":", {"warp", "-", path("lens.artcam"), "-o", "-", "--format", "png"},
                      ">&- <" + path("photo.png"));
    QCOMPARE(run.exit_code, 1);
    QVERIFY2(run.err.contains("<stdout>: cannot write: standard output is closed"),
             qPrintable(run.err));
    QVERIFY(!run.err.contains("wrote"));
  }

  // Runs racing for one name without --overwrite: exactly one writes it, the others fail
  // naming it, and the file is the winner's whole.
  void concurrentWritersOneWins() {
    const QString out = path("race.png");
    constexpr int kRuns = 3;
    QList<QProcess*> runs;
    for (int k = 0; k < kRuns; ++k) {
      auto* p = new QProcess(this);
      p->start(QStringLiteral(ARTCAM_CLI_PATH),
               {"warp", path("big.png"), path("big.artcam"), "-o", out, "--quiet"});
      runs << p;
    }
    int written = 0, refused = 0;
    for (QProcess* p : runs) {
      QVERIFY(p->waitForFinished(300000));
      const QString err = QString::fromUtf8(p->readAllStandardError());
      if (p->exitCode() == 0) {
        ++written;
      } else {
        QCOMPARE(p->exitCode(), 1);
        QVERIFY2(err.contains(out) && err.contains("--overwrite"), qPrintable(err));
        ++refused;
      }
      delete p;
    }
    QCOMPARE(written, 1);
    QCOMPARE(refused, kRuns - 1);
    const auto back = readImage(out.toStdString());
    QVERIFY2(back.ok(), back.status.message.c_str());
    QCOMPARE(back->image.width, 1500);
    QVERIFY(hiddenFiles(path("")).isEmpty());
  }

  // Every output's folder is checked before anything is written.
  void missingCameraFolderWritesNothing() {
    const QString project = path("p.artcamproj");
    QVERIFY(writeBytes(project, QByteArray(R"({"format": "artcam-studio-project", "version": 2,
        "photo": "photo.png", "model": "auto", "pairs": [], "camera": )") +
                                    fileBytes(path("lens.artcam")) + "}"));
    const QString out = path("exported.png");
    const CliRun run =
        artcamCli({"export", project, "-o", out, "--camera-out", path("missing/x.artcam")});
    QCOMPARE(run.exit_code, 1);
    QVERIFY2(run.err.contains("missing") && run.err.contains("does not exist"),
             qPrintable(run.err));
    QVERIFY(!QFile::exists(out));
  }

  // Metadata no JPEG segment holds, or that does not parse: left out with one warning line,
  // the photo written.
  void unwritableMetadataIsLeftOut_data() {
    QTest::addColumn<QByteArray>("type");
    QTest::addColumn<QByteArray>("data");
    QTest::addColumn<QString>("extension");
    QTest::addColumn<QString>("named");
    const QByteArray history =
        xmpPacket("<dc:description>" + QByteArray(100000, 'h') + "</dc:description>");
    const QByteArray broken = xmpPacket("<dc:title>never closed</rdf:Description>");
    // Ten entities, each ten of the one before: 10^10 bytes once expanded.
    QByteArray bomb = "<?xml version=\"1.0\"?><!DOCTYPE b [<!ENTITY a0 \"aaaaaaaaaa\">";
    for (int k = 1; k <= 9; ++k)
      bomb += "<!ENTITY a" + QByteArray::number(k) + " \"" +
              ("&a" + QByteArray::number(k - 1) + ";").repeated(10) + "\">";
    bomb += "]>" + xmpPacket("<dc:title>&a9;</dc:title>");
    const QByteArray xmp_key = QByteArray("XML:com.adobe.xmp") + QByteArray(5, '\0');
    QTest::newRow("comment over 64 KiB to jpeg")
        << QByteArray("tEXt") << QByteArray("Description") + '\0' + QByteArray(70000, 'd') << "jpg"
        << "ImageDescription";
    QTest::newRow("xmp over 64 KiB to jpeg") << QByteArray("iTXt") << xmp_key + history << "jpg"
                                             << "XMP packet";
    QTest::newRow("malformed xmp to png") << QByteArray("iTXt") << xmp_key + broken << "png"
                                          << "does not parse";
    QTest::newRow("malformed xmp to jpeg") << QByteArray("iTXt") << xmp_key + broken << "jpg"
                                           << "does not parse";
    QTest::newRow("entity bomb xmp to png") << QByteArray("iTXt") << xmp_key + bomb << "png"
                                            << "does not parse";
  }
  void unwritableMetadataIsLeftOut() {
    QFETCH(QByteArray, type);
    QFETCH(QByteArray, data);
    QFETCH(QString, extension);
    QFETCH(QString, named);
    const QString tag = QString::fromLatin1(QTest::currentDataTag()).replace(' ', '-');
    const QString photo = photoWith(tag + ".png", type, data);
    QVERIFY(!photo.isEmpty());
    const QString out = path(tag + "-out." + extension);
    const CliRun run = artcamCli({"warp", photo, path("lens.artcam"), "-o", out, "--quiet"});
    QVERIFY2(run.exit_code == 0, qPrintable(run.err));
    const QStringList lines = ourLines(run.err);
    QVERIFY2(lines.size() == 1, qPrintable(run.err));
    QVERIFY2(lines[0].contains("warning") && lines[0].contains(out) &&
                 lines[0].contains("metadata left out") && lines[0].contains(named),
             qPrintable(run.err));
    const auto back = readImage(out.toStdString());
    QVERIFY2(back.ok(), back.status.message.c_str());
    QCOMPARE(back->image.width, 400);

    // In batch the file is written too, and the run goes on to the next.
    const QString folder = path(tag + "-batch");
    const CliRun batch = artcamCli({"batch", path("lens.artcam"), photo, path("photo.png"), "-o",
                                    folder, "--format", extension, "--quiet"});
    QVERIFY2(batch.exit_code == 0, qPrintable(batch.err));
    QCOMPARE(artcam::test::visibleFiles(folder).size(), 2);
  }
};

QTEST_GUILESS_MAIN(TestCliWriteFaults)
#include "test_cli_write_faults.moc"
