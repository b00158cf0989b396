// SPDX-License-Identifier: Apache-2.0
// What the binding's files share: the camera value as Python holds it, refusals as Python
// exceptions carrying the CLI's messages, and keyword options read in the CLI's own words.
#pragma once

#include "app/cli/args.h"
#include "core/model/artcam.h"
#include "core/model/status.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <nlohmann/json.hpp>

#include <memory>
#include <string>
#include <vector>

namespace artcam::python {

namespace py = pybind11;

// An immutable camera value and the name its messages use (its file, or "<camera>").
struct PyCamera {
  std::shared_ptr<const Artcam> camera;
  std::string name;
};

// FileNotFoundError / PermissionError / OSError with `message` as its text (the CLI's line).
[[noreturn]] void raiseOSError(const std::string& message);
// A failed read of `path`: FileNotFoundError when it is missing, PermissionError when it cannot
// be opened, else ValueError (the file is there and says something wrong).
[[noreturn]] void raiseReadError(const std::string& path, const std::string& message);
[[noreturn]] void raiseValueError(const std::string& message);

// Keyword options → the CLI's argv ("bit_depth=16" → "--bit-depth 16"; True → the bare flag;
// None and False → left out), parsed by the CLI's own parser against `specs`, so Python accepts
// and refuses exactly what the command line does, with its messages.
// A JSON report of the CLI (app/cli/reports.h) as the Python dict/list/str/number it reads as.
py::object fromJson(const nlohmann::json& value);

// (width, height) from 1 to 2^20, as every size option takes it; ValueError naming `what`.
FrameSize sizeArgument(const py::handle& size, const char* what);

// A str or os.PathLike as a path.
bool isPathLike(const py::handle& value);
std::string pathOf(const py::handle& value);

cli::Args argsFromKeywords(const py::dict& options, const std::vector<cli::OptionSpec>& specs,
                           std::vector<std::string> positional = {});

void registerCameras(py::module_& m);
void registerImages(py::module_& m);
void registerBatch(py::module_& m);
void registerFitting(py::module_& m);
void registerLenses(py::module_& m);
void registerExports(py::module_& m);
void registerPresets(py::module_& m);

}  // namespace artcam::python

namespace artcam::python {

// Camera.warp (images.cpp), bound on the Camera class (cameras.cpp).
py::array warpArray(const PyCamera& camera, const py::array& image, const py::object& depth,
                    const py::object& size, const std::string& filter, const std::string& edge,
                    bool alpha, int threads, const py::object& out, const py::object& finish);

}  // namespace artcam::python
