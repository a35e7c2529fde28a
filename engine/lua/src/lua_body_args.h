// Reading the options that make bodies and shapes: one reader per group of options, shared by the
// world:add_* functions (a body with one shape, a concave polygon's pieces, a chain) and
// body:add_shape{...} (docs/lua-api.md "Bodies" and "Shapes").
#pragma once

#include <string_view>

#include "lua_args.h"
#include "rigidlab/world.h"

namespace rigidlab::lua {

// The shape kinds a script names: body:add_shape{shape = ...} and the one-shape world:add_*.
enum class ShapeKind { Circle, Box, Polygon, Capsule, Segment };
ShapeKind shapeKind(const Options& o, std::string_view key);  // "circle" | "box" | ... (required)
const char* shapeKindName(ShapeKind kind);
// The geometry options of a kind, in the order messages list them.
const std::vector<std::string_view>& geometryOptions(ShapeKind kind);

// The geometry of `kind` from its options (radius; width, height; vertices; a, b, radius), in
// body coordinates. Core refusals become errors of the function, naming the option.
Shape readGeometry(const Options& o, ShapeKind kind);

// The body options of api::kBodyOptions except user_data (the binding keeps it: storeUserData).
// `type` (or the older `static = true`) defaults to `fallback`. A static body given a velocity is
// refused here, naming the option and the value.
BodyDef readBodyDef(const Options& o, BodyType fallback);
// body.type = ... and the `type` option: "static" | "kinematic" | "dynamic".
BodyType bodyType(lua_State* L, std::string_view function, std::string_view subject, const sol::object& value);

// The shape options of api::kShapeOptions: density, restitution, friction, static_friction,
// sensor, category, mask, group (def.shape is left empty). `area`: false for a segment or chain,
// which has no density (giving one is refused, saying why).
ShapeDef readShapeOptions(const Options& o, bool area);
// The collision filter options alone (category, mask, group), over `fallback`.
Filter readFilter(const Options& o, const Filter& fallback);

}  // namespace rigidlab::lua
