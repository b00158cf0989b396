// SPDX-License-Identifier: Apache-2.0
// The command line speaks one dialect: sizes WxH (preset --size also W,H, as before); every
// command that writes refuses an existing output without --overwrite (alias --force) and never
// writes over one of its own inputs, whatever the path's spelling (symlink, hard link, ./..);
// usage errors are at most three lines with a "did you mean" for a near miss; --json reports
// (fit --piecewise, warp --stats, render, batch) parse back and agree with the text reports and
// the files written.
#include "core/io/artcam_file.h"
#include "core/io/image_io.h"
#include "core/io/matches_csv.h"
#include "core/io/artcam_file.h"
#include "core/io/ply.h"
#include "tests/app/cli_files.h"
#include "tests/app/cli_run.h"

#include <QtTest/QtTest>

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QRegularExpression>
#include <QTemporaryDir>

#include <algorithm>
#include <cmath>
#include <unistd.h>

using namespace artcam;
using artcam::test::artcamCli;
using artcam::test::fileBytes;
using Run = artcam::test::CliRun;

namespace {

const QString kResources = QStringLiteral(ARTCAM_RESOURCES_DIR);

QStringList errorLines(const Run& r) { return r.err.split('\n', Qt::SkipEmptyParts); }

QJsonObject jsonOf(const Run& r) {
  QJsonParseError error;
  const QJsonDocument doc = QJsonDocument::fromJson(r.out.toUtf8(), &error);
  if (error.error != QJsonParseError::NoError || !doc.isObject()) return {};
  return doc.object();
}

}  // namespace

