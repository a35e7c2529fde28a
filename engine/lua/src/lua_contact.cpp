// Contacts as Lua tables (lua_contact.h): the event hooks' and pre_solve functions' argument,
// body:contacts() and world:contact_events().
#include "lua_contact.h"

#include <cstddef>
#include <cstdint>
#include <type_traits>

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

// What a contact table has beyond its plain fields, in one small userdata: `points` is it (a list
// of the manifold's points, each {point, separation, normal_impulse, tangent_impulse}, made into a
// table when read), and the contact table's metatable reads friction, static_friction,
// restitution, tangent_speed, rolling_resistance and touching from it. The userdata holds only the
// contact's points (no user value, so the collector has nothing in it to walk): a contact costs
// this one allocation more than before, not a table and a vec2 per point and six more fields.
// Instructions per contact event delivered (callgrind of bench events): 7 160 on main, 9 290 with
// those, 8 500 with a fixed-size userdata holding a cache of the point tables, 8 430 with this.
struct ContactPointData {
  double x, y, separation, normal_impulse, tangent_impulse;
};
struct LuaContactExtra {
  static constexpr const char* kMetatable = "rigidlab.contact_points";
  uint8_t count;
  bool touching;
  double friction, static_friction, restitution, tangent_speed, rolling_resistance;
  ContactPointData points[2];  // `count` of them are allocated
};
constexpr size_t extraBytes(int count) { return offsetof(LuaContactExtra, points) + count * sizeof(ContactPointData); }
constexpr const char* kContactMetatable = "rigidlab.contact";

int contactPointsIndex(lua_State* L) {
  const auto* p = toHandle<LuaContactExtra>(L, 1);
  if (!p) fail(L, "contact.points", "expects the points of a contact");
  if (!lua_isinteger(L, 2))
    fail(L, "contact.points", "is a list: index it with 1 .. #points, got " + describe(L, 2));
  const lua_Integer i = lua_tointeger(L, 2);
  if (i < 1 || i > p->count) return 0;  // nil: the end of the list
  const ContactPointData& d = p->points[i - 1];
  lua_createtable(L, 0, 4);
  pushVec(L, Vec2(d.x, d.y));
  lua_setfield(L, -2, "point");
  lua_pushnumber(L, d.separation);
  lua_setfield(L, -2, "separation");
  lua_pushnumber(L, d.normal_impulse);
  lua_setfield(L, -2, "normal_impulse");
  lua_pushnumber(L, d.tangent_impulse);
  lua_setfield(L, -2, "tangent_impulse");
  return 1;
}

int contactPointsLength(lua_State* L) {
  const auto* p = toHandle<LuaContactExtra>(L, 1);
  lua_pushinteger(L, p ? p->count : 0);
  return 1;
}

// pairs(contact.points) walks it as ipairs does.
int contactPointsNext(lua_State* L) {
  const lua_Integer i = luaL_checkinteger(L, 2) + 1;
  lua_settop(L, 1);
  lua_pushinteger(L, i);
  if (contactPointsIndex(L) == 0) return 0;  // past the last: done
  lua_pushinteger(L, i);
  lua_insert(L, -2);  // i, point
  return 2;
}

int contactPointsPairs(lua_State* L) {
  lua_pushcfunction(L, guarded<contactPointsNext>);
  lua_pushvalue(L, 1);
  lua_pushinteger(L, 0);
  return 3;
}

int contactPointsNewIndex(lua_State* L) { fail(L, "contact.points", "is read-only"); }

int contactPointsToString(lua_State* L) {
  const auto* p = toHandle<LuaContactExtra>(L, 1);
  lua_pushfstring(L, "contact points (%d)", p ? p->count : 0);
  return 1;
}

// The contact table's __index: the surface fields from its `points` (a field written into the
// table itself, as pre_solve functions do, is found before this is asked); any other name is nil,
// as in a plain table.
int contactIndex(lua_State* L) {
  lua_pushliteral(L, "points");
  lua_rawget(L, 1);
  const auto* p = toHandle<LuaContactExtra>(L, -1);
  const char* k = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : "";
  if (!p) return 0;
  const std::string_view key(k);
  if (key == "touching") {
    lua_pushboolean(L, p->touching);
    return 1;
  }
  const double* x = key == "friction"             ? &p->friction
                    : key == "static_friction"    ? &p->static_friction
                    : key == "restitution"        ? &p->restitution
                    : key == "tangent_speed"      ? &p->tangent_speed
                    : key == "rolling_resistance" ? &p->rolling_resistance
                                                  : nullptr;
  if (!x) return 0;
  lua_pushnumber(L, *x);
  return 1;
}

