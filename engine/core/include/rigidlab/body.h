// Rigid bodies: static, kinematic or dynamic, made of one or more shapes (docs/design/thesis.md §3 "Bodies";
// docs/physics.md "Bodies").
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

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

// Static bodies never move; no force acts on them. Kinematic bodies move by their velocity alone
// (no gravity, no forces, no contact impulses: infinite mass) and push dynamic bodies, which they
// carry by friction. Dynamic bodies respond to everything. A body can switch at run time
// (World::setType).
enum class BodyType : uint8_t { Static, Kinematic, Dynamic };
const char* bodyTypeName(BodyType t);  // "static", "kinematic", "dynamic"

// Everything needed to create a body. Every field has a default. `shape`, if given, becomes the
// body's first shape with the material, density and filter below (a one-shape body); more shapes
// are added with World::createShape.
struct BodyDef {
  BodyType type = BodyType::Dynamic;
  std::optional<Shape> shape;                  // makeCircle / makeBox / makePolygon / makeCapsule / ...
  Vec2 position = Vec2::Zero();                // world position of the body origin [m]
  double angle = 0.0;                          // [rad], counter-clockwise
  Vec2 velocity = Vec2::Zero();                // of the centre of mass [m/s] (static: must be zero)
  double angular_velocity = 0.0;               // [rad/s]
  double density = 1.0;                        // [kg/m²] of `shape`, used when `mass` is not given
  std::optional<double> mass;                  // [kg]; overrides density (density = mass / area)
  double restitution = 0.0;                    // of `shape`, see Material
  double friction = 0.6;                       // dynamic friction of `shape`
  std::optional<double> static_friction;       // defaults to `friction`
  Filter filter;                               // of `shape`
  bool sensor = false;                         // `shape` is a sensor
  // Damping of the body's own motion, implicit: v ← v / (1 + h c) per step, so it never flips a
  // velocity whatever c and the step h [1/s] ≥ 0.
  double linear_damping = 0.0;
  double angular_damping = 0.0;
  double gravity_scale = 1.0;                  // multiplies the world's gravity for this body
  // This body's own gravity [m/s²], in place of the world's (planet gravity, a balloon that rises):
  // integrated exactly as the world's is, still times gravity_scale. Not given: the world's.
  std::optional<Vec2> gravity;
  bool fixed_rotation = false;                 // never turns (infinite inertia), contacts included
  // Swept against dynamic bodies too (every body is swept against static ones), so a fast small
  // body does not pass through a thin moving one.
  bool bullet = false;
  // A disabled body is out of the simulation (no contacts, no motion, no forces) but keeps its id,
  // shapes and state, and comes back where it was when enabled again.
  bool enabled = true;
  // false: created asleep (a dynamic body with zero velocity, in a world that sleeps): it costs
  // nothing until something touches, pushes or edits it, like a body that fell asleep (a pile
  // built at rest, debris waiting to be hit).
  bool awake = true;
  // false: never falls asleep, nor lets its island sleep (a player's body, a sensor carrier).
  bool sleeping_allowed = true;
  std::string name;                            // optional, for lookups and messages
};

// A body as the world holds it. Read it with World::body(id); change it through World's setters
// so that derived data (transform, bounds, inverse mass) stays consistent.
struct Body {
  BodyId id;
  uint32_t uid = 0;  // 1, 2, 3, ... in creation order, never reused: the id scripts and reports show
  BodyType type = BodyType::Dynamic;
  bool enabled = true;  // BodyDef::enabled
  // Sleeping (World::step, sleep.cpp): a dynamic body whose island has been nearly still for
  // WorldDef::time_to_sleep stops being simulated until something touches, pushes or edits it.
  bool awake = true;
  // Set by the NaN firewall (World::incidents): the body's state became non-finite during a step,
  // so it was put back where the step began and made static, so it cannot poison other bodies
  // through contacts. Switching it back to dynamic (World::setType) clears the flag.
  bool frozen = false;
  bool fixed_rotation = false, bullet = false;  // BodyDef
  bool own_gravity = false;       // BodyDef::gravity was given (or set): `gravity` replaces the world's
  bool sleeping_allowed = true;   // BodyDef
  bool inertia_set = false;       // World::setInertia overrides the shapes' inertia (until the shapes change)

  // State. The centre of mass is what is integrated; the origin transform follows from it.
  Transform xf;                  // body origin → world
  Vec2 center = Vec2::Zero();    // world centre of mass [m]
  double angle = 0.0;            // [rad]
  double sleep_time = 0.0;       // how long it has been below the sleep speeds [s]
  Vec2 velocity = Vec2::Zero();  // centre-of-mass velocity [m/s]
  double angular_velocity = 0.0; // [rad/s]

  // Mass properties, summed over the shapes (parallel-axis theorem). `mass` and `inertia` are
  // those of the shapes even for a static or kinematic body (so it can be switched back to
  // dynamic); the inverse values are 0 for those, and inv_inertia for a fixed-rotation body. A
  // dynamic body without shapes has mass 1 kg and inertia 1 kg·m².
  double inv_mass = 0.0;
  double inv_inertia = 0.0;
  // BodyDef. Beside the inverse mass: the integrator reads them with it, body by body (the fields
  // a step reads of every body are kept within the first three cache lines).
  double linear_damping = 0.0, angular_damping = 0.0, gravity_scale = 1.0;
  double mass = 0.0;             // kg
  double inertia = 0.0;          // kg·m², about the centre of mass
  Vec2 local_center = Vec2::Zero();  // centre of mass in body coordinates
  double density = 1.0;          // kg/m²: mass / area (the shapes' common density if they share one)
  double area = 0.0;             // m², of all shapes
  // Of the shapes that are not sensors (derived): the smallest inner radius and the largest
  // distance from the origin, which bound what the body can skip in a step and how fast its
  // points move as it turns (continuous collision detection).
  double min_inradius = 0.0, max_extent = 0.0;

  std::vector<ShapeId> shapes;  // in the order they were added (World::shape)
  std::string name;
  // BodyDef::gravity, read only when own_gravity is set (kept out of the fields every step reads).
  Vec2 gravity = Vec2::Zero();

  Vec2 position() const { return xf.p; }
  bool isStatic() const { return type == BodyType::Static; }
  bool isKinematic() const { return type == BodyType::Kinematic; }
  bool isDynamic() const { return type == BodyType::Dynamic; }
  // Velocity of a world point attached to the body: v + ω × (p − c).
  Vec2 pointVelocity(const Vec2& world_point) const { return velocity + cross(angular_velocity, world_point - center); }
  // The gravity acting on the body: its own or the world's, before gravity_scale.
  Vec2 gravityOr(const Vec2& world_gravity) const { return own_gravity ? gravity : world_gravity; }
};

// A shape attached to a body, as the world holds it (World::shape). Change it through World's
// setters (setShapeMaterial, setShapeFilter, ...).
struct BodyShape {
  BodyId body;
  bool sensor = false;
  bool default_filter = true;  // derived: `filter` is Filter{} (the narrow phase skips the test)
  bool contact_events = false, hit_events = false, pre_solve = false;  // ShapeDef
  double hit_speed = 1.0;
  std::optional<Vec2> one_way;  // ShapeDef (unit, body coordinates)
  double tangent_speed = 0.0, rolling_resistance = 0.0;  // ShapeDef
  uint32_t chain = 0;      // chain segments: 1-based number of their chain (World::createChain), else 0
  ShapeId id;
  Material material;
  Filter filter;
  double density = 1.0;    // kg/m²
  Shape geometry;          // body coordinates
};

}  // namespace rigidlab
