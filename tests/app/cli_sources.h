// SPDX-License-Identifier: Apache-2.0
// What the CLI's sources say it accepts, read from the files rather than from the program, so
// tests can hold the help pages, the manual page and the shell completions to it: the command
// table in app/cli/dispatch.cpp ({"name", "summary", kNameUsage, nameCommand}) and the
// OptionSpec literals ({"--name", "-x", takes_value}) in app/cli/cmd_<command>*.cpp.
// ARTCAM_SOURCE_DIR is defined for every test (tests/CMakeLists.txt).
#pragma once

#include <QFile>
#include <QRegularExpression>
#include <QString>
#include <QStringList>

namespace artcam::test {

inline const QString kCliDir = QStringLiteral(ARTCAM_SOURCE_DIR "/app/cli");

inline QString readText(const QString& path) {
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) return {};
  return QString::fromUtf8(f.readAll());
}

// Command names from the dispatcher's table.
inline QStringList commandsFromDispatch() {
  static const QRegularExpression row(
      QStringLiteral("\\{\"([a-z][a-z-]*)\",\\s*\"[^\"]*\",\\s*k\\w+Usage,"));
  QStringList names;
  for (auto it = row.globalMatch(readText(kCliDir + "/dispatch.cpp")); it.hasNext();)
    names << it.next().captured(1);
  return names;
}

// The source file stem of a command: "export-map" → "cmd_export_map".
inline QString commandStem(const QString& command) {
  return QStringLiteral("cmd_") + QString(command).replace('-', '_');
}

// Whether `base` (a cmd_*.cpp name without ".cpp") belongs to `command`: its own file, or a
// part cmd_<command>_<part> — unless that name is another command's own file (cmd_export_map
// is export-map's, not a part of export).
inline bool isSourceOf(const QString& base, const QString& command, const QStringList& commands) {
  const QString stem = commandStem(command);
  if (base == stem) return true;
  if (!base.startsWith(stem + '_')) return false;
  for (const QString& other : commands)
    if (other != command && commandStem(other) == base) return false;
  return true;
}

// Long and short option names of every OptionSpec literal in a source file.
inline QStringList optionsInSource(const QString& path) {
  static const QRegularExpression spec(
      QStringLiteral("\\{\"(--[a-z0-9][a-z0-9-]*)\",\\s*\"(-[A-Za-z0-9])?\",\\s*(true|false)\\}"));
  QStringList options;
  for (auto it = spec.globalMatch(readText(path)); it.hasNext();) {
    const QRegularExpressionMatch m = it.next();
    options << m.captured(1);
    if (!m.captured(2).isEmpty()) options << m.captured(2);
  }
  return options;
}

// Whole option names only: "--size" must not be satisfied by "--target-size" or "--sizes".
inline bool mentionsOption(const QString& text, const QString& option) {
  const QRegularExpression word(QStringLiteral("(^|[^A-Za-z0-9-])") +
                                QRegularExpression::escape(option) +
                                QStringLiteral("($|[^A-Za-z0-9-])"));
  return word.match(text).hasMatch();
}

}  // namespace artcam::test
