// Where the sandbox's panels sit in the window (panels.cpp lays them out from these), and the part
// of the window they leave free for the world: the initial view and Fit frame the scene there, so
// that no body starts behind a panel.
#pragma once

#include "camera.h"

namespace rigidlab::sandbox {

// The controls column on the left, the readouts column on the right (statistics, energy, exact
// solution, the scene's controls), with a margin around each.
inline constexpr float kLeftPanelWidth = 280.0f, kRightPanelWidth = 320.0f, kPanelMargin = 8.0f;
// Narrower than this between the columns (a small window), the whole window is used instead.
inline constexpr double kMinFreeWidth = 200.0;

// The window area between the two columns (the whole window when the panels are hidden, Tab).
ScreenRect freeViewArea(int width_px, int height_px, bool panels_shown);

}  // namespace rigidlab::sandbox
