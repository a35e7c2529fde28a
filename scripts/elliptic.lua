--- Complete elliptic integrals and Jacobi's elliptic functions, for closed-form mechanisms: the
--- pendulum at any amplitude, a rod whirled over the top, linkages that reduce to a pendulum.
---     local elliptic = require "elliptic"
---     local swing = elliptic.pendulum{ theta0 = 3.0, omega0 = 3.13 }  -- released from rest
---     local theta, omega = swing.at(t)                                 -- swing.period: 4 K(k) / ω0
--- Pure Lua (math only): the accuracy report's plain Lua state loads it too.
local M = {}

--- Arithmetic–geometric mean of a ≥ b > 0: a_{n+1} = (a_n + b_n)/2, b_{n+1} = √(a_n b_n).
function M.agm(a, b)
  for _ = 1, 60 do
    if math.abs(a - b) <= 1e-16 * a then break end
    a, b = 0.5 * (a + b), math.sqrt(a * b)
  end
  return a
end

--- The complete elliptic integral of the first kind, K(k) = π / (2 AGM(1, √(1 − k²))), 0 ≤ k < 1.
function M.K(k)
  return math.pi / (2 * M.agm(1, math.sqrt(1 - k * k)))
end

--- Jacobi's amplitude am(u, k) and sn, cn, dn of (u, k), 0 ≤ k < 1, by the descending Landen
--- (AGM) scheme: a_0 = 1, b_0 = k', c_0 = k; a_{n+1} = (a_n + b_n)/2, b_{n+1} = √(a_n b_n),
--- c_{n+1} = (a_n − b_n)/2 until c_N is negligible; φ_N = 2^N a_N u and
--- φ_{n−1} = (φ_n + asin(c_n sin φ_n / a_n)) / 2. Then am = φ_0 (continuous in u: it grows by π
--- every 2K), sn = sin φ_0, cn = cos φ_0, dn = cos φ_0 / cos(φ_1 − φ_0).
function M.jacobi(u, k)
  local a, b, c = { 1.0 }, math.sqrt(1 - k * k), { k }
  local n = 1
  while math.abs(c[n]) > 1e-16 and n < 30 do
    a[n + 1], c[n + 1], b = 0.5 * (a[n] + b), 0.5 * (a[n] - b), math.sqrt(a[n] * b)
    n = n + 1
  end
  local phi = { [n] = 2 ^ (n - 1) * a[n] * u }
  for i = n, 2, -1 do phi[i - 1] = 0.5 * (phi[i] + math.asin(c[i] * math.sin(phi[i]) / a[i])) end
  local phi1 = phi[2] or phi[1]
  return phi[1], math.sin(phi[1]), math.cos(phi[1]), math.cos(phi[1]) / math.cos(phi1 - phi[1])
end

--- A pendulum θ'' = −ω0² sin θ released from rest at θ0 (|θ0| < π): sin(θ/2) = k sn(K − ω0 t, k)
--- with k = sin(θ0/2), period 4 K(k) / ω0. Returns { k, period, at = function(t) → θ, θ' }.
function M.pendulum(o)
  local k = math.sin(o.theta0 / 2)
  local K = M.K(k)
  local self = { k = k, period = 4 * K / o.omega0 }
  function self.at(t)
    local _, sn, cn, dn = M.jacobi(K - o.omega0 * t, k)
    local s = k * sn
    local theta = 2 * math.asin(s)
    return theta, -2 * o.omega0 * k * cn * dn / math.sqrt(1 - s * s)
  end
  return self
end

--- A pendulum θ'' = −ω0² sin θ sent over the top from θ = 0 at speed Ω > 2 ω0: θ = 2 am(Ω t / 2, k)
--- with k = 2 ω0 / Ω, one turn every 4 K(k) / Ω. Returns { k, period, at = function(t) → θ, θ' }.
function M.whirl(o)
  local k = 2 * o.omega0 / o.speed
  local self = { k = k, period = 4 * M.K(k) / o.speed }
  function self.at(t)
    local am, _, _, dn = M.jacobi(0.5 * o.speed * t, k)
    return 2 * am, o.speed * dn
  end
  return self
end

return M
