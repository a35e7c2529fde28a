// The docked layout of the panels (panel_layout.h dockPanels): two columns, panels stacked in order,
// none over another, over the window's edge or over the scene's HUD, whatever the panels' heights;
// and the Profile panel's figures (profile_history.h).
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "panel_layout.h"
#include "profile_history.h"

using namespace rigidlab;
using namespace rigidlab::sandbox;

namespace {

constexpr float kTitle = 19.0f;

bool overlap(const ScreenRect& a, const ScreenRect& b) {
  return a.lower.x() < b.upper.x() && b.lower.x() < a.upper.x() && a.lower.y() < b.upper.y() && b.lower.y() < a.upper.y();
}

// Every shown panel inside the window, none over another or over a kept-clear rectangle, each
// column in the order given; returns how many were shown.
int checkLayout(int w, int h, const std::vector<PanelRequest>& panels, const std::vector<ScreenRect>& clear) {
  const std::vector<PanelPlace> places = dockPanels(w, h, panels, clear);
  REQUIRE(places.size() == panels.size());
  int shown = 0;
  double last_left = -1, last_right = -1;
  for (size_t i = 0; i < places.size(); ++i) {
    const PanelPlace& p = places[i];
    if (!p.shown()) continue;
    ++shown;
    CAPTURE(i);
    const ScreenRect& r = p.rect;
    CHECK(r.lower.x() >= 0);
    CHECK(r.lower.y() >= 0);
    CHECK(r.upper.x() <= w);
    CHECK(r.upper.y() <= h);
    CHECK(r.width() == (panels[i].column == Column::Left ? kLeftPanelWidth : kRightPanelWidth));
    if (p.collapsed) CHECK(r.height() == doctest::Approx(panels[i].title_height));
    else CHECK(r.height() >= std::min<double>(panels[i].height, kMinPanelHeight) - 1e-9);
    CHECK(r.height() <= std::max(panels[i].height, panels[i].title_height) + 1e-9);
    double& last = panels[i].column == Column::Left ? last_left : last_right;
    CHECK(r.lower.y() > last);  // order kept down the column
    last = r.lower.y();
    for (size_t j = i + 1; j < places.size(); ++j)
      if (places[j].shown()) CHECK_FALSE(overlap(r, places[j].rect));
    for (const ScreenRect& c : clear) CHECK_FALSE(overlap(r, c));
  }
  return shown;
}

}  // namespace

TEST_CASE("panel layout: the default panels in two columns at 1280x800 and 1920x1080, whole and apart") {
  const std::vector<PanelRequest> panels = {
      {Column::Left, 350, kTitle}, {Column::Left, 300, kTitle},                                  // controls, scenes
      {Column::Right, 116, kTitle}, {Column::Right, 200, kTitle}, {Column::Right, 310, kTitle},  // stats, energy, profile
  };
  for (const auto& [w, h] : {std::pair{1280, 800}, std::pair{1920, 1080}}) {
    CAPTURE(w);
    const std::vector<PanelPlace> places = dockPanels(w, h, panels, {});
    CHECK(checkLayout(w, h, panels, {}) == 5);
    for (size_t i = 0; i < panels.size(); ++i) {
      CHECK_FALSE(places[i].collapsed);
      CHECK(places[i].rect.height() == panels[i].height);  // each whole
    }
    CHECK(places[0].rect.lower == Vec2(kPanelMargin, kPanelMargin));
    CHECK(places[1].rect.lower.y() == kPanelMargin + 350 + kPanelMargin);
    CHECK(places[2].rect.lower == Vec2(w - kPanelMargin - kRightPanelWidth, kPanelMargin));
    // The columns leave the free view area alone.
    const ScreenRect free = freeViewArea(w, h, true);
    for (const PanelPlace& p : places) CHECK_FALSE(overlap(p.rect, free));
    CHECK(free.middle().x() == doctest::Approx(0.5 * w));  // as wide columns: the window's middle
  }
}

TEST_CASE("panel layout: a panel that grows pushes the ones below it down instead of covering them") {
  // Statistics with its sections opened, then the Body panel under World settings: the panels
  // after them move down; in the last stretch they get what is left.
  std::vector<PanelRequest> panels = {{Column::Right, 116, kTitle}, {Column::Right, 200, kTitle}, {Column::Right, 310, kTitle}};
  const auto before = dockPanels(1280, 800, panels, {});
  panels[0].height = 300;
  const auto after = dockPanels(1280, 800, panels, {});
  CHECK(after[1].rect.lower.y() == doctest::Approx(before[1].rect.lower.y() + 184));
  CHECK(after[2].rect.lower.y() >= after[1].rect.upper.y() + kPanelMargin);
  CHECK(after[2].rect.upper.y() <= 800 - kPanelMargin);
  CHECK(after[2].rect.height() < 310);  // squeezed: its content scrolls
  checkLayout(1280, 800, panels, {});
}

