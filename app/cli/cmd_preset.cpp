// SPDX-License-Identifier: Apache-2.0
// artcam preset: cameras made from a few numbers (the paper's Fig 1 set by "explicitly setting
// numbers"), and the project's sample clouds.
//
// Adding a view camera is one line in kPresets: its name, a summary, its parameters as
// "name=default …" (numbers, or comma-separated vectors), and a function from the parsed
// parameters to a Camera. The image effects and the 3D effects of Fig 1 are core's tables
// (effects/effect_table.h, effects/effects_3d_table.h, which the studio's panels and 3D view
// read too): their options, ranges, listing and help pages are made from its rows, and their
// cameras by its builders.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/outputs.h"
#include "app/cli/stdio_paths.h"
#include "core/cameras/glc.h"
#include "core/cameras/projective_cameras.h"
#include "core/cloud/sample_clouds.h"
#include "core/effects/effect_table.h"
#include "core/effects/effects_3d_table.h"
#include "core/io/artcam_file.h"
#include "core/io/ply.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

namespace artcam::cli {

namespace {

// Parsed parameters of one preset: every value a list of numbers.
class Params {
 public:
  explicit Params(std::map<std::string, std::vector<double>> values) : values_(std::move(values)) {}
  double number(const std::string& name) const { return get(name, 1)[0]; }
  Eigen::Vector3d vec3(const std::string& name) const {
    const auto& v = get(name, 3);
    return {v[0], v[1], v[2]};
  }
  Eigen::Vector4d vec4(const std::string& name) const {
    const auto& v = get(name, 4);
    return {v[0], v[1], v[2], v[3]};
  }
  const std::vector<double>& list(const std::string& name) const { return values_.at(name); }

