// Contacts as Lua tables (lua_contact.h): the event hooks' and pre_solve functions' argument,
// body:contacts() and world:contact_events().
#include "lua_contact.h"

#include "lua_args.h"
#include "lua_shape.h"

namespace rigidlab::lua {

ContactView contactView(const World::ContactEvent& e) {
  return {e.a, e.b, e.shape_a, e.shape_b, e.point, e.normal, e.approach_speed, e.normal_impulse, e.tangent_impulse};
}

ContactView contactView(const World& world, const ContactInfo& c) {
  const Vec2 point = c.count == 2 ? Vec2(0.5 * (c.points[0] + c.points[1])) : c.points[0];
  double normal_impulse = 0.0, tangent_impulse = 0.0;
  for (int i = 0; i < c.count; ++i) {
    normal_impulse += c.normal_impulses[i];
    tangent_impulse += c.tangent_impulses[i];
  }
  const double approach = -(world.body(c.b).pointVelocity(point) - world.body(c.a).pointVelocity(point)).dot(c.normal);
  return {c.a, c.b, c.shape_a, c.shape_b, point, c.normal, approach, normal_impulse, tangent_impulse};
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

void pushContact(lua_State* L, Scene::Impl& scene, const ContactView& c, const char* kind) {
  const World& w = *scene.world;
  lua_createtable(L, 0, kind ? 10 : 9);
  const auto body = [&](const char* name, BodyId id) {
    if (w.isValid(id)) {
      pushBodyHandle(L, scene, id);
      lua_setfield(L, -2, name);
    }
  };
  const auto shape = [&](const char* name, ShapeId id) {
    pushShapeHandle(L, scene, id);
    lua_setfield(L, -2, name);
  };
  const auto number = [&](const char* name, double x) {
    lua_pushnumber(L, x);
    lua_setfield(L, -2, name);
  };
  body("a", c.a);
  body("b", c.b);
  shape("shape_a", c.shape_a);
  shape("shape_b", c.shape_b);
  pushVec(L, c.point);
  lua_setfield(L, -2, "point");
  pushVec(L, c.normal);
  lua_setfield(L, -2, "normal");
  number("approach_speed", c.approach_speed);
  number("normal_impulse", c.normal_impulse);
  number("tangent_impulse", c.tangent_impulse);
  if (kind) {
    lua_pushstring(L, kind);
    lua_setfield(L, -2, "kind");
  }
}

namespace {

int bodyContacts(lua_State* L) {
  const LuaBody* b = toHandle<LuaBody>(L, 1);
  if (!b) fail(L, "contacts", "call it as body:contacts(), with a colon; got " + describe(L, 1) + " as the body");
  const BodyId id = liveBody(L, *b, "contacts");
  const World& w = *b->scene->world;
  const std::vector<ContactInfo> contacts = w.contactsOf(id);
  lua_createtable(L, static_cast<int>(contacts.size()), 0);
  for (size_t i = 0; i < contacts.size(); ++i) {
    pushContact(L, *b->scene, contactView(w, contacts[i]));
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

int contactEvents(lua_State* L) {
  Scene::Impl& scene = selfWorld(L, "contact_events");
  const std::vector<World::ContactEvent>& events = scene.world->contactEvents();
  lua_createtable(L, static_cast<int>(events.size()), 0);
  for (size_t i = 0; i < events.size(); ++i) {
    pushContact(L, scene, contactView(events[i]), contactEventKind(events[i].kind));
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

}  // namespace

int bodyContactsMethod(lua_State* L) { return guarded<bodyContacts>(L); }
int contactEventsMethod(lua_State* L) { return guarded<contactEvents>(L); }

}  // namespace rigidlab::lua
