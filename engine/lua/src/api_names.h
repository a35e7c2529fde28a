// The names of the Lua API, in one place: the bindings check fields and options against them, and
// tests/lua/test_annotations.cpp checks the editor annotations (scripts/meta/rigidlab.lua) list
// exactly these.
#pragma once

#include <string_view>
#include <vector>

namespace rigidlab::lua::api {

// body.<field>: readable ones (methods included) and the writable subset.
inline const std::vector<std::string_view> kBodyReadable = {
    "position", "angle", "velocity", "angular_velocity", "mass", "static", "name", "restitution",
    "friction", "static_friction", "awake", "id", "center", "inertia", "density", "shape", "radius", "vertices",
    "removed", "apply_impulse", "apply_force"};
inline const std::vector<std::string_view> kBodyWritable = {
    "position", "angle", "velocity", "angular_velocity", "mass", "static", "name", "restitution",
    "friction", "static_friction", "awake"};

inline const std::vector<std::string_view> kWorldFields = {"gravity", "integrator", "dt", "solver", "iterations",
                                                           "substeps", "sleeping", "time", "step_count", "title"};
inline const std::vector<std::string_view> kWorldMethods = {
    "add_box", "add_circle", "add_polygon", "add_spring", "add_damper", "add_force", "bodies", "find", "remove",
    "step", "kinetic_energy", "potential_energy"};

inline const std::vector<std::string_view> kBodyOptions = {"position", "angle", "velocity", "angular_velocity",
                                                           "density", "mass", "restitution", "friction",
                                                           "static_friction", "static", "name"};
inline const std::vector<std::string_view> kSpringOptions = {"a", "b", "anchor", "local_a", "local_b", "stiffness",
                                                             "rest_length", "damping"};
inline const std::vector<std::string_view> kDamperOptions = {"body", "coefficient", "angular_coefficient"};
inline const std::vector<std::string_view> kForceOptions = {"body", "evaluate", "duration", "point", "other"};
inline const std::vector<std::string_view> kSceneOptions = {"title", "gravity", "dt", "integrator", "solver",
                                                            "iterations", "substeps", "sleeping", "duration",
                                                            "camera", "memory_limit", "expect_incidents",
                                                            "impacts"};

}  // namespace rigidlab::lua::api
