-- require of a name holding a NUL was cut at the NUL and loaded another module ("check\0evil"
-- loaded check). Names with NUL or other control characters are refused, whole.
-- exit: 1
-- expect: require_nul.lua:8: require: module name must look like "forces.spring", got "check\x00evil"
assert(not pcall(require, "check\n"))
assert(not pcall(require, "check\27"))
function PopulateWorld(world)
  require("check\0evil")
end
