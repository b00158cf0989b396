// SPDX-License-Identifier: Apache-2.0
// One memory budget for a whole project (studio_project.h, "One memory budget"): a few bytes of
// JSON asking for gigabytes of masks are refused from the sizes they state, before any mask is
// decoded, naming the project, the JSON place and the budget; a project whose photo, masks and
// depth raster together exceed the budget is refused from the photo's header before the photo
// is decoded, though each alone would fit. The address space is capped at 3 GiB, so a reader
// that allocated what the bomb asks for fails here with bad_alloc instead of taking the
// machine's memory.
#include "core/io/image_io.h"
#include "core/project/project_render.h"
#include "core/project/studio_project.h"

#include <QtTest/QtTest>

#include <chrono>

#include <sys/resource.h>

using namespace artcam;

namespace {

// One run of n uncovered pixels in region_mask.h's run bytes, as base64.
std::string oneRunMask(std::uint64_t n) {
  std::string runs(1, '\0');
  do {
    runs.push_back(static_cast<char>((n & 0x7f) | (n >= 0x80 ? 0x80 : 0)));
    n >>= 7;
  } while (n != 0);
  // base64 of at most 7 bytes, by hand (the test must not share the reader's decoder).
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < runs.size(); i += 3) {
    const size_t left = runs.size() - i;
    const std::uint32_t v = (static_cast<std::uint8_t>(runs[i]) << 16) |
                            (left > 1 ? static_cast<std::uint8_t>(runs[i + 1]) << 8 : 0) |
                            (left > 2 ? static_cast<std::uint8_t>(runs[i + 2]) : 0);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += left > 1 ? kAlphabet[(v >> 6) & 63] : '=';
    out += left > 2 ? kAlphabet[v & 63] : '=';
  }
  return out;
}

std::string projectWithLayers(int count, int side) {
  std::string layers;
  const std::string mask = oneRunMask(static_cast<std::uint64_t>(side) * side);
  for (int i = 0; i < count; ++i)
    layers += std::string(i ? "," : "") + "{\"name\": \"p\", \"size\": [" + std::to_string(side) +
              ", " + std::to_string(side) + "], \"mask\": \"" + mask + "\", \"anchors\": []}";
  return "{\"format\": \"artcam-studio-project\", \"version\": 2, \"photo\": \"p.png\", "
         "\"pairs\": [], \"depth\": {\"layers\": [" +
         layers + "]}}";
}

class Budget {
 public:
  explicit Budget(const char* mb) { qputenv("ARTCAM_MAX_MEMORY_MB", mb); }
  ~Budget() { qunsetenv("ARTCAM_MAX_MEMORY_MB"); }
};

}  // namespace

class TestProjectBudget : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    const rlimit cap{rlim_t{3} << 30, rlim_t{3} << 30};
    QCOMPARE(::setrlimit(RLIMIT_AS, &cap), 0);
  }

  void aProjectBombIsRefusedFromItsJsonAtOnce() {
    // Twelve 32768² masks in 1.3 KB: 12 GiB of masks, every one within the per-mask limit.
    const std::string text = projectWithLayers(12, 32768);
    QVERIFY(text.size() < 2000);
    const auto start = std::chrono::steady_clock::now();
    const Result<StudioProject> read = parseStudioProject(text, "/work/bomb.artcamproj");
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    QVERIFY(!read);
    const std::string& m = read.status.message;
    QVERIFY2(m.rfind("bomb.artcamproj: /depth/layers: 12 depth masks (12.0 GiB)", 0) == 0,
             m.c_str());
    QVERIFY2(m.find("more than the memory budget of") != std::string::npos, m.c_str());
    QVERIFY2(m.find("ARTCAM_MAX_MEMORY_MB") != std::string::npos, m.c_str());
    QVERIFY2(seconds < 0.5, qPrintable(QString("took %1 s").arg(seconds)));
  }

  void oneMaskCountsThePhotoItWasPaintedOn() {
    // A 4096² mask is 16 MiB; the photo of its size, float with its depth raster, 384 MiB more.
    const std::string text = projectWithLayers(1, 4096);
    {
      Budget budget("256");
      const Result<StudioProject> read = parseStudioProject(text, "/work/one.artcamproj");
      QVERIFY(!read);
      QVERIFY2(
          read.status.message.find("/depth/layers: 1 depth mask (16.0 MiB)") != std::string::npos,
          read.status.message.c_str());
      QVERIFY2(read.status.message.find("(ARTCAM_MAX_MEMORY_MB)") != std::string::npos,
               read.status.message.c_str());
    }
    Budget budget("1024");
    const Result<StudioProject> read = parseStudioProject(text, "/work/one.artcamproj");
    QVERIFY2(read, read.status.message.c_str());
    QCOMPARE(read->depth_layers.size(), size_t{1});
    QCOMPARE(read->depth_layers[0].mask.width(), 4096);
  }

  void theWholeDocumentIsCheckedBeforeThePhotoIsDecoded() {
    // A 1000² photo: 16 MB as float RGBA, within a 20 MiB budget on its own (readImage takes
    // it); four masks of its size and the depth raster make the document 29 MB.
    QTemporaryDir dir;
    const std::string photo = dir.filePath("p.png").toStdString();
    ImageF image(1000, 1000, 3);
    for (size_t i = 0; i < image.data.size(); ++i) image.data[i] = static_cast<float>(i % 7) / 7.0f;
    QVERIFY(writeImage(photo, image).ok);
    StudioProject project;
    project.photo_path = photo;
    for (int i = 0; i < 4; ++i) project.depth_layers.push_back({"p", RegionMask(1000, 1000), {}});
    Budget budget("20");
    QVERIFY(readImage(photo));  // the photo alone fits
    const Result<ProjectScene> scene = loadProjectScene(project, "doc.artcamproj");
    QVERIFY(!scene);
    const std::string& m = scene.status.message;
    QVERIFY2(
        m.rfind("doc.artcamproj: photo: 4 depth masks (3.8 MiB) and the 1000x1000 photo", 0) == 0,
        m.c_str());
    QVERIFY2(m.find("more than the memory budget of 20.0 MiB (ARTCAM_MAX_MEMORY_MB)") !=
                 std::string::npos,
             m.c_str());
    QVERIFY(checkProjectMemory(project, {1000, 1000}, 3, "doc").ok == false);
    project.depth_layers.resize(1);
    Budget more("40");
    QVERIFY2(loadProjectScene(project, "doc.artcamproj"), "the document fits 40 MiB");
  }

  void anEffectStackHasAStatedLimit() {
    const auto withEffects = [](size_t n) {
      std::string effects;
      for (size_t i = 0; i < n; ++i)
        effects +=
            std::string(i ? "," : "") + "{\"effect\": \"twist\", \"params\": {\"rate\": 0.01}}";
      return "{\"format\": \"artcam-studio-project\", \"version\": 3, \"photo\": \"p.png\", "
             "\"effects\": [" +
             effects + "]}";
    };
    const Result<StudioProject> most =
        parseStudioProject(withEffects(kMaxProjectEffects), "/w/s.artcamproj");
    QVERIFY2(most, most.status.message.c_str());
    QCOMPARE(most->effects.size(), kMaxProjectEffects);
    const Result<StudioProject> over =
        parseStudioProject(withEffects(kMaxProjectEffects + 1), "/w/s.artcamproj");
    QVERIFY(!over);
    QCOMPARE(
        over.status.message,
        std::string("s.artcamproj: /effects: 257 effects, more than the 256 a stack may hold"));
  }
};

QTEST_GUILESS_MAIN(TestProjectBudget)
#include "test_project_budget.moc"
