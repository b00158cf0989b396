// SPDX-License-Identifier: Apache-2.0
// Files for the CLI process tests (batch, interruption, kill recovery): photos made in code,
// polling a folder while a process runs, and the hidden temporaries of atomic saves.
#pragma once

#include "core/io/image_io.h"
#include "tests/support/test_support.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QRegularExpression>
#include <QString>
#include <QStringList>
#include <QThread>

#include <functional>

namespace artcam::test {

// Smooth colour ramps plus noise: every pixel differs, so a wrong warp or a truncated file shows.
inline bool writeNoisePhoto(const QString& path, int width, int height) {
  ImageF image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        image.pixel(x, y)[c] =
            static_cast<float>(0.5 * (x + c * y) / (width + height) + uniform(0.0, 0.5));
  return writeImage(path.toStdString(), image).ok;
}

inline QByteArray fileBytes(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

// Hidden files: the ".name.tmp-<pid>-<n>.ext" temporaries of saves (core/io/atomic_file.h).
inline QStringList hiddenFiles(const QString& folder) {
  return QDir(folder)
      .entryList(QDir::Files | QDir::Hidden | QDir::NoDotAndDotDot)
      .filter(QRegularExpression("^\\."));
}
inline QStringList visibleFiles(const QString& folder) {
  return QDir(folder).entryList(QDir::Files | QDir::NoDotAndDotDot, QDir::Name);
}

// Polls every 5 ms until `done` or `limit_ms` (a guard against hanging, not a timing check).
inline bool waitUntil(const std::function<bool()>& done, int limit_ms = 120000) {
  QElapsedTimer clock;
  clock.start();
  while (!done()) {
    if (clock.elapsed() > limit_ms) return false;
    QThread::msleep(5);
  }
  return true;
}

}  // namespace artcam::test
