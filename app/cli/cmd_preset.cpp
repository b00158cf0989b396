// artcam preset: cameras made from a few numbers (the paper's Fig 1 set by "explicitly setting
// numbers"), and the project's sample clouds.
//
// Adding a preset is one line in kPresets: its name, a summary, its parameters as
// "name=default …" (numbers, or comma-separated vectors), and a function from the parsed
// parameters to a Camera. Image-space (2D) presets fit the same table.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/outputs.h"
#include "core/cameras/effects_3d.h"
#include "core/cameras/glc.h"
#include "core/cameras/projective_cameras.h"
#include "core/cloud/sample_clouds.h"
#include "core/effects/aerial.h"
#include "core/effects/chromatic.h"
#include "core/effects/depth_of_field.h"
#include "core/effects/image_warps.h"
#include "core/io/artcam_file.h"
#include "core/io/ply.h"

#include <array>
#include <charconv>
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

std::vector<double> parseNumbers(const std::string& text, const std::string& name) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    double v = 0;
    const auto r = std::from_chars(item.data(), item.data() + item.size(), v);
    if (r.ec != std::errc() || r.ptr != item.data() + item.size() || !std::isfinite(v))
      throw UsageError("--" + name + ": \"" + text +
                       "\" is not a number or a comma-separated list");
    out.push_back(v);
  }
  if (out.empty()) throw UsageError("--" + name + " needs a value");
  return out;
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
Camera twist(const Params& p) { return twistEffect({p.number("rate")}); }
Camera pincushion(const Params& p) { return pincushionEffect({p.number("k"), p.vec3("centre")}); }
Camera inversePerspective(const Params& p) {
  return inversePerspectiveEffect({p.vec3("eye"), p.vec3("at"), p.vec3("up"), p.number("gain")});
}
Camera colourScale(const Params& p) {
  return colourScaleEffect({p.number("strength"), p.vec3("centre")});
}
Camera chromaticAberration(const Params& p) {
  return chromaticAberrationEffect(
      {p.number("red"), p.number("green"), p.number("blue"), p.vec3("centre")});
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

// View cameras default to the view of the sample cube (cloud_render.h defaultViewPose of
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
    {"twist-3d", "3D (Fig 1): twist about y, atan(rate·Y)", "rate=0.35", twist},
    {"pincushion-3d", "3D (Fig 1): P/(1 - k|P - c|²); k < 0 barrel", "k=0.12 centre=0,0,0",
     pincushion},
    {"inverse-perspective-3d", "3D (Fig 1): objects magnify as they recede from eye",
     "eye=2.744,2.058,-3.430 at=0,0,0 up=0,1,0 gain=0", inversePerspective},
    {"colour-scale", "3D (Fig 1): warm expands, cold shrinks, scale 1 + s(r - b)",
     "strength=0.35 centre=0,0,0", colourScale},
    {"chromatic-aberration-3d", "3D (Fig 1): per-layer scale; render with --layers rgb",
     "red=0.06 green=0 blue=-0.06 centre=0,0,0", chromaticAberration},
};

