// SPDX-License-Identifier: Apache-2.0
// Text inputs (core/io/text_input.h) are bounded: every reader of a camera, CSV, project or
// cloud refuses a named pipe, a device and a folder at once with one line naming the file,
// and a file larger than the cap before reading it. Each case runs the public readers, so a
// reader that bypassed the one bounded path would block (the FIFO) or read gigabytes.
#include "core/io/artcam_file.h"
#include "core/io/matches_csv.h"
#include "core/io/ply.h"
#include "core/io/text_input.h"
#include "core/project/studio_project.h"

#include <QtTest/QtTest>

#include <algorithm>
#include <chrono>
#include <functional>

#include <sys/stat.h>
#include <unistd.h>

using namespace artcam;

namespace {

// Every reader of text, by name, each returning its failure message ("" when it read).
std::vector<std::pair<const char*, std::function<std::string(const std::string&)>>> readers() {
  const auto message = [](const auto& result) {
    return result ? std::string() : result.status.message;
  };
  return {
      {"text", [=](const std::string& p) { return message(readTextInput(p)); }},
      {"camera", [=](const std::string& p) { return message(readArtcam(p)); }},
      {"matches", [=](const std::string& p) { return message(readMatchesCsv(p)); }},
      {"points", [=](const std::string& p) { return message(readPointsCsv(p)); }},
      {"lines", [=](const std::string& p) { return message(readLinesCsv(p)); }},
      {"samples", [=](const std::string& p) { return message(readColourSamplesCsv(p)); }},
      {"project", [=](const std::string& p) { return message(readStudioProject(p)); }},
      {"cloud", [=](const std::string& p) { return message(readPly(p)); }},
  };
}

// Runs every reader on `path` with a watchdog: alarm() ends the test program if one blocks.
void expectRefusedAtOnce(const std::string& path, const std::string& cause) {
  for (const auto& [name, read] : readers()) {
    ::alarm(10);
    const auto start = std::chrono::steady_clock::now();
    const std::string message = read(path);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ::alarm(0);
    const QString what =
        QString("%1 reader on %2: \"%3\"").arg(name, path.c_str(), message.c_str());
    QVERIFY2(!message.empty(), qPrintable(what + ": read"));
    QVERIFY2(message.rfind(path + ": cannot read: ", 0) == 0, qPrintable(what));
    QVERIFY2(message.find(cause) != std::string::npos,
             qPrintable(what + " lacks " + cause.c_str()));
    QVERIFY2(message.find('\n') == std::string::npos, qPrintable(what));
    QVERIFY2(seconds < 1.0, qPrintable(what + QString(": took %1 s").arg(seconds)));
  }
}

}  // namespace

class TestTextInput : public QObject {
  Q_OBJECT

 private slots:
  void aNamedPipeIsRefusedWithoutWaitingForAWriter() {
    QTemporaryDir dir;
    const std::string fifo = dir.filePath("camera.artcam").toStdString();
    QCOMPARE(::mkfifo(fifo.c_str(), 0600), 0);
    expectRefusedAtOnce(fifo, "named pipe");
  }

  void aDeviceIsRefusedWithoutReadingIt() {
    // /dev/zero never ends: reading it whole grows to the address-space limit.
    expectRefusedAtOnce("/dev/zero", "a device");
  }

  void aFolderIsRefused() {
    QTemporaryDir dir;
    expectRefusedAtOnce(dir.path().toStdString(), "a folder");
  }

  void aFileOverTheCapIsRefusedBeforeItIsRead() {
    // Sparse: a file that size costs nothing on disk, and the refusal must not read it.
    QTemporaryDir dir;
    const std::string path = dir.filePath("huge.csv").toStdString();
    const off_t size = static_cast<off_t>(kMaxTextInputBytes) + 1;
    QFile f(QString::fromStdString(path));
    QVERIFY(f.open(QIODevice::WriteOnly));
    QVERIFY(f.resize(size));
    f.close();
    const auto start = std::chrono::steady_clock::now();
    const Result<std::string> text = readTextInput(path);
    QVERIFY(!text);
    QVERIFY2(text.status.message.find("64.0 MiB") != std::string::npos,
             text.status.message.c_str());
    QVERIFY(std::chrono::steady_clock::now() - start < std::chrono::milliseconds(200));
    const Result<std::vector<PointMatch>> matches = readMatchesCsv(path);
    QVERIFY(!matches);
    QVERIFY2(matches.status.message.find("a text input may hold") != std::string::npos,
             matches.status.message.c_str());
  }

  void aFileWithinTheCapReadsWhole() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("m.csv").toStdString();
    QFile f(QString::fromStdString(path));
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("src_x,src_y,dst_x,dst_y\n1,2,3,4\n");
    f.close();
    const Result<std::string> text = readTextInput(path);
    QVERIFY2(text, text.status.message.c_str());
    QCOMPARE(*text, std::string("src_x,src_y,dst_x,dst_y\n1,2,3,4\n"));
    TextInputOptions small;
    small.max_bytes = 10;
    QVERIFY(!readTextInput(path, small));
  }

  void manyLinesParseInLinearTime() {
    // Lines of one point each: a search of the lines so far per row took 29 s for 200 000. The
    // bound is on growth, not on seconds, so that it holds under a sanitizer's slow allocator
    // too: eight times the lines must take well under the 64 times a quadratic parse would.
    const auto linesText = [](int count) {
      std::string text = "line,x,y\n";
      for (int k = 0; k < count; ++k)
        text += "L" + std::to_string(k) + "," + std::to_string(k % 64) + ".5,1.5\n";
      return text + "L7,3.5,2.5\n";  // a later row of an early line joins it
    };
    const auto fastestParse = [](const std::string& text, int count) {
      double best = 1e9;
      for (int round = 0; round < 3; ++round) {
        const auto start = std::chrono::steady_clock::now();
        const Result<std::vector<LineTrace>> lines = parseLinesCsv(text, "many.csv");
        best = std::min(
            best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        if (!lines || lines->size() != size_t(count)) return -1.0;
      }
      return best;
    };
    const int few = 5000, many = 40000;
    const std::string text = linesText(many);
    const Result<std::vector<LineTrace>> lines = parseLinesCsv(text, "many.csv");
    QVERIFY2(lines, lines.status.message.c_str());
    QCOMPARE(lines->size(), size_t(many));
    QCOMPARE((*lines)[7].label, std::string("L7"));
    QCOMPARE((*lines)[7].points.size(), size_t{2});
    QCOMPARE((*lines)[7].points[1].x(), 3.5);
    QCOMPARE(lines->back().label, "L" + std::to_string(many - 1));
    const double few_seconds = fastestParse(linesText(few), few);
    const double many_seconds = fastestParse(text, many);
    QVERIFY(few_seconds > 0 && many_seconds > 0);
    QVERIFY2(many_seconds < 24 * few_seconds,
             qPrintable(QString("%1 lines took %2 s, %3 lines %4 s")
                            .arg(few)
                            .arg(few_seconds)
                            .arg(many)
                            .arg(many_seconds)));
  }

  void aMissingFileSaysSo() {
    const Result<std::string> text = readTextInput("/nonexistent/cam.artcam");
    QVERIFY(!text);
    QCOMPARE(text.status.message,
             std::string("/nonexistent/cam.artcam: cannot read: no such file"));
  }
};

QTEST_GUILESS_MAIN(TestTextInput)
#include "test_text_input.moc"
