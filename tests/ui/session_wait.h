// SPDX-License-Identifier: Apache-2.0
// The session's reads and writes run off the GUI thread and end with a signal: these helpers
// start one and wait for that signal, for tests that go on with the file.
#pragma once

#include "ui/session.h"

#include <QSignalSpy>
#include <QString>

namespace artcam::ui::test {

// Saves the project and waits for projectSaved; true when it was written.
inline bool saveAndWait(Session& session, const QString& path, int timeout_ms = 20000) {
  QSignalSpy saved(&session, &Session::projectSaved);
  if (!session.saveProjectTo(path)) return false;
  if (saved.isEmpty() && !saved.wait(timeout_ms)) return false;
  return saved.front().at(0).toBool();
}

// Session::save() (the project's own path) and waits; true when it was written.
inline bool saveOwnAndWait(Session& session, int timeout_ms = 20000) {
  QSignalSpy saved(&session, &Session::projectSaved);
  if (!session.save()) return false;
  if (saved.isEmpty() && !saved.wait(timeout_ms)) return false;
  return saved.front().at(0).toBool();
}

// Imports an .artcam onto the open photo and waits for importFinished; true when imported.
inline bool importAndWait(Session& session, const QString& path, int timeout_ms = 20000) {
  QSignalSpy finished(&session, &Session::importFinished);
  session.importArtcam(path);
  if (finished.isEmpty() && !finished.wait(timeout_ms)) return false;
  return finished.front().at(0).toBool();
}

// Starts a file export (`start` returns whether it started) and waits for fileWritten.
template <class Start>
bool writeAndWait(Session& session, Start start, int timeout_ms = 20000) {
  QSignalSpy written(&session, &Session::fileWritten);
  if (!start()) return false;
  if (written.isEmpty() && !written.wait(timeout_ms)) return false;
  return written.front().at(0).toBool();
}

}  // namespace artcam::ui::test
