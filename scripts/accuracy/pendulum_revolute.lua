-- A rigid pendulum on a revolute joint, released from rest at θ0 = 2 rad (115°) from the hanging
-- position: the joints' reference problem (docs/integrators.md, "The pendulum on a joint").
-- The bob is a disc of m = 1 kg, radius r = 0.1 m, its centre L = 1 m from a pin to the world at
-- the origin. About the pin I_p = ½ m r² + m L², so I_p θ'' = −m g L sin θ, ω0² = m g L / I_p.
-- Released from rest, sin(θ/2) = k sn(K − ω0 t, k) with k = sin(θ0/2) (Jacobi's sn with modulus k),
-- and the period is the exact large-amplitude one, T = 4 K(k) / ω0, K the complete elliptic integral
-- of the first kind: K(k) = π / (2 AGM(1, √(1 − k²))). Here ω0 = 3.124291 rad/s, K = 2.087438,
-- T = 2.672527 s (the small-angle 2π/ω0 = 2.011080 s is 25 % short). Exact(t) agrees with an RK4
-- of θ'' = −ω0² sin θ at h = 1e-5 s to 3e-13 rad over 6 s. The run is one period (t_end = 2.7 s).
-- The integrators integrate the free bob under gravity; the joint's velocity solve and position
-- pass hold it on its circle. So the order is that of the joint solver, not of the integrator
-- (docs/integrators.md): every integrator is first order here.
scene = { sleeping = false, title = "Pendulum on a revolute joint (θ0 = 2 rad)", dt = 1 / 60, duration = 2.7,
          camera = { center = {0, -0.3}, height = 3 } }

local m, r, L, g, theta0 = 1.0, 0.1, 1.0, 9.81, 2.0
local I_p = 0.5 * m * r * r + m * L * L
local w0 = math.sqrt(m * g * L / I_p)
local k = math.sin(theta0 / 2)

-- Arithmetic–geometric mean, and K(k) = π / (2 AGM(1, k')).
local function agm(a, b)
  for _ = 1, 60 do
    if math.abs(a - b) <= 1e-16 * a then break end
    a, b = 0.5 * (a + b), math.sqrt(a * b)
  end
  return a
end
local K = math.pi / (2 * agm(1, math.sqrt(1 - k * k)))
local period = 4 * K / w0

-- Jacobi's sn, cn, dn of (u, k) by the descending Landen / AGM scheme: a_{n+1} = (a_n + b_n)/2,
-- b_{n+1} = √(a_n b_n), c_{n+1} = (a_n − b_n)/2 from a_0 = 1, b_0 = k', c_0 = k, until c_N is
-- negligible; φ_N = 2^N a_N u; φ_{n−1} = (φ_n + asin(c_n sin φ_n / a_n)) / 2; then sn = sin φ_0,
-- cn = cos φ_0, dn = cos φ_0 / cos(φ_1 − φ_0).
local function jacobi(u)
  local a, b, c = { 1.0 }, math.sqrt(1 - k * k), { k }
  local n = 1
  while math.abs(c[n]) > 1e-16 and n < 30 do
    a[n + 1], c[n + 1], b = 0.5 * (a[n] + b), 0.5 * (a[n] - b), math.sqrt(a[n] * b)
    n = n + 1
  end
  local phi = { [n] = 2 ^ (n - 1) * a[n] * u }
  for i = n, 2, -1 do phi[i - 1] = 0.5 * (phi[i] + math.asin(c[i] * math.sin(phi[i]) / a[i])) end
  local phi1 = phi[2] or phi[1]
  return math.sin(phi[1]), math.cos(phi[1]), math.cos(phi[1]) / math.cos(phi1 - phi[1])
end

local E0 = -m * g * L * math.cos(theta0)

accuracy = {
  group = "smooth",
  t_end = 2.7,  -- one period and a little
  reference_length = L,  -- the arm [m]
  metrics = { "energy", "velocity" },
  reference_speed = w0 * L,
  period = period,
  period_body = "bob",
  expected_order = { euler = 1, semi_implicit_euler = 1, rk4 = 1, implicit_euler = 1 },
  note = string.format("T = 4K(k)/ω0 = %.6f s, k = sin 1; E0 = %.5f J; the joint's solve sets the order", period, E0),
}

function PopulateWorld(world)
  local bob = world:add_circle{ name = "bob", radius = r, mass = m,
                                position = { L * math.sin(theta0), -L * math.cos(theta0) }, angle = theta0 }
  world:add_revolute{ a = bob, anchor = { 0, 0 } }  -- b omitted: pinned to the world
end

function Exact(t)
  local sn, cn, dn = jacobi(K - w0 * t)
  local s = k * sn  -- sin(θ/2)
  local theta = 2 * math.asin(s)
  local omega = -2 * w0 * k * cn * dn / math.sqrt(1 - s * s)
  return { bob = { position = { L * math.sin(theta), -L * math.cos(theta) },
                   velocity = { L * omega * math.cos(theta), L * omega * math.sin(theta) },
                   angle = theta, angular_velocity = omega } }
end
