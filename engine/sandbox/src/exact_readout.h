// The live error of a scene that knows its closed-form solution (Scene::exact, scripts/accuracy/):
// after each frame's steps the sandbox asks Exact(t) for the true states and shows how far the
// simulation is from them, and draws the exact positions as ghosts beside the bodies.
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "rigidlab/lua/scene.h"

namespace rigidlab::sandbox {

struct BodyError {
  uint32_t uid = 0;
  std::string name;
  Vec2 exact_position = Vec2::Zero();  // body origin [m]
  double position = 0.0;               // ‖p − p_exact‖ [m]
  double velocity = -1.0;              // ‖v − v_exact‖ [m/s], −1 if Exact gives no velocity
  double angle = -1.0;                 // |θ − θ_exact| [rad], −1 if not given
};

struct ExactReadout {
  bool active = false;        // the scene defines Exact and it has not failed
  double time = 0.0;          // [s] of the last comparison
  std::vector<BodyError> bodies;
  double max_position = 0.0;  // [m] over the bodies, now
  double max_velocity = -1.0; // [m/s], −1 if no body has an exact velocity
  double worst_position = 0.0;  // [m] the largest max_position since the scene started
  std::deque<std::pair<double, double>> history;  // (t, max_position) for the plot, last 20 s
  std::string error;          // Exact failed: shown, and Exact is not called again until a reload

  void reset(const lua::Scene& scene);
  // Compares the world with Exact(world.time()). Velocities compare the body's centre-of-mass
  // velocity with the answer's (they coincide for the point masses and discs Exact is used with).
  void update(lua::Scene& scene);
};

}  // namespace rigidlab::sandbox
