// The Controller's input handling (docs/design/thesis.md §11 "Events handled"): SDL mouse and keyboard events
// become camera moves, edits and tool gestures on the Session. Events that Dear ImGui wants (the
// cursor is over a panel, a text field has focus) are left to ImGui.
#pragma once

#include <span>

#include <SDL.h>

#include "session.h"

namespace rigidlab::sandbox {

class Renderer;

struct InputCapture {
  bool mouse = false;     // ImGui's io.WantCaptureMouse
  bool keyboard = false;  // ImGui's io.WantCaptureKeyboard
};

void handleEvent(Session& s, const SDL_Event& event, InputCapture capture);
// Per frame: the drag target follows the cursor even when only the camera moved under it.
void updateTools(Session& s);
// Previews of the gesture in progress (the body being drawn, the polygon so far, the drag spring).
void drawToolOverlay(const Session& s, Renderer& r);

struct Shortcut {
  const char* keys;
  const char* action;
};
// Every shortcut, for the F1 help and docs/sandbox.md.
std::span<const Shortcut> shortcuts();
const char* toolName(Tool tool);

// Switches tool, dropping a half-drawn polygon.
void selectTool(Session& s, Tool tool);
// Turns the selected body by `radians` about its centre of mass (paused only; undoable).
void rotateSelected(Session& s, double radians);
// Closes the polygon being drawn into a body (≥ 3 points).
void finishPolygon(Session& s);

}  // namespace rigidlab::sandbox