class TestCliDialect : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

  // The refusal every writing command gives for an output that is one of its inputs: exit 1,
  // the input named, the file untouched — with and without --overwrite/--force.
  void expectInputKept(QStringList args, const QString& input, const char* what) {
    const QByteArray before = fileBytes(input);
    QVERIFY2(!before.isEmpty(), what);
    for (const char* flag : {"", "--overwrite", "--force"}) {
      QStringList call = args;
      if (*flag) call << flag;
      const Run r = artcamCli(call);
      QVERIFY2(r.exit_code == 1, qPrintable(QString(what) + " " + flag + ": " + r.err));
      QVERIFY2(r.err.contains("refusing to overwrite the input"), qPrintable(r.err));
      QCOMPARE(errorLines(r).size(), 1);
      QVERIFY2(fileBytes(input) == before, what);
    }
  }

  // An output that exists: refused (exit 1, the name and the option in one line, the file
  // untouched); --overwrite and --force each replace it.
  void expectOverwriteRule(const QStringList& args, const QString& output, const char* what) {
    QVERIFY2(QFile::exists(output), what);
    QFile::remove(output);
    QVERIFY(QFile::copy(kResources + "/sample-matches.csv", output));  // a stand-in old file
    const QByteArray before = fileBytes(output);
    const Run refused = artcamCli(args);
    QVERIFY2(refused.exit_code == 1, qPrintable(QString(what) + ": " + refused.err));
    QVERIFY2(refused.err.contains(output + " exists; pass --overwrite to replace it"),
             qPrintable(refused.err));
    QCOMPARE(fileBytes(output), before);
    for (const char* flag : {"--overwrite", "--force"}) {
      const Run r = artcamCli(QStringList(args) << flag);
      QVERIFY2(r.exit_code == 0, qPrintable(QString(what) + " " + flag + ": " + r.err));
      QVERIFY2(fileBytes(output) != before, what);
    }
  }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(QFile::copy(kResources + "/sample-matches.csv", path("m.csv")));
    QVERIFY(QFile::copy(kResources + "/coffee.png", path("photo.png")));
    QVERIFY(QFile::copy(kResources + "/sample.artcam", path("cam.artcam")));
    for (const char* f : {"water-glass.png", "water-glass-grid.csv", "emblem.png"})
      QVERIFY(QFile::copy(kResources + "/insertion/" + f, path(f)));
  }

  // WxH everywhere; preset --size keeps W,H; other sizes refuse W,H naming WxH.
  void sizesAreWxH() {
    for (const char* size : {"300x200", "300,200"}) {
      const QString out =
          path(QStringLiteral("size-%1.artcam").arg(QString(size).replace(',', '_')));
      const Run r = artcamCli({"preset", "barrel", "--size", size, "-o", out});
      QVERIFY2(r.exit_code == 0, qPrintable(r.err));
      const auto doc = readArtcam(out.toStdString());
      QVERIFY(doc.ok());
      QCOMPARE(doc->main().sourceSize().width, 300);
      QCOMPARE(doc->main().sourceSize().height, 200);
    }
    const Run fit = artcamCli(
        {"fit", path("m.csv"), "-o", path("size-fit.artcam"), "--size", "320x240", "--json"});
    QVERIFY2(fit.exit_code == 0, qPrintable(fit.err));
    const auto doc = readArtcam(path("size-fit.artcam").toStdString());
    QVERIFY(doc.ok());
    QCOMPARE(doc->main().sourceSize().width, 320);
    QCOMPARE(doc->main().sourceSize().height, 240);
    const Run comma =
        artcamCli({"fit", path("m.csv"), "-o", path("comma.artcam"), "--size", "320,240"});
    QCOMPARE(comma.exit_code, 2);
    QVERIFY2(comma.err.contains("--size expects WxH"), qPrintable(comma.err));
    QVERIFY(!QFile::exists(path("comma.artcam")));
    // No help page still teaches the old spelling.
    for (const char* command : {"fit", "warp", "batch", "preset", "render", "insert", "sample"}) {
      const Run help = artcamCli({command, "--help"});
      QVERIFY2(!help.out.contains("--size W,H"), command);
    }
  }

  // The two reported losses: fit's matches and render's cloud written over by their output.
  void fitAndRenderNeverOverwriteTheirInput() {
    expectInputKept({"fit", path("m.csv"), "-o", path("m.csv"), "--size", "600x400"},
                    path("m.csv"), "fit");
    expectInputKept(
        {"fit", path("m.csv"), "-o", path("./m.csv"), "--size", "600x400", "--piecewise"},
        path("m.csv"), "fit --piecewise");
    QVERIFY(artcamCli({"preset", "cube-of-cubes", "--samples", "2", "-o", path("c.ply")})
                .exit_code == 0);
    QVERIFY(artcamCli({"preset", "identity", "-o", path("id.artcam")}).exit_code == 0);
    expectInputKept({"render", path("c.ply"), path("id.artcam"), "-o", path("c.ply")},
                    path("c.ply"), "render cloud");
    expectInputKept({"render", path("c.ply"), path("id.artcam"), "-o", path("id.artcam")},
                    path("id.artcam"), "render camera");
  }

  // A hard link and a symbolic link are the input under another name; so is a path through
  // "..". The link may be the output or the input's spelling.
  void linksAreTheSameFile() {
    QVERIFY(::link(QFile::encodeName(path("photo.png")).constData(),
                   QFile::encodeName(path("hard.png")).constData()) == 0);
    QVERIFY(QFile::link(path("photo.png"), path("soft.png")));
    QVERIFY(QDir().mkpath(path("sub")));
    const QStringList warp = {"warp", path("photo.png"), path("cam.artcam"), "-o"};
    expectInputKept(QStringList(warp) << path("hard.png"), path("photo.png"), "warp hard link");
    expectInputKept(QStringList(warp) << path("soft.png"), path("photo.png"), "warp symlink");
    expectInputKept(QStringList(warp) << path("sub/../photo.png"), path("photo.png"), "warp ..");
    expectInputKept({"warp", path("soft.png"), path("cam.artcam"), "-o", path("photo.png")},
                    path("photo.png"), "warp from a symlink");
    expectInputKept(QStringList(warp) << path("cam.artcam"), path("cam.artcam"), "warp camera");
    QVERIFY(::link(QFile::encodeName(path("m.csv")).constData(),
                   QFile::encodeName(path("m-hard.csv")).constData()) == 0);
    expectInputKept({"fit", path("m.csv"), "-o", path("m-hard.csv"), "--size", "600x400"},
                    path("m.csv"), "fit hard link");
    QVERIFY(QFile::link(path("m.csv"), path("m-soft.csv")));
    expectInputKept({"fit", path("m.csv"), "-o", path("m-soft.csv"), "--size", "600x400"},
                    path("m.csv"), "fit symlink");
  }

  void everyWritingCommandHasTheOverwriteRule() {
    const QString fitted = path("ow-fit.artcam");
    const QStringList fit = {"fit", path("m.csv"), "-o", fitted, "--size", "600x400"};
    QVERIFY(artcamCli(fit).exit_code == 0);
    expectOverwriteRule(fit, fitted, "fit");
    const QString pieces = path("ow-pieces.artcam");
    const QStringList piecewise = {"fit",  path("water-glass-grid.csv"), "-o", pieces, "--size",
                                   "512x512", "--target-size", "640x480", "--piecewise"};
    QVERIFY(artcamCli(piecewise).exit_code == 0);
    expectOverwriteRule(piecewise, pieces, "fit --piecewise");

    const QString warped = path("ow-warp.png");
    const QStringList warp = {"warp", path("photo.png"), path("cam.artcam"), "-o", warped};
    QVERIFY(artcamCli(warp).exit_code == 0);
    expectOverwriteRule(warp, warped, "warp");

    QVERIFY(QDir().mkpath(path("ow-batch")));
    const QStringList batch = {"batch", path("cam.artcam"), path("photo.png"), "-o",
                               path("ow-batch")};
    QVERIFY(artcamCli(batch).exit_code == 0);
    expectOverwriteRule(batch, path("ow-batch/photo.png"), "batch");
    expectInputKept({"batch", path("cam.artcam"), path("photo.png"), "-o", path("sub/..")},
                    path("photo.png"), "batch");

    const QString composed = path("ow-compose.artcam");
    const QStringList compose = {"compose", path("cam.artcam"), path("cam.artcam"), "-o",
                                 composed};
    QVERIFY(artcamCli(compose).exit_code == 0);
    expectOverwriteRule(compose, composed, "compose");
    expectInputKept({"compose", path("cam.artcam"), path("id.artcam"), "-o", path("cam.artcam")},
                    path("cam.artcam"), "compose");

    const QString preset = path("ow-preset.artcam");
    const QStringList twist = {"preset", "twist", "-o", preset};
    QVERIFY(artcamCli(twist).exit_code == 0);
    expectOverwriteRule(twist, preset, "preset");

    const QString rendered = path("ow-render.png");
    const QStringList render = {"render", path("c.ply"), path("id.artcam"), "-o", rendered,
                                "--size", "64x48"};
    QVERIFY(artcamCli(render).exit_code == 0);
    expectOverwriteRule(render, rendered, "render");

    const QString inserted = path("ow-insert.png");
    const QStringList insert = {"insert", path("water-glass.png"), path("emblem.png"),
                                "--matches", path("water-glass-grid.csv"), "-o", inserted};
    QVERIFY(artcamCli(insert).exit_code == 0);
    expectOverwriteRule(insert, inserted, "insert");
    expectInputKept(QStringList(insert.mid(0, 6)) << path("emblem.png"), path("emblem.png"),
                    "insert graphic");
    expectInputKept(QStringList(insert) << "--save-camera" << path("water-glass-grid.csv"),
                    path("water-glass-grid.csv"), "insert --save-camera");

    const QStringList sample = {"sample", "water-glass", "-o", path("ow-sample"), "--size",
                                "96x64", "--squares", "4"};
    QVERIFY(artcamCli(sample).exit_code == 0);
    expectOverwriteRule(sample, path("ow-sample/water-glass.png"), "sample");

    // bench checks its plot before it starts timing.
    QVERIFY(QFile::copy(path("photo.png"), path("plot.png")));
    const Run bench = artcamCli({"bench", "fit", "--plot", path("plot.png")});
    QCOMPARE(bench.exit_code, 1);
    QVERIFY2(bench.err.contains("plot.png exists; pass --overwrite"), qPrintable(bench.err));
  }

  // The error, the hint, where the help is: never the help page itself.
  void usageErrorsAreThreeLines() {
    struct Case {
      QStringList args;
      QString first, hint, help;
    };
    const QList<Case> cases = {
        {{"warp", "--filtr", "bilinear"}, "artcam warp: unknown option --filtr",
         "did you mean --filter?", "see 'artcam warp --help'"},
        {{"warp", path("photo.png"), "--fitler", "bicubic"}, "artcam warp: unknown option --fitler",
         "did you mean --filter?", "see 'artcam warp --help'"},
        {{"fit", path("m.csv"), "--jsn"}, "artcam fit: unknown option --jsn",
         "did you mean --json?", "see 'artcam fit --help'"},
        {{"batch", "--suf", "_x"}, "artcam batch: unknown option --suf", "did you mean --suffix?",
         "see 'artcam batch --help'"},
        {{"wrap", "a.png"}, "artcam: unknown command \"wrap\"", "did you mean warp?",
         "see 'artcam --help'"},
        {{"compse"}, "artcam: unknown command \"compse\"", "did you mean compose?",
         "see 'artcam --help'"},
        {{"preset", "barel", "-o", path("x.artcam")}, "artcam preset: unknown preset \"barel\"",
         "did you mean barrel?", "see 'artcam preset --help'"},
        {{"bench", "fit", "--count", "9"}, "artcam bench: unknown option --count",
         "did you mean --counts?", "see 'artcam bench fit --help'"},
        // Two transpositions are distance 2 (plain Levenshtein would say 4): a hint.
        {{"warp", "--flitre", "bicubic"}, "artcam warp: unknown option --flitre",
         "did you mean --filter?", "see 'artcam warp --help'"},
        // Distance 3 from --filter, further from the rest: no hint.
        {{"warp", "--xfiltrx", "bicubic"}, "artcam warp: unknown option --xfiltrx", "",
         "see 'artcam warp --help'"},
        // No single near option: no hint (--d is a prefix of three).
        {{"warp", "--d", "x"}, "artcam warp: unknown option --d", "", "see 'artcam warp --help'"},
        {{"warp", path("photo.png"), path("cam.artcam")}, "artcam warp: missing -o OUT", "",
         "see 'artcam warp --help'"},
        {{"frobnicate"}, "artcam: unknown command \"frobnicate\"", "", "see 'artcam --help'"},
        {{}, "artcam: missing the command", "", "see 'artcam --help'"},
    };
    for (const Case& c : cases) {
      const Run r = artcamCli(c.args);
      const QString call = "artcam " + c.args.join(' ') + ":\n" + r.err;
      QVERIFY2(r.exit_code == 2, qPrintable(call));
      QVERIFY2(r.out.isEmpty(), qPrintable(call));
      QStringList expected = {c.first};
      if (!c.hint.isEmpty()) expected << c.hint;
      expected << c.help;
      const QStringList lines = errorLines(r);
      QVERIFY2(lines.size() == expected.size(), qPrintable(call));
      for (int i = 0; i < lines.size(); ++i)
        QVERIFY2(lines[i].startsWith(expected[i]), qPrintable(call));
    }
  }

  // fit --piecewise --json against the file it wrote and the text report of the same fit.
  void piecewiseFitJson() {
    const QStringList fit = {"fit",       path("water-glass-grid.csv"), "--size", "512x512",
                             "--target-size", "640x480", "--piecewise", "--max-error", "0.25"};
    const Run j = artcamCli(QStringList(fit) << "-o" << path("pw-json.artcam") << "--json");
    QVERIFY2(j.exit_code == 0, qPrintable(j.err));
    const QJsonObject o = jsonOf(j);
    QVERIFY2(!o.isEmpty(), qPrintable(j.out));
    QCOMPARE(o["output"].toString(), path("pw-json.artcam"));
    QVERIFY(o["piecewise"].toBool());
    const auto doc = readArtcam(path("pw-json.artcam").toStdString());
    QVERIFY2(doc.ok() && doc->pieces, doc.status.message.c_str());
    const std::vector<CameraPatch>& patches = doc->pieces->patches;
    const QJsonArray list = o["patch_list"].toArray();
    QCOMPARE(o["patches"].toInt(), static_cast<int>(patches.size()));
    QCOMPARE(list.size(), static_cast<qsizetype>(patches.size()));
    QVERIFY(patches.size() > 1);
    bool all_within = true;
    for (qsizetype i = 0; i < list.size(); ++i) {
      const QJsonObject p = list[i].toObject();
      const QJsonArray rect = p["rect"].toArray();
      QCOMPARE(rect.size(), 4);
      QCOMPARE(rect[0].toDouble(), patches[i].rect.x0);
      QCOMPARE(rect[3].toDouble(), patches[i].rect.y1);
      QCOMPARE(p["model"].toString(), QString::fromStdString(patches[i].model));
      QCOMPARE(p["matches"].toInt(), patches[i].matches);
      QVERIFY(p["rms_px"].toDouble() <= p["max_px"].toDouble());
      all_within = all_within && p["within_tolerance"].toBool();
    }
    // The totals: every match of the CSV through the camera read back from the file.
    const auto matches = readMatchesCsv(path("water-glass-grid.csv").toStdString());
    QVERIFY(matches.ok());
    QCOMPARE(o["matches"].toInt(), static_cast<int>(matches->size()));
    double worst = 0.0, sum2 = 0.0;
    for (const PointMatch& m : *matches) {
      const auto y = doc->pieces->targetPixelFromSourcePixel(m.source.head<2>());
      QVERIFY(y);
      const double r = (*y - m.target.head<2>()).norm();
      worst = std::max(worst, r);
      sum2 += r * r;
    }
    QVERIFY(std::abs(o["max_px"].toDouble() - worst) <= 1e-6 * worst + 1e-9);
    QVERIFY(std::abs(o["rms_px"].toDouble() - std::sqrt(sum2 / double(matches->size()))) <=
            1e-6 * worst + 1e-9);
    QCOMPARE(o["converged"].toBool(), all_within);
    QCOMPARE(o["max_error_px"].toDouble(), 0.25);
    if (all_within) QVERIFY(o["max_px"].toDouble() <= 0.25);

    const Run t = artcamCli(QStringList(fit) << "-o" << path("pw-text.artcam"));
    QVERIFY2(t.exit_code == 0, qPrintable(t.err));
    const QRegularExpressionMatch m =
        QRegularExpression("piecewise: (\\d+) patches, (\\d+) matches, RMS ([0-9.e+-]+) px, "
                           "max ([0-9.e+-]+) px, held-out max [0-9.e+-]+ px, "
                           "seam gap ([0-9.e+-]+) px")
            .match(t.out);
    QVERIFY2(m.hasMatch(), qPrintable(t.out));
    QCOMPARE(m.captured(1).toInt(), o["patches"].toInt());
    QCOMPARE(m.captured(2).toInt(), o["matches"].toInt());
    QVERIFY(std::abs(m.captured(3).toDouble() - o["rms_px"].toDouble()) <=
            1e-3 * o["rms_px"].toDouble());
    QVERIFY(std::abs(m.captured(5).toDouble() - o["seam_gap_px"].toDouble()) <=
            1e-2 * o["seam_gap_px"].toDouble() + 1e-12);
  }

  // warp --stats --json: the numbers of the file written and of the text report.
  void warpStatsJson() {
    const Run j = artcamCli({"warp", path("photo.png"), path("cam.artcam"), "-o",
                             path("wj.png"), "--size", "300x200", "--stats", "--json"});
    QVERIFY2(j.exit_code == 0, qPrintable(j.err));
    const QJsonObject o = jsonOf(j);
    QVERIFY2(!o.isEmpty(), qPrintable(j.out));
    QCOMPARE(o["output"].toString(), path("wj.png"));
    const auto written = readImage(path("wj.png").toStdString());
    QVERIFY(written.ok());
    QCOMPARE(o["width"].toInt(), 300);
    QCOMPARE(o["height"].toInt(), 200);
    QCOMPARE(written->image.width, 300);
    QCOMPARE(written->image.height, 200);
    const double ms = o["render_ms"].toDouble();
    QVERIFY(ms > 0);
    QVERIFY(std::abs(o["mpix_per_s"].toDouble() - 0.06 / (ms / 1000.0)) <=
            1e-9 * o["mpix_per_s"].toDouble());
    QVERIFY2(!j.err.contains("render_ms="), qPrintable(j.err));  // in the JSON instead

    const Run t = artcamCli({"warp", path("photo.png"), path("cam.artcam"), "-o",
                             path("wt.png"), "--size", "300x200"});
    QVERIFY2(t.exit_code == 0, qPrintable(t.err));
    QCOMPARE(t.out.trimmed(), "wrote " + path("wt.png") + " (300x200, " +
                                  o["description"].toString() + ")");
    QVERIFY(jsonOf(artcamCli({"warp", path("photo.png"), path("cam.artcam"), "-o",
                              path("wn.png"), "--json"}))
                .contains("description"));
  }

  // render --json: a cloud's point count against the PLY written and the closed form (27 cubes,
  // 6 faces, n² samples each); an image's size against the file and its counts against the text.
  void renderJson() {
    const Run ply = artcamCli(
        {"render", path("c.ply"), path("id.artcam"), "-o", path("rj.ply"), "--json"});
    QVERIFY2(ply.exit_code == 0, qPrintable(ply.err));
    const QJsonObject p = jsonOf(ply);
    QCOMPARE(p["output"].toString(), path("rj.ply"));
    QCOMPARE(p["points"].toInt(), 27 * 6 * 2 * 2);
    QCOMPARE(p["dropped"].toInt(), 0);
    const auto cloud = readPly(path("rj.ply").toStdString());
    QVERIFY(cloud.ok());
    QCOMPARE(static_cast<int>(cloud->size()), p["points"].toInt());

    const QStringList render = {"render", path("c.ply"), path("id.artcam"), "--size", "64x48"};
    const Run image = artcamCli(QStringList(render) << "-o" << path("rj.png") << "--json");
    QVERIFY2(image.exit_code == 0, qPrintable(image.err));
    const QJsonObject o = jsonOf(image);
    const auto written = readImage(path("rj.png").toStdString());
    QVERIFY(written.ok());
    QCOMPARE(o["width"].toInt(), written->image.width);
    QCOMPARE(o["height"].toInt(), written->image.height);
    QCOMPARE(o["width"].toInt(), 64);
    QCOMPARE(o["points"].toInt(), 27 * 6 * 2 * 2);
    QVERIFY(o["render_ms"].toDouble() > 0);
    const Run text = artcamCli(QStringList(render) << "-o" << path("rt.png"));
    QCOMPARE(text.out.trimmed(), QStringLiteral("wrote %1 (64x48, %2 points drawn, %3 dropped)")
                                     .arg(path("rt.png"))
                                     .arg(o["drawn"].toInt())
                                     .arg(o["dropped"].toInt()));
  }

  // batch --json: one entry per file (written or failed, with the error), totals that add up.
  void batchJson() {
    QVERIFY(QDir().mkpath(path("bj-in")));
    QVERIFY(test::writeNoisePhoto(path("bj-in/b.png"), 90, 60));
    QVERIFY(QFile::copy(path("photo.png"), path("bj-in/a.png")));
    const Run r = artcamCli({"batch", path("cam.artcam"), path("bj-in/a.png"),
                             path("bj-in/missing.png"), path("bj-in/b.png"), "-o", path("bj-out"),
                             "--json", "--quiet"});
    QCOMPARE(r.exit_code, 1);
    const QJsonObject o = jsonOf(r);
    QVERIFY2(!o.isEmpty(), qPrintable(r.out));
    const QJsonArray files = o["files"].toArray();
    QCOMPARE(files.size(), 3);
    QCOMPARE(files[0].toObject()["status"].toString(), "written");
    QCOMPARE(files[1].toObject()["status"].toString(), "failed");
    QVERIFY(files[1].toObject()["error"].toString().contains("missing.png"));
    QCOMPARE(files[2].toObject()["status"].toString(), "written");
    for (const int i : {0, 2}) {
      const QJsonObject f = files[i].toObject();
      const auto image = readImage(f["output"].toString().toStdString());
      QVERIFY(image.ok());
      QCOMPARE(f["width"].toInt(), image->image.width);
      QCOMPARE(f["height"].toInt(), image->image.height);
      QVERIFY(f["render_ms"].toDouble() > 0);
    }
    const QJsonObject totals = o["totals"].toObject();
    QCOMPARE(totals["files"].toInt(), 3);
    QCOMPARE(totals["written"].toInt(), 2);
    QCOMPARE(totals["failed"].toInt(), 1);
    QCOMPARE(totals["not_done"].toInt(), 0);
    double megapixels = 0.0;
    for (const int i : {0, 2}) {
      const QJsonObject f = files[i].toObject();
      megapixels += f["width"].toDouble() * f["height"].toDouble() / 1e6;
    }
    QVERIFY(std::abs(totals["megapixels"].toDouble() - megapixels) < 1e-9);
    QCOMPARE(o["interrupted"].toBool(), false);
  }
};

QTEST_GUILESS_MAIN(TestCliDialect)
#include "test_cli_dialect.moc"
