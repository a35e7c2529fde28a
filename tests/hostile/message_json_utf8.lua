-- --json wrote invalid UTF-8 bytes from a body name raw, so the output was not JSON: they become
-- U+FFFD; control characters are escaped by the JSON encoder.
-- run: --time 0.1 --json
-- json
-- no-control
function PopulateWorld(world)
  world:add_circle{ radius = 1, name = "bad \xff\xfe utf-8 \xc3\x28 and \27[2J" }
  world:add_circle{ radius = 1, position = {3, 0}, name = "truncated \xe2\x82" }
end
