// The docked layout and the area the panels leave free (panel_layout.h).
#include "panel_layout.h"

#include <algorithm>

namespace rigidlab::sandbox {

ScreenRect freeViewArea(int width_px, int height_px, bool panels_shown) {
  const ScreenRect window{Vec2::Zero(), Vec2(width_px, height_px)};
  if (!panels_shown) return window;
  const double left = 2.0 * kPanelMargin + kLeftPanelWidth;
  const double right = width_px - (2.0 * kPanelMargin + kRightPanelWidth);
  if (right - left < kMinFreeWidth) return window;
  return ScreenRect{Vec2(left, 0.0), Vec2(right, height_px)};
}

namespace {

struct Stretch {
  double top, bottom;  // free from `top` to `bottom` [px]
};

// The free stretches of a column between x0 and x1: the window's height less the margins, less
// what the rectangles to keep clear cover (grown by the margin).
std::vector<Stretch> freeStretches(double x0, double x1, int height_px, std::span<const ScreenRect> keep_clear) {
  std::vector<Stretch> free{{kPanelMargin, height_px - kPanelMargin}};
  for (const ScreenRect& r : keep_clear) {
    if (r.upper.x() + kPanelMargin <= x0 || r.lower.x() - kPanelMargin >= x1) continue;  // beside the column
    const double top = r.lower.y() - kPanelMargin, bottom = r.upper.y() + kPanelMargin;
    std::vector<Stretch> next;
    for (const Stretch& s : free) {
      if (bottom <= s.top || top >= s.bottom) {
        next.push_back(s);
        continue;
      }
      if (top > s.top) next.push_back({s.top, top});
      if (bottom < s.bottom) next.push_back({bottom, s.bottom});
    }
    free = std::move(next);
  }
  return free;
}

}  // namespace

std::vector<PanelPlace> dockPanels(int width_px, int height_px, std::span<const PanelRequest> panels,
                                   std::span<const ScreenRect> keep_clear) {
  std::vector<PanelPlace> places(panels.size());
  for (const Column column : {Column::Left, Column::Right}) {
    const double width = column == Column::Left ? kLeftPanelWidth : kRightPanelWidth;
    const double x0 = column == Column::Left ? kPanelMargin : width_px - kPanelMargin - width;
    const std::vector<Stretch> stretches = freeStretches(x0, x0 + width, height_px, keep_clear);
    size_t k = 0;                                           // the stretch being filled
    double y = stretches.empty() ? 0.0 : stretches[0].top;  // its first free pixel
    for (size_t i = 0; i < panels.size(); ++i) {
      if (panels[i].column != column) continue;
      double titles_after = 0.0;  // the title bars the panels after this one need at least
      for (size_t j = i + 1; j < panels.size(); ++j)
        if (panels[j].column == column) titles_after += panels[j].title_height + kPanelMargin;
      const auto top = [&](size_t m) { return m == k ? y : stretches[m].top; };
      const auto room = [&](size_t m) {
        return stretches[m].bottom - top(m) - (m + 1 == stretches.size() ? titles_after : 0.0);
      };
      const auto place = [&](size_t m, double h, bool collapsed) {
        const double at = top(m);
        places[i] = {ScreenRect{Vec2(x0, at), Vec2(x0 + width, at + h)}, collapsed};
        k = m;
        y = at + h + kPanelMargin;
      };
      // Whole, in the first stretch it fits in; else squeezed into the roomiest (its content
      // scrolls); else collapsed where its title bar fits.
      size_t m = k;
      while (m < stretches.size() && panels[i].height > room(m)) ++m;
      if (m < stretches.size()) {
        place(m, panels[i].height, false);
        continue;
      }
      size_t roomiest = k;
      for (m = k; m < stretches.size(); ++m)
        if (room(m) > room(roomiest)) roomiest = m;
      if (roomiest < stretches.size() && room(roomiest) >= kMinPanelHeight) {
        place(roomiest, room(roomiest), false);
        continue;
      }
      for (m = k; m < stretches.size(); ++m)
        if (stretches[m].bottom - top(m) >= panels[i].title_height) {
          place(m, panels[i].title_height, true);
          break;
        }
    }
  }
  return places;
}

}  // namespace rigidlab::sandbox
