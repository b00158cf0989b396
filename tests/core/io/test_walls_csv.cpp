// SPDX-License-Identifier: Apache-2.0
// The walls CSV of artcam unfold: the lines CSV's strict reader under the header wall,x,y, its
// bounds (walls, corners) and refusals naming the file and the line.
#include "core/io/walls_csv.h"

#include <QtTest/QtTest>

#include <string>

using namespace artcam;

class TestWallsCsv : public QObject {
  Q_OBJECT

  static QString refusal(const std::string& text) {
    const auto r = parseWallsCsv(text, "walls.csv");
    return r.ok() ? QStringLiteral("ACCEPTED") : QString::fromStdString(r.status.message);
  }

 private slots:
  void wallsInOrderOfFirstAppearance() {
    const auto r = parseWallsCsv(
        "# marked on the left view\r\nwall,x,y\r\nfront,10,300\nfront,200,300\nside,200,300\n"
        "front,200,100\nside, 330 ,280\nfront,10,100\nside,330,120\nside,200,100\n",
        "walls.csv");
    QVERIFY2(r.ok(), r.status.message.c_str());
    QCOMPARE(r->size(), size_t{2});
    QCOMPARE((*r)[0].name, std::string("front"));
    QCOMPARE((*r)[0].photo_px.size(), size_t{4});
    QCOMPARE((*r)[0].photo_px[1].x(), 200.0);
    QCOMPARE((*r)[1].name, std::string("side"));
    QCOMPARE((*r)[1].photo_px[1].x(), 330.0);
  }

  void refusalsNameTheLineAndTheCause() {
    QVERIFY(refusal("front,1,2\n").contains("walls.csv:1: expected the header wall,x,y"));
    QVERIFY(refusal("").contains("walls.csv: empty"));
    QVERIFY(refusal("wall,x,y\n").contains("no rows after the header"));
    QVERIFY(refusal("wall,x,y\nfront,1,nope\n").contains("walls.csv:2: column 3 (y)"));
    QVERIFY(refusal("wall,x,y\nfront,1,2,3\n").contains("walls.csv:2: expected a wall label"));
    QVERIFY(refusal("wall,x,y\n,1,2\n").contains("column 1 (wall): empty"));
    // The strict numbers of every CSV: no NaN, inf, hex or overflow slips through strtod.
    for (const char* number : {"nan", "inf", "-inf", "0x10", "1e999", "1,5"})
      QVERIFY2(refusal(std::string("wall,x,y\nfront,1,") + number + "\n") != "ACCEPTED", number);
  }

  void boundedWallsAndCorners() {
    std::string many = "wall,x,y\n";
    for (size_t k = 0; k <= kMaxWalls; ++k) many += "w" + std::to_string(k) + ",1,2\n";
    QVERIFY(refusal(many).contains("walls.csv:" + QString::number(kMaxWalls + 2) +
                                   ": more than 64 walls"));
    std::string corners = "wall,x,y\n";
    for (size_t k = 0; k <= kMaxWallCorners; ++k) corners += "front," + std::to_string(k) + ",2\n";
    QVERIFY(refusal(corners).contains("wall \"front\" (from line 2) has more than 64 corners"));
  }
};

QTEST_GUILESS_MAIN(TestWallsCsv)
#include "test_walls_csv.moc"
