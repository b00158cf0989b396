// SPDX-License-Identifier: Apache-2.0
// artcam._artcam: the extension behind `import artcam` (python/artcam/__init__.py re-exports it).
#include "app/cli/commands.h"
#include "python/src/common.h"

#include <filesystem>
#include <fstream>
#include <string_view>

namespace artcam::python {

void raiseOSError(const std::string& message) {
  PyErr_SetString(PyExc_OSError, message.c_str());
  throw py::error_already_set();
}

void raiseReadError(const std::string& path, const std::string& message) {
  std::error_code ec;
  PyObject* type = PyExc_ValueError;
  if (!std::filesystem::exists(path, ec))
    type = PyExc_FileNotFoundError;
  else if (std::filesystem::is_directory(path, ec))
    type = PyExc_IsADirectoryError;
  else if (!std::ifstream(path).good())
    type = PyExc_PermissionError;
  PyErr_SetString(type, message.c_str());
  throw py::error_already_set();
}

void raiseValueError(const std::string& message) { throw py::value_error(message); }

py::object fromJson(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

FrameSize sizeArgument(const py::handle& size, const char* what) {
  const auto wh = size.cast<std::pair<long long, long long>>();
  constexpr long long kMax = 1 << 20;
  if (wh.first < 1 || wh.second < 1 || wh.first > kMax || wh.second > kMax)
    raiseValueError(std::string(what) + " expects (width, height) from 1 to 2^20");
  return {static_cast<int>(wh.first), static_cast<int>(wh.second)};
}

bool isPathLike(const py::handle& value) {
  return py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__");
}

std::string pathOf(const py::handle& value) {
  return py::module_::import("os").attr("fspath")(value).cast<std::string>();
}

cli::Args argsFromKeywords(const py::dict& options, const std::vector<cli::OptionSpec>& specs,
                           std::vector<std::string> positional) {
  std::vector<std::string> argv = std::move(positional);
  for (const auto& [key, value] : options) {
    if (value.is_none()) continue;
    std::string name = "--" + py::str(key).cast<std::string>();
    for (char& c : name)
      if (c == '_') c = '-';
    bool known = false;
    for (const cli::OptionSpec& spec : specs) known = known || spec.name == name;
    if (!known)
      throw py::type_error("unexpected keyword argument '" + py::str(key).cast<std::string>() +
                           "'");
    if (py::isinstance<py::bool_>(value)) {
      if (value.cast<bool>()) argv.push_back(name);
      continue;
    }
    argv.push_back(name);
    if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {
      // A size (width, height) as the CLI's WxH; any other sequence (a fill colour) as its
      // comma-separated list.
      const py::sequence items = value.cast<py::sequence>();
      std::string text;
      for (const py::handle item : items)
        text += (text.empty()        ? ""
                 : items.size() == 2 ? "x"
                                     : ",") +
                py::str(item).cast<std::string>();
      argv.push_back(text);
    } else {
      argv.push_back(py::str(value).cast<std::string>());
    }
  }
  return cli::Args(argv, specs);
}

}  // namespace artcam::python

namespace py = pybind11;

PYBIND11_MODULE(_artcam, m) {
  using namespace artcam;
  m.doc() = "The ARTcam engine (Attributed Rational Tensor cameras): read, fit, map and render.";
  // The CLI's refusals are Python's: a bad option value is a ValueError, a file that fails a
  // ValueError or OSError (the functions that read files say which), each with the CLI's line.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const cli::UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const cli::CommandError& e) {
      // The readers' one wording for a missing file (core/io/file_kind.cpp): Python's own
      // exception for it, as open() raises.
      const bool missing =
          std::string_view(e.what()).find(": cannot read: no such file") != std::string_view::npos;
      PyErr_SetString(missing ? PyExc_FileNotFoundError : PyExc_OSError, e.what());
    }
  });
  python::registerCameras(m);
  python::registerImages(m);
  python::registerBatch(m);
  python::registerFitting(m);
  python::registerLenses(m);
  python::registerExports(m);
  python::registerPresets(m);
}
