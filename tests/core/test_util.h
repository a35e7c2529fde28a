// Small helpers shared by the core tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "rigidlab/error.h"
#include "rigidlab/world.h"

namespace rigidlab::test {

// The message of the InputError `f` throws, or "(no error)".
inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

inline BodyId addBox(World& w, double width, double height, Vec2 position, bool is_static = false,
                     double angle = 0.0) {
  BodyDef d;
  d.type = is_static ? BodyType::Static : BodyType::Dynamic;
  d.shape = makeBox(width, height);
  d.position = position;
  d.angle = angle;
  return w.createBody(d);
}

inline BodyId addCircle(World& w, double radius, Vec2 position, double mass = 1.0) {
  BodyDef d;
  d.shape = makeCircle(radius);
  d.position = position;
  d.mass = mass;
  return w.createBody(d);
}

// A user-defined force, written only against the public Force interface: a Hooke spring pulling
// body a's centre towards the world origin, F = −k c. Used to show custom forces get the same
// treatment as built-in ones (RK4 stages).
class HookeToOrigin final : public Force {
 public:
  explicit HookeToOrigin(double k) : k_(k) {}
  void evaluate(const ForceInput& in, ForceOutput& out) override { out.a.force = -k_ * in.a.center; }
  double potentialEnergy(const BodyState& a, const BodyState*) const override {
    return 0.5 * k_ * a.center.squaredNorm();
  }
  std::string_view kind() const override { return "test_hooke"; }

 private:
  double k_;
};

// A revolute joint between a and b (null: the world) at a world anchor.
inline JointId revolute(World& w, BodyId a, BodyId b, Vec2 anchor) {
  JointDef d;
  d.type = JointType::Revolute;
  d.a = a;
  d.b = b;
  d.anchor_a = anchor;
  return w.createJoint(d);
}

// The largest distance between the two anchors of any of the joints [m].
inline double largestGap(const World& w, const std::vector<JointId>& joints) {
  double gap = 0.0;
  for (JointId j : joints) {
    const JointState s = w.jointState(j);
    gap = std::max(gap, (s.world_anchor_a - s.world_anchor_b).norm());
  }
  return gap;
}

// Least-squares slope of log(err) against log(dt): the observed order of convergence.
inline double fittedOrder(const std::vector<double>& dts, const std::vector<double>& errs) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(dts.size());
  for (size_t i = 0; i < dts.size(); ++i) {
    const double x = std::log(dts[i]), y = std::log(errs[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace rigidlab::test
