// Rigid bodies: one shape each, static or dynamic (origin.md §3 "Bodies").
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "rigidlab/math.h"
#include "rigidlab/shape.h"

namespace rigidlab {

// A handle: slot index plus generation. A handle to a destroyed body is detected (the generation no
// longer matches), never dereferenced.
struct BodyId {
  uint32_t index = UINT32_MAX;
  uint32_t generation = 0;

  bool isNull() const { return index == UINT32_MAX; }
  friend bool operator==(const BodyId&, const BodyId&) = default;
};

// Static bodies have infinite mass: no force acts on them and integration skips them. A body can
// switch between the two at run time (World::setType).
enum class BodyType { Static, Dynamic };

// Surface material. When two bodies touch, their values combine as (README "Materials"):
//   restitution  e  = max(e_A, e_B)            a bouncy ball bounces on any floor
//   friction     μ  = sqrt(μ_A · μ_B)          for both dynamic and static friction;
//                                               a frictionless body slides on anything
struct Material {
  double restitution = 0.0;      // Newton's coefficient, 0 (plastic) … 1 (elastic)
  double friction = 0.6;         // dynamic (sliding) friction coefficient f_d ≥ 0
  double static_friction = 0.6;  // static friction coefficient f_s ≥ 0 (holds up to f_s·F_n)
};

// Everything needed to create a body. Every field has a default except the shape.
struct BodyDef {
  BodyType type = BodyType::Dynamic;
  Shape shape;                                 // makeCircle / makeBox / makePolygon
  Vec2 position = Vec2::Zero();                // world position of the body origin [m]
  double angle = 0.0;                          // [rad], counter-clockwise
  Vec2 velocity = Vec2::Zero();                // of the centre of mass [m/s]
  double angular_velocity = 0.0;               // [rad/s]
  double density = 1.0;                        // [kg/m²], used when `mass` is not given
  std::optional<double> mass;                  // [kg]; overrides density (density = mass / area)
  double restitution = 0.0;                    // see Material
  double friction = 0.6;                       // dynamic friction
  std::optional<double> static_friction;       // defaults to `friction`
  std::string name;                            // optional, for lookups and messages
};

// A body as the world holds it. Read it with World::body(id); change it through World's setters
// so that derived data (transform, bounds, inverse mass) stays consistent.
struct Body {
  BodyId id;
  uint32_t uid = 0;  // 1, 2, 3, ... in creation order, never reused: the id scripts and reports show
  std::string name;
  BodyType type = BodyType::Dynamic;
  Shape shape;
  Material material;

  // Mass properties. `mass` and `inertia` are those of the shape even for a static body (so it can
  // be switched back to dynamic); the inverse values are 0 for a static body.
  double density = 1.0;          // kg/m²
  double area = 0.0;             // m²
  double mass = 0.0;             // kg
  double inertia = 0.0;          // kg·m², about the centre of mass
  double inv_mass = 0.0;
  double inv_inertia = 0.0;
  Vec2 local_center = Vec2::Zero();  // centre of mass in body coordinates

  // State. The centre of mass is what is integrated; the origin transform follows from it.
  Vec2 center = Vec2::Zero();    // world centre of mass [m]
  double angle = 0.0;            // [rad]
  Vec2 velocity = Vec2::Zero();  // centre-of-mass velocity [m/s]
  double angular_velocity = 0.0; // [rad/s]
  Transform xf;                  // body origin → world

  // Set by the NaN firewall (World::incidents): the body's state became non-finite during a step,
  // so it was put back where the step began and made static, so it cannot poison other bodies
  // through contacts. Switching it back to dynamic (World::setType) clears the flag.
  bool frozen = false;

  // Sleeping (World::step, sleep.cpp): a dynamic body whose island has been nearly still for
  // WorldDef::time_to_sleep stops being simulated until something touches, pushes or edits it.
  bool awake = true;
  double sleep_time = 0.0;  // how long it has been below the sleep speeds [s]

  Vec2 position() const { return xf.p; }
  bool isStatic() const { return type == BodyType::Static; }
  // Velocity of a world point attached to the body: v + ω × (p − c).
  Vec2 pointVelocity(const Vec2& world_point) const { return velocity + cross(angular_velocity, world_point - center); }
};

}  // namespace rigidlab
