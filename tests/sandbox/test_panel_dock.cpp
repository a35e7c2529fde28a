// The docked panels in a real Dear ImGui context, headless (no window, no renderer: frames are
// built and ended, the mouse is fed to ImGui's io): panels are stacked from the heights their
// content takes, re-stacked when one grows, and a panel dragged by its title bar is undocked,
// follows the mouse and leaves its place to the next one until dockAll.
#include <doctest/doctest.h>

#include <imgui.h>
#include <imgui_internal.h>

#include <vector>

#include "panel_dock.h"

using namespace rigidlab;
using namespace rigidlab::sandbox;

namespace {

struct HeadlessImGui {
  HeadlessImGui() {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(1280, 720);
    io.DeltaTime = 1.0f / 60.0f;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);  // builds the font atlas NewFrame needs
  }
  ~HeadlessImGui() { ImGui::DestroyContext(); }
};

// One frame: the right column's Statistics (`lines` lines of text) above Energy (fixed 200 px).
void frame(PanelDock& dock, int lines, ImVec2 mouse = ImVec2(-FLT_MAX, -FLT_MAX), bool down = false) {
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = mouse;
  io.MouseDown[0] = down;
  ImGui::NewFrame();
  const std::vector<DockedPanel> panels = {{"Statistics", Column::Right, 130.0f}, {"Energy", Column::Right, 200.0f, true}};
  dock.layout(panels, io.DisplaySize, {});
  if (dock.begin("Statistics"))
    for (int i = 0; i < lines; ++i) ImGui::Text("line %d", i);
  dock.end();
  if (dock.begin("Energy")) ImGui::Text("plot");
  dock.end();
  ImGui::Render();
}

ScreenRect rect(const char* name) {
  const ImGuiWindow* w = ImGui::FindWindowByName(name);
  REQUIRE(w);
  return {Vec2(w->Pos.x, w->Pos.y), Vec2(w->Pos.x + w->Size.x, w->Pos.y + w->Size.y)};
}

}  // namespace

TEST_CASE("panel dock: panels stacked from their content's height, re-stacked as it grows, undocked by a drag") {
  HeadlessImGui imgui;
  PanelDock dock;
  for (int i = 0; i < 3; ++i) frame(dock, 4);
  const ScreenRect stats = rect("Statistics"), energy = rect("Energy");
  const float column_x = 1280 - kPanelMargin - kRightPanelWidth;
  CHECK(stats.lower == Vec2(column_x, kPanelMargin));
  CHECK(stats.width() == kRightPanelWidth);
  // As tall as its four lines, not the first guess of 130 px.
  const ImGuiStyle& style = ImGui::GetStyle();
  const double content = ImGui::GetFrameHeight() + style.WindowPadding.y * 2 + 4 * ImGui::GetTextLineHeightWithSpacing() -
                         style.ItemSpacing.y;
  CHECK(stats.height() == doctest::Approx(content).epsilon(0.01));
  CHECK(energy.lower.y() == doctest::Approx(stats.upper.y() + kPanelMargin));
  CHECK(energy.height() == 200);

  // Statistics grows by 10 lines: Energy moves down instead of being covered.
  for (int i = 0; i < 2; ++i) frame(dock, 14);
  const ScreenRect grown = rect("Statistics"), pushed = rect("Energy");
  CHECK(grown.height() > stats.height() + 9 * ImGui::GetTextLineHeight());
  CHECK(pushed.lower.y() == doctest::Approx(grown.upper.y() + kPanelMargin));

  // A drag of Statistics' title bar: pressed, then moved 400 px left and 250 down, then released.
  CHECK_FALSE(dock.anyUndocked());
  const ImVec2 grab(1150, kPanelMargin + 8);
  frame(dock, 4, grab, false);
  frame(dock, 4, grab, true);
  for (int step = 1; step <= 10; ++step) frame(dock, 4, ImVec2(grab.x - 40 * step, grab.y + 25 * step), true);
  frame(dock, 4, ImVec2(grab.x - 400, grab.y + 250), false);
  frame(dock, 4);
  CHECK(dock.anyUndocked());
  const ScreenRect moved = rect("Statistics"), closed_up = rect("Energy");
  CHECK(moved.lower.x() == doctest::Approx(column_x - 400));
  CHECK(moved.lower.y() == doctest::Approx(kPanelMargin + 250));
  CHECK(closed_up.lower == Vec2(column_x, kPanelMargin));  // Energy took its place

  // Dock panels: back in the column, Energy below it again.
  dock.dockAll();
  frame(dock, 4);
  CHECK_FALSE(dock.anyUndocked());
  CHECK(rect("Statistics").lower == Vec2(column_x, kPanelMargin));
  CHECK(rect("Energy").lower.y() == doctest::Approx(rect("Statistics").upper.y() + kPanelMargin));
}
