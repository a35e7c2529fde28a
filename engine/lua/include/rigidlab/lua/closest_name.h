// "Did you mean ...?": the valid name a mistyped one was probably meant to be. One implementation
// for the Lua API's options and fields and for the rigidlab program's commands and flags.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rigidlab::lua {

// How close a name must be to a candidate to be taken for a typo of it.
struct Closeness {
  size_t min_length = 4;  // shorter names get no suggestion
  size_t min_edits = 0;   // edits always allowed, whatever the length (a command line's short words)
};

// The valid name `name` was probably meant to be, among `candidates`, or "" if none is close
// enough to be a typo of it: a name of at least `min_length` characters that differs from a
// candidate only in case, or by at most one edit (a letter added, dropped, changed, or two
// neighbours swapped: the optimal string alignment distance) per 5 characters of the longer name
// (at least `min_edits`), or that begins the candidate. So 'widht' → 'width', 'radus' → 'radius'
// and 'angular' → 'angular_velocity', but 'mask' suggests nothing: one letter in four changed is
// another word ('mass'), not a slip.
std::string closestName(std::string_view name, const std::vector<std::string_view>& candidates, Closeness rule = {});

}  // namespace rigidlab::lua
