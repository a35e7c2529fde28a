// The Dear ImGui panels: controls (scene, tools, world settings, drawing), scene browser,
// statistics, profile, energy plot, the selected body or joint, help, save dialog, and the error
// overlay.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "panel_dock.h"
#include "session.h"

namespace rigidlab::sandbox {

class Renderer;

struct PanelState {
  // A property edit in progress in the Body or Joint panel: the state before it, committed to the
  // undo history when the field is left (one undo step per edit, not per keystroke).
  std::optional<BodyProps> edit_before;
  BodyId edit_body;
  std::optional<JointDef> joint_before;
  JointId edit_joint;
  BodyId shown_body;    // the body the Body panel shows
  int shape_index = 0;  // which of its shapes (0-based)
  std::vector<std::filesystem::path> scenes;  // browser list, refreshed when the browser opens
  bool browser_was_open = false;
  double fps = 0.0;  // smoothed
  PanelDock dock;
};

// Builds this frame's panels (between ImGui::NewFrame and ImGui::Render).
void drawPanels(Session& s, PanelState& p, Renderer& renderer);

}  // namespace rigidlab::sandbox
