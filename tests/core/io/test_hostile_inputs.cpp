// SPDX-License-Identifier: Apache-2.0
// Replays every input of the checked-in fuzz corpus (fuzz/corpus/<reader>/: seeds made from
// resources/ and the grammars, plus every nasty input the fuzzers found) through the file
// readers of the normal build. Each must parse or be refused with ONE line that names the file
// and gives a cause; a crash, hang (CTest's timeout) or giant allocation (ASan/RSS) fails the
// test. Known nasty inputs must also be refused for the reason they were kept.
// The fuzz targets themselves are in fuzz/ (a clang build, docs/robustness.md, "Fuzzing").
#include "core/io/artcam_file.h"
#include "core/io/matches_csv.h"
#include "core/io/ply.h"
#include "core/io/walls_csv.h"

#include <QtTest/QtTest>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace artcam;
namespace fs = std::filesystem;

namespace {

struct Outcome {
  bool ok = false;
  std::string message;
  size_t items = 0;  // points, matches, tensors…: what a success produced
};

using Reader = std::function<Outcome(const std::string& path)>;

template <class T>
Outcome outcomeOf(const Result<T>& r, size_t items) {
  return {r.ok(), r.status.message, r.ok() ? items : 0};
}

std::vector<fs::path> corpusFiles(const std::string& reader) {
  std::vector<fs::path> files;
  for (const auto& entry :
       fs::directory_iterator(fs::path(ARTCAM_SOURCE_DIR) / "fuzz/corpus" / reader))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The fuzz targets pick the variant the same way (a text starting "line" is a traced-lines CSV)
// (fuzz/fuzz_matches_csv.cpp, fuzz_colour_csv.cpp).
int matchDimension(const std::string& text) {
  return text.find("src_z") != std::string::npos ? 3 : 2;
}
ColourEncoding colourEncoding(const std::string& text) {
  return text.size() % 2 ? ColourEncoding::Srgb : ColourEncoding::Linear;
}

std::map<std::string, Reader> readers() {
  return {
      {"artcam",
       [](const std::string& p) {
         const auto r = readArtcam(p);
         return outcomeOf(r, r.ok() ? r->layers.size() : 0);
       }},
      {"piecewise",
       [](const std::string& p) {
         const auto r = readArtcam(p);
         return outcomeOf(r, r.ok() ? 1 + (r->pieces ? r->pieces->patches.size() : 0)
                                    : 0);  // the whole camera + patches
       }},
      {"matches_csv",
       [](const std::string& p) {
         const std::string text = slurp(p);
         if (text.rfind("line", 0) == 0) {
           const auto r = readLinesCsv(p);
           return outcomeOf(r, r.ok() ? r->size() : 0);
         }
         const auto r = readMatchesCsv(p, matchDimension(text));
         return outcomeOf(r, r.ok() ? r->size() : 0);
       }},
      {"colour_csv",
       [](const std::string& p) {
         const auto r = readColourSamplesCsv(p, colourEncoding(slurp(p)));
         return outcomeOf(r, r.ok() ? r->size() : 0);
       }},
      {"walls_csv",
       [](const std::string& p) {
         const auto r = readWallsCsv(p);
         return outcomeOf(r, r.ok() ? r->size() : 0);
       }},
      {"ply",
       [](const std::string& p) {
         const auto r = readPly(p);
         return outcomeOf(r, r.ok() ? r->positions.size() : 0);
       }},
  };
}

}  // namespace

class TestHostileInputs : public QObject {
  Q_OBJECT

 private slots:
  void corpus_data() {
    QTest::addColumn<QString>("reader");
    QTest::addColumn<QString>("file");
    for (const auto& [reader, read] : readers()) {
      const std::vector<fs::path> files = corpusFiles(reader);
      // Seeds of every reader are checked in; an empty folder means the corpus went missing.
      QVERIFY2(files.size() >= 3, ("fuzz/corpus/" + reader + " has fewer than 3 inputs").c_str());
      for (const fs::path& f : files)
        QTest::newRow((reader + "/" + f.filename().string()).c_str())
            << QString::fromStdString(reader) << QString::fromStdString(f.string());
    }
  }

