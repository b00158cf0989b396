#include "ui/image_loader.h"

#include <exception>

namespace artcam::ui {

ImageLoader::ImageLoader(QString path, QObject* parent) : QThread(parent), path_(std::move(path)) {
  qRegisterMetaType<PhotoPtr>();
}

ImageLoader::~ImageLoader() {
  cancel_ = true;
  wait();
}

void ImageLoader::run() {
  try {
    ReadImageOptions options;
    int last = -1;
    options.progress = [this, &last](double f) {
      const int percent = static_cast<int>(f * 90.0);  // the last 10 % are the reduced copies
      if (percent != last) {
        last = percent;
        emit progressChanged(percent);
      }
      return !cancel_.load();
    };
    Result<LoadedImage> result = readImage(path_.toStdString(), options);
    if (cancel_) return;
    if (!result) {
      emit failed(QString::fromStdString(result.status.message));
      return;
    }
    PhotoPtr photo = makePhoto(path_, std::move(*result.value));
    if (cancel_) return;
    emit progressChanged(100);
    emit loaded(std::move(photo));
  } catch (const std::exception& e) {
    emit failed(tr("Could not load %1: %2").arg(path_, QString::fromUtf8(e.what())));
  } catch (...) {
    emit failed(tr("Could not load %1: unknown error").arg(path_));
  }
}

}  // namespace artcam::ui
