// The windows of the selection: the Body panel (body_panel.cpp: the body's fields and its shapes')
// and the Joint panel (joint_panel.cpp).
#pragma once

#include "panels.h"

namespace rigidlab::sandbox {

void bodyWindow(Session& s, PanelState& p);
void jointWindow(Session& s, PanelState& p);

}  // namespace rigidlab::sandbox
