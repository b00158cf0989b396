// SPDX-License-Identifier: Apache-2.0
// PLY point clouds: exact round trips in all three encodings, hand-written files with skipped
// properties and elements, and refusals that name the file, the header line or vertex and the
// cause (including lying counts, which must fail before any allocation).
#include "core/io/ply.h"
#include "core/colour/transfer.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

using namespace artcam;

namespace {

// A cloud whose colours are exactly representable in uchar sRGB (so writing is lossless).
PointCloud randomCloud(size_t n, bool alpha) {
  PointCloud cloud;
  const Transfer srgb = Transfer::srgb();
  for (size_t i = 0; i < n; ++i) {
    cloud.positions.emplace_back(test::uniform(-10, 10), test::uniform(-10, 10),
                                 test::uniform(-10, 10));
    const float a = alpha ? static_cast<float>(std::lround(test::uniform(1, 255))) / 255.0f : 1.0f;
    Eigen::Vector4f c;
    for (int k = 0; k < 3; ++k)
      c[k] = static_cast<float>(srgb.decode(std::lround(test::uniform(0, 255)) / 255.0)) * a;
    c[3] = a;
    cloud.colours.push_back(c);
  }
  cloud.has_alpha = alpha;
  return cloud;
}

template <class T>
void put(std::string& out, T v, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

QString refusal(const std::string& bytes) {
  const auto r = parsePly(bytes, "t.ply");
  return r.ok() ? QString("ACCEPTED") : QString::fromStdString(r.status.message);
}

}  // namespace

class TestPly : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  std::string path(const char* name) { return dir_.filePath(name).toStdString(); }

