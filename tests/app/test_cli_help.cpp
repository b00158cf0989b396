// SPDX-License-Identifier: Apache-2.0
// `artcam --help` and every `artcam COMMAND --help` are complete: each option a command's parser
// accepts is named on its help page and in the manual page docs/man/artcam.1, and each page
// carries an example. The expected options are not taken from the help text (that is what is
// under test) but read from the sources: the command table in app/cli/dispatch.cpp and the
// OptionSpec lists ({"--name", "-x", takes_value}) in app/cli/cmd_<command>*.cpp, so an option
// added to a parser without documentation fails here.
#include "core/effects/effect_table.h"
#include "tests/app/cli_run.h"
#include "tests/app/cli_sources.h"

#include <QtTest/QtTest>

#include <QDir>
#include <QRegularExpression>
#include <QSet>

using artcam::test::artcamCli;
using artcam::test::commandsFromDispatch;
using artcam::test::kCliDir;
using artcam::test::mentionsOption;
using artcam::test::optionsInSource;
using artcam::test::readText;

namespace {

// One help page and the options it must document: cmd_<command>.cpp is checked against
// `artcam <command> --help`, cmd_<command>_<sub>.cpp against `artcam <command> <sub> --help`
// (bench fit, bench effects), so a sub-command's options are found on the page the user reaches.
struct HelpPage {
  QStringList invocation;
  QString source;
  QStringList options;
};

QList<HelpPage> helpPages(const QStringList& commands) {
  QList<HelpPage> pages;
  const QStringList sources = QDir(kCliDir).entryList({QStringLiteral("cmd_*.cpp")}, QDir::Files);
  for (const QString& command : commands) {
    const QString stem = artcam::test::commandStem(command);
    for (const QString& file : sources) {
      const QString base = file.chopped(4);  // without ".cpp"
      if (!artcam::test::isSourceOf(base, command, commands)) continue;
      QStringList invocation{command};
      if (base != stem) invocation << base.mid(stem.size() + 1);
      pages.append(
          {invocation << QStringLiteral("--help"), file, optionsInSource(kCliDir + '/' + file)});
    }
  }
  return pages;
}

// The manual page's text as a reader sees it: roff's "\-" is a plain hyphen-minus.
QString manPageText() {
  return readText(QStringLiteral(ARTCAM_SOURCE_DIR "/docs/man/artcam.1")).replace("\\-", "-");
}

}  // namespace

class TestCliHelp : public QObject {
  Q_OBJECT

 private slots:
  // The source scan itself: if the patterns stopped matching, every later check would pass
  // vacuously. These commands and options are the ones the user guide's tour uses.
  void sourceScanFindsKnownCommandsAndOptions() {
    const QStringList commands = commandsFromDispatch();
    for (const char* c :
         {"fit", "map", "warp", "info", "bench", "render", "preset", "compose", "insert", "sample"})
      QVERIFY2(commands.contains(QString::fromUtf8(c)), c);
    const QStringList warp = optionsInSource(kCliDir + "/cmd_warp.cpp");
    for (const char* o : {"--output", "-o", "--size", "--filter", "--threads", "--force"})
      QVERIFY2(warp.contains(QString::fromUtf8(o)), o);
    QVERIFY(optionsInSource(kCliDir + "/cmd_bench_effects.cpp").contains("--sigmas"));
    QVERIFY(mentionsOption("a --size b", "--size"));
    QVERIFY(!mentionsOption("a --target-size b", "--size"));
    QVERIFY(!mentionsOption("a --sizes b", "--size"));
  }

  void topLevelHelpListsEveryCommand() {
    const artcam::test::CliRun r = artcamCli({"--help"});
    QCOMPARE(r.exit_code, 0);
    for (const QString& c : commandsFromDispatch())
      QVERIFY2(r.out.contains(QStringLiteral("  ") + c + ' '),
               qPrintable(c + " missing from:\n" + r.out));
    QVERIFY2(r.out.contains("--version"), qPrintable(r.out));
    const artcam::test::CliRun version = artcamCli({"--version"});
    QCOMPARE(version.exit_code, 0);
    QVERIFY2(version.out.startsWith("artcam "), qPrintable(version.out));
  }

  void everyOptionIsOnItsHelpPage() {
    const QList<HelpPage> pages = helpPages(commandsFromDispatch());
    QVERIFY(pages.size() >= 12);  // ten commands plus bench fit and bench effects at least
    QStringList problems;         // all of them at once, so one run lists every gap
    for (const HelpPage& page : pages) {
      const QString call = QStringLiteral("artcam ") + page.invocation.join(' ');
      const artcam::test::CliRun r = artcamCli(page.invocation);
      if (r.exit_code != 0) problems << call + " exited " + QString::number(r.exit_code);
      if (!r.out.startsWith("usage: artcam ")) problems << call + " does not start with usage:";
      if (!r.out.contains("example", Qt::CaseInsensitive)) problems << call + " shows no example";
      for (const QString& option : page.options)
        if (!mentionsOption(r.out, option))
          problems << call + " does not mention " + option + " (accepted in " + page.source + ")";
    }
    QVERIFY2(problems.isEmpty(), qPrintable(problems.join('\n')));
  }

