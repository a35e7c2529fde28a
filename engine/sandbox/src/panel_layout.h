// Where the sandbox's panels sit in the window (panel_dock.h places them from here), and the part
// of the window they leave free for the world: the initial view, a scene's own view, Fit and the
// followed body are framed there, so that no body starts behind a panel.
#pragma once

#include <span>
#include <string_view>
#include <vector>

#include "camera.h"

namespace rigidlab::sandbox {

// The controls column on the left (the controls, the selection's inspectors, the scene browser),
// the readouts column on the right (statistics, the scene's controls, energy, exact solution,
// profile), with a margin around each. The two are as wide, so the free area's middle is the
// window's: a scene's centre stays the window's middle whether the panels are shown or not.
inline constexpr float kLeftPanelWidth = 300.0f, kRightPanelWidth = 300.0f, kPanelMargin = 8.0f;
// Narrower than this between the columns (a small window), the whole window is used instead.
inline constexpr double kMinFreeWidth = 200.0;
// A docked panel given less room than this is shown collapsed (its title bar) instead.
inline constexpr float kMinPanelHeight = 80.0f;

// The window area between the two columns (the whole window when the panels are hidden, Tab).
ScreenRect freeViewArea(int width_px, int height_px, bool panels_shown);

enum class Column { Left, Right };

struct PanelRequest {
  Column column = Column::Left;
  float height = 0.0f;        // what its content wants [px], title bar included
  float title_height = 0.0f;  // its title bar alone: its height collapsed
};

struct PanelPlace {
  ScreenRect rect;          // empty (zero height) when the column has no room left for it at all
  bool collapsed = false;   // given only its title bar: the room left was under kMinPanelHeight
  bool shown() const { return rect.height() > 0.0; }
};

// Docks the panels: each column stacks its panels from the top in the order given, a margin apart
// and from the window's edges, none over another nor over a `keep_clear` rectangle (the scene's
// screen-space HUD) that reaches into the column, which splits the column into free stretches.
// A panel goes whole into the first stretch it fits in (in the last one, leaving room for the
// title bars of the panels after it); if none holds it whole it gets the roomiest stretch (its
// content then scrolls) if that has kMinPanelHeight, else only its title bar (collapsed) where
// that fits, else an empty rectangle. Panels keep their order down a column.
std::vector<PanelPlace> dockPanels(int width_px, int height_px, std::span<const PanelRequest> panels,
                                   std::span<const ScreenRect> keep_clear);

}  // namespace rigidlab::sandbox