// The names of a contact table, pushed once per pusher (ContactPusher::key): a key pushed from the
// stack and set with rawset skips the lookup of its C string that lua_setfield makes.
constexpr const char* kKeys[] = {"a", "b", "shape_a", "shape_b", "point", "normal", "approach_speed",
                                 "normal_impulse", "tangent_impulse", "kind", "x", "y", "points"};
enum Key { A, B, ShapeA, ShapeB, Point, Normal, ApproachSpeed, NormalImpulse, TangentImpulse, Kind, X, Y, Points, KeyCount };
constexpr int kSlots = 5 + KeyCount;  // the two caches, the vec2, points and contact metatables, the keys

}  // namespace

ContactPusher::ContactPusher(lua_State* L, Scene::Impl& scene) : L_(L), scene_(scene) {
  luaL_checkstack(L, kSlots + 8, "contacts");
  scene.handles.push(L);
  base_ = lua_gettop(L);
  scene.shape_handles.push(L);
  lua_rawgeti(L, LUA_REGISTRYINDEX, hostOf(L).vec2_metatable_ref);
  luaL_getmetatable(L, LuaContactExtra::kMetatable);
  luaL_getmetatable(L, kContactMetatable);
  for (const char* k : kKeys) lua_pushstring(L, k);
}

// The values pushed since (the contact tables) moved down over the slots: one copy each, where
// removing the slots one by one rotated everything above them each time (a pre_solve call, which
// pushes one table: 2 700 instructions of its 20 000, cachegrind).
void ContactPusher::done() {
  const int first = base_ + kSlots, top = lua_gettop(L_);
  for (int i = first; i <= top; ++i) lua_copy(L_, i, base_ + (i - first));
  lua_settop(L_, base_ + (top - first));
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
  const int metatable = base_ + 2, points_metatable = base_ + 3, contact_metatable = base_ + 4;
  const auto key = [&](int k) { lua_pushvalue(L, base_ + 5 + k); };
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
  lua_createtable(L, 0, kind ? 11 : 10);
  lua_pushvalue(L, contact_metatable);
  lua_setmetatable(L, -2);
  body(A, c.a);
  body(B, c.b);
  shape(ShapeA, c.shape_a);
  shape(ShapeB, c.shape_b);
  vec(Point, c.point);
  vec(Normal, c.normal);
  number(ApproachSpeed, c.approach_speed);
  number(NormalImpulse, c.normal_impulse);
  number(TangentImpulse, c.tangent_impulse);
  // points: the manifold's, each {point, separation, normal_impulse, tangent_impulse} once read.
  key(Points);
  auto* points = static_cast<LuaContactExtra*>(lua_newuserdatauv(L, extraBytes(c.count), 0));
  points->count = static_cast<uint8_t>(c.count);
  points->touching = c.touching;
  points->friction = c.friction;
  points->static_friction = c.static_friction;
  points->restitution = c.restitution;
  points->tangent_speed = c.tangent_speed;
  points->rolling_resistance = c.rolling_resistance;
  for (int i = 0; i < c.count; ++i) {
    points->points[i] = {c.points[i].x(), c.points[i].y(), c.separations[i], c.normal_impulses[i], c.tangent_impulses[i]};
  }
  lua_pushvalue(L, points_metatable);
  lua_setmetatable(L, -2);
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

void registerContactTypes(lua_State* L) {
  static_assert(std::is_trivially_destructible_v<LuaContactExtra>, "a handle must need no finalizer (no __gc)");
  registerHandleType(L, LuaContactExtra::kMetatable, guarded<contactPointsIndex>, guarded<contactPointsNewIndex>,
                     guarded<contactPointsToString>, nullptr);
  // The contact tables': only __index (a write goes into the table), and protected.
  luaL_newmetatable(L, kContactMetatable);
  lua_pushcfunction(L, guarded<contactIndex>);
  lua_setfield(L, -2, "__index");
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");
  lua_pop(L, 1);
  luaL_getmetatable(L, LuaContactExtra::kMetatable);
  lua_pushcfunction(L, guarded<contactPointsLength>);
  lua_setfield(L, -2, "__len");
  lua_pushcfunction(L, guarded<contactPointsPairs>);
  lua_setfield(L, -2, "__pairs");
  lua_pop(L, 1);
}

int bodyContactsMethod(lua_State* L) { return guarded<bodyContacts>(L); }
int contactEventsMethod(lua_State* L) { return guarded<contactEvents>(L); }
int worldContactsMethod(lua_State* L) { return guarded<worldContacts>(L); }

}  // namespace rigidlab::lua
