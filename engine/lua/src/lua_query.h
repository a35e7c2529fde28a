// The world's queries in Lua (docs/lua-api.md "Queries"): ray_cast, ray_cast_all, query_box,
// query_point, overlap, shape_cast and explode, over the core's (World::rayCast, ...).
#pragma once

#include <string_view>

#include "bindings.h"

namespace rigidlab::lua {

// world:<name> for the queries and world:contact_events(); nullptr for another name.
lua_CFunction queryWorldMethod(std::string_view name);

}  // namespace rigidlab::lua