  void compareClouds(const PointCloud& a, const PointCloud& b, bool exact_positions) {
    QCOMPARE(a.size(), b.size());
    QCOMPARE(a.hasColour(), b.hasColour());
    for (size_t i = 0; i < a.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        if (exact_positions)
          QCOMPARE(b.positions[i][k], a.positions[i][k]);
        else
          QCOMPARE(b.positions[i][k], static_cast<double>(static_cast<float>(a.positions[i][k])));
      }
      if (a.hasColour())
        for (int k = 0; k < 4; ++k) QVERIFY(std::abs(b.colours[i][k] - a.colours[i][k]) < 1e-6f);
    }
  }

 private slots:
  void roundTripsEveryEncoding() {
    const PointCloud cloud = randomCloud(500, true);
    for (const PlyFormat format :
         {PlyFormat::Ascii, PlyFormat::BinaryLittleEndian, PlyFormat::BinaryBigEndian})
      for (const bool dbl : {false, true}) {
        PlyWriteOptions o;
        o.format = format;
        o.double_positions = dbl;
        const std::string p = path("rt.ply");
        const Status s = writePly(p, cloud, o);
        QVERIFY2(s.ok, s.message.c_str());
        const auto back = readPly(p);
        QVERIFY2(back.ok(), back.status.message.c_str());
        QVERIFY(back->has_alpha);
        compareClouds(cloud, *back, dbl);
      }
  }

  void writesNoAlphaForOpaqueAndNoColourForPlain() {
    PointCloud cloud = randomCloud(10, false);
    QVERIFY(plyBytes(cloud).find("alpha") == std::string::npos);
    cloud.colours.clear();
    const std::string bytes = plyBytes(cloud, {PlyFormat::Ascii, false, ""});
    QVERIFY(bytes.find("red") == std::string::npos);
    const auto back = parsePly(bytes, "plain.ply");
    QVERIFY2(back.ok(), back.status.message.c_str());
    QVERIFY(!back->hasColour());
    QCOMPARE(back->colour(3), Eigen::Vector4f(1, 1, 1, 1));
  }

  void readsHandWrittenAsciiDecodingSrgbAndPremultiplying() {
    const std::string text =
        "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info nothing\r\n"
        "element vertex 2\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\n"
        "property float nx\r\nproperty uchar red\r\nproperty uchar green\r\nproperty uchar blue\r\n"
        "property uchar alpha\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\n"
        "end_header\r\n"
        "1 2 3 0.5 255 128 0 255\r\n\r\n"
        "-1.5 2e-3 nan 7 0 0 255 51\r\n"
        "3 0 1 2\r\n";
    const auto r = parsePly(text, "hand.ply");
    QVERIFY2(r.ok(), r.status.message.c_str());
    QCOMPARE(r->size(), size_t(2));
    QCOMPARE(r->positions[0], Eigen::Vector3d(1, 2, 3));
    QCOMPARE(r->positions[1].x(), -1.5);
    QVERIFY(std::isnan(r->positions[1].z()));
    QCOMPARE(r->colours[0][0], 1.0f);
    QVERIFY(std::abs(r->colours[0][1] - 0.2158605f) < 1e-6f);  // sRGB 128 in linear light
    const float a = 51.0f / 255.0f;
    QVERIFY(std::abs(r->colours[1][2] - a) < 1e-7f);  // premultiplied: 1·a
    QVERIFY(std::abs(r->colours[1][3] - a) < 1e-7f);
  }

  void readsBigEndianMixedTypesSkippingElementsWithLists() {
    // An element with a list BEFORE vertex must be walked entry by entry; int/short/double
    // positions; float colours are linear and taken as they are.
    std::string b =
        "ply\nformat binary_big_endian 1.0\nelement camera 2\n"
        "property list ushort float k\nproperty uchar tag\n"
        "element vertex 2\nproperty int x\nproperty double y\nproperty short z\n"
        "property double quality\nproperty float red\nproperty float green\nproperty float blue\n"
        "end_header\n";
    put<std::uint16_t>(b, 3, true);
    for (float f : {1.f, 2.f, 3.f}) put(b, f, true);
    put<std::uint8_t>(b, 7, true);
    put<std::uint16_t>(b, 0, true);
    put<std::uint8_t>(b, 8, true);
    for (int v = 0; v < 2; ++v) {
      put<std::int32_t>(b, -70000 + v, true);
      put<double>(b, 0.1 * v, true);
      put<std::int16_t>(b, static_cast<std::int16_t>(-3 - v), true);
      put<double>(b, 99.0, true);
      for (float f : {0.25f, 0.5f, 2.0f}) put(b, f, true);
    }
    const auto r = parsePly(b, "be.ply");
    QVERIFY2(r.ok(), r.status.message.c_str());
    QCOMPARE(r->positions[1], Eigen::Vector3d(-69999, 0.1, -4));
    QCOMPARE(r->colours[0], Eigen::Vector4f(0.25f, 0.5f, 2.0f, 1.0f));
  }

  void refusesMalformedInputNamingThePlace() {
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
        "property float z\n";
    struct Case {
      std::string bytes;
      const char* expected;
    };
    const std::vector<Case> cases = {
        {"", "t.ply: not a PLY file"},
        {"PLY\nformat ascii 1.0\n", "t.ply: not a PLY file (the first line is not \"ply\")"},
        {"ply\nformat ascii 1.0\nelement vertex 1\n", "t.ply: header has no end_header line"},
        {"ply\nformat binary_middle_endian 1.0\nend_header\n",
         "t.ply: header line 2: unknown format \"binary_middle_endian\""},
        {"ply\nformat ascii 2.0\nend_header\n", "header line 2: unsupported PLY version \"2.0\""},
        {"ply\nformat ascii 1.0\nelement vertex -5\nend_header\n",
         "header line 3: bad element count \"-5\""},
        {"ply\nformat ascii 1.0\nproperty float x\nend_header\n",
         "header line 3: property before any element"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
         "header line 4: unsupported property type \"float128\""},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
         "x\nend_header\n",
         "header line 5: property \"x\" declared twice"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nbogus\nend_header\n",
         "header line 4: unknown header keyword \"bogus\""},
        {"ply\nformat ascii 1.0\nelement face 0\nend_header\n", "t.ply: no vertex element"},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
         "y\nend_header\n0 0\n",
         "header line 3: vertex element lacks an x, y or z"},
        {head + "property list uchar float w\nend_header\n",
         "header line 7: list property \"w\" on vertex is not supported"},
        {head + "property ushort red\nproperty uchar green\nproperty uchar blue\nend_header\n",
         "header line 7: unsupported type ushort for colour property \"red\""},
        {head + "property uchar red\nend_header\n1 2 3 4\n5 6 7 8\n",
         "header line 3: vertex colour needs all of red, green and blue"},
        {head + "end_header\n1.000 2.000 3.000\n",
         "t.ply: vertex 1: file ends early (truncated data; the header promised 2 vertices)"},
        {head + "end_header\n1 2 3\n",
         "t.ply: header line 3: element vertex claims 2 entries (at least 12 bytes) but only 7 "
         "bytes"},
        {head + "end_header\n1 2 3\n4 5     \n",
         "t.ply: vertex 1 (line 9): expected 3 values, found 2"},
        {head + "end_header\n1 2 3\n4 five 6\n",
         "t.ply: vertex 1 (line 9): \"five\" is not a number (property y)"},
        {head + "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n1 2 3 "
                "4 5 6\n1 2 3 4 256 6\n",
         "vertex 1 (line 12): \"256\" is not a uchar 0…255 (property green)"},
        {"ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float "
         "x\nproperty float y\n"
         "property float z\nend_header\n0123456789",
         "header line 3: element vertex claims 1000000000000 entries (at least 12000000000000 "
         "bytes) but only 10 bytes"},
        {"ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty double x\nproperty "
         "float y\n"
         "property float z\nend_header\n01234567890",
         "claims 1 entries (at least 16 bytes) but only 11 bytes"},
        {"ply\nformat ascii 1.0\nelement vertex 18446744073709551615\nproperty float x\nproperty "
         "float y\n"
         "property float z\nend_header\n1 2 3\n",
         "claims 18446744073709551615 entries (at least 2^64 bytes)"},
    };
    for (const Case& c : cases) {
      const QString got = refusal(c.bytes);
      QVERIFY2(got.contains(QString::fromUtf8(c.expected)),
               qPrintable("expected \"" + QString::fromUtf8(c.expected) + "\" in \"" + got + "\""));
    }
  }

  void refusesTruncatedBinaryListBeforeVertex() {
    std::string b =
        "ply\nformat binary_little_endian 1.0\nelement face 1\nproperty list uint uchar i\n"
        "element vertex 1\nproperty uchar x\nproperty uchar y\nproperty uchar z\nend_header\n";
    put<std::uint32_t>(b, 4000000000u, false);  // a list "of 4e9 items" in a tiny file
    b += "abc";
    QVERIFY(
        refusal(b).contains("t.ply: element face 0: list i of 4000000000 items runs past the end"));
  }

  void everyTruncationAndCorruptionIsRefusedCleanly() {
    // Every prefix of a valid file, in all encodings, is refused with a message (never a crash
    // or a partial cloud); random byte changes either parse or are refused, never crash.
    for (const PlyFormat format :
         {PlyFormat::Ascii, PlyFormat::BinaryLittleEndian, PlyFormat::BinaryBigEndian}) {
      PlyWriteOptions o;
      o.format = format;
      const std::string full = plyBytes(randomCloud(20, true), o);
      for (size_t n = 0; n + 1 < full.size(); ++n) {
        const auto r = parsePly(std::string_view(full).substr(0, n), "cut.ply");
        // An ASCII file cut inside its last number still has every value: that may parse.
        if (r.ok())
          QVERIFY2(format == PlyFormat::Ascii && n + 12 > full.size(),
                   qPrintable(QString::number(n)));
        else
          QVERIFY(r.status.message.rfind("cut.ply: ", 0) == 0);
      }
      for (int t = 0; t < 300; ++t) {
        std::string bad = full;
        const size_t at = static_cast<size_t>(test::uniform(0, static_cast<double>(bad.size())));
        bad[std::min(at, bad.size() - 1)] = static_cast<char>(test::uniform(0, 256));
        const auto r = parsePly(bad, "bad.ply");
        if (r.ok()) QCOMPARE(r->size(), size_t(20));
      }
    }
  }

  void unreadableAndUnwritablePathsAreReported() {
    const auto r = readPly(path("missing.ply"));
    QVERIFY(!r.ok());
    QVERIFY(QString::fromStdString(r.status.message)
                .contains("missing.ply: cannot read: no such file"));
    const std::string bad = path("no-such-folder/out.ply");
    const Status s = writePly(bad, randomCloud(3, false));
    QVERIFY(!s.ok);
    QVERIFY(!std::filesystem::exists(bad));
  }

  void rewriteReplacesAtomically() {
    const std::string p = path("atomic.ply");
    QVERIFY(writePly(p, randomCloud(5, false)).ok);
    QVERIFY(writePly(p, randomCloud(7, false)).ok);
    QCOMPARE(readPly(p)->size(), size_t(7));
    size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir_.path().toStdString()))
      files += entry.path().filename().string().find(".tmp-") != std::string::npos;
    QCOMPARE(files, size_t(0));
  }
};

QTEST_GUILESS_MAIN(TestPly)
#include "test_ply.moc"
