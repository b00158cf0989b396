// SPDX-License-Identifier: Apache-2.0
// The camera value: everything one `.artcam` file holds, and what every command, renderer and
// studio panel takes. One type, so a reader cannot keep half of a camera and a renderer cannot
// forget a part of it.
//
//   layers        one or more chains of stages over the same blocks and frames (eq 3, 5). A
//                 single camera is one layer; chromatic aberration (the paper's Fig 4) is three,
//                 one per colour layer, and the picture is the sum of the layers' colours.
//   pieces        a piecewise camera (the paper's §5): position-only patches of the source, each
//                 with its own camera. layers[0] then holds the single camera fitted to all the
//                 matches, kept so a reader that ignores patches still gets the best one camera.
//   depth_output  what the depth block's output means: a depth, or the blur variance σ² of
//                 depth of field.
//   matches, fit  the point pairs it was fitted to, and the report of that fit (optional).
//
// Invariants (validateArtcam): at least one layer; every layer valid with the blocks and frames
// of layers[0]; patches only on a single-layer position-only image camera, each patch camera
// valid, finite and with the same frames, rectangles finite, non-empty and inside the source
// frame, at most kMaxPatches of them; every frame side at most kMaxFrameSide pixels.
#pragma once

#include "core/model/camera.h"
#include "core/model/structure.h"
#include "core/model/fit_record.h"
#include "core/model/piecewise_camera.h"
#include "core/model/status.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace artcam {

enum class DepthOutput { Depth, BlurVariance };
std::string_view depthOutputName(DepthOutput output);  // "depth", "blur-variance"
std::optional<DepthOutput> depthOutputFromName(std::string_view name);

// The raster a camera was made for (core/pipeline/camera_frame.h): the photo as the sensor
// stored it (a lens camera: the lens projects onto the sensor, whatever way the camera was
// held), or the photo as shown, turned upright by its EXIF orientation (cameras fitted to what
// the user sees). Unset (files that do not say): decided by the camera's source frame.
enum class CameraFrame { Upright, Sensor };
std::string_view cameraFrameName(CameraFrame frame);  // "upright", "sensor"
std::optional<CameraFrame> cameraFrameFromName(std::string_view name);

// What kind of camera it is, most specific first: what `artcam info` reports and what the render
// front door dispatches on (together with the structure analysis of each layer).
enum class ArtcamKind {
  Single,      // one stage, position only
  Chained,     // several stages, position only
  Attributed,  // reads or writes colour or depth (eq 4, 8, 9), one layer
  Layered,     // several layers
  Piecewise,   // patches
};
std::string_view artcamKindName(ArtcamKind kind);

inline constexpr int kMaxPatches = 1024;
// A frame is the size of the image a renderer allocates; a side beyond 2^20 pixels (a million)
// is no photo but a corrupt or hostile header. The reader refuses it, so validateArtcam does
// too: a camera that is written can always be read back.
inline constexpr int kMaxFrameSide = 1 << 20;

struct Artcam {
  std::vector<Camera> layers;
  std::optional<PiecewiseCamera> pieces;
  DepthOutput depth_output = DepthOutput::Depth;
  std::optional<CameraFrame> frame;
  std::vector<PointMatch> matches;
  std::optional<FitRecord> fit;

  Artcam() = default;
  explicit Artcam(Camera main) { layers.push_back(std::move(main)); }

  // layers[0]: the camera itself, the first layer, or a piecewise camera's single fit.
  const Camera& main() const { return layers.at(0); }
  Camera& main() { return layers.at(0); }
  const std::vector<Block>& blocks() const { return main().blocks(); }
  FrameSize sourceSize() const { return main().sourceSize(); }
  FrameSize targetSize() const { return main().targetSize(); }
  void setFrames(FrameSize source_size, FrameSize target_size);

  bool isLayered() const { return layers.size() > 1; }
  bool isPiecewise() const { return pieces.has_value(); }
  ArtcamKind kind() const;
};

// Whether the camera has a depth block: its renders read a depth image (RenderInputs::depth).
bool readsDepth(const Artcam& camera);

// The invariants above; the message names the part ("layer 2: …", "patch 3: rect …").
// The file's invariants, and that every camera in it renders something (coverage.h): a camera
// whose pole crosses the whole frame, or that maps it onto a line, is refused with the reason.
// `layer_structures` (may be null) receives each layer's structure analysis, in layer order:
// the analysis the check makes anyway, kept so a render analyses its camera once.
Status validateArtcam(const Artcam& camera, std::vector<CameraStructure>* layer_structures = nullptr);
// What validateArtcam lets through but a user should hear: a pole that takes part of the frame.
std::vector<std::string> cameraWarnings(const Artcam& camera);

}  // namespace artcam
