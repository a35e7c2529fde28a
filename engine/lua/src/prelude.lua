-- rigidlab prelude: runs in every scene's Lua state before the scene. Compiled into the binary
-- (engine/lua/CMakeLists.txt embeds this file). It receives the host's private functions as
-- arguments and leaves only the public API in the globals.
local host = ...
local setmetatable, getmetatable, type, error = setmetatable, getmetatable, type, error

---------------------------------------------------------------------------------------------------
-- vec2: a 2D vector as a plain table {x = ..., y = ...} with arithmetic metamethods. Plain tables
-- keep vector maths inside Lua (no call into C++ per operation).

local vec2_mt = {}
local vec2_methods = {}
vec2_mt.__index = vec2_methods
vec2_mt.__metatable = "vec2"

local function is_vec2(v) return type(v) == "table" and getmetatable(v) == "vec2" end

local function number_arg(fname, index, v)
  if type(v) ~= "number" then
    error(string.format("%s: argument %d must be a number, got %s", fname, index, host.describe(v)), 3)
  end
  return v
end

local function vec2(x, y)
  return setmetatable({x = number_arg("vec2", 1, x), y = number_arg("vec2", 2, y)}, vec2_mt)
end

local function other(fname, v)
  if is_vec2(v) then return v.x, v.y end
  if type(v) == "table" and #v == 2 and type(v[1]) == "number" and type(v[2]) == "number" then
    return v[1], v[2]
  end
  error(string.format("%s: expected a vector (vec2 or {x, y}), got %s", fname, host.describe(v)), 3)
end

function vec2_mt.__add(a, b)
  local ax, ay = other("vec2 +", a)
  local bx, by = other("vec2 +", b)
  return setmetatable({x = ax + bx, y = ay + by}, vec2_mt)
end

function vec2_mt.__sub(a, b)
  local ax, ay = other("vec2 -", a)
  local bx, by = other("vec2 -", b)
  return setmetatable({x = ax - bx, y = ay - by}, vec2_mt)
end

function vec2_mt.__mul(a, b)
  if type(a) == "number" then a, b = b, a end
  if type(b) ~= "number" then
    error("vec2 *: a vector can only be multiplied by a number (use v:dot(w) or v:cross(w)), got " ..
          host.describe(b), 2)
  end
  return setmetatable({x = a.x * b, y = a.y * b}, vec2_mt)
end

function vec2_mt.__div(a, b)
  if type(b) ~= "number" or not is_vec2(a) then
    error("vec2 /: a vector can only be divided by a number, got " .. host.describe(b), 2)
  end
  return setmetatable({x = a.x / b, y = a.y / b}, vec2_mt)
end

function vec2_mt.__unm(a) return setmetatable({x = -a.x, y = -a.y}, vec2_mt) end
function vec2_mt.__eq(a, b) return a.x == b.x and a.y == b.y end
function vec2_mt.__tostring(a) return string.format("vec2(%.17g, %.17g)", a.x, a.y) end

function vec2_methods.dot(a, b)
  local bx, by = other("vec2:dot", b)
  return a.x * bx + a.y * by
end

-- 2D cross product: a vector gives the scalar a.x b.y − a.y b.x.
function vec2_methods.cross(a, b)
  local bx, by = other("vec2:cross", b)
  return a.x * by - a.y * bx
end

function vec2_methods.length(a) return math.sqrt(a.x * a.x + a.y * a.y) end

-- Unit vector in the same direction; the zero vector stays zero.
function vec2_methods.normalized(a)
  local l = math.sqrt(a.x * a.x + a.y * a.y)
  if l == 0 then return setmetatable({x = 0.0, y = 0.0}, vec2_mt) end
  return setmetatable({x = a.x / l, y = a.y / l}, vec2_mt)
end

-- Counter-clockwise perpendicular (−y, x).
function vec2_methods.perp(a) return setmetatable({x = -a.y, y = a.x}, vec2_mt) end

