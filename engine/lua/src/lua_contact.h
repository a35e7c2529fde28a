// Contacts as Lua tables (docs/lua-api.md "Events"): what event hooks, pre_solve functions,
// body:contacts() and world:contact_events() give, with the names of api::kContactFields.
#pragma once

#include "bindings.h"

namespace rigidlab::lua {

// A contact in the words of the Lua API: one point (the middle of the manifold's points) and the
// totals of its impulses, the manifold's points, and its surface.
struct ContactView {
  BodyId a, b;
  ShapeId shape_a, shape_b;
  Vec2 point = Vec2::Zero(), normal = Vec2::Zero();  // normal: unit, from a to b
  double approach_speed = 0.0;  // closing speed along the normal [m/s], > 0 approaching
  double normal_impulse = 0.0, tangent_impulse = 0.0;  // [N·s]
  int count = 0;  // the manifold's points:
  Vec2 points[2] = {Vec2::Zero(), Vec2::Zero()};
  double separations[2] = {0, 0}, normal_impulses[2] = {0, 0}, tangent_impulses[2] = {0, 0};
  double friction = 0.0, static_friction = 0.0, restitution = 0.0, tangent_speed = 0.0, rolling_resistance = 0.0;
  bool touching = true;
};
// An event of the step: the core's values (approach speed at the start of the step).
ContactView contactView(const World::ContactEvent& e);
// A current contact (World::contactsOf, the pre-solve callback): the closing speed with the bodies'
// velocities now, −n · (v_b(p) − v_a(p)); the impulses the last step applied.
ContactView contactView(const World& world, const ContactInfo& c);

// Pushes {a, b, shape_a, shape_b, point, normal, approach_speed, normal_impulse, tangent_impulse,
// points} and, if `kind` is given, kind = "begin" | "end" | "hit"; `points` lists the manifold's
// points ({point, separation, normal_impulse, tangent_impulse} each) and the table's metatable reads
// friction, static_friction, restitution, tangent_speed, rolling_resistance and touching
// (api::kContactFields). A body removed since is nil; a removed shape's handle says removed.
void pushContact(lua_State* L, Scene::Impl& scene, const ContactView& c, const char* kind = nullptr);

// pushContact for many contacts: what each table needs from the registry (the body and shape
// handle caches, the vec2 metatable, the field names) is pushed once, when the pusher is made,
// and removed by done(), which leaves what was pushed after them (docs/performance.md "Events").
class ContactPusher {
 public:
  ContactPusher(lua_State* L, Scene::Impl& scene);
  void push(const ContactView& c, const char* kind = nullptr);
  void done();

 private:
  lua_State* L_;
  Scene::Impl& scene_;
  int base_;  // the body handle cache; the shape handle cache and the metatable above it
};
const char* contactEventKind(World::ContactEvent::Kind kind);

// The metatables of contact tables and their points (lua_contact.cpp), at load.
void registerContactTypes(lua_State* L);

// body:contacts(), world:contact_events() and world:contacts().
int bodyContactsMethod(lua_State* L);
int contactEventsMethod(lua_State* L);
int worldContactsMethod(lua_State* L);

}  // namespace rigidlab::lua
