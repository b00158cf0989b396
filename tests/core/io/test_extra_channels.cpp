// SPDX-License-Identifier: Apache-2.0
// Extra channels and windows at the io level (image_io.h): which names are depth, how the
// channels are grouped, that writeImage and writeStoredImage put them back by name after RGBA
// only into OpenEXR, and that an EXR output keeps the display-window origin of `like`.
#include "core/io/image_io.h"
#include "core/io/stored_image.h"
#include "tests/support/exr_files.h"

#include <OpenImageIO/imageio.h>

#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <string>
#include <utility>
#include <vector>

using namespace artcam;

namespace {

constexpr int kW = 8, kH = 6;

// Channel c of texel (x, y): 100 c + x + 10 y, so a value names its channel and texel.
float valueOf(int c, int x, int y) { return static_cast<float>(100 * c + x + 10 * y); }

bool writeFile(const std::string& path, const std::vector<std::string>& names, int x0, int y0) {
  return test::writeFloatExr(path, kW, kH, names, 3, x0, y0,
                             [](int c, int x, int y) { return c == 3 ? 1.0f : valueOf(c, x, y); });
}

}  // namespace

class TestExtraChannels : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  std::string path(const char* name) const { return dir_.filePath(name).toStdString(); }

  // In the order OpenImageIO's EXR reader hands channels back (RGBA, other unlayered ones, then
  // layers by name), so the file's order is the one written here.
  const std::vector<std::string> names_ = {"R",   "G",   "B",   "A",   "Z",        "N.x",
                                           "N.y", "N.z", "P.x", "P.y", "pass.depth", "pass.mask"};

 private slots:
  void depthNames() {
    for (const char* depth : {"Z", "ZBack", "depth", "Depth", "beauty.Z", "pass.depth"})
      QVERIFY2(isDepthChannel(depth), depth);
    for (const char* other : {"N.z", "P.z", "z", "R", "Zoom", "depthless", "mask"})
      QVERIFY2(!isDepthChannel(other), other);
  }

  void groupsAreRunsOfOneKindCutAtFour() {
    const std::string file = path("in.exr");
    QVERIFY(writeFile(file, names_, 0, 0));
    auto loaded = readImage(file);
    QVERIFY2(loaded.ok(), loaded.status.message.c_str());
    auto extra = readExtraChannels(file, loaded->info);
    QVERIFY2(extra.ok(), extra.status.message.c_str());
    std::vector<std::vector<std::string>> groups;
    for (const ChannelGroup& g : extra->groups) groups.push_back(g.names);
    const std::vector<std::vector<std::string>> want = {
        {"Z"}, {"N.x", "N.y", "N.z", "P.x"}, {"P.y"}, {"pass.depth"}, {"pass.mask"}};
    QCOMPARE(groups, want);
    QCOMPARE(extra->groups[0].depth, true);
    QCOMPARE(extra->groups[1].depth, false);
    QCOMPARE(extra->groups[3].depth, true);
    // The values are the file's, channel by channel (no transfer, no premultiplication).
    for (size_t k = 0, c = 4; k < extra->groups.size(); ++k)
      for (int i = 0; i < extra->groups[k].image.channels; ++i, ++c)
        QCOMPARE(extra->groups[k].image.pixel(5, 3)[i], valueOf(static_cast<int>(c), 5, 3));
  }

  void writersPutThemBackByNameAndKeepTheDisplayWindow() {
    const std::string file = path("origin.exr");
    QVERIFY(writeFile(file, names_, 3, -2));
    auto loaded = readImage(file);
    QVERIFY(loaded.ok());
    auto extra = readExtraChannels(file, loaded->info);
    QVERIFY(extra.ok());
    auto stored = readStoredImage(file);
    QVERIFY(stored.ok());
    for (const bool stored_writer : {false, true}) {
      const std::string out = path(stored_writer ? "stored.exr" : "float.exr");
      WriteImageOptions options;
      options.extra_channels = &*extra;
      const Status s = stored_writer
                           ? writeStoredImage(out, std::as_const(*stored).view(), &stored->info, options)
                           : writeImage(out, loaded->image, &loaded->info, options);
      QVERIFY2(s.ok, s.message.c_str());
      auto in = OIIO::ImageInput::open(out);
      QVERIFY(in);
      const OIIO::ImageSpec& spec = in->spec();
      QCOMPARE(spec.channelnames, names_);
      QCOMPARE(spec.x, 3);
      QCOMPARE(spec.y, -2);
      QCOMPARE(spec.full_x, 3);
      QCOMPARE(spec.full_y, -2);
      QCOMPARE(spec.full_width, kW);
      QCOMPARE(spec.full_height, kH);
      std::vector<float> pixels(static_cast<size_t>(kW * kH) * names_.size());
      QVERIFY(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
      const float* px = &pixels[(3 * kW + 5) * names_.size()];
      for (int c = 0; c < static_cast<int>(names_.size()); ++c)
        QCOMPARE(px[c], c == 3 ? 1.0f : valueOf(c, 5, 3));
    }
  }

  void aFormatWithoutExtraChannelsRefusesThem() {
    const std::string file = path("in.exr");
    QVERIFY(writeFile(file, names_, 0, 0));
    auto loaded = readImage(file);
    QVERIFY(loaded.ok());
    auto extra = readExtraChannels(file, loaded->info);
    QVERIFY(extra.ok());
    WriteImageOptions options;
    options.extra_channels = &*extra;
    const Status s = writeImage(path("out.png"), loaded->image, &loaded->info, options);
    QVERIFY(!s.ok);
    QVERIFY2(s.message.find("out.png: cannot write: the png format holds no extra channels") !=
                 std::string::npos,
             s.message.c_str());
    QVERIFY(!QFile::exists(QString::fromStdString(path("out.png"))));
    QVERIFY(formatStoresExtraChannels(path("x.exr")));
    QVERIFY(!formatStoresExtraChannels(path("x.tif")));
  }
};

QTEST_GUILESS_MAIN(TestExtraChannels)
#include "test_extra_channels.moc"