-- Rotated by `angle` radians counter-clockwise.
function vec2_methods.rotated(a, angle)
  local c, s = math.cos(angle), math.sin(angle)
  return setmetatable({x = c * a.x - s * a.y, y = s * a.x + c * a.y}, vec2_mt)
end

host.register_vec2(vec2_mt)
_ENV.vec2 = vec2

---------------------------------------------------------------------------------------------------
-- Sandbox wrappers (docs/security.md): text-only, size-capped load, no __gc finalizers, no
-- garbage-collector control, pcall/xpcall that cannot swallow a spent budget, no way back to the
-- originals (they live only in these upvalues).

local raw_load, raw_setmetatable, raw_collectgarbage = load, _ENV.setmetatable, collectgarbage
local raw_pcall, raw_xpcall, raw_rawset, source_limit = pcall, xpcall, rawset, host.source_limit
local budget_check, budget_expired = host.budget_check, host.budget_expired
local record_scene_line, release_globals = host.record_scene_line, host.release_globals
local globals = _ENV

-- A reader function's pieces, counted: past source_limit bytes in all, the reader fails (and so
-- does load, which returns nil and the message), so the parser never gets more than a string chunk.
local function capped_reader(reader)
  local total = 0
  return function()
    local piece = reader()
    if type(piece) == "string" then
      total = total + #piece
      if total > source_limit then
        error(string.format("load: the reader function returned more than %d bytes in all", source_limit), 0)
      end
    end
    return piece
  end
end

function load(chunk, chunkname, mode, env)
  if mode ~= nil and mode ~= "t" then
    error("load: only text chunks can be loaded (mode \"t\"), got mode " .. host.describe(mode), 2)
  end
  -- The parser runs in C, where the time budget cannot stop it: cap what it is given.
  if type(chunk) == "string" and #chunk > source_limit then
    error(string.format("load: chunk is %d bytes, larger than the limit of %d", #chunk, source_limit), 2)
  end
  if type(chunk) == "function" then chunk = capped_reader(chunk) end
  if env == nil then return raw_load(chunk, chunkname, "t") end
  return raw_load(chunk, chunkname, "t", env)
end

function _ENV.setmetatable(t, mt)
  if type(mt) == "table" and rawget(mt, "__gc") ~= nil then
    error("setmetatable: __gc metamethods are not allowed in scenes", 2)
  end
  if rawequal(t, globals) then release_globals() end  -- the host's watcher of `scene` steps aside
  return raw_setmetatable(t, mt)
end

-- rawset(_G, "scene", {...}) bypasses the host's watcher of `scene` (scene_line.h): note its line.
function rawset(t, k, v)
  if rawequal(t, globals) and k == "scene" then record_scene_line() end
  return raw_rawset(t, k, v)
end

function collectgarbage(opt, ...)
  if opt == "count" then return raw_collectgarbage("count") end
  error("collectgarbage: only collectgarbage(\"count\") is available in scenes", 2)
end

-- A spent time budget (budget.h) is not an error a script may catch: once the call that failed
-- returns, the budget error is raised again (the sticky hook does the same at the next instruction).
local function rethrow_budget(ok, ...)
  if not ok then budget_check() end
  return ok, ...
end

function pcall(f, ...) return rethrow_budget(raw_pcall(f, ...)) end

-- The message handler of an error raised by the budget hook runs with Lua's hooks disabled (the
-- error leaves the hook by a throw, and the handler runs before the unwinding), so a looping
-- handler could never be stopped: once the budget is spent, the user's handler is not called.
function xpcall(f, handler, ...)
  if type(handler) ~= "function" then return raw_xpcall(f, handler, ...) end
  return rethrow_budget(raw_xpcall(f, function(m)
    if budget_expired() then return m end
    return handler(m)
  end, ...))
end

dofile, loadfile = nil, nil
string.dump = nil
