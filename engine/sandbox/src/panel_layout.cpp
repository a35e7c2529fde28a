// The area the panels leave free (panel_layout.h).
#include "panel_layout.h"

namespace rigidlab::sandbox {

ScreenRect freeViewArea(int width_px, int height_px, bool panels_shown) {
  const ScreenRect window{Vec2::Zero(), Vec2(width_px, height_px)};
  if (!panels_shown) return window;
  const double left = 2.0 * kPanelMargin + kLeftPanelWidth;
  const double right = width_px - (2.0 * kPanelMargin + kRightPanelWidth);
  if (right - left < kMinFreeWidth) return window;
  return ScreenRect{Vec2(left, 0.0), Vec2(right, height_px)};
}

}  // namespace rigidlab::sandbox