  void manPageNamesEveryCommandAndOption() {
    const QString man = manPageText();
    QVERIFY2(man.contains(".TH ARTCAM 1"), "docs/man/artcam.1 missing or without its title line");
    const QStringList commands = commandsFromDispatch();
    for (const QString& c : commands)
      QVERIFY2(man.contains(QStringLiteral(".SS ") + c),
               qPrintable("artcam.1 has no section for " + c));
    QStringList missing;
    for (const HelpPage& page : helpPages(commands))
      for (const QString& option : page.options)
        if (!mentionsOption(man, option)) missing << option + " of " + page.source;
    QVERIFY2(missing.isEmpty(),
             qPrintable("docs/man/artcam.1 does not mention " + missing.join(", ")));
  }

  // The image effects are core's table (effect_table.h), not OptionSpec literals: every effect
  // and each of its parameters must be on `artcam preset --help`, in artcam.1, and (names) in
  // `artcam preset list` beside the view and 3D presets, which keep their own table.
  void presetPagesListEveryTableEffect() {
    const artcam::test::CliRun help = artcamCli({"preset", "--help"});
    QCOMPARE(help.exit_code, 0);
    const artcam::test::CliRun list = artcamCli({"preset", "list"});
    QCOMPARE(list.exit_code, 0);
    const QString man = manPageText();
    const auto listed = [](const QString& text, const QString& name) {
      return text.contains(QRegularExpression(QStringLiteral("(^|\\n)  ") +
                                              QRegularExpression::escape(name) + QStringLiteral(" ")));
    };
    QVERIFY(artcam::effectSpecs().size() >= 8);
    QStringList problems;
    for (const artcam::EffectSpec& effect : artcam::effectSpecs()) {
      const QString name = QString::fromStdString(effect.name);
      if (!listed(help.out, name)) problems << name + " not on preset --help";
      if (!listed(list.out, name)) problems << name + " not in preset list";
      if (!man.contains(QStringLiteral(".B ") + name + '\n')) problems << name + " not in artcam.1";
      for (const artcam::EffectParam& p : effect.params) {
        const QString option = QStringLiteral("--") + QString::fromStdString(p.name);
        // On the help page, on the effect's own rows (after its name, before the next effect).
        const qsizetype at = help.out.indexOf(QStringLiteral("\n  ") + name + ' ');
        const QString rows = help.out.mid(at, help.out.indexOf(QRegularExpression("\n  [a-z]"), at + 1) - at);
        if (!mentionsOption(rows, option)) problems << option + " of " + name + " not on preset --help";
        const qsizetype man_at = man.indexOf(QStringLiteral(".B ") + name + '\n');
        const QString man_rows = man.mid(man_at, man.indexOf(QStringLiteral("\n.B "), man_at + 1) - man_at);
        if (!mentionsOption(man_rows, option)) problems << option + " of " + name + " not in artcam.1";
        if (!rows.contains(QString::fromStdString(artcam::rangeText(p))))
          problems << option + " of " + name + ": range not on preset --help";
      }
    }
    for (const char* other : {"pinhole", "xslit", "twist-3d", "chromatic-aberration-3d", "cube-of-cubes"})
      if (!listed(list.out, QString::fromUtf8(other))) problems << QString(other) + " not in preset list";
    QVERIFY2(problems.isEmpty(), qPrintable(problems.join('\n')));
  }

  // `artcam help CMD` is CMD's own page (what `artcam CMD --help` prints), for every command.
  void helpCommandPrintsThatCommandsPage() {
    for (const QString& command : commandsFromDispatch()) {
      const auto own = artcamCli({command, "--help"});
      const auto help = artcamCli({"help", command});
      QCOMPARE(help.exit_code, 0);
      QVERIFY2(help.out.startsWith("usage: artcam " + command), qPrintable(command));
      QCOMPARE(help.out, own.out);
    }
    QCOMPARE(artcamCli({"help", "bench", "effects"}).out,
             artcamCli({"bench", "effects", "--help"}).out);
    QCOMPARE(artcamCli({"help", "nosuch"}).exit_code, 2);
  }
};

QTEST_GUILESS_MAIN(TestCliHelp)
#include "test_cli_help.moc"
