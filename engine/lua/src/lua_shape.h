// Shape handles (lua_shape.cpp), for the other binding files: the body's fields that stand for its
// shapes, world:remove(shape) and messages.
#pragma once

#include <string>
#include <string_view>

#include "bindings.h"

namespace rigidlab::lua {

// The handle of a live shape (cached, weak), and the shape a handle designates (fails
// "<function>: the shape was removed ..." for a stale one).
sol::object shapeHandle(lua_State* L, Scene::Impl& scene, ShapeId id);
void pushShapeHandle(lua_State* L, Scene::Impl& scene, ShapeId id);  // the same, pushed
ShapeId liveShape(lua_State* L, const LuaShape& shape, std::string_view function);
// Forgets the user_data kept under the shape's key (a shape made or removed).
void forgetShapeUserData(Scene::Impl& scene, ShapeId id);
// world:remove(shape) and shape:remove(): the shape and its host memory.
void removeShape(lua_State* L, Scene::Impl& scene, ShapeId id);
// body:add_shape{...}
int addShapeMethod(lua_State* L);
// "circle shape", "shape (removed)".
std::string describeShape(const LuaShape& shape);

// The shape properties a body also has for all its shapes (restitution, friction, static_friction,
// sensor, category, mask, group) and density: read, and written after the value is checked
// (messages of `function`, e.g. "body.friction: must be >= 0, got -1").
sol::object shapeProperty(lua_State* L, const BodyShape& shape, std::string_view name);
void setShapeProperty(lua_State* L, World& world, ShapeId id, std::string_view function, std::string_view name,
                      const sol::object& value);

}  // namespace rigidlab::lua
