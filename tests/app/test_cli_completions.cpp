// SPDX-License-Identifier: Apache-2.0
// The shell completions in packaging/completions/ (artcam.bash for bash, _artcam for zsh) offer
// every command and every option each command's parser accepts. The expected names are read
// from the sources (tests/app/cli_sources.h: the dispatcher's table and the OptionSpec lists),
// and the preset names and parameters from core's effects table, never from the completion
// files themselves. The bash file is exercised as bash runs it: sourced in `bash -c`, its
// function called with COMP_WORDS/COMP_CWORD as on a TAB press. The zsh file is checked as text
// (each command's branch names its options), since zsh is not among the build dependencies.
#include "core/effects/effect_table.h"
#include "tests/app/cli_sources.h"

#include <QtTest/QtTest>

#include <QDir>
#include <QProcess>
#include <QStandardPaths>

using artcam::test::commandsFromDispatch;
using artcam::test::kCliDir;
using artcam::test::mentionsOption;
using artcam::test::optionsInSource;
using artcam::test::readText;

namespace {

const QString kBashFile = QStringLiteral(ARTCAM_SOURCE_DIR "/packaging/completions/artcam.bash");
const QString kZshFile = QStringLiteral(ARTCAM_SOURCE_DIR "/packaging/completions/_artcam");
const QString kFishFile = QStringLiteral(ARTCAM_SOURCE_DIR "/packaging/completions/artcam.fish");

// Option values as the manual page (docs/man/artcam.1) documents them: each row an option of a
// page and the words its parser accepts, written here by hand, never read from a completion file
// or from the --help text the completions parse.
struct ValueRow {
  QStringList words;
  QString option;
  QStringList values;
};
const QList<ValueRow> kValueRows = {
    {{"warp"}, "--filter", {"nearest", "bilinear", "bicubic"}},
    {{"warp"}, "--edge", {"transparent", "extend", "black"}},
    {{"batch"}, "--subsampling", {"444", "422", "420"}},
    {{"export"}, "--bit-depth", {"8", "16", "half", "float"}},
    {{"export-map"}, "--convention", {"stmap", "opencv"}},
};

// One completion page: the words that reach it after `artcam` and the options its parser takes.
// bench is the one command with sub-commands: cmd_bench.cpp is `bench render` (also bench with
// no sub-command), cmd_bench_<sub>.cpp `bench <sub>`. Any other cmd_<command>_<part>.cpp is a
// piece of <command>'s parser (fit's piecewise options), so its options join that page.
struct Page {
  QStringList words;
  QStringList options;
};

QList<Page> pagesFromSources() {
  QList<Page> pages;
  const QStringList files = QDir(kCliDir).entryList({QStringLiteral("cmd_*.cpp")}, QDir::Files);
  const QStringList commands = commandsFromDispatch();
  for (const QString& command : commands) {
    const QString stem = artcam::test::commandStem(command);
    Page own{{command}, {}};
    for (const QString& file : files) {
      const QString base = file.chopped(4);  // without ".cpp"
      if (!artcam::test::isSourceOf(base, command, commands)) continue;
      const QStringList options = optionsInSource(kCliDir + '/' + file);
      if (command == QStringLiteral("bench"))
        pages.append({{command, base == stem ? QStringLiteral("render") : base.mid(stem.size() + 1)},
                      options});
      else
        own.options << options;
    }
    if (command != QStringLiteral("bench")) pages.append(own);
  }
  return pages;
}

// What bash's completion offers for the words typed so far (the last one being completed).
QStringList bashComplete(const QStringList& words, QString* registration = nullptr) {
  const QString script = QStringLiteral(
      "source \"$1\" || exit 3\n"
      "complete -p artcam >&2\n"
      "shift\n"
      "COMP_WORDS=(\"$@\"); COMP_CWORD=$(( $# - 1 )); COMPREPLY=()\n"
      "_artcam\n"
      "printf '%s\\n' \"${COMPREPLY[@]}\"\n");
  QProcess bash;
  bash.start(QStringLiteral("bash"), QStringList{"-c", script, "bash", kBashFile} + words);
  if (!bash.waitForFinished(60000) || bash.exitCode() != 0) return {QStringLiteral("<bash failed>")};
  if (registration) *registration = QString::fromUtf8(bash.readAllStandardError()).trimmed();
  return QString::fromUtf8(bash.readAllStandardOutput()).split('\n', Qt::SkipEmptyParts);
}

// What fish offers for a command line ending in the given (possibly empty) word, with the
// completion file loaded; empty when fish is not installed.
QStringList fishComplete(const QString& line) {
  QProcess fish;
  fish.start(QStringLiteral("fish"),
             {QStringLiteral("--no-config"), QStringLiteral("-c"),
              QStringLiteral("source $argv[1]; and complete -C $argv[2]"), kFishFile, line});
  if (!fish.waitForFinished(60000) || fish.exitCode() != 0)
    return {QStringLiteral("<fish failed: ") + QString::fromUtf8(fish.readAllStandardError()) +
            '>'};
  QStringList words;
  for (const QString& row :
       QString::fromUtf8(fish.readAllStandardOutput()).split('\n', Qt::SkipEmptyParts))
    words << row.section('\t', 0, 0);
  return words;
}

// The text of a `(label)` branch of a zsh case statement at the given indentation, up to the
// next branch at that indentation.
QString zshBranch(const QString& text, const QString& label, int indent,
                  qsizetype from = 0) {
  const QString pad(indent, ' ');
  const qsizetype at = text.indexOf('\n' + pad + '(' + label + ')', from);
  if (at < 0) return {};
  const qsizetype next =
      text.indexOf(QRegularExpression(QStringLiteral("\n") + pad + QStringLiteral("\\(")), at + 1);
  return text.mid(at, next < 0 ? -1 : next - at);
}

}  // namespace

