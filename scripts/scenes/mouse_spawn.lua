-- A mod made of the sandbox hooks: a left click drops a ball where it was made (OnMouse; Shift: a
-- box), R takes the dropped bodies away instead of resetting the scene (scene.keys), a slider sets
-- the size and a button clears (scene.controls, OnControl), and a HUD in the window's corner counts
-- them (OnDraw, draw.screen).
--
-- Headless there is no mouse: the scene clicks through its own OnMouse with events of the same
-- form as the sandbox's, at t = 0 (PopulateWorld) and at t = 0.5 s (OnStep), and Check verifies
-- that the bodies appeared where those clicks were and fell as gravity predicts, that the clicks
-- the scene leaves to the sandbox made nothing, and that OnMouse said which events it consumed.
local check = require "check"

scene = {
  title = "Mouse spawn",
  duration = 1,
  -- world (x, y) → pixel (640 + 72x, 360 − 72y) in a 1280×720 window (tests/sandbox/mouse_spawn_test.sh)
  camera = {center = {0, 0}, height = 10},
  keys = {"r"},
  controls = {
    {name = "size", min = 0.1, max = 1, value = 0.3},
    {name = "clear", kind = "button"},
  },
}

local spawned = {}  -- {body =, x =, y =, time =} in the order made
local cursor        -- the last position a "move" event gave

local function spawn(world, at, box)
  local size = world.controls.size
  local options = {position = at, name = "spawned " .. (#spawned + 1)}
  local body
  if box then
    options.width, options.height = 2 * size, 2 * size
    body = world:add_box(options)
  else
    options.radius = size
    body = world:add_circle(options)
  end
  spawned[#spawned + 1] = {body = body, x = at.x, y = at.y, time = world.time}
  print(string.format("spawned %d at %.3f %.3f", #spawned, at.x, at.y))
end

local function clear(world)
  for _, s in ipairs(spawned) do
    if not s.body.removed then world:remove(s.body) end
  end
  print(string.format("cleared %d", #spawned))
  spawned = {}
end

function PopulateWorld(world)
  world:add_box{static = true, position = {0, -4.25}, width = 16, height = 0.5}
  -- Headless clicks (the sandbox's real ones come through the same function).
  check.that("a left press is consumed", OnMouse(world, {kind = "press", button = "left", position = vec2(-2, 3),
                                                           screen = vec2(496, 144), shift = false, ctrl = false, alt = false}))
  check.that("a right press is left to the sandbox", not OnMouse(world, {kind = "press", button = "right",
    position = vec2(1, 1), screen = vec2(712, 288), shift = false, ctrl = false, alt = false}))
  check.that("a wheel turn is left to the sandbox", not OnMouse(world, {kind = "wheel", position = vec2(0, 0),
    screen = vec2(640, 360), shift = false, ctrl = false, alt = false, wheel = 1}))
end

function OnMouse(world, event)
  if event.kind == "move" then cursor = event.position end
  if event.kind == "press" and event.button == "left" then
    spawn(world, event.position, event.shift)
    return true  -- the sandbox's tool does not act on it
  end
  return false  -- right drag still pans, the wheel still zooms
end

local clicked_later = false
function OnStep(world, dt)
  if not clicked_later and world.time >= 0.5 then
    clicked_later = true
    OnMouse(world, {kind = "press", button = "left", position = vec2(2, 3.5), screen = vec2(784, 108),
                    shift = true, ctrl = false, alt = false})
  end
end

-- The variables the hooks change, in snapshots (docs/lua-api.md "Snapshots"): a resumed or rewound
-- run does not click a second time, and `spawned` lists the bodies (handles are saved by id and
-- name the restored bodies; one made after the snapshot is gone again, and so is its entry).
function SaveState(world)
  return { spawned = spawned, cursor = cursor, clicked_later = clicked_later }
end

function LoadState(world, s)
  spawned, cursor, clicked_later = s.spawned, s.cursor, s.clicked_later
end

function OnKey(world, key)
  if key == "r" then clear(world) end
end

function OnControl(world, name)
  if name == "clear" then clear(world) end
end

function OnDraw(draw, world)
  if cursor then draw:circle(cursor, world.controls.size, {1, 0.85, 0.2, 0.8}) end
  for _, s in ipairs(spawned) do
    if not s.body.removed then draw:line({s.x, s.y}, s.body.position, {1, 1, 1, 0.4}) end
  end
  -- HUD: a filled panel in the bottom-right corner of the window, in pixels.
  draw.screen:polygon({{1100, 640}, {1270, 640}, {1270, 690}, {1100, 690}}, {1, 1, 1}, {0.8, 0.1, 0.1, 1})
  draw.screen:text({1110, 655}, string.format("%d spawned", #spawned))
end

function Check(world)
  check.near("bodies spawned", #spawned, 2, 0)
  check.near("bodies in the world", #world:bodies(), 3, 0)
  local g = -world.gravity.y
  for i, s in ipairs(spawned) do
    local t = world.time - s.time
    check.near("body " .. i .. " x (where it was clicked)", s.body.position.x, s.x, 1e-9)
    -- Free fall from rest: rk4 integrates constant gravity exactly, to rounding.
    check.near("body " .. i .. " y after falling " .. t .. " s", s.body.position.y, s.y - 0.5 * g * t * t, 1e-9)
    check.near("body " .. i .. " vy", s.body.velocity.y, -g * t, 1e-9)
  end
  check.near("the second click came at", spawned[2].time, 0.5, 1 / 60)
  check.that("the second click held shift: a box", spawned[2].body.shape == "polygon", spawned[2].body.shape)
end
