// The panels docked in Dear ImGui (Dear ImGui 1.86 has no docking of its own): each frame the
// panels to show are laid out in their columns (panel_layout.h dockPanels) from the heights their
// content took the frame before, and each panel's window is put there. A panel the user drags
// away is undocked: it stays where it is put, and the others close up, until dockAll.
#pragma once

#include <imgui.h>

#include <map>
#include <span>
#include <string>
#include <vector>

#include "panel_layout.h"

namespace rigidlab::sandbox {

struct DockedPanel {
  const char* name;  // the ImGui window's name
  Column column;
  // The height before the content has been measured [px]; with `fixed`, always this height (a
  // panel whose content fills what it is given, as a plot).
  float height;
  bool fixed = false;
};

class PanelDock {
 public:
  // Lays out this frame's panels (in column order, the ones to show only) in a window of `size`,
  // clear of `keep_clear` (the scene's HUD).
  void layout(std::span<const DockedPanel> panels, ImVec2 size, std::span<const ScreenRect> keep_clear);
  // ImGui::Begin of a panel laid out this frame: docked, in its place (collapsed when it has no
  // room); undocked, where the user left it. Call end() whatever it returns.
  bool begin(const char* name, bool* open = nullptr, ImGuiWindowFlags flags = 0);
  // ImGui::End, noting the height the panel's content wants.
  void end();
  // Docks every panel again ("Dock panels").
  void dockAll();
  bool anyUndocked() const;

 private:
  struct State {
    float wanted = 0.0f;     // [px], title bar included
    bool measured = false;   // wanted is the content's (not the first guess)
    bool fixed = false;
    bool undocked = false;
    bool forced_collapse = false;  // collapsed by the layout, not by the user
    PanelPlace place;
    int frame = -1;          // the ImGui frame it was laid out in
  };
  std::map<std::string, State, std::less<>> states_;
  State* current_ = nullptr;
  bool skipped_ = false;  // the current panel had no room and was not begun
};

// Automation (--layout-file): every window Dear ImGui shows this frame, and the rectangles the
// docking kept clear, written to `file` as lines "panel X0 Y0 X1 Y1 NAME" (pixels from the
// window's top-left corner) after "window W H" and "view X0 Y0 X1 Y1" (the free area). Call after
// ImGui::Render. False with `error` set if the file cannot be written.
bool writeWindowRects(const std::string& file, ImVec2 size, const ScreenRect& view, std::span<const ScreenRect> hud,
                      const std::vector<std::string>& extra_lines, std::string& error);

}  // namespace rigidlab::sandbox
