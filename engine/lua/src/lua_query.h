// The world's queries in Lua (docs/lua-api.md "Queries"): ray_cast, ray_cast_all, query_box,
// query_point, overlap, shape_cast and explode, over the core's (World::rayCast, ...).
#pragma once

#include <string_view>

#include "bindings.h"

namespace rigidlab::lua {

// world:<name> for the queries and world:contact_events(); nullptr for another name.
lua_CFunction queryWorldMethod(std::string_view name);
// Pushes a ray or shape cast's hit as a table {body, shape, point, normal, fraction}
// (api::kQueryHitFields), or nothing for none; returns the number of values pushed (0 or 1).
int pushOptionalHit(lua_State* L, Scene::Impl& scene, const std::optional<RayHit>& hit);

}  // namespace rigidlab::lua
