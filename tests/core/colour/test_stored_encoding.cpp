// SPDX-License-Identifier: Apache-2.0
// StoredEncoding (core/colour/stored_encoding.h): the tabled curves agree with the exact
// transfer formulas far below an 8-bit step, alpha is honoured (premultiplied in the domain the
// values are in, alpha 0 stays 0), an ICC profile converts as the reader does, a grey profile
// applies to each channel of replicated RGB, and a linear encoding touches nothing.
#include "core/colour/icc_profile.h"
#include "core/colour/stored_encoding.h"
#include "tests/support/icc_files.h"

#include <QtTest/QtTest>

#include <cmath>
#include <vector>

using namespace artcam;

class TestStoredEncoding : public QObject {
  Q_OBJECT

 private slots:
  void tablesFollowTheExactCurves() {
    for (const Transfer t : {Transfer::srgb(), Transfer{Transfer::Kind::Rec709, 1.0},
                             Transfer{Transfer::Kind::Gamma, 2.2}}) {
      const StoredEncoding e = StoredEncoding::ofTransfer(t);
      double worst_encode = 0, worst_decode = 0;
      constexpr int kN = 200003;  // not a multiple of the table's steps: values between them
      std::vector<float> v(kN);
      for (int i = 0; i < kN; ++i) v[static_cast<size_t>(i)] = static_cast<float>(i) / (kN - 1);
      std::vector<float> encoded = v, decoded = v;
      e.encode(encoded.data(), kN, 1, -1);
      e.decode(decoded.data(), kN, 1, -1);
      for (int i = 0; i < kN; ++i) {
        const double x = v[static_cast<size_t>(i)];
        worst_encode = std::max(worst_encode, std::abs(encoded[static_cast<size_t>(i)] - t.encode(x)));
        worst_decode = std::max(worst_decode, std::abs(decoded[static_cast<size_t>(i)] - t.decode(x)));
      }
      // An 8-bit step is 3.9e-3: the table is a thousand times finer, but where BT.709's
      // published constants leave its curve a 2e-4 step at the toe (0.018), which a chord
      // across it halves.
      const double bound = t.kind == Transfer::Kind::Rec709 ? 3e-4 : 4e-6;
      QVERIFY2(worst_encode < bound, qPrintable(QString("encode %1").arg(worst_encode)));
      QVERIFY2(worst_decode < bound, qPrintable(QString("decode %1").arg(worst_decode)));
    }
  }

  void outsideTheUnitRangeIsExact() {
    const Transfer t = Transfer::srgb();
    const StoredEncoding e = StoredEncoding::ofTransfer(t);
    float v[3] = {-0.25f, 1.5f, 3.0f};
    e.encode(v, 3, 1, -1);
    QCOMPARE(v[0], static_cast<float>(t.encode(-0.25)));
    QCOMPARE(v[1], static_cast<float>(t.encode(1.5)));
    QCOMPARE(v[2], static_cast<float>(t.encode(3.0)));
  }

  void premultipliedInTheDomainOfTheValues() {
    const Transfer t = Transfer::srgb();
    const StoredEncoding e = StoredEncoding::ofTransfer(t);
    // Linear 0.2 at alpha 0.5 is stored as encode(0.2) · 0.5; alpha itself is never encoded.
    float px[8] = {0.1f, 0.05f, 0.0f, 0.5f, 0.7f, 0.7f, 0.7f, 0.0f};
    e.encode(px, 2, 4, 3);
    QVERIFY(std::abs(px[0] - t.encode(0.2) * 0.5) < 1e-5);
    QVERIFY(std::abs(px[1] - t.encode(0.1) * 0.5) < 1e-5);
    QCOMPARE(px[2], 0.0f);
    QCOMPARE(px[3], 0.5f);
    for (int c = 4; c < 8; ++c) QCOMPARE(px[c], 0.0f);  // alpha 0: nothing to encode
    e.decode(px, 2, 4, 3);
    QVERIFY(std::abs(px[0] - 0.1f) < 1e-5f);
    QVERIFY(std::abs(px[1] - 0.05f) < 1e-5f);
  }

  void linearTouchesNothing() {
    const StoredEncoding e;
    QVERIFY(e.isLinear());
    float px[4] = {0.3f, -2.0f, 7.0f, 0.25f};
    e.encode(px, 1, 4, 3);
    QCOMPARE(px[0], 0.3f);
    QCOMPARE(px[1], -2.0f);
    QCOMPARE(px[2], 7.0f);
    QCOMPARE(px[3], 0.25f);
  }

  void profilesConvertAsTheReaderDoes() {
    auto adobe = IccProfile::fromBytes(test::adobeRgbProfile(), 3, "adobe.icc");
    QVERIFY2(adobe.ok(), adobe.status.message.c_str());
    const auto profile = std::make_shared<const IccProfile>(std::move(*adobe));
    const StoredEncoding e = StoredEncoding::ofProfile(profile);
    QVERIFY(!e.isLinear());
    float stored[4] = {0.2f, 0.5f, 0.9f, 1.0f};
    float want[3] = {0.2f, 0.5f, 0.9f};
    profile->toWorking(want, 1, 3, -1);
    float got[4] = {stored[0], stored[1], stored[2], stored[3]};
    e.decode(got, 1, 4, 3);
    for (int c = 0; c < 3; ++c) QVERIFY(std::abs(got[c] - want[c]) < 1e-6f);
    e.encode(got, 1, 4, 3);
    for (int c = 0; c < 3; ++c) QVERIFY(std::abs(got[c] - stored[c]) < 1e-4f);

    // A grey profile over RGB that replicates grey: each channel as a grey value.
    auto grey = IccProfile::fromBytes(test::greyGammaProfile(2.2), 1, "grey.icc");
    QVERIFY2(grey.ok(), grey.status.message.c_str());
    const StoredEncoding g = StoredEncoding::ofProfile(std::make_shared<const IccProfile>(std::move(*grey)));
    float rgb[4] = {0.5f, 0.5f, 0.5f, 1.0f};
    g.decode(rgb, 1, 4, 3);
    QVERIFY(std::abs(rgb[0] - std::pow(0.5, 2.2)) < 2e-3);
    QCOMPARE(rgb[0], rgb[1]);
    QCOMPARE(rgb[1], rgb[2]);
  }
};

QTEST_GUILESS_MAIN(TestStoredEncoding)
#include "test_stored_encoding.moc"
