// SPDX-License-Identifier: Apache-2.0
// The OpenImageIO module is loaded only when an image needs it (core/io/oiio_io.h): a JPEG to
// JPEG warp runs with the module out of reach (ARTCAM_IO_MODULE naming a file that is not
// there), writing the same pixels as with it; a PNG then fails in one line that names the module
// and leaves no output; commands without images never need it.
#include "tests/app/cli_files.h"
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QFileInfo>
#include <QTemporaryDir>

#include <OpenImageIO/imageio.h>

#include <vector>

using namespace artcam;
using namespace artcam::test;

namespace {

const QStringList kNoModule = {QStringLiteral("ARTCAM_IO_MODULE=/nonexistent/libartcam_io_oiio.so")};

std::vector<unsigned char> pixelsOf(const QString& path) {
  auto in = OIIO::ImageInput::open(path.toStdString());
  if (!in) return {};
  const OIIO::ImageSpec spec = in->spec();
  std::vector<unsigned char> bytes(spec.image_bytes());
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, bytes.data())) return {};
  return bytes;
}

}  // namespace

class TestCliImageModule : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(writeNoisePhoto(path("photo.png"), 320, 200));
    const CliRun jpeg = artcamCli({"warp", path("photo.png"), resourcePath("sample.artcam").c_str(),
                                   "-o", path("photo.jpg"), "--quiet"});
    QVERIFY2(jpeg.exit_code == 0, qPrintable(jpeg.err));
  }

  void jpegWarpNeedsNoModule() {
    const QString camera = QString::fromStdString(resourcePath("sample.artcam"));
    const CliBytesRun without =
        artcamCliPiped({"warp", path("photo.jpg"), camera, "-o", path("without.jpg"), "--quiet"}, {}, kNoModule);
    QVERIFY2(without.exit_code == 0, qPrintable(without.err));
    const CliRun with = artcamCli({"warp", path("photo.jpg"), camera, "-o", path("with.jpg"), "--quiet"});
    QVERIFY2(with.exit_code == 0, qPrintable(with.err));
    const std::vector<unsigned char> a = pixelsOf(path("without.jpg")), b = pixelsOf(path("with.jpg"));
    QVERIFY(!a.empty());
    QVERIFY(a == b);
  }

  void pngWithoutModuleFailsInOneLine() {
    const QString camera = QString::fromStdString(resourcePath("sample.artcam"));
    const CliBytesRun run =
        artcamCliPiped({"warp", path("photo.png"), camera, "-o", path("out.png"), "--quiet"}, {}, kNoModule);
    QVERIFY(run.exit_code > 0);
    QVERIFY2(run.err.contains(path("photo.png")) && run.err.contains("libartcam_io_oiio.so"), qPrintable(run.err));
    QCOMPARE(run.err.trimmed().count('\n'), 0);
    QVERIFY(!QFileInfo::exists(path("out.png")));
  }

  void versionNeedsNoModule() {
    const CliBytesRun run = artcamCliPiped({"--version"}, {}, kNoModule);
    QCOMPARE(run.exit_code, 0);
  }
};

QTEST_GUILESS_MAIN(TestCliImageModule)
#include "test_cli_image_module.moc"
