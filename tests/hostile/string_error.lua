-- An error message of a megabyte, full of control characters: it comes out cut to 4 KiB and
-- escaped.
-- exit: 1
-- no-control
-- expect: string_error.lua:8: PopulateWorld: x\x1b[2Jx\x1b[2Jx
-- expect: more bytes)
function PopulateWorld(world)
  error(string.rep("x\27[2J", 200000))
end