TEST_CASE("panel layout: the scene's HUD is kept clear; a panel goes below it or into the roomiest stretch") {
  // mouse_spawn's HUD, bottom right of a 1280x800 window.
  const std::vector<ScreenRect> hud = {{Vec2(1088, 628), Vec2(1282, 702)}};
  const std::vector<PanelRequest> panels = {{Column::Right, 116, kTitle}, {Column::Right, 77, kTitle},
                                            {Column::Right, 200, kTitle}, {Column::Right, 310, kTitle}};
  const auto places = dockPanels(1280, 800, panels, hud);
  checkLayout(1280, 800, panels, hud);
  // The profile (310) fits neither above the HUD nor below it: it takes the larger stretch, above.
  CHECK(places[3].rect.upper.y() <= hud[0].lower.y() - kPanelMargin);
  CHECK(places[3].rect.height() >= kMinPanelHeight);
  // A small panel after it goes below the HUD.
  std::vector<PanelRequest> more = panels;
  more.push_back({Column::Right, 70, kTitle});
  const auto with_small = dockPanels(1280, 800, more, hud);
  CHECK(with_small[4].rect.lower.y() >= hud[0].upper.y() + kPanelMargin);
  checkLayout(1280, 800, more, hud);
  // A HUD in the middle of the window does not touch the columns.
  const std::vector<ScreenRect> middle = {{Vec2(500, 0), Vec2(700, 800)}};
  const auto untouched = dockPanels(1280, 800, panels, middle);
  CHECK(untouched[3].rect.height() == 310);
}

TEST_CASE("panel layout: too many panels for the window: squeezed, then collapsed, then left out, never over each other") {
  const auto count = [](const std::vector<PanelPlace>& places, auto pred) {
    return std::count_if(places.begin(), places.end(), pred);
  };
  // Twelve: the first gets what the others' title bars leave (its content scrolls), they collapse.
  std::vector<PanelRequest> panels(12, PanelRequest{Column::Left, 200, kTitle});
  auto places = dockPanels(1280, 400, panels, {});
  CHECK(places[0].rect.height() >= kMinPanelHeight);
  CHECK(places[0].rect.height() < 200);
  CHECK(count(places, [](const PanelPlace& p) { return p.collapsed; }) == 11);
  checkLayout(1280, 400, panels, {});
  // Twenty: not even the title bars fit; the last ones are left out.
  panels.resize(20, panels[0]);
  places = dockPanels(1280, 400, panels, {});
  CHECK(count(places, [](const PanelPlace& p) { return p.collapsed; }) > 0);
  CHECK(count(places, [](const PanelPlace& p) { return !p.shown(); }) > 0);
  CHECK_FALSE(places.back().shown());
  checkLayout(1280, 400, panels, {});
}

TEST_CASE("panel layout: random heights, columns and HUDs: never a panel over another, a HUD or the window's edge") {
  std::mt19937 rng(35);
  std::uniform_real_distribution<float> height(10, 600);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int round = 0; round < 2000; ++round) {
    const int w = 700 + static_cast<int>(unit(rng) * 1400), h = 300 + static_cast<int>(unit(rng) * 900);
    std::vector<PanelRequest> panels(1 + rng() % 9);
    for (PanelRequest& p : panels) p = {rng() % 2 ? Column::Left : Column::Right, height(rng), kTitle};
    std::vector<ScreenRect> hud(rng() % 3);
    for (ScreenRect& r : hud) {
      const Vec2 a(unit(rng) * w, unit(rng) * h);
      r = {a, a + Vec2(20 + unit(rng) * 300, 20 + unit(rng) * 200)};
    }
    CAPTURE(round);
    checkLayout(w, h, panels, hud);
  }
}

TEST_CASE("profile: each stage's last, average and largest time over the window of wall time") {
  ProfileHistory h(2.0);
  StepStats a;
  a.integrate_ms = 1.0;
  a.solve_ms = 3.0;
  StepStats b = a;
  b.integrate_ms = 3.0;
  b.solve_ms = 1.0;
  h.add(a, 10.0);
  h.add(b, 10.5);
  const auto integrate = h.stage(0), solve = h.stage(4), step = h.stage(kProfileStages.size() - 1);
  CHECK(integrate.last == 3.0);
  CHECK(integrate.average == 2.0);
  CHECK(integrate.maximum == 3.0);
  CHECK(solve.maximum == 3.0);
  CHECK(step.average == 4.0);  // the step is the stages' sum
  CHECK(h.stepTimes() == std::vector<float>{4.0f, 4.0f});
  // Two seconds later the first step has left the window.
  StepStats c;
  c.integrate_ms = 0.5;
  h.add(c, 12.2);
  CHECK(h.steps() == 2);
  CHECK(h.stage(0).maximum == 3.0);
  CHECK(h.stage(0).average == doctest::Approx(1.75));
  h.add(c, 20.0);
  CHECK(h.steps() == 1);
  CHECK(h.stage(0).maximum == 0.5);
  h.clear();
  CHECK(h.stage(0).average == 0.0);
}
