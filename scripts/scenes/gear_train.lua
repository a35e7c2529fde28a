-- A gear train of gear joints, Box2D's convention: a gear holds coordinate_a + ratio · coordinate_b
-- constant, so ω_b = −ω_a / ratio. A driving wheel (a motor on its pin) meshes with a wheel half its
-- radius (ratio ½: it turns twice as fast the other way), which drives a wheel of three times that
-- radius (ratio 3), whose pinion (radius 0.25) moves a rack on a prismatic joint below it: the rack's
-- speed is the pinion's rim speed, v = ω r, which the gear gives with ratio −1/r. The ratios hold to
-- the solver's tolerance at every step.
local check = require "check"

scene = { title = "Gear train", dt = 1/60, duration = 2, gravity = {0, 0}, camera = { center = {2, 0}, height = 6 } }

local r1, r2, r3, pinion = 1.0, 0.5, 1.5, 0.25
local pins, gears, rack, slide = {}, {}, nil, nil
local worst = { ratio12 = 0, ratio23 = 0, rack = 0 }

function PopulateWorld(world)
  local centres = { vec2(0, 0), vec2(r1 + r2, 0), vec2(r1 + 2 * r2 + r3, 0) }
  local radii = { r1, r2, r3 }
  local wheels = {}
  for i = 1, 3 do
    wheels[i] = world:add_circle{ radius = radii[i], position = centres[i], mask = 0 }
    pins[i] = i == 1 and world:add_revolute{ a = wheels[1], anchor = centres[1], motor_speed = 2, max_motor_torque = 50 }
                     or world:add_revolute{ a = wheels[i], anchor = centres[i] }
  end
  gears[1] = world:add_gear{ joint_a = pins[1], joint_b = pins[2], ratio = r2 / r1 }
  gears[2] = world:add_gear{ joint_a = pins[2], joint_b = pins[3], ratio = r3 / r2 }
  -- The rack: a bar under the third wheel's pinion, sliding along x.
  rack = world:add_box{ width = 4, height = 0.2, position = centres[3] + vec2(0, -pinion - 0.1), mask = 0 }
  slide = world:add_prismatic{ a = rack, anchor = rack.position, axis = {1, 0} }
  gears[3] = world:add_gear{ joint_a = pins[3], joint_b = slide, ratio = -1 / pinion }
end

local function relative_error(actual, expected) return math.abs(actual - expected) / math.max(math.abs(expected), 1e-12) end

function OnStep(world, dt)
  local w1, w2, w3 = pins[1].speed, pins[2].speed, pins[3].speed
  worst.ratio12 = math.max(worst.ratio12, relative_error(w2, -w1 * r1 / r2))
  worst.ratio23 = math.max(worst.ratio23, relative_error(w3, -w2 * r2 / r3))
  worst.rack = math.max(worst.rack, relative_error(slide.speed, w3 * pinion))
end

function Check(world)
  print(string.format("ω = %.6f, %.6f, %.6f rad/s, rack %.6f m/s; worst relative ratio errors %.2g, %.2g, %.2g",
                      pins[1].speed, pins[2].speed, pins[3].speed, slide.speed, worst.ratio12, worst.ratio23, worst.rack))
  check.near("the driver at its motor speed", pins[1].speed, 2, 1e-6)
  check.less("ω₂ = −ω₁ r₁ / r₂", worst.ratio12, 1e-6)
  check.less("ω₃ = −ω₂ r₂ / r₃", worst.ratio23, 1e-6)
  check.less("rack speed = ω₃ r_pinion", worst.rack, 1e-6)
  check.near("the coordinates: θ₁ + ½ θ₂ = 0", pins[1].angle + gears[1].ratio * pins[2].angle, 0, 1e-6)
end