// Image-space (2D) cameras over [position 3 (| colour 4) (| depth 2)], stored in the normalised
// frame of a size×size image; layered ones (chromatic aberration, the paper's Fig 4) and depth
// of field use the .artcam extras (artcam_file.h). They have the plain effect names (issue 6's
// `artcam preset NAME`, the studio's effects panel: effect_presets.h); the point-cloud versions
// of the paper's Fig 1 end in "-3d".
FrameSize frameOf(const Params& p) {
  const std::vector<double>& v = p.list("size");
  if (v.size() != 2 || !(v[0] >= 1) || !(v[1] >= 1) || v[0] != std::floor(v[0]) || v[1] != std::floor(v[1]))
    throw UsageError("--size expects WxH in whole pixels");
  return {static_cast<int>(v[0]), static_cast<int>(v[1])};
}
std::array<double, 3> rgb(const Params& p, const char* r, const char* g, const char* b) {
  return {p.number(r), p.number(g), p.number(b)};
}
struct ImageCamera {
  std::vector<Camera> layers;
  std::string depth_output = "depth";
};
ImageCamera radial2d(const Params& p) { return {{radialLensCamera(p.number("k"), frameOf(p))}}; }
ImageCamera twist2d(const Params& p) { return {{twistCamera(p.number("rate"), frameOf(p))}}; }
ImageCamera inversePerspective2d(const Params& p) {
  return {{inversePerspectiveCamera(p.number("gain"), frameOf(p))}};
}
ImageCamera rgbShift2d(const Params& p) {
  return {rgbShiftLayers({rgb(p, "red", "green", "blue"), rgb(p, "red-dx", "green-dx", "blue-dx"),
                          rgb(p, "red-dy", "green-dy", "blue-dy")},
                         frameOf(p), frameOf(p))};
}
ImageCamera colourShift2d(const Params& p) {
  return {colourShiftLayers({rgb(p, "s-red", "s-green", "s-blue")}, frameOf(p), frameOf(p))};
}
ImageCamera aerial2d(const Params& p) {
  return {{aerialPerspectiveCamera({p.vec3("haze"), p.number("strength"), p.number("near"), p.number("far")},
                                   frameOf(p), frameOf(p))}};
}
ImageCamera depthOfField2d(const Params& p) {
  return {{depthOfFieldCamera({p.number("focus"), p.number("blur"), p.number("thin-lens")},
                              frameOf(p), frameOf(p))},
          "blur-variance"};
}

struct ImagePreset {
  const char* name;
  const char* summary;
  const char* params;
  ImageCamera (*build)(const Params&);
};

const ImagePreset kImagePresets[] = {
    {"barrel", "2D: radial lens u' = u/(1 - k r^2), k < 0 barrel", "k=-0.15 size=600x400", radial2d},
    {"pincushion", "2D: radial lens u' = u/(1 - k r^2), k > 0 pincushion", "k=0.15 size=600x400", radial2d},
    {"twist", "2D: each row turns by atan(rate·v): v' = v + rate·u·v", "rate=0.3 size=600x400", twist2d},
    {"inverse-perspective", "2D: far (upper) rows magnify: p' = p/(1 + gain·v)", "gain=0.35 size=600x400", inversePerspective2d},
    {"chromatic-aberration", "2D (Fig 4 middle): three RTcams scale/shift R, G, B", "red=0.006 green=0 blue=-0.006 red-dx=0 green-dx=0 blue-dx=0 red-dy=0 green-dy=0 blue-dy=0 size=600x400", rgbShift2d},
    {"colour-shift", "2D (Fig 4 right, eq 8/9): each layer moves by its colour, p(1 + s_k c_k)", "s-red=0.05 s-green=0 s-blue=-0.03 size=600x400", colourShift2d},
    {"aerial-perspective", "2D (§3): contrast falls with log depth towards haze (needs --depth)", "haze=0.62,0.72,0.86 strength=0.7 near=1 far=100 size=600x400", aerial2d},
    {"depth-of-field", "2D (§3): Gaussian blur, sigma = blur·|d - focus|/(focus + thin-lens·(d - focus)); thin-lens 1: /d (thin lens), 0: /focus (linear) (needs --depth)", "focus=2 blur=0.01 thin-lens=1 size=600x400", depthOfField2d},
};

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

std::string listing() {
  std::string s;
  const auto add = [&](const char* name, const char* summary, const char* params) {
    char line[512];
    std::snprintf(line, sizeof line, "  %-21s %s\n", name, summary);
    s += line;
    if (*params) s += std::string("  ") + std::string(23, ' ') + params + "\n";
  };
  for (const Preset& p : kPresets) add(p.name, p.summary, p.params);
  for (const ImagePreset& p : kImagePresets) add(p.name, p.summary, p.params);
  for (const CloudPreset& p : kCloudPresets) add(p.name, p.summary, p.params);
  return s;
}

