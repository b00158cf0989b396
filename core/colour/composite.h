// SPDX-License-Identifier: Apache-2.0
// Compositing as an ARTcam colour stage: the paper's eq 6/7 says the colour-only part Q_icc of
// each tensor "can be used for both linear and non-linear compositing operations" and
// generalises projective alpha (Willis, [Wil07]). Here the colour input is two homogeneous
// colours, x = [position (u, v, w) | A | B], A the photo's premultiplied colour
// (a·r, a·g, a·b, a) (the colour block) and B the second image's (the second-colour block,
// camera.h), and every output colour element is one quadratic form of x (eq 3):
//
//   z_k = a·A_k·w + b·B_k·w + cA·A_k·α_B + cB·B_k·α_A + p·A_k·B_k        k = r, g, b, α
//
// w = 1 is the position weight (the identity's unit, architecture.md "The model"). The same
// form serves the three colour elements and alpha, and gives each operator's alpha exactly:
//
//   over      A + (1 − α_A)·B                 a=1 b=1 cB=−1
//   under     B + (1 − α_B)·A  (B over A)     a=1 b=1 cA=−1
//   in        A·α_B                            cA=1
//   out       A·(1 − α_B)                      a=1 cA=−1
//   atop      A·α_B + B·(1 − α_A)              b=1 cA=1 cB=−1
//   xor       A·(1 − α_B) + B·(1 − α_A)        a=1 b=1 cA=−1 cB=−1
//   add       A + B                            a=1 b=1
//   multiply  A·B + A·(1 − α_B) + B·(1 − α_A)  a=1 b=1 cA=−1 cB=−1 p=1
//   screen    A + B − A·B                      a=1 b=1 p=−1
//   mix       B (with the amount t below: the dissolve (1 − t)·A + t·B)
//
// The amount t ∈ [0, 1] blends the result with the photo: z = (1 − t)·A + t·(A op B), still one
// quadratic form per element; t = 1 is the operator itself. eq 5 then divides the colour by its
// weight z_α and keeps z_α, clamped to [0, 1], as the output alpha: where z_α ≤ 1 (every
// operator but add, whose alpha may pass 1) the rendered premultiplied pixel is z itself.
//
// The geometry is the identity on the frame, so the renderer takes its colour-only path (no
// resampling); the second-colour outputs pass B through unchanged and are not rendered.
#pragma once

#include "core/model/camera.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace artcam {

enum class CompositeOp { Over, Under, In, Out, Atop, Xor, Add, Multiply, Screen, Mix };

// In this order, the names `artcam preset composite --op NAME` takes: "over", "under", ….
const std::vector<std::string>& compositeOpNames();
std::string_view compositeOpName(CompositeOp op);
std::optional<CompositeOp> compositeOpFromName(std::string_view name);

// Blocks [position 3 | colour 4 | second-colour 4], one stage, identity geometry on `frame`
// (source and target), colour outputs (1 − amount)·A + amount·(A op B) as above. Throws
// std::invalid_argument for an amount outside [0, 1] or a frame that is not an image.
Camera compositeCamera(CompositeOp op, double amount, FrameSize frame);

}  // namespace artcam
