// SPDX-License-Identifier: Apache-2.0
// Hostile image files through every reader entry point (openImageInput, readImage,
// readStoredImage, and the ST map reader readStmapSamples): truncated PNG/JPEG/TIFF, empty and zero-sized files, 1×1 images, headers
// that claim giant sizes (bytes crafted here), unsupported formats, a directory. Each must be
// read correctly or refused with one line naming the file — never a crash or a giant
// allocation (the giant headers would ask for 30 GB and 2 GB; the ASan build makes such an
// allocation fail the test). `artcam warp` on the same files is tests/app/test_hostile_warp.cpp.
#include "core/io/image_input.h"
#include "core/io/image_io.h"
#include "core/io/stmap_file.h"
#include "core/io/stored_image.h"
#include "tests/core/io/hostile_bytes.h"

#include <QtTest/QtTest>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

using namespace artcam;
using namespace artcam::test;

namespace {

ImageF gradient(int w, int h, int channels) {
  ImageF image(w, h, channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c)
        image.pixel(x, y)[c] = static_cast<float>((x * 7 + y * 13 + c * 50) % 256) / 255.0f;
  return image;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void spit(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace

class TestHostileImages : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  std::string path(const std::string& name) {
    return dir_.filePath(QString::fromStdString(name)).toStdString();
  }

  // Every entry point refuses `file` with one line that starts with its path and contains `cause`.
  void expectRefusedEverywhere(const std::string& file, const std::string& cause) {
    const std::string prefix = file + ": cannot read: ";
    const std::string messages[] = {io_input::openImageInput(file).status.message,
                                    readImage(file).status.message,
                                    readStoredImage(file).status.message,
                                    readStmapSamples(file).status.message};
    for (const std::string& m : messages) {
      QVERIFY2(m.rfind(prefix, 0) == 0, (file + " gave: \"" + m + "\"").c_str());
      QVERIFY2(m.find('\n') == std::string::npos, m.c_str());
      QVERIFY2(m.find(cause) != std::string::npos, (m + " lacks \"" + cause + "\"").c_str());
    }
  }

 private slots:
  void truncatedFilesAreRefused_data() {
    QTest::addColumn<QString>("extension");
    QTest::newRow("png") << "png";
    QTest::newRow("jpeg") << "jpg";
    QTest::newRow("tiff") << "tif";
  }

  // Written whole, then cut: after the header (the reader opens it) and inside the header.
  void truncatedFilesAreRefused() {
    QFETCH(QString, extension);
    const std::string whole = path("whole." + extension.toStdString());
    QVERIFY(writeImage(whole, gradient(256, 128, 3)).ok);
    const std::string bytes = slurp(whole);
    QVERIFY(bytes.size() > 1000);
    const std::string cut = path("cut." + extension.toStdString());
    spit(cut, bytes.substr(0, bytes.size() / 3));
    // Opening may succeed (the header is intact); decoding must fail.
    QVERIFY2(readImage(cut).status.message.rfind(cut + ": cannot read: ", 0) == 0,
             readImage(cut).status.message.c_str());
    QVERIFY2(readStoredImage(cut).status.message.rfind(cut + ": cannot read: ", 0) == 0,
             readStoredImage(cut).status.message.c_str());
    const std::string stub = path("stub." + extension.toStdString());
    spit(stub, bytes.substr(0, 12));
    expectRefusedEverywhere(stub, "");
  }

  void emptyAndZeroSizedFilesAreRefused() {
    spit(path("empty.png"), "");
    expectRefusedEverywhere(path("empty.png"), "");
    // An IHDR with width 0: a PNG of no pixels.
    spit(path("zero.png"), pngHeaderOnly(0, 16));
    expectRefusedEverywhere(path("zero.png"), "");
  }

  void onePixelImagesAreRead_data() {
    QTest::addColumn<QString>("extension");
    QTest::newRow("png") << "png";
    QTest::newRow("jpeg") << "jpg";
    QTest::newRow("tiff") << "tif";
    QTest::newRow("exr") << "exr";
  }

  void onePixelImagesAreRead() {
    QFETCH(QString, extension);
    const std::string file = path("one." + extension.toStdString());
    ImageF one(1, 1, 3);
    one.pixel(0, 0)[0] = 0.25f, one.pixel(0, 0)[1] = 0.5f, one.pixel(0, 0)[2] = 0.75f;
    QVERIFY(writeImage(file, one).ok);
    const auto read = readImage(file);
    QVERIFY2(read.ok(), read.status.message.c_str());
    QCOMPARE(read->image.width, 1);
    QCOMPARE(read->image.height, 1);
    // JPEG is lossy (and chroma-subsampled): a few codes off; the others store these exactly
    // enough (8-bit sRGB: half a code is < 0.005 in linear light here).
    const float tolerance = extension == "jpg" ? 0.05f : 0.005f;
    for (int c = 0; c < 3; ++c)
      QVERIFY2(std::abs(read->image.pixel(0, 0)[c] - one.pixel(0, 0)[c]) < tolerance,
               std::to_string(read->image.pixel(0, 0)[c]).c_str());
    const auto stored = readStoredImage(file);
    QVERIFY2(stored.ok(), stored.status.message.c_str());
    QCOMPARE(stored->width, 1);
    QCOMPARE(stored->height, 1);
  }

  // 100 000 × 100 000 RGB is 30 GB decoded (120 GB as float) from a 59-byte file.
  void giantPngHeaderIsRefusedBeforeAllocating() {
    const std::string file = path("giant.png");
    spit(file, pngHeaderOnly(100000, 100000));
    QCOMPARE(std::filesystem::file_size(file), std::uintmax_t{59});
    expectRefusedEverywhere(file, "claims 100000x100000 pixels");
  }

  // Padding defeats a bytes-per-file-byte bound: 100 000 × 100 000 RGB claimed by a file padded
  // to 8 MB passes it (30 GB decoded < 4096 × 8 MB), but its float copy (160 GB) is far over the
  // memory budget, which is checked from the header before anything is allocated.
  void paddedGiantHeaderIsRefusedByTheMemoryBudget() {
    const std::string file = path("giant-padded.png");
    spit(file, pngHeaderOnly(100000, 100000) + std::string(8u << 20, '\0'));
    expectRefusedEverywhere(file, "more than the memory budget");
  }

  // The budget is a setting: ARTCAM_MAX_MEMORY_MB below a photo's float size refuses it, naming
  // the size and the budget; without it the same photo reads.
  void memoryBudgetCanBeSet() {
    const std::string file = path("budget.png");
    ImageF img(400, 300, 3);
    QVERIFY(writeImage(file, img).ok);
    qputenv("ARTCAM_MAX_MEMORY_MB", "1");
    const auto refused = readImage(file);
    const auto refused_stored = readStoredImage(file);
    qunsetenv("ARTCAM_MAX_MEMORY_MB");
    QVERIFY(!refused.ok() && !refused_stored.ok());
    // 400 × 300 × 4 channels × 4 bytes = 1 920 000 bytes = 1.8 MiB.
    QVERIFY2(refused.status.message.find("400x300 pixels need 1.8 MiB as float, more than the "
                                         "memory budget of 1.0 MiB") != std::string::npos,
             refused.status.message.c_str());
    QVERIFY(readImage(file).ok());
    QVERIFY(io_input::memoryBudgetBytes() > 256.0 * 1024 * 1024);  // half of any real machine
  }

  // 65 536 × 32 768 = 2^31 grey pixels from a 126-byte file.
  void giantTiffHeaderIsRefusedBeforeAllocating() {
    const std::string file = path("giant.tif");
    spit(file, tiffHeaderOnly(65536, 32768));
    expectRefusedEverywhere(file, "");
  }

  void unsupportedFormatsAreRefused() {
    spit(path("notes.txt"), "just some text, no image here\n");
    expectRefusedEverywhere(path("notes.txt"), "");
    // A known extension with other content: whatever reader OIIO picks must refuse it. These
    // 34 bytes make OIIO 2.4's GIF reader throw std::length_error (oiiotool aborts on them).
    spit(path("fake.png"), "GIF89a but not really a GIF either");
    expectRefusedEverywhere(path("fake.png"), "the decoder failed");
  }

  void directoryAndMissingFileAreRefused() {
    std::filesystem::create_directory(path("folder.png"));
    expectRefusedEverywhere(path("folder.png"), "not a file");
    expectRefusedEverywhere(path("missing.png"), "no such file");
  }
};

QTEST_GUILESS_MAIN(TestHostileImages)
#include "test_hostile_images.moc"