  // Parse, or one line naming the file with a cause after it. A parsed file yields no more
  // items than it has bytes (the readers check counts against the size before allocating).
  void corpus() {
    QFETCH(QString, reader);
    QFETCH(QString, file);
    const std::string path = file.toStdString();
    const Outcome outcome = readers().at(reader.toStdString())(path);
    if (outcome.ok) {
      QVERIFY(outcome.items <= fs::file_size(path));
      return;
    }
    QVERIFY2(outcome.message.rfind(path + ":", 0) == 0, outcome.message.c_str());
    QVERIFY2(outcome.message.size() > path.size() + 3, outcome.message.c_str());
    QVERIFY2(outcome.message.find('\n') == std::string::npos, outcome.message.c_str());
  }

  // Every seed (a valid file of some shape) parses; only nasty-* inputs may be refused.
  void seedsParse() {
    for (const auto& [reader, read] : readers())
      for (const fs::path& f : corpusFiles(reader)) {
        if (f.filename().string().rfind("seed-", 0) != 0) continue;
        const Outcome outcome = read(f.string());
        QVERIFY2(outcome.ok, outcome.message.c_str());
        QVERIFY2(outcome.items > 0, f.string().c_str());
      }
  }

  // The known nasty inputs are refused for the reason they were kept (the cause is named).
  void nastyRefusedForTheirReason_data() {
    QTest::addColumn<QString>("reader");
    QTest::addColumn<QString>("name");
    QTest::addColumn<QString>("cause");
    const auto row = [](const char* reader, const char* name, const char* cause) {
      QTest::newRow(name) << reader << name << cause;
    };
    row("artcam", "nasty-deep-nesting.artcam", "nested deeper than 64 levels");
    row("artcam", "nasty-deep-object.artcam", "nested deeper than 64 levels");
    row("artcam", "nasty-overflow.artcam", "not a finite number: 1e999");
    row("artcam", "nasty-nan.artcam", "invalid JSON");
    row("artcam", "nasty-giant-frame.artcam",
        "/frames/source/0: number out of range: 2147483648 (at most 1048576)");
    row("artcam", "nasty-frame-negative.artcam",
        "/frames/source/0: expected a whole number of at least 0, found -1");
    row("artcam", "nasty-empty-rows.artcam",
        "/stages/0/tensors/0/0: expected 9000 numbers, found 0");
    row("artcam", "nasty-kind-newline.artcam", "/blocks/0/kind: unknown block kind \"posi\\ntion\"");
    row("artcam", "nasty-version.artcam", "/version: expected a whole number, found");
    row("piecewise", "nasty-model-not-string.artcam", "/patches/0/model: expected a string");
    row("piecewise", "nasty-deep-camera.artcam", "nested deeper than 64 levels");
    row("matches_csv", "nasty-out-of-range.csv", ":2: column 1 (src_x): out of range for a double");
    row("matches_csv", "nasty-inf.csv", ":2: column 1 (src_x): not a finite number");
    row("matches_csv", "nasty-commas.csv", ":2: expected 4 numbers, found 5001");
    row("colour_csv", "nasty-srgb-huge.csv", ":2: column 1 (src_r): \"1e308\" is beyond any coordinate");
    row("ply", "nasty-trillion-vertices.ply", "claims 1000000000000 entries");
    row("ply", "nasty-count-overflow.ply",
        "claims 18446744073709551615 entries (at least 2^64 bytes)");
    row("ply", "nasty-list-count.ply", "list v of 4294967295 items runs past the end of the file");
  }

  void nastyRefusedForTheirReason() {
    QFETCH(QString, reader);
    QFETCH(QString, name);
    QFETCH(QString, cause);
    const fs::path path =
        fs::path(ARTCAM_SOURCE_DIR) / "fuzz/corpus" / reader.toStdString() / name.toStdString();
    QVERIFY2(fs::exists(path), path.c_str());
    const Outcome outcome = readers().at(reader.toStdString())(path.string());
    QVERIFY2(!outcome.ok, name.toUtf8().constData());
    QVERIFY2(outcome.message.find(cause.toStdString()) != std::string::npos,
             outcome.message.c_str());
  }
};

QTEST_GUILESS_MAIN(TestHostileInputs)
#include "test_hostile_inputs.moc"