class TestCliCompletions : public QObject {
  Q_OBJECT

 private slots:
  // The page map itself: without it every later check could pass on an empty list.
  void sourcesGiveThePages() {
    const QList<Page> pages = pagesFromSources();
    QVERIFY(pages.size() >= 13);  // eleven commands, bench as render, fit and effects
    bool warp = false, bench_fit = false;
    for (const Page& p : pages) {
      if (p.words == QStringList{"warp"}) warp = p.options.contains("--depth-scale");
      if (p.words == QStringList{"bench", "fit"}) bench_fit = p.options.contains("--counts");
    }
    QVERIFY(warp);
    QVERIFY(bench_fit);
  }

  void bashRegistersAndCompletesAPrefix() {
    QString registration;
    QCOMPARE(bashComplete({"artcam", "wa"}, &registration), QStringList{"warp"});
    QCOMPARE(registration, QStringLiteral("complete -F _artcam artcam"));
    QCOMPARE(bashComplete({"artcam", "bench", "ef"}), QStringList{"effects"});
    QCOMPARE(bashComplete({"artcam", "warp", "--depth-s"}), QStringList{"--depth-scale"});
  }

  void bashOffersEveryCommandAndOption() {
    const QStringList top = bashComplete({"artcam", ""});
    QStringList problems;
    for (const QString& c : commandsFromDispatch())
      if (!top.contains(c)) problems << "artcam <TAB> does not offer " + c;
    for (const Page& page : pagesFromSources()) {
      const QStringList offered = bashComplete(QStringList{"artcam"} + page.words + QStringList{"-"});
      for (const QString& option : page.options)
        if (!offered.contains(option))
          problems << "artcam " + page.words.join(' ') + " -<TAB> does not offer " + option;
    }
    QVERIFY2(problems.isEmpty(), qPrintable(problems.join('\n')));
  }

  // Preset names and parameters come from `artcam preset list` at completion time: each row of
  // the effects table is offered, and each of its parameters after its name.
  void bashOffersEveryTableEffectAndParameter() {
    const QString cli = QStringLiteral(ARTCAM_CLI_PATH);
    const QStringList names = bashComplete({cli, "preset", ""});
    QVERIFY2(names.contains("list") && names.contains("cube-of-cubes"), qPrintable(names.join(' ')));
    QVERIFY(artcam::effectSpecs().size() >= 8);
    QStringList problems;
    for (const artcam::EffectSpec& effect : artcam::effectSpecs()) {
      const QString name = QString::fromStdString(effect.name);
      if (!names.contains(name)) problems << "artcam preset <TAB> does not offer " + name;
      const QStringList offered = bashComplete({cli, "preset", name, "--"});
      for (const artcam::EffectParam& p : effect.params)
        if (!offered.contains(QStringLiteral("--") + QString::fromStdString(p.name)))
          problems << "artcam preset " + name + " --<TAB> does not offer --" +
                          QString::fromStdString(p.name);
      if (offered.count(QStringLiteral("--size")) != 1)
        problems << "artcam preset " + name + " --<TAB> offers --size " +
                        QString::number(offered.count(QStringLiteral("--size"))) + " times";
    }
    QVERIFY2(problems.isEmpty(), qPrintable(problems.join('\n')));
  }

