-- Names and texts from scenes went raw into error messages and the terminal ("\27[2J\27]0;..."
-- reached the terminal): control characters are escaped and long values shortened.
-- exit: 1
-- no-control
-- expect: message_escapes.lua:11: apply_force: force must be a vector {x, y} or vec2(x, y), got "\x1b[2J\x1b]0;pwned\x07"
-- expect: body 'evil\x1b[2J\x1b]0;pwned\x07' (id 1)
function PopulateWorld(world)
  local b = world:add_circle{ radius = 1, name = "evil\27[2J\27]0;pwned\7" }
  print(tostring(b))
  print("line\27[31m red \r carriage")
  b:apply_force("\27[2J\27]0;pwned\7")
end