 private:
  const std::vector<double>& get(const std::string& name, size_t count) const {
    const std::vector<double>& v = values_.at(name);
    if (v.size() != count)
      throw UsageError("--" + name + " expects " + std::to_string(count) +
                       " comma-separated numbers");
    return v;
  }
  std::map<std::string, std::vector<double>> values_;
};

// Every parameter is a number or a list; its range, where it has one, is the effects table's
// (checkEffectValue) or the camera builder's.
std::vector<double> parseNumbers(const std::string& text, const std::string& name) {
  return parseNumberList(text, "--" + name, -kUnbounded, kUnbounded);
}

CameraPose pose(const Params& p) {
  return CameraPose::lookAt(p.vec3("eye"), p.vec3("at"), p.vec3("up"));
}

Camera pinhole(const Params& p) {
  PinholeParams c;
  c.focal = p.number("focal");
  c.principal = {p.number("cx"), p.number("cy")};
  c.pose = pose(p);
  return pinholeCamera(c);
}
Camera orthographic(const Params& p) {
  OrthographicParams c;
  c.scale = p.number("scale");
  c.far = p.number("far");
  c.pose = pose(p);
  return orthographicCamera(c);
}
Camera pushbroom(const Params& p) {
  PushbroomParams c;
  c.focal = p.number("focal");
  c.scale = p.number("scale");
  c.pose = pose(p);
  return pushbroomCamera(c);
}
Camera xslit(const Params& p) {
  XSlitParams c;
  c.focal = p.number("focal");
  c.slit_u_depth = p.number("slit-u-depth");
  c.slit_v_depth = p.number("slit-v-depth");
  c.pose = pose(p);
  return xslitCamera(c);
}
Camera glc(const Params& p) {
  GlcParams c =
      glcFromTwoPlanes({p.vec4("ray1"), p.vec4("ray2"), p.vec4("ray3")}, p.number("focal"));
  c.pose = pose(p);
  return glcCamera(c);
}
Camera rationalLens(const Params& p) {
  RationalLensParams c;
  c.focal = p.number("focal");
  c.k = p.number("k");
  c.pose = pose(p);
  const std::vector<double>& m = p.list("matrix");
  if (m.size() == 1 && m[0] == 0) return rationalLensCamera(c);
  if (m.size() != 18)
    throw UsageError("--matrix expects the 3×6 matrix A of [CF05], 18 numbers by rows");
  return rationalLensCamera(Eigen::Matrix<double, 3, 6, Eigen::RowMajor>(m.data()), c.pose);
}
Camera identity3d(const Params&) {
  return Camera::identity({Block{BlockKind::Position, 4}, Block{BlockKind::Colour, 4}}, {}, {});
}

struct Preset {
  const char* name;
  const char* summary;
  const char* params;  // "name=default …"
  Camera (*build)(const Params&);
};

// View cameras (and identity, the 3D camera that does nothing; the Fig 1 effects are core's 3D
// table) default to the view of the sample cube (cloud_render.h defaultViewPose of
// [-1, 1]³), so `artcam render cube.ply … --view` frames it.
const Preset kPresets[] = {
    {"pinhole", "3D→image: central projection, u = f·X/Z (view camera)",
     "focal=2.4 cx=0 cy=0 eye=2.744,2.058,-3.430 at=0,0,0 up=0,1,0", pinhole},
    {"orthographic", "3D→image: parallel projection, u = s·X (view camera)",
     "scale=0.5 far=1e6 eye=2.744,2.058,-3.430 at=0,0,0 up=0,1,0", orthographic},
    {"pushbroom", "3D→image: push-broom, u = s·X, v = f·Y/Z (view camera)",
     "focal=2.4 scale=0.5 eye=2.744,2.058,-3.430 at=0,0,0 up=0,1,0", pushbroom},
    {"xslit", "3D→image: crossed slits at depths a (sets u) and b (sets v) (view camera)",
     "focal=1.9 slit-u-depth=1.2 slit-v-depth=-1.2 eye=2.744,2.058,-3.430 at=0,0,0 up=0,1,0",
     xslit},
    {"glc", "3D→image: general linear camera, generator rays s,t,u,v (view camera)",
     "focal=1.2 ray1=-0.3,-0.3,-0.5,-0.3 ray2=0.3,-0.3,0.4,-0.45 ray3=0,0.35,0.1,0.5 "
     "eye=2.744,2.058,-3.430 at=0,0,0 up=0,1,0",
     glc},
    {"rational-lens",
     "3D→image: Claus–Fitzgibbon rational lens, u = f·x/(1 + k|x|²), or --matrix A (view camera)",
     "focal=2.4 k=0.5 matrix=0 eye=2.744,2.058,-3.430 at=0,0,0 up=0,1,0", rationalLens},
    {"identity", "3D: leaves points and colours as they are", "", identity3d},
};

// Image effects (effect_table.h): 2D cameras over [position 3 (| colour 4) (| depth 2)] in the
// normalised frame of the photo's size (--size); the point-cloud versions of the paper's Fig 1
// end in "-3d".
constexpr const char* kDefaultEffectSize = "600x400";

// --size WxH; "W,H" is still accepted (the form this command took first).
FrameSize effectFrame(const std::string& text) { return parseSize(text, "--size", true); }

std::string effectSummary(const EffectSpec& effect) {
  return "2D, " + effect.label + ": " + effect.summary +
         (effect.needs_depth ? " (needs --depth)" : "") +
         (effect.needs_second ? " (needs --second)" : "");
}

// "k=-0.15 [-1 … 0]" for each parameter, then the frame.
std::vector<std::string> effectParamWords(const std::vector<EffectParam>& params,
                                          const std::vector<std::string>& frame_words) {
  std::vector<std::string> words;
  for (const EffectParam& p : params)
    words.push_back(p.name + "=" + defaultText(p) + " [" + rangeText(p) + "]");
  words.insert(words.end(), frame_words.begin(), frame_words.end());
  return words;
}

// 3D effects (effects_3d_table.h): their parameters are in the object frame given by these two
// options (default: the origin and 1, object units). Like the parameters, they are offered per
// preset from `artcam preset list` (the shell completions read it), not as literals.
constexpr const char* kObjectCentre = "object-centre";
constexpr const char* kObjectRadius = "object-radius";
constexpr const char* kDefaultObjectCentre = "0,0,0";
constexpr const char* kDefaultObjectRadius = "1";

std::string effect3dSummary(const Effect3dSpec& effect) {
  return "3D (Fig 1): " + effect.summary +
         (effect.colour_layers ? " (render with --layers rgb)" : "");
}

std::vector<std::string> objectFrameWords() {
  return {std::string(kObjectCentre) + "=" + kDefaultObjectCentre,
          std::string(kObjectRadius) + "=" + kDefaultObjectRadius};
}

struct CloudPreset {
  const char* name;
  const char* summary;
  const char* params;
  PointCloud (*build)(const Params&);
};

PointCloud cubeCloud(const Params& p) {
  CubeOfCubesOptions o;
  o.samples_per_edge = static_cast<int>(p.number("samples"));
  o.half_size = p.number("half-size");
  o.gap = p.number("gap");
  return cubeOfCubes(o);
}

const CloudPreset kCloudPresets[] = {
    {"cube-of-cubes", "cloud (.ply): the coloured 3×3×3 cube of cubes of Fig 1 (27·6·n² points)",
     "samples=10 half-size=1 gap=0.12", cubeCloud},
};

std::vector<std::pair<std::string, std::string>> defaults(const char* spec) {
  std::vector<std::pair<std::string, std::string>> out;
  std::stringstream ss(spec);
  std::string item;
  while (ss >> item) {
    const size_t eq = item.find('=');
    out.emplace_back(item.substr(0, eq), item.substr(eq + 1));
  }
  return out;
}

// Words joined into lines indented under the name column, at most ~96 columns wide.
std::string wrapped(const std::vector<std::string>& words) {
  const std::string indent(26, ' ');
  std::string s, line;
  for (const std::string& w : words) {
    if (!line.empty() && line.size() + 1 + w.size() > 70) {
      s += indent + line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + w;
  }
  return line.empty() ? s : s + indent + line + "\n";
}

std::string listing() {
  std::string s;
  const auto add = [&](const std::string& name, const std::string& summary,
                       const std::vector<std::string>& params) {
    char line[512];
    std::snprintf(line, sizeof line, "  %-23s %s\n", name.c_str(), summary.c_str());
    s += line + wrapped(params);
  };
  const auto words = [](const char* params) {
    std::vector<std::string> out;
    for (const auto& [name, value] : defaults(params)) out.push_back(name + "=" + value);
    return out;
  };
  for (const Preset& p : kPresets) add(p.name, p.summary, words(p.params));
  for (const Effect3dSpec& e : effect3dSpecs())
    add(e.name, effect3dSummary(e), effectParamWords(e.params, objectFrameWords()));
  for (const EffectSpec& e : effectSpecs())
    add(e.name, effectSummary(e),
        effectParamWords(e.params, {std::string("size=") + kDefaultEffectSize}));
  for (const CloudPreset& p : kCloudPresets) add(p.name, p.summary, words(p.params));
  return s;
}

std::string requiredOutput(const Args& args) {
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o OUT");
  checkOutputs(args, {*output}, {});
  return *output;
}

// Parses "--name value" pairs against a preset's defaults; `output` (when asked for) gets -o's
// file, checked as every output is.
Params parseParams(const char* spec, const std::vector<std::string>& argv, std::string* output,
                   std::string& summary) {
  std::vector<OptionSpec> specs = {
      {"--output", "-o", true}, {"--overwrite", "", false}, {"--force", "", false}};
  const auto defs = defaults(spec);
  for (const auto& [name, value] : defs) specs.push_back({"--" + name, "", true});
  const Args args(argv, specs);
  args.expectPositional(1, "NAME");
  if (output) *output = requiredOutput(args);
  std::map<std::string, std::vector<double>> values;
  for (const auto& [name, fallback] : defs) {
    const std::string text = args.valueOr("--" + name, fallback);
    if (name == "size") {  // WxH like every size, W,H as before
      const FrameSize size = parseSize(text, "--size", true);
      values[name] = {double(size.width), double(size.height)};
    } else {
      values[name] = parseNumbers(text, name);
    }
    summary += (summary.empty() ? "" : " ") + name + "=" + text;
  }
  return Params(std::move(values));
}

// The values of a table row's parameters from "--NAME VALUE" options (its defaults for the
// missing ones), each checked against its range; `summary` gets "name=value " for each.
EffectValues parseEffectValues(const std::vector<EffectParam>& params, const Args& args,
                               std::string& summary) {
  EffectValues values;
  for (const EffectParam& p : params) {
    const std::string text = args.valueOr("--" + p.name, defaultText(p));
    if (p.isChoice()) {
      const auto index = choiceValue(p, text);
      if (!index)
        throw UsageError("--" + p.name + ": \"" + text + "\" is not one of " + rangeText(p));
      values[p.name] = {*index};
    } else {
      values[p.name] = parseNumbers(text, p.name);
    }
    if (const std::string problem = checkEffectValue(p, values[p.name]); !problem.empty())
      throw UsageError("--" + problem);
    summary += p.name + "=" +
               (p.isChoice() ? p.choices[static_cast<size_t>(values[p.name][0])] : text) + " ";
  }
  return values;
}

// The options of a table row's preset: -o, --overwrite/--force, its parameters, then `extra`.
Args effectArgs(const std::vector<EffectParam>& params, const std::vector<std::string>& argv,
                std::vector<OptionSpec> specs) {
  specs.insert(specs.end(),
               {{"--output", "-o", true}, {"--overwrite", "", false}, {"--force", "", false}});
  for (const EffectParam& p : params) specs.push_back({"--" + p.name, "", true});
  Args args(argv, specs);
  args.expectPositional(1, "NAME");
  return args;
}

// `artcam preset EFFECT [--PARAM VALUE …] [--size WxH]` for a row of the effects table.
PresetCamera makeEffect(const EffectSpec& effect, const std::vector<std::string>& argv,
                        std::string* output) {
  const Args args = effectArgs(effect.params, argv, {{"--size", "", true}});
  if (output) *output = requiredOutput(args);
  const std::string size = args.valueOr("--size", kDefaultEffectSize);
  const FrameSize frame = effectFrame(size);
  std::string summary;
  const EffectValues values = parseEffectValues(effect.params, args, summary);
  PresetCamera made;
  try {
    made.camera = buildEffect(effect.name, values, frame);
  } catch (const std::invalid_argument& e) {
    throw CommandError("preset " + effect.name + ": " + e.what());
  }
  made.summary = effect.name + ": " + summary + "size=" + size;
  return made;
}

// `artcam preset EFFECT-3D [--PARAM VALUE …] [--object-centre X,Y,Z] [--object-radius R]` for a
// row of the 3D effects table.
PresetCamera makeEffect3d(const Effect3dSpec& effect, const std::vector<std::string>& argv,
                          std::string* output) {
  const std::string centre_option = std::string("--") + kObjectCentre;
  const std::string radius_option = std::string("--") + kObjectRadius;
  const Args args =
      effectArgs(effect.params, argv, {{centre_option, "", true}, {radius_option, "", true}});
  if (output) *output = requiredOutput(args);
  const std::string centre = args.valueOr(centre_option, kDefaultObjectCentre);
  const std::string radius = args.valueOr(radius_option, kDefaultObjectRadius);
  ObjectFrame frame;
  const std::vector<double> c = parseNumberList(centre, centre_option, -kUnbounded, kUnbounded);
  if (c.size() != 3) throw UsageError(centre_option + " expects X,Y,Z, got \"" + centre + "\"");
  frame.centre = {c[0], c[1], c[2]};
  frame.radius = parseNumber(radius, radius_option, 0, kUnbounded, Ends::OpenMin);
  std::string summary;
  const EffectValues values = parseEffectValues(effect.params, args, summary);
  PresetCamera made;
  try {
    made.camera = Artcam(buildEffect3d(effect.name, values, frame));
  } catch (const std::invalid_argument& e) {
    throw CommandError("preset " + effect.name + ": " + e.what());
  }
  made.summary = effect.name + ": " + summary + kObjectCentre + "=" + centre + " " + kObjectRadius +
                 "=" + radius;
  made.colour_layers = effect.colour_layers;
  return made;
}

PresetCamera makePresetCamera(const std::vector<std::string>& argv, std::string* output) {
  if (argv.empty() || argv[0].starts_with("-")) throw UsageError("missing NAME");
  const std::string& name = argv[0];
  for (const Preset& p : kPresets) {
    if (name != p.name) continue;
    std::string summary;
    const Params params = parseParams(p.params, argv, output, summary);
    PresetCamera made;
    try {
      made.camera = Artcam(p.build(params));
    } catch (const std::invalid_argument& e) {
      throw CommandError(std::string("preset ") + p.name + ": " + e.what());
    }
    made.summary = p.name + std::string(summary.empty() ? "" : ": ") + summary;
    return made;
  }
  if (const Effect3dSpec* effect = findEffect3d(name)) return makeEffect3d(*effect, argv, output);
  if (const EffectSpec* effect = findEffect(name)) return makeEffect(*effect, argv, output);
  std::vector<std::string> names;
  for (const Preset& p : kPresets) names.push_back(p.name);
  for (const Effect3dSpec& e : effect3dSpecs()) names.push_back(e.name);
  for (const EffectSpec& e : effectSpecs()) names.push_back(e.name);
  for (const CloudPreset& p : kCloudPresets)
    if (name == p.name) throw UsageError("preset " + name + " makes a point cloud, not a camera");
  throw UsageError("unknown preset \"" + name + "\" (artcam preset list shows them)",
                   didYouMean(name, names));
}

}  // namespace

// A literal: the dispatcher's command table reads it during static initialisation.
const char* const kPresetUsage =
    "usage: artcam preset NAME [--PARAM VALUE …] -o OUT\n"
    "       artcam preset list\n\n"
    "Writes a camera made from a few numbers to OUT (.artcam), or a sample cloud to OUT (.ply).\n"
    "View cameras (pinhole, orthographic, pushbroom, xslit, glc, rational-lens) project object\n"
    "space to the image: outputs (u, v, nearness), (u, v) in the normalised frame (the larger\n"
    "image side spans [-1, 1], v down); use them with artcam render --view. 3D cameras (identity,\n"
    "twist-3d, pincushion-3d, inverse-perspective-3d, colour-scale, chromatic-aberration-3d) move\n"
    "points and colours before the view; the Fig 1 effects' lengths are in radii of the object\n"
    "frame --object-radius R about --object-centre X,Y,Z (default 1 about the origin: object\n"
    "units). cube-of-cubes writes the sample cloud of the paper's Fig 1. Image effects (artcam\n"
    "preset --help lists them and the 3D effects with their parameters) apply to photos with\n"
    "artcam warp (those marked \"needs --depth\" with --depth FILE, \"needs --second\" with\n"
    "--second FILE); --size WxH is the photo's size (default 600x400; W,H also accepted). A\n"
    "NAME parameter takes one of the names its range lists (--op over). Vectors are\n"
    "comma-separated (--eye 3,2,-4). `artcam preset list` shows every preset with its\n"
    "parameters and defaults; every parameter is optional, and an effect's parameter outside\n"
    "its range is refused. -o/--output names OUT (required); an existing OUT is refused unless\n"
    "--overwrite (--force is the same).\n\n"
    "Examples:\n"
    "  artcam preset list\n"
    "  artcam preset barrel --k -0.2 --size 6000x4000 -o barrel.artcam\n"
    "  artcam preset aerial-perspective --haze 0.6,0.7,0.9 --far 50 -o haze.artcam\n"
    "  artcam preset composite --op over --size 1920x1080 -o over.artcam\n"
    "  artcam preset pinhole --eye 3,2,-4 -o view.artcam\n"
    "  artcam preset pincushion-3d --k 0.3 --object-radius 1.8 -o swell.artcam\n";

// One help row per parameter: "--k  N  radial coefficient; -1 … 0, default -0.15", indented.
std::string paramRows(const std::vector<EffectParam>& params) {
  std::string s;
  for (const EffectParam& p : params) {
    std::string value = p.isChoice() ? "NAME" : "N";
    for (int i = 1; i < p.size(); ++i) value += ",N";
    char line[512];
    std::snprintf(line, sizeof line, "      --%-10s %-6s %s; %s, default %s\n", p.name.c_str(),
                  value.c_str(), p.meaning.c_str(), rangeText(p).c_str(), defaultText(p).c_str());
    s += line;
  }
  return s;
}

// The usage above, then every image effect and every 3D effect of the tables with its
// parameters: type, range, default and meaning ("norm": normalised units, 1 = half the larger
// image side; "radii": units of the object frame).
std::string presetHelp() {
  std::string s = kPresetUsage;
  s += "\nImage effects (--PARAM VALUE, ranges inclusive; norm = normalised units, 1 = half the\n"
       "larger image side; depth units = those of the --depth file given to artcam warp):\n";
  for (const EffectSpec& e : effectSpecs())
    s += "  " + e.name + "  " + e.summary + (e.needs_depth ? " (needs --depth)" : "") +
         (e.needs_second ? " (needs --second)" : "") + "\n" + paramRows(e.params);
  s += "\n3D effects of Fig 1 (--PARAM VALUE, ranges inclusive) in the object frame:\n"
       "--object-centre X,Y,Z (default 0,0,0) and --object-radius R (default 1); radii = units of\n"
       "R from the centre, every length scales with R, so the defaults are object units (the\n"
       "studio's 3D view builds them in its cloud's frame: the centre and radius of its bounds):\n";
  for (const Effect3dSpec& e : effect3dSpecs())
    s += "  " + e.name + "  " + e.summary + (e.colour_layers ? " (render with --layers rgb)" : "") +
         "\n" + paramRows(e.params);
  return s;
}

PresetCamera presetCamera(const std::vector<std::string>& argv) {
  return makePresetCamera(argv, nullptr);
}

std::vector<std::string> presetCameraNames() {
  std::vector<std::string> names;
  for (const Preset& p : kPresets) names.push_back(p.name);
  for (const Effect3dSpec& e : effect3dSpecs()) names.push_back(e.name);
  for (const EffectSpec& e : effectSpecs()) names.push_back(e.name);
  return names;
}

std::string presetListing() { return listing(); }

int presetCommand(const std::vector<std::string>& argv) {
  if (argv.empty() || argv[0].starts_with("-")) throw UsageError("missing NAME");
  const std::string& name = argv[0];
  if (name == "list" && argv.size() == 1) {
    std::printf("%s", listing().c_str());
    return 0;
  }
  std::string output, summary;
  for (const CloudPreset& p : kCloudPresets) {
    if (name != p.name) continue;
    const Params params = parseParams(p.params, argv, &output, summary);
    PointCloud cloud;
    try {
      cloud = p.build(params);
    } catch (const std::invalid_argument& e) {
      throw CommandError(std::string("preset ") + p.name + ": " + e.what());
    }
    if (const Status s = writePly(output, cloud); !s) throw CommandError(s.message);
    std::printf("wrote %s (%zu points; %s: %s)\n", outputName(output).c_str(), cloud.size(), p.name,
                summary.c_str());
    return 0;
  }
  const PresetCamera made = makePresetCamera(argv, &output);
  if (const Status s = writeArtcam(output, made.camera); !s) throw CommandError(s.message);
  std::printf("wrote %s (%s)\n", outputName(output).c_str(), made.summary.c_str());
  if (made.colour_layers)
    std::printf("render it with --layers rgb: each colour layer moves by its own scale\n");
  return 0;
}

}  // namespace artcam::cli
