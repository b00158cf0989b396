// SPDX-License-Identifier: Apache-2.0
// The canvas's view-mode controls (canvas_view_mode.h): View menu entries Photo, Result, Split
// and Onion (Alt+1 … Alt+4, one checked), "Before/After" on `\` (Photo ↔ the last mode that
// showed the result, as in Photoshop), and a "Canvas" toolbar with the same modes and the onion
// opacity slider. The Split divider is dragged on the canvas itself (its handle, or Alt+drag).
// Kept apart from main_window.cpp, which only calls this.
#pragma once

class QMainWindow;
class QMenu;

namespace artcam::ui {

class Canvas;

void addCanvasViewActions(QMainWindow* window, Canvas* canvas, QMenu* view_menu);

}  // namespace artcam::ui
