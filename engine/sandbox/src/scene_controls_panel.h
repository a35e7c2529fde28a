// The Controls panel: the sliders and buttons a scene declares in `scene.controls`.
#pragma once

#include "panel_dock.h"
#include "session.h"

namespace rigidlab::sandbox {

// Shown while the scene has controls (between ImGui::NewFrame and ImGui::Render). A moved slider
// sets the scene's value (world.controls.<name>) and calls OnControl(world, name); so does a
// pressed button.
void sceneControlsWindow(Session& s, PanelDock& dock);

}  // namespace rigidlab::sandbox
