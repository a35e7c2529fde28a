-- The vec2 type and vector arguments: every operation the API promises, with exact values.
local check = require "check"

scene = { title = "vec2 API", duration = 0 }

function PopulateWorld(world)
  local a, b = vec2(3, 4), vec2(1, -2)
  check.that("a + b", a + b == vec2(4, 2))
  check.that("a - b", a - b == vec2(2, 6))
  check.that("a * 2", a * 2 == vec2(6, 8))
  check.that("2 * a", 2 * a == vec2(6, 8))
  check.that("a / 2", a / 2 == vec2(1.5, 2))
  check.that("-a", -a == vec2(-3, -4))
  check.that("a == vec2(3, 4)", a == vec2(3, 4))
  check.that("a ~= b", a ~= b)
  check.near("a:dot(b)", a:dot(b), -5, 0)
  check.near("a:cross(b)", a:cross(b), -10, 0)
  check.near("a:length()", a:length(), 5, 0)
  check.that("a:normalized()", a:normalized() == vec2(0.6, 0.8))
  check.that("zero:normalized()", vec2(0, 0):normalized() == vec2(0, 0))
  check.near("a.x", a.x, 3, 0)
  check.near("a.y", a.y, 4, 0)
  check.that("tostring", tostring(vec2(0.5, -1)) == "vec2(0.5, -1)", tostring(vec2(0.5, -1)))
  check.that("a + {x, y}", a + {1, 1} == vec2(4, 5))
  check.that("getmetatable(vec2) is locked", getmetatable(a) == "vec2")
  local ok, message = pcall(function() return a * b end)
  check.that("vec2 * vec2 is an error", not ok and message:find("can only be multiplied by a number", 1, true) ~= nil, message)
  -- Vectors are accepted as {x, y}, {x = , y = } or vec2 wherever the API takes one.
  local p = world:add_circle{ radius = 1, position = {1, 2} }
  local q = world:add_circle{ radius = 1, position = {x = 5, y = 2} }
  local r = world:add_circle{ radius = 1, position = vec2(9, 2) }
  check.that("positions", p.position == vec2(1, 2) and q.position == vec2(5, 2) and r.position == vec2(9, 2))
end
