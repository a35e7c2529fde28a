// pairs() and next() whose order depends neither on Lua's hash seed nor on addresses, so a scene
// that builds its world inside pairs() over a table gives bit-identical runs in every process
// (docs/security.md: Repeatable). Lua 5.4 seeds its string hashes from an address and the time,
// and hashes tables, functions and userdata by address, so its own order changes from run to run.
//
// Keys come in this order: numbers (ascending), strings (bytewise), false then true, tables and
// functions (in the order they were created, blockSerial), the host's handles (bodies by id,
// forces, springs and dampers by slot), C functions (by library and address within it).
//
// pairs(t) sorts a snapshot of t's keys and visits those still in t when their turn comes, with
// their current values: removing or changing fields during the traversal is fine; keys added
// during it are not visited (Lua leaves that undefined). A table's __pairs metamethod is honoured
// as by Lua's pairs. next(t) (no key) scans t for its smallest key, O(n); next(t, k) finds k in a
// sorted snapshot of t taken at the first such call after next(t) (O(n log n) once, then
// O(log n)). Costs are measured in tests/hardening/test_determinism.cpp and given in docs/security.md.
#pragma once

struct lua_State;

namespace rigidlab::lua {

// Replaces the globals pairs and next (called once by ScriptHost, before the prelude).
void installOrderedPairs(lua_State* L);

}  // namespace rigidlab::lua
