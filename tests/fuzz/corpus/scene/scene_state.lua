-- Seed: a scene's own state through snapshots (SaveState/LoadState, scene_state.h): every kind of
-- value, shared and cyclic tables, handles as values and keys, restored in PopulateWorld and OnStep.
local t = {n = 0, f = 0.1, z = -0.0, big = 1e308, nan = 0/0, max = math.maxinteger, s = "a\0b", v = vec2(1, 2)}
t.self = t
function PopulateWorld(world)
  local b = world:add_box{ width = 1, height = 1, position = {0, 1} }
  local g = world:add_box{ static = true, width = 10, height = 1, position = {0, -0.5} }
  t.body, t.shape, t.world = b, b.shapes[1], world
  t.joint = world:add_revolute{ a = b, b = g, anchor = {0, 0.5} }
  t.spring = world:add_spring{ a = b, anchor = {0, 5}, stiffness = 10 }
  t.by = {[b] = "box", [true] = 1, [2.5] = {t}}
  local s = world:snapshot()
  t.n = 99
  world:restore(s)
  assert(t.n == 0)
  start = s
end
function SaveState(world) return t end
function LoadState(world, s) t = s end
function OnStep(world)
  t.n = t.n + 1
  if t.n == 10 then world:restore(start) end
end
