// Live error against Exact(t) (exact_readout.h).
#include "exact_readout.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rigidlab::sandbox {

void ExactReadout::reset(const lua::Scene& scene) {
  *this = ExactReadout{};
  active = scene.hasExact();
}

void ExactReadout::update(lua::Scene& scene) {
  if (!active) return;
  const World& world = scene.world();
  std::vector<lua::Scene::ExactState> states;
  try {
    states = scene.exact(world.time());
  } catch (const std::exception& e) {
    error = e.what();
    active = false;
    return;
  }
  time = world.time();
  bodies.clear();
  max_position = 0.0;
  max_velocity = -1.0;
  for (const auto& s : states) {
    const auto id = world.findBody(s.uid);
    if (!id) continue;  // removed since (by an edit): nothing to compare
    const Body& b = world.body(*id);
    BodyError e;
    e.uid = b.uid;
    e.name = b.name;
    e.exact_position = s.position;
    e.position = (b.xf.p - s.position).norm();
    if (s.velocity) e.velocity = (b.velocity - *s.velocity).norm();
    if (s.angle) e.angle = std::abs(std::remainder(b.angle - *s.angle, 2.0 * std::numbers::pi));
    max_position = std::max(max_position, e.position);
    max_velocity = std::max(max_velocity, e.velocity);
    bodies.push_back(e);
  }
  worst_position = std::max(worst_position, max_position);
  if (!history.empty() && time < history.back().first) history.clear();
  if (!history.empty() && time == history.back().first) history.pop_back();
  history.emplace_back(time, max_position);
  while (!history.empty() && history.front().first < time - 20.0) history.pop_front();
}

}  // namespace rigidlab::sandbox
