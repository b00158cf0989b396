// SPDX-License-Identifier: Apache-2.0
// The straight lines on the canvas (document.h, LineSet), drawn like the pairs whatever tool is
// active:
// - where the photo shows (Photo, Onion, left of the Split divider): each traced line as its
//   clicked points joined, labelled with its name and its remaining bow after the fit (the
//   largest distance of its mapped points from their own straight line, in px: DocumentFit's
//   line bows), coloured by that bow on the pairs' residual ramp (Canvas::residualColour), so
//   a line the camera cannot straighten stands out; the open line dashed;
// - where the result shows (Result, right of the divider): the same points mapped through the
//   geometry, i.e. where the edge lies in the result, which should now be straight.
// Disabled lines are grey and dashed, and a geometry that is not a line fit (a hand-set camera,
// a refused fit) leaves the lines neutral and unlabelled by a bow.
// Widget coordinates; line points are photo pixels (centres at i + 0.5).
#pragma once

class QPainter;

namespace artcam::ui {

class Canvas;
class Document;

void paintLines(QPainter& painter, const Canvas& canvas, const Document& document);

}  // namespace artcam::ui