  // After an option that takes one of a few words, bash offers those words.
  void bashOffersOptionValues() {
    const QString cli = QStringLiteral(ARTCAM_CLI_PATH);
    QStringList problems;
    for (const ValueRow& row : kValueRows) {
      const QStringList offered =
          bashComplete(QStringList{cli} + row.words + QStringList{row.option, ""});
      for (const QString& v : row.values)
        if (!offered.contains(v))
          problems << "artcam " + row.words.join(' ') + ' ' + row.option +
                          " <TAB> does not offer " + v + " (offers: " + offered.join(' ') + ')';
    }
    QCOMPARE(bashComplete({cli, "warp", "--edge", "ex"}), QStringList{"extend"});
    QVERIFY2(problems.isEmpty(), qPrintable(problems.join('\n')));
  }

  // fish: the same commands, every option of every page, and the option values.
  void fishOffersCommandsOptionsAndValues() {
    if (QStandardPaths::findExecutable(QStringLiteral("fish")).isEmpty())
      QFAIL("fish is not installed (packaging/install-deps.sh installs it; a missing peer is a failed check, not a pass)");
    const QString cli = QStringLiteral(ARTCAM_CLI_PATH);
    QStringList problems;
    const QStringList top = fishComplete(cli + ' ');
    for (const QString& c : commandsFromDispatch())
      if (!top.contains(c)) problems << "fish: artcam <TAB> does not offer " + c;
    for (const Page& page : pagesFromSources()) {
      const QStringList offered = fishComplete(cli + ' ' + page.words.join(' ') + " -");
      for (const QString& option : page.options)
        if (!offered.contains(option))
          problems << "fish: artcam " + page.words.join(' ') + " -<TAB> does not offer " + option;
    }
    for (const ValueRow& row : kValueRows) {
      const QStringList offered =
          fishComplete(cli + ' ' + row.words.join(' ') + ' ' + row.option + ' ');
      for (const QString& v : row.values)
        if (!offered.contains(v))
          problems << "fish: artcam " + row.words.join(' ') + ' ' + row.option +
                          " <TAB> does not offer " + v;
    }
    const QStringList presets = fishComplete(cli + " preset ");
    if (!presets.contains(QStringLiteral("cube-of-cubes")))
      problems << "fish: artcam preset <TAB> does not offer cube-of-cubes";
    QVERIFY2(problems.isEmpty(), qPrintable(problems.join('\n')));
  }

  void zshNamesEveryCommandAndOption() {
    const QString zsh = readText(kZshFile);
    QVERIFY2(zsh.startsWith("#compdef artcam\n"), "_artcam must open with #compdef artcam");
    QStringList problems;
    for (const QString& c : commandsFromDispatch())
      if (!zsh.contains(QStringLiteral("\n    '") + c + ':')) problems << c + " not in commands";
    const QString bench = zshBranch(zsh, QStringLiteral("bench"), 4);
    QVERIFY(!bench.isEmpty());
    for (const Page& page : pagesFromSources()) {
      QString branch;
      if (page.words.first() != QStringLiteral("bench"))
        branch = zshBranch(zsh, page.words.first(), 4);
      else if (page.words.last() == QStringLiteral("render"))
        branch = zshBranch(bench, QStringLiteral("*"), 8);  // bench render is bench's default
      else
        branch = zshBranch(bench, page.words.last(), 8);
      if (branch.isEmpty()) problems << "no branch for " + page.words.join(' ');
      for (const QString& option : page.options)
        if (!mentionsOption(branch, option))
          problems << "zsh: artcam " + page.words.join(' ') + " does not name " + option;
    }
    QVERIFY2(problems.isEmpty(), qPrintable(problems.join('\n')));
    // Where zsh is installed, the file must at least parse.
    if (!QStandardPaths::findExecutable(QStringLiteral("zsh")).isEmpty()) {
      QProcess z;
      z.start(QStringLiteral("zsh"), {QStringLiteral("-n"), kZshFile});
      QVERIFY(z.waitForFinished(60000));
      QVERIFY2(z.exitCode() == 0, qPrintable(QString::fromUtf8(z.readAllStandardError())));
    }
  }
};

QTEST_GUILESS_MAIN(TestCliCompletions)
#include "test_cli_completions.moc"
