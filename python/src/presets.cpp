// SPDX-License-Identifier: Apache-2.0
// artcam.preset and artcam.compose: cameras made from a few numbers (the effects tables, through
// the very parser of `artcam preset`) and cameras chained (core/model/compose.h).
#include "app/cli/commands.h"
#include "core/io/artcam_file.h"
#include "core/model/compose.h"
#include "python/src/common.h"

#include <sstream>

namespace artcam::python {
namespace {

// A keyword's value in the CLI's words: a sequence comma-separated (--eye 3,2,-4), a number as
// Python writes it (the shortest text that reads back the same), a name as it is.
std::string optionText(const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::bool_>(value))
    raiseValueError("preset parameters are numbers, lists of numbers or names, not True/False");
  if (py::isinstance<py::sequence>(value)) {
    std::string text;
    for (const py::handle item : value.cast<py::sequence>())
      text += (text.empty() ? "" : ",") + optionText(item);
    return text;
  }
  return py::repr(value).cast<std::string>();
}

PyCamera preset(const std::string& name, const py::kwargs& params) {
  std::vector<std::string> argv = {name};
  for (const auto& [key, value] : params) {
    std::string option = "--" + py::str(key).cast<std::string>();
    for (char& c : option)
      if (c == '_') c = '-';
    argv.push_back(option);
    argv.push_back(optionText(value));
  }
  cli::PresetCamera made = cli::presetCamera(argv);
  return {std::make_shared<const Artcam>(std::move(made.camera)), "preset " + made.summary};
}

PyCamera compose(const py::args& cameras) {
  if (cameras.size() < 2) raiseValueError("compose needs at least two cameras");
  std::vector<PyCamera> steps;
  for (const py::handle c : cameras) {
    if (!py::isinstance<PyCamera>(c))
      throw py::type_error("compose takes artcam.Camera values (artcam.read reads a file)");
    steps.push_back(c.cast<PyCamera>());
  }
  Artcam composed = *steps[0].camera;
  std::string name = steps[0].name;
  for (size_t i = 1; i < steps.size(); ++i) {
    auto next = composeArtcams(composed, *steps[i].camera, nullptr);
    if (!next)
      raiseValueError(steps[i].name + ": cannot follow " + steps[i - 1].name + ": " +
                      next.status.message);
    composed = std::move(*next);
    name += " then " + steps[i].name;
  }
  if (const Status s = validateArtcam(composed); !s)
    raiseValueError("the composed camera is not usable: " + s.message);
  return {std::make_shared<const Artcam>(std::move(composed)), name};
}

}  // namespace

void registerPresets(py::module_& m) {
  m.def("preset", &preset, py::arg("name"), R"doc(
A camera made from a few numbers, as `artcam preset NAME --PARAM VALUE …` makes it: the image
effects of the effects table (barrel, aerial-perspective, composite, …; `size=(w, h)` is the
photo's size, default 600×400), the 3D effects of Fig 1 (twist-3d, …; object_centre, object_radius)
and the view cameras (pinhole, orthographic, pushbroom, xslit, glc, rational-lens).
Parameters are keywords (hyphens as underscores): numbers, sequences for vectors (eye=(3, 2, -4)),
names for choices (op="over"). Every parameter is optional; one outside its range raises
ValueError with the CLI's message. artcam.presets() lists the names, artcam.preset_listing()
every parameter with its default and range.

    barrel = artcam.preset("barrel", k=-0.2, size=(6000, 4000)))doc");
  m.def("presets", &cli::presetCameraNames,
        "The names artcam.preset takes: view cameras, 3D effects, image effects.");
  m.def("preset_listing", &cli::presetListing,
        "`artcam preset list`'s text: every preset with its parameters, defaults and ranges.");
  m.def("compose", &compose, R"doc(
compose(a, b, *more): one camera that applies `a`, then `b` (then each of `more`), as
`artcam compose` writes it: tensors multiplied where the algebra is exact, else chained. Raises
ValueError naming the pair that cannot follow each other (a depth that is not a depth, a
composed camera that renders nothing).)doc");
}

}  // namespace artcam::python
