// Events in Lua (docs/lua-api.md "Events"): the shapes' event options and fields, their pre_solve
// functions, and the hooks a scene defines for what a step reported.
//
// Pay for what you use: the core keeps contact events only for shapes flagged contact_events or
// hit_events, asks about contacts only of shapes with a one_way normal or a pre_solve function,
// and a scene that defines no event hook makes no Lua call and builds no table after a step.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "bindings.h"
#include "lua_args.h"

namespace rigidlab::lua {

// The event options of a shape (api::kShapeEventOptions) into `def`: contact_events, hit_events,
// hit_speed (giving it turns hit_events on unless hit_events = false is given), one_way (a
// direction {nx, ny}, normalised), and pre_solve (a function: def.pre_solve is set; the function
// is kept by attachShapeEvents once the shape exists).
void readShapeEventOptions(const Options& o, ShapeDef& def);
// After the shape `id` was made from options `o` (read by readShapeEventOptions): gives it the
// event flags, for the shapes the core made without them (a one-shape body, a chain's segments),
// and keeps its pre_solve function. Does nothing when `o` has no event option.
void attachShapeEvents(lua_State* L, Scene::Impl& scene, const Options& o, ShapeId id);

// shape.<k> for the event fields (api::kShapeEventOptions): true if `k` is one of them (and then
// pushed / written).
bool pushShapeEventField(lua_State* L, Scene::Impl& scene, const BodyShape& shape, std::string_view k);
bool setShapeEventField(lua_State* L, Scene::Impl& scene, ShapeId id, std::string_view function, std::string_view k,
                        const sol::object& value);
// Forgets the pre_solve function of a shape being removed.
void forgetShapeEvents(Scene::Impl& scene, ShapeId id);

// The event hooks (api::kEventHooks): the slot of each in Scene::Impl, read by the loader.
struct EventHook {
  std::string_view name;
  sol::object Scene::Impl::*slot;
};
const std::vector<EventHook>& eventHooks();

// Gives the scene's world a collision filter that calls ShouldCollide(shape_a, shape_b) when the
// scene defines it (Scene::Impl::should_collide); nothing otherwise.
void installShouldCollide(Scene::Impl& scene);
// After PopulateWorld: a warning for each contact hook (OnContactBegin, OnContactEnd, OnHit) the
// scene defines while none of its shapes can raise its event, naming the option that would
// (contact_events, hit_events). Made by walking the shapes once, at load.
std::vector<std::string> unraisedEventWarnings(const Scene::Impl& scene);

// One call of an event hook: hook(world, args[first] [, args[second]]), args being the table
// pushEventCalls leaves on the stack.
struct EventCall {
  const sol::object* hook;
  std::string_view name;
  int first, second;  // second 0: the hook takes one argument after the world
};
// The hook calls for the events of the step just made, in the order they are to be made: contact
// events as the core lists them (by shape pair; begin before hit), then sensor events (by sensor,
// then visitor), then joint breaks. Pushes one table holding all their arguments, made before any
// hook runs, so a hook that removes a body does not change what the later hooks are given; every
// event gets a contact table of its own (a hook may keep it). Pushes nothing, and leaves `calls`
// empty, when the scene defines no event hook. Call it inside ScriptHost::run.
void pushEventCalls(Scene::Impl& scene, std::vector<EventCall>& calls);

}  // namespace rigidlab::lua
