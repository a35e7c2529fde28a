// Worlds for the save → load round trip (test_scene_writer.cpp through the scene API double,
// test_saved_world_lua.cpp through the real bindings), and what "the same world" means there.
#pragma once

#include <cstdint>
#include <string>

#include "rigidlab/world.h"

namespace rigidlab::sandbox_test {

// Every shape kind (circle, polygon, capsule, segment, open chain, loop chain), compound bodies
// (a concave L split into convex pieces, a ring of circles with a sensor), every body type and
// option (damping, gravity scale, fixed rotation, bullet, disabled, filters), and every joint
// kind (revolute with limits and motor, prismatic, distance as a rope and spring, soft weld,
// wheel, motor, friction, pulley, gear), each body made with all its shapes before the next.
World everyKindWorld();

// Hashes (FNV-1a over the bits, as tests/hardening/test_determinism.cpp). bodyHash: every body in
// order: type, origin position, angle, velocity, angular velocity, mass, inertia, and each shape's kind, geometry, density, material, filter and sensor flag. jointHash: every
// joint in order: type, readings (anchors, angle, translation, axis, speed). Neither includes ids,
// time or step count (a loaded world starts at t = 0 with ids 1, 2, ...).
uint64_t bodyHash(const World& world);
uint64_t jointHash(const World& world);

// Compares two worlds body by body and joint by joint with doctest CHECKs: bodies bit for bit
// (their centres of mass to 1e-15), joint definitions exactly, joint readings within
// `joint_tolerance` (0: bit for bit).
void checkSameWorld(const World& original, const World& loaded, double joint_tolerance);

}  // namespace rigidlab::sandbox_test
