// The Controls panel (scene_controls_panel.h).
#include "scene_controls_panel.h"

#include <imgui.h>

namespace rigidlab::sandbox {

void sceneControlsWindow(Session& s, PanelDock& dock) {
  const auto& controls = s.scene->settings().controls;
  if (controls.empty()) return;
  if (!dock.begin("Controls")) {
    dock.end();
    return;
  }
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
  dock.end();
}

}  // namespace rigidlab::sandbox
