// Caps on the C library functions a scene can call that the budget hook (budget.h) cannot
// interrupt, because Lua's hooks only fire while Lua code runs (docs/design/reliability.md §0.4b, §1.5 item 4).
// Implemented in script_host.cpp (installGuards); documented in docs/security.md.
#pragma once

#include <cstddef>
#include <string_view>

namespace rigidlab::lua {

// Worst-case steps of Lua's backtracking pattern matcher allowed for one string.find, match,
// gmatch or gsub call (see patternWork). Measured on the development machine: the slowest pattern
// shapes at this limit take up to ~100 ms (tests/hardening/test_budget.cpp prints them).
constexpr double kPatternWorkLimit = 5e7;
// table.sort of more elements than this, without a comparator or with a C function as comparator,
// compares through a Lua function, so the budget can stop it.
constexpr long long kNativeSortLimit = 100000;
// table.move loops in C over every index of its range, nil or not: at most this many per call.
constexpr long long kMoveLimit = 10000000;
// load() parses in C: chunks of at most this many bytes, as one string or in all the pieces a
// reader function returns (and never more than ScriptLimits::source_bytes). Parsing 1 MiB takes
// about 75 ms here.
constexpr size_t kLoadChunkLimit = size_t{1} << 20;

// Worst-case work of Lua's pattern matcher for `pattern` on `subject` (n bytes): start positions
// (one if anchored by a leading '^' and `anchor` is true) × pattern items × (k + 1) × the ways to
// split the subject among the k repeated items (*, +, -, %b, back-references), which is at most
// C(n + k, k) and at most Π (longest run of subject characters item i matches + 1), × 2 per
// optional item (?). So `("a"):rep(200):find(".-.-.-.-b$")` is refused, while trimming or splitting
// ordinary text (short runs of spaces or commas) is not. `plain` (or a pattern without special
// characters): the naive substring search, (n − m + 1)·m.
double patternWork(std::string_view pattern, std::string_view subject, bool plain, bool anchor);

}  // namespace rigidlab::lua
