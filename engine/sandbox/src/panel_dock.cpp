// Docked panels in Dear ImGui (panel_dock.h).
#include "panel_dock.h"

#include <imgui_internal.h>  // GImGui->MovingWindow (a drag of a window) and the window list

#include <cstdio>
#include <memory>

namespace rigidlab::sandbox {

void PanelDock::layout(std::span<const DockedPanel> panels, ImVec2 size, std::span<const ScreenRect> keep_clear) {
  const int frame = ImGui::GetFrameCount();
  const float title = ImGui::GetFrameHeight();
  std::vector<PanelRequest> requests;
  std::vector<State*> docked;
  for (const DockedPanel& p : panels) {
    State& st = states_[p.name];
    st.frame = frame;
    st.fixed = p.fixed;
    if (p.fixed || !st.measured) st.wanted = p.height;
    if (st.undocked) continue;
    requests.push_back({p.column, st.wanted, title});
    docked.push_back(&st);
  }
  const std::vector<PanelPlace> places =
      dockPanels(static_cast<int>(size.x), static_cast<int>(size.y), requests, keep_clear);
  for (size_t i = 0; i < docked.size(); ++i) docked[i]->place = places[i];
}

bool PanelDock::begin(const char* name, bool* open, ImGuiWindowFlags flags) {
  current_ = &states_[name];
  State& st = *current_;
  skipped_ = false;
  const bool docked = !st.undocked && st.frame == ImGui::GetFrameCount();
  if (docked) {
    if (!st.place.shown()) {  // no room at all in a tiny window
      skipped_ = true;
      return false;
    }
    const ScreenRect& r = st.place.rect;
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(r.lower.x()), static_cast<float>(r.lower.y())), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(r.width()), static_cast<float>(r.height())), ImGuiCond_Always);
    if (st.place.collapsed) {
      ImGui::SetNextWindowCollapsed(true, ImGuiCond_Always);
      st.forced_collapse = true;
    } else if (st.forced_collapse) {
      ImGui::SetNextWindowCollapsed(false, ImGuiCond_Always);  // room again
      st.forced_collapse = false;
    }
    flags |= ImGuiWindowFlags_NoResize;
  }
  const bool shown = ImGui::Begin(name, open, flags);
  // Dragged by its title bar: undocked from the next frame on (this frame it stays in place).
  const ImGuiContext& g = *GImGui;
  if (docked && g.MovingWindow && g.MovingWindow->RootWindow == ImGui::GetCurrentWindow()) st.undocked = true;
  return shown;
}

void PanelDock::end() {
  if (skipped_ || !current_) return;
  State& st = *current_;
  if (!st.fixed && !st.forced_collapse) {
    if (ImGui::IsWindowCollapsed()) {
      st.wanted = ImGui::GetFrameHeight();  // collapsed by the user: its title bar
    } else {
      // The content's bottom in window coordinates (scrolled content included), as tall as the
      // window must be to show it all.
      const ImGuiStyle& style = ImGui::GetStyle();
      st.wanted = ImGui::GetCursorPosY() - style.ItemSpacing.y + style.WindowPadding.y;
    }
    st.measured = true;
  }
  ImGui::End();
  current_ = nullptr;
}

void PanelDock::dockAll() {
  for (auto& [name, st] : states_) st.undocked = false;
}

bool PanelDock::anyUndocked() const {
  for (const auto& [name, st] : states_)
    if (st.undocked) return true;
  return false;
}

bool writeWindowRects(const std::string& file, ImVec2 size, const ScreenRect& view, std::span<const ScreenRect> hud,
                      const std::vector<std::string>& extra_lines, std::string& error) {
  const std::unique_ptr<FILE, int (*)(FILE*)> out(std::fopen(file.c_str(), "w"), std::fclose);
  if (!out) {
    error = "cannot write " + file;
    return false;
  }
  std::fprintf(out.get(), "window %.0f %.0f\n", size.x, size.y);
  std::fprintf(out.get(), "view %.1f %.1f %.1f %.1f\n", view.lower.x(), view.lower.y(), view.upper.x(), view.upper.y());
  for (const ScreenRect& r : hud)
    std::fprintf(out.get(), "hud %.1f %.1f %.1f %.1f\n", r.lower.x(), r.lower.y(), r.upper.x(), r.upper.y());
  for (const ImGuiWindow* w : GImGui->Windows) {
    if (!w->Active || w->Hidden || (w->Flags & (ImGuiWindowFlags_ChildWindow | ImGuiWindowFlags_Tooltip))) continue;
    std::fprintf(out.get(), "panel %.1f %.1f %.1f %.1f %s\n", w->Pos.x, w->Pos.y, w->Pos.x + w->Size.x,
                 w->Pos.y + w->Size.y, w->Name);
  }
  for (const std::string& line : extra_lines) std::fprintf(out.get(), "%s\n", line.c_str());
  if (std::ferror(out.get())) {
    error = "cannot write " + file;
    return false;
  }
  return true;
}

}  // namespace rigidlab::sandbox
