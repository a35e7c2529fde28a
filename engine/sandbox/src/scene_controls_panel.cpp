// The Controls panel (scene_controls_panel.h).
#include "scene_controls_panel.h"

#include <imgui.h>

#include <cfloat>

#include "panel_layout.h"

namespace rigidlab::sandbox {

void sceneControlsWindow(Session& s) {
  const auto& controls = s.scene->settings().controls;
  if (controls.empty()) return;
  const ImGuiIO& io = ImGui::GetIO();
  // In the readouts column, under the energy plot (and the exact solution's readout, if shown).
  const float top = s.exact.active || !s.exact.error.empty() ? 560.0f : 350.0f;
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - kRightPanelWidth - kPanelMargin, top), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSizeConstraints(ImVec2(kRightPanelWidth, 0), ImVec2(kRightPanelWidth, FLT_MAX));
  ImGui::Begin("Controls", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::PushItemWidth(180);
  for (size_t i = 0; i < controls.size(); ++i) {
    const auto& c = controls[i];
    ImGui::PushID(static_cast<int>(i));
    bool changed = false;
    if (c.kind == lua::SceneSettings::Control::Kind::Button) {
      changed = ImGui::Button(c.name.c_str());
    } else {
      double v = s.scene->controlValue(i);
      changed = ImGui::SliderScalar(c.name.c_str(), ImGuiDataType_Double, &v, &c.min, &c.max, "%.4g");
      if (changed) s.scene->setControlValue(i, v);
    }
    if (changed) runSceneHook(s, [&] {
        s.scene->onControl(c.name);
        return true;
      });
    ImGui::PopID();
  }
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace rigidlab::sandbox
