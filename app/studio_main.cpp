// artcam-studio: the GUI. Thin: application setup and optional files to open; the work is in
// ui/ (MainWindow) and core/.
#include "ui/main_window.h"
#include "ui/session.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QStringList>

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  QApplication::setOrganizationName("ARTcam");
  QApplication::setApplicationName("ARTcam Studio");
  QApplication::setApplicationVersion("0.1.0");

  QCommandLineParser parser;
  parser.setApplicationDescription("Warp photographs through an ARTcam camera.");
  parser.addHelpOption();
  parser.addVersionOption();
  parser.addPositionalArgument("file",
                               "A photo, project (.artcamproj) or camera (.artcam) to open.");
  parser.process(app);

  artcam::ui::MainWindow window;
  window.show();
  const QStringList files = parser.positionalArguments();
  if (!files.isEmpty())
    window.session()->openPath(files.front());  // a project's own recovery is offered there
  else
    window.session()->offerRecovery();  // work left by a session that did not close cleanly
  return QApplication::exec();
}
