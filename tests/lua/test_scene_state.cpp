// A scene's own state in snapshots (scene_state.h, docs/lua-api.md "Snapshots"): SaveState's value
// comes back to LoadState exactly (every kind, floats to the bit, integers as integers), its
// handles name the restored objects, the same state gives the same bytes, a value that cannot be
// saved is an error naming its path, and a scene without the hooks is as before.
#include <doctest/doctest.h>

#include <string>

#include "rigidlab/lua/scene.h"
#include "rigidlab/world_snapshot.h"
#include "scene_test_util.h"

using namespace rigidlab;
using lua_test::load;

namespace {

// The message of the SceneError `f` throws.
template <typename F>
std::string errorFrom(F f) {
  try {
    f();
  } catch (const lua::SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

// A scene whose SaveState returns `state` (made by make_state(world)) and whose LoadState keeps
// the value it gets in `loaded`; `same(a, b)` compares two states kind for kind and bit for bit.
const char* kKindsScene = R"lua(
  scene = { dt = 1 / 60 }
  local function make_state(world)
    local ball = world:find("ball")
    local shared = {name = "shared"}
    local state = {
      t = true, f = false,
      max = math.maxinteger, min = math.mininteger, zero = 0, one_float = 1.0,
      tenth = 0.1, negative_zero = -0.0, big = 1e308, tiny = 5e-324, inf = math.huge, ninf = -math.huge,
      nan = 0 / 0,
      text = "a\0b\255", empty = "",
      list = {1, 2.5, "x", {deep = {deeper = {true}}}},
      [1] = "integer key", [2.5] = "float key", [true] = "boolean key", [-7] = "negative key",
      v = vec2(1.5, -2),
      ball = ball, shape = ball.shapes[1], joint = world:joints()[1], spring = spring, world = world,
      by_body = {[ball] = "the ball"},
      gone = gone,
      a = shared, b = shared,
    }
    state.self = state  -- a cycle
    return state
  end
  local function bits(x) return string.pack("<d", x) end
  local function same(a, b, path)
    path = path or "state"
    if type(a) ~= type(b) then error(path .. ": " .. type(a) .. " against " .. type(b)) end
    if type(a) == "number" then
      assert(math.type(a) == math.type(b), path .. ": " .. math.type(a) .. " against " .. math.type(b))
      if math.type(a) == "float" then assert(bits(a) == bits(b), path .. ": other bits") else assert(a == b, path) end
    elseif type(a) == "table" then
      assert(getmetatable(a) == getmetatable(b), path .. ": metatable")
      for k, v in pairs(a) do
        if k ~= "self" and k ~= "by_body" then same(v, b[k], path .. "." .. tostring(k)) end
      end
      for k in pairs(b) do assert(a[k] ~= nil, path .. ": extra key " .. tostring(k)) end
    else
      assert(rawequal(a, b) or a == b, path .. ": " .. tostring(a) .. " against " .. tostring(b))
    end
  end
  function PopulateWorld(world)
    world:add_box{ static = true, width = 20, height = 1, position = {0, -0.5} }
    local ball = world:add_circle{ name = "ball", radius = 0.3, position = {0, 2} }
    world:add_revolute{ a = ball, anchor = {0, 3} }
    spring = world:add_spring{ a = ball, anchor = {2, 4}, stiffness = 10 }
    gone = world:add_circle{ name = "gone", radius = 0.1, position = {5, 5} }
    world:remove(gone)
  end
  function SaveState(world) return make_state(world) end
  function LoadState(world, value) loaded = value; loads = (loads or 0) + 1 end
  function Check(world)
    assert(loads == 1, "LoadState called " .. tostring(loads) .. " times")
    same(make_state(world), loaded)
    -- Handles are the restored world's, the same Lua objects the API gives.
    local ball = world:find("ball")
    assert(rawequal(loaded.ball, ball), "the ball handle")
    assert(rawequal(loaded.shape, ball.shapes[1]), "the shape handle")
    assert(rawequal(loaded.joint, world:joints()[1]), "the joint handle")
    assert(loaded.spring == spring, "the spring handle")
    assert(rawequal(loaded.world, world), "the world")
    assert(loaded.by_body[ball] == "the ball", "a handle as a key")
    assert(loaded.gone.removed, "a removed body stays removed")
    -- Shared tables stay shared, cycles stay cycles, a vec2 is a vec2.
    assert(rawequal(loaded.a, loaded.b) and rawequal(loaded.self, loaded), "sharing")
    assert((loaded.v + vec2(1, 1)).x == 2.5, "vec2 arithmetic")
    assert(1 / loaded.negative_zero == -math.huge, "-0.0")
    assert(loaded.nan ~= loaded.nan, "nan")
    assert(math.type(loaded.one_float) == "float" and math.type(loaded.zero) == "integer", "subtypes")
  end
)lua";

}  // namespace

TEST_CASE("scene state: every kind of value comes back through a snapshot file, exactly, handles naming the restored objects") {
  auto first = load(kKindsScene);
  for (int i = 0; i < 20; ++i) first->step();
  const WorldSnapshot s = first->snapshot();
  CHECK(!s.appData().empty());
  const std::string bytes = serializeSnapshot(s);
  for (int i = 0; i < 30; ++i) first->step();
  auto second = load(kKindsScene);
  for (int i = 0; i < 5; ++i) second->step();  // elsewhere: the restore must bring it back
  second->restore(deserializeSnapshot(bytes));
  CHECK(second->world().stepCount() == 20);
  CHECK_NOTHROW(second->runCheck());
}

TEST_CASE("scene state: the same state gives the same bytes, whatever order its tables were filled in") {
  const auto scene = [](bool backwards) {
    return load(std::string("backwards = ") + (backwards ? "true" : "false") + R"lua(
      function PopulateWorld(world)
        for i = 1, 5 do world:add_circle{ name = "b" .. i, radius = 0.2, position = {i, 1} } end
      end
      function SaveState(world)
        local t, by_body, first, last, step = {}, {}, 1, 60, 1
        if backwards then first, last, step = 60, 1, -1 end
        for i = first, last, step do
          t["key" .. i] = i * 0.5
          t[i * 3] = {i, tostring(i)}
          t[i + 0.25] = i
        end
        local bodies = world:bodies()
        for i = (backwards and #bodies or 1), (backwards and 1 or #bodies), (backwards and -1 or 1) do
          by_body[bodies[i]] = bodies[i].name
        end
        t.by_body = by_body
        return t
      end)lua");
  };
  auto forwards = scene(false), backwards = scene(true);
  const std::string a = forwards->snapshot().appData();
  CHECK(a.size() > 1000);
  CHECK(forwards->snapshot().appData() == a);  // twice: the same bytes
  CHECK(backwards->snapshot().appData() == a);
}

TEST_CASE("scene state: world:snapshot() and world:restore(s) call the hooks, LoadState gets the saved value") {
  auto scene = load(R"lua(
    local counter, phase, got = 0, "start", {}
    function PopulateWorld(world) world:add_circle{ radius = 1 } end
    function SaveState(world) return {counter = counter, phase = phase} end
    function LoadState(world, value)
      got[#got + 1] = value
      counter, phase = value.counter, value.phase
    end
    function Check(world)
      counter, phase = 5, "walking"
      local s = world:snapshot()
      counter, phase = 99, "jumping"
      world:step()
      world:restore(s)
      assert(counter == 5 and phase == "walking", counter .. " " .. phase)
      assert(#got == 1 and got[1].counter == 5, "LoadState once, with the saved value")
      counter = 7
      world:restore(s)
      assert(counter == 5 and #got == 2 and got[1] ~= got[2], "each restore reads a fresh value")
    end)lua");
  CHECK_NOTHROW(scene->runCheck());
}

TEST_CASE("scene state: a scene without the hooks behaves as before (its Lua variables are its own)") {
  auto scene = load(R"lua(
    counter = 0
    function PopulateWorld(world) world:add_circle{ radius = 1 } end
    function OnStep(world) counter = counter + 1 end
    function Check(world)
      local s = world:snapshot()
      counter = 42
      world:restore(s)
      assert(counter == 42, "a restore without LoadState leaves the variables alone")
    end)lua");
  for (int i = 0; i < 3; ++i) scene->step();
  const WorldSnapshot s = scene->snapshot();
  CHECK(s.appData().empty());
  for (int i = 0; i < 3; ++i) scene->step();
  scene->restore(deserializeSnapshot(serializeSnapshot(s)));
  CHECK(scene->world().stepCount() == 3);
  CHECK_NOTHROW(scene->runCheck());
}

TEST_CASE("scene state: LoadState gets nil from a snapshot without a saved state") {
  auto without = load("function PopulateWorld(world) end");
  const WorldSnapshot s = without->snapshot();
  auto with = load(R"lua(
    function PopulateWorld(world) end
    function LoadState(world, value) called = true; got = value end
    function Check(world) assert(called and got == nil) end)lua");
  with->restore(s);
  CHECK_NOTHROW(with->runCheck());
}

TEST_CASE("scene state: a value that cannot be saved is an error naming its path, at SaveState's line") {
  const auto saving = [](const std::string& returned) {
    return errorFrom([&] {
      auto scene = load("function PopulateWorld(world) end\nfunction SaveState(world)\n  " + returned + "\nend");
      (void)scene->snapshot();
    });
  };
  CHECK(saving("return {enemies = {1, 2, {think = function() end}}}") ==
        "test.lua:2: SaveState: value at state.enemies[3].think is a function; only nil, booleans, numbers, "
        "strings, tables and body/shape/joint/force handles can be saved");
  CHECK(saving("return print") ==
        "test.lua:2: SaveState: value at state is a function; only nil, booleans, numbers, strings, tables and "
        "body/shape/joint/force handles can be saved");
  CHECK(saving("if inner then return 0 end inner = true local s = world:snapshot() return {snap = s}").starts_with(
      "test.lua:2: SaveState: value at state.snap is a snapshot (snapshots are kept in memory, not saved)"));
  CHECK(saving("return {[\"odd key\"] = {setmetatable({}, {})}}") ==
        "test.lua:2: SaveState: value at state[\"odd key\"][1] is a table with a metatable; only plain "
        "tables and vec2 can be saved (a metatable's functions cannot)");
  CHECK(saving("return {x = {[{}] = 1}}") ==
        "test.lua:2: SaveState: key in state.x is a table; only booleans, numbers, strings and body/shape/joint/force "
        "handles can be saved as keys");
  CHECK(saving("local t = {} for i = 1, 200 do t = {t} end return t") ==
        "test.lua:2: SaveState: value at state[1][1][1][1][1]...[1][1][1][1][1] is a table nested 100 tables deep; "
        "at most 100 levels of tables can be saved");
  // An error raised inside SaveState is located like any hook's.
  CHECK(saving("error(\"no state today\")") == "test.lua:3: SaveState: no state today");
  // From world:snapshot(), the same error, raised at the caller.
  const std::string from_lua = errorFrom([] {
    auto scene = load(R"lua(
      function PopulateWorld(world) end
      function SaveState(world) return {f = print} end
      function Check(world) world:snapshot() end)lua");
    scene->runCheck();
  });
  CHECK(from_lua.starts_with("test.lua:3: SaveState: value at state.f is a function;"));
}

TEST_CASE("scene state: errors in LoadState, and bytes that are not a saved state") {
  auto scene = load(R"lua(
    function PopulateWorld(world) end
    function SaveState(world) return 1 end
    function LoadState(world, value)
      error("cannot load " .. value)
    end)lua");
  WorldSnapshot s = scene->snapshot();
  CHECK(errorFrom([&] { scene->restore(s); }) == "test.lua:5: LoadState: cannot load 1");
  s.setAppData("garbage");
  CHECK(errorFrom([&] { scene->restore(s); }).starts_with("test.lua:4: LoadState: the saved state is corrupt: it is not a saved scene state"));
  s.setAppData(std::string("RLSS\x01\x06\xff\xff\xff\xff\xff\xff\xff\x7f", 14));  // a table of 2^63 pairs
  CHECK(errorFrom([&] { scene->restore(s); }).find("cannot fit in what is left") != std::string::npos);
}
