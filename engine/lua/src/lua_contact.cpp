// Contacts as Lua tables (lua_contact.h): the event hooks' and pre_solve functions' argument,
// body:contacts() and world:contact_events().
#include "lua_contact.h"

#include "lua_args.h"
#include "lua_shape.h"

namespace rigidlab::lua {

namespace {

// The fields events and current contacts share (the manifold's points, the surface).
template <typename C>
void copyPoints(const C& c, ContactView& v) {
  v.count = c.count;
  for (int i = 0; i < c.count; ++i) {
    v.points[i] = c.points[i];
    v.separations[i] = c.separations[i];
    v.normal_impulses[i] = c.normal_impulses[i];
    v.tangent_impulses[i] = c.tangent_impulses[i];
  }
  v.friction = c.friction;
  v.static_friction = c.static_friction;
  v.restitution = c.restitution;
  v.tangent_speed = c.tangent_speed;
  v.rolling_resistance = c.rolling_resistance;
}

}  // namespace

ContactView contactView(const World::ContactEvent& e) {
  ContactView v{e.a, e.b, e.shape_a, e.shape_b, e.point, e.normal, e.approach_speed, e.normal_impulse, e.tangent_impulse};
  copyPoints(e, v);
  v.touching = e.kind != World::ContactEvent::Kind::End;
  return v;
}

ContactView contactView(const World& world, const ContactInfo& c) {
  const Vec2 point = c.count == 2 ? Vec2(0.5 * (c.points[0] + c.points[1])) : c.points[0];
  double normal_impulse = 0.0, tangent_impulse = 0.0;
  for (int i = 0; i < c.count; ++i) {
    normal_impulse += c.normal_impulses[i];
    tangent_impulse += c.tangent_impulses[i];
  }
  const double approach = -(world.body(c.b).pointVelocity(point) - world.body(c.a).pointVelocity(point)).dot(c.normal);
  ContactView v{c.a, c.b, c.shape_a, c.shape_b, point, c.normal, approach, normal_impulse, tangent_impulse};
  copyPoints(c, v);
  v.touching = c.touching;
  return v;
}

const char* contactEventKind(World::ContactEvent::Kind kind) {
  switch (kind) {
    case World::ContactEvent::Kind::Begin:
      return "begin";
    case World::ContactEvent::Kind::End:
      return "end";
    case World::ContactEvent::Kind::Hit:
      return "hit";
  }
  return "?";
}

namespace {

// The names of a contact table, pushed once per pusher (ContactPusher::key): a key pushed from the
// stack and set with rawset skips the lookup of its C string that lua_setfield makes.
constexpr const char* kKeys[] = {"a", "b", "shape_a", "shape_b", "point", "normal", "approach_speed",
                                 "normal_impulse", "tangent_impulse", "kind", "x", "y", "points", "separation",
                                 "friction", "static_friction", "restitution", "tangent_speed", "rolling_resistance",
                                 "touching"};
enum Key {
  A, B, ShapeA, ShapeB, Point, Normal, ApproachSpeed, NormalImpulse, TangentImpulse, Kind, X, Y, Points, Separation,
  Friction, StaticFriction, Restitution, TangentSpeed, RollingResistance, Touching, KeyCount
};
constexpr int kSlots = 3 + KeyCount;  // the two caches, the metatable, the keys

}  // namespace

ContactPusher::ContactPusher(lua_State* L, Scene::Impl& scene) : L_(L), scene_(scene) {
  luaL_checkstack(L, kSlots + 8, "contacts");
  scene.handles.push(L);
  base_ = lua_gettop(L);
  scene.shape_handles.push(L);
  lua_rawgeti(L, LUA_REGISTRYINDEX, hostOf(L).vec2_metatable_ref);
  for (const char* k : kKeys) lua_pushstring(L, k);
}

void ContactPusher::done() {
  for (int k = 0; k < kSlots; ++k) lua_remove(L_, base_);
}

void pushContact(lua_State* L, Scene::Impl& scene, const ContactView& c, const char* kind) {
  ContactPusher pusher(L, scene);
  pusher.push(c, kind);
  pusher.done();
}

void ContactPusher::push(const ContactView& c, const char* kind) {
  lua_State* L = L_;
  Scene::Impl& scene = scene_;
  const World& w = *scene.world;
  const int metatable = base_ + 2;
  const auto key = [&](int k) { lua_pushvalue(L, base_ + 3 + k); };
  const auto vec = [&](int k, const Vec2& v) {
    key(k);
    lua_createtable(L, 0, 2);
    key(X);
    lua_pushnumber(L, v.x());
    lua_rawset(L, -3);
    key(Y);
    lua_pushnumber(L, v.y());
    lua_rawset(L, -3);
    lua_pushvalue(L, metatable);
    lua_setmetatable(L, -2);
    lua_rawset(L, -3);
  };
  const auto body = [&](int k, BodyId id) {
    if (!w.isValid(id)) return;
    const uint32_t uid = w.body(id).uid;
    key(k);
    pushCachedHandleAt(L, base_, uid, LuaBody{&scene, id, uid});
    lua_rawset(L, -3);
  };
  const auto shape = [&](int k, ShapeId id) {
    key(k);
    pushCachedHandleAt(L, base_ + 1, handleKey(id.index, id.generation), LuaShape{&scene, id});
    lua_rawset(L, -3);
  };
  const auto number = [&](int k, double x) {
    key(k);
    lua_pushnumber(L, x);
    lua_rawset(L, -3);
  };
  lua_createtable(L, 0, kind ? 17 : 16);
  body(A, c.a);
  body(B, c.b);
  shape(ShapeA, c.shape_a);
  shape(ShapeB, c.shape_b);
  vec(Point, c.point);
  vec(Normal, c.normal);
  number(ApproachSpeed, c.approach_speed);
  number(NormalImpulse, c.normal_impulse);
  number(TangentImpulse, c.tangent_impulse);
  number(Friction, c.friction);
  number(StaticFriction, c.static_friction);
  number(Restitution, c.restitution);
  number(TangentSpeed, c.tangent_speed);
  number(RollingResistance, c.rolling_resistance);
  key(Touching);
  lua_pushboolean(L, c.touching);
  lua_rawset(L, -3);
  // points: the manifold's, each {point, separation, normal_impulse, tangent_impulse}.
  key(Points);
  lua_createtable(L, c.count, 0);
  for (int i = 0; i < c.count; ++i) {
    lua_createtable(L, 0, 4);
    vec(Point, c.points[i]);
    number(Separation, c.separations[i]);
    number(NormalImpulse, c.normal_impulses[i]);
    number(TangentImpulse, c.tangent_impulses[i]);
    lua_rawseti(L, -2, i + 1);
  }
  lua_rawset(L, -3);
  if (kind) {
    key(Kind);
    lua_pushstring(L, kind);
    lua_rawset(L, -3);
  }
}

namespace {

// A list of current contacts (body:contacts(), world:contacts()).
int pushContactList(lua_State* L, Scene::Impl& scene, const std::vector<ContactInfo>& contacts) {
  const World& w = *scene.world;
  lua_createtable(L, static_cast<int>(contacts.size()), 0);
  const int list = lua_gettop(L);
  ContactPusher pusher(L, scene);
  for (size_t i = 0; i < contacts.size(); ++i) {
    pusher.push(contactView(w, contacts[i]));
    lua_rawseti(L, list, static_cast<lua_Integer>(i + 1));
  }
  pusher.done();
  return 1;
}

int bodyContacts(lua_State* L) {
  const LuaBody* b = toHandle<LuaBody>(L, 1);
  if (!b) fail(L, "contacts", "call it as body:contacts(), with a colon; got " + describe(L, 1) + " as the body");
  const BodyId id = liveBody(L, *b, "contacts");
  return pushContactList(L, *b->scene, b->scene->world->contactsOf(id));
}

int contactEvents(lua_State* L) {
  Scene::Impl& scene = selfWorld(L, "contact_events");
  const std::vector<World::ContactEvent>& events = scene.world->contactEvents();
  lua_createtable(L, static_cast<int>(events.size()), 0);
  const int list = lua_gettop(L);
  ContactPusher pusher(L, scene);
  for (size_t i = 0; i < events.size(); ++i) {
    pusher.push(contactView(events[i]), contactEventKind(events[i].kind));
    lua_rawseti(L, list, static_cast<lua_Integer>(i + 1));
  }
  pusher.done();
  return 1;
}

// world:contacts(): every touching contact (World::touchingContacts), as body:contacts() gives them.
int worldContacts(lua_State* L) {
  Scene::Impl& scene = selfWorld(L, "contacts");
  return pushContactList(L, scene, scene.world->touchingContacts());
}

}  // namespace

int bodyContactsMethod(lua_State* L) { return guarded<bodyContacts>(L); }
int contactEventsMethod(lua_State* L) { return guarded<contactEvents>(L); }
int worldContactsMethod(lua_State* L) { return guarded<worldContacts>(L); }

}  // namespace rigidlab::lua