// Parses "--name value" pairs against a preset's defaults.
Params parseParams(const char* spec, const std::vector<std::string>& argv, std::string& output,
                   std::string& summary) {
  std::vector<OptionSpec> specs = {
      {"--output", "-o", true}, {"--overwrite", "", false}, {"--force", "", false}};
  const auto defs = defaults(spec);
  for (const auto& [name, value] : defs) specs.push_back({"--" + name, "", true});
  const Args args(argv, specs);
  args.expectPositional(1, "NAME");
  const auto out = args.value("--output");
  if (!out) throw UsageError("missing -o OUT");
  output = *out;
  checkOutputs(args, {output}, {});
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
    "points and colours before the view. cube-of-cubes writes the sample cloud of the paper's\n"
    "Fig 1. Image cameras (barrel, pincushion, twist, inverse-perspective, chromatic-aberration,\n"
    "colour-shift, aerial-perspective, depth-of-field) apply to photos with artcam warp (the\n"
    "last two need --depth FILE); --size WxH is the photo's size (W,H is also read).\n"
    "Vectors are comma-separated (--eye 3,2,-4). `artcam preset list` shows every preset with\n"
    "its parameters and defaults; every parameter is optional. -o/--output names OUT (required);\n"
    "an existing OUT is refused unless --overwrite (--force is the same).\n\n"
    "Examples:\n"
    "  artcam preset list\n"
    "  artcam preset barrel --k -0.2 --size 6000x4000 -o barrel.artcam\n"
    "  artcam preset pinhole --eye 3,2,-4 -o view.artcam\n";

int presetCommand(const std::vector<std::string>& argv) {
  if (argv.empty() || argv[0].starts_with("-")) throw UsageError("missing NAME");
  const std::string& name = argv[0];
  if (name == "list" && argv.size() == 1) {
    std::printf("%s", listing().c_str());
    return 0;
  }
  std::string output, summary;
  for (const Preset& p : kPresets) {
    if (name != p.name) continue;
    const Params params = parseParams(p.params, argv, output, summary);
    ArtcamDocument doc;
    try {
      doc.camera = p.build(params);
    } catch (const std::invalid_argument& e) {
      throw CommandError(std::string("preset ") + p.name + ": " + e.what());
    }
    if (const Status s = writeArtcamFile(output, doc); !s) throw CommandError(s.message);
    std::printf("wrote %s (%s%s%s)\n", output.c_str(), p.name, summary.empty() ? "" : ": ",
                summary.c_str());
    if (name == "chromatic-aberration-3d")
      std::printf("render it with --layers rgb: each colour layer moves by its own scale\n");
    return 0;
  }
  for (const ImagePreset& p : kImagePresets) {
    if (name != p.name) continue;
    const Params params = parseParams(p.params, argv, output, summary);
    ImageCamera made;
    try {
      made = p.build(params);
    } catch (const std::invalid_argument& e) {
      throw CommandError(std::string("preset ") + p.name + ": " + e.what());
    }
    ArtcamDocument doc{made.layers.front(), {}, std::nullopt};
    ArtcamExtras extras;
    extras.layers.assign(made.layers.begin() + 1, made.layers.end());
    extras.depth_output = made.depth_output;
    if (const Status s = writeArtcamFile(output, doc, extras); !s) throw CommandError(s.message);
    std::printf("wrote %s (%s: %s)\n", output.c_str(), p.name, summary.c_str());
    return 0;
  }
  for (const CloudPreset& p : kCloudPresets) {
    if (name != p.name) continue;
    const Params params = parseParams(p.params, argv, output, summary);
    PointCloud cloud;
    try {
      cloud = p.build(params);
    } catch (const std::invalid_argument& e) {
      throw CommandError(std::string("preset ") + p.name + ": " + e.what());
    }
    if (const Status s = writePly(output, cloud); !s) throw CommandError(s.message);
    std::printf("wrote %s (%zu points; %s: %s)\n", output.c_str(), cloud.size(), p.name,
                summary.c_str());
    return 0;
  }
  std::vector<std::string> names = {"list"};
  for (const Preset& p : kPresets) names.push_back(p.name);
  for (const ImagePreset& p : kImagePresets) names.push_back(p.name);
  for (const CloudPreset& p : kCloudPresets) names.push_back(p.name);
  throw UsageError("unknown preset \"" + name + "\" (artcam preset list shows them)",
                   didYouMean(name, names));
}

}  // namespace artcam::cli
