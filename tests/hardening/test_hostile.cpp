// Hostile scenes, the parts best tested from C++: the suggestion rule for misspelt
// names, how text from a scene is shown, that no finalizer exists in a scene's state, and memory
// pressure at every point of loading. The scenes themselves are in tests/hostile/.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "bindings.h"
#include "lua_args.h"
#include "rigidlab/lua/scene_text.h"
#include "util.h"

using namespace hardening;
using namespace rigidlab;
using namespace rigidlab::lua;

TEST_CASE("hostile: suggestions for misspelt names are typos of them, not other words") {
  const std::vector<std::string_view> body = {"position", "angle", "velocity", "angular_velocity", "density", "mass",
                                              "restitution", "friction", "static_friction", "static", "name", "radius",
                                              "width", "height"};
  const std::pair<const char*, const char*> cases[] = {
      {"widht", "width"},         {"radus", "radius"},        {"positon", "position"},
      {"velocty", "velocity"},    {"frcition", "friction"},   {"restitutoin", "restitution"},
      {"angular", "angular_velocity"},  // a name cut short
      {"Mass", "mass"},           {"MASS", "mass"},           {"denisty", "density"},
      {"mask", ""},               // one letter in four: another word ("mass"), not a slip
      {"mas", ""},                {"nam", ""},                {"x", ""},
      {"colour", ""},             {"elasticity", ""},         {"mask_bits", ""},
  };
  for (const auto& [typo, expected] : cases) {
    CAPTURE(typo);
    CHECK(closestName(typo, body) == expected);
  }
}

TEST_CASE("hostile: text from a scene is shown escaped, shortened and as valid UTF-8") {
  CHECK(displayText("plain text, é ü 漢字", 100) == "plain text, é ü 漢字");
  CHECK(displayText("\x1b[2J\x1b]0;title\x07", 100) == "\\x1b[2J\\x1b]0;title\\x07");
  CHECK(displayText("a\nb\tc\rd", 100) == "a\\nb\\tc\\rd");
  CHECK(displayText("a\nb\tc", 100, "\n\t") == "a\nb\tc");
  CHECK(displayText(std::string("nul\0x", 5), 100) == "nul\\x00x");
  CHECK(displayText("\x7f del", 100) == "\\x7f del");
  CHECK(displayText("c1 \xc2\x9b csi", 100) == "c1 \\xc2\\x9b csi");  // U+009B: a C1 control
  CHECK(displayText("bad \xff\xfe end", 100) == "bad \\xff\\xfe end");
  CHECK(displayText("overlong \xc0\xaf", 100) == "overlong \\xc0\\xaf");
  CHECK(displayText("surrogate \xed\xa0\x80", 100) == "surrogate \\xed\\xa0\\x80");
  CHECK(displayText(std::string(5000, 'x'), 10) == "xxxxxxxxxx... (4990 more bytes)");
  CHECK(displayText("日本語テキスト", 6) == "日本... (15 more bytes)");  // cut between characters
  CHECK(validUtf8("ok é") == "ok é");
  CHECK(validUtf8("bad \xff and \xe2\x82") == "bad \xef\xbf\xbd and \xef\xbf\xbd\xef\xbf\xbd");
  CHECK(utf8Sequence("\xf4\x8f\xbf\xbf", 0) == 4);  // U+10FFFF
  CHECK(utf8Sequence("\xf4\x90\x80\x80", 0) == 0);  // past U+10FFFF
}

TEST_CASE("hostile: no finalizer exists in a scene's state: handles have none and metatables are locked") {
  ScriptHost host(quiet(), ".");
  lua_State* L = host.L();
  int metatables = 0, finalizers = 0, unlocked = 0;
  const auto error = host.run([&] {
    registerBodyType(L);
    registerWorldType(L);
    registerDrawType(L);
    // Every table in the registry, and every metatable of one.
    lua_pushnil(L);
    while (lua_next(L, LUA_REGISTRYINDEX)) {
      if (lua_type(L, -1) == LUA_TTABLE) {
        lua_pushliteral(L, "__gc");
        finalizers += lua_rawget(L, -2) != LUA_TNIL;
        lua_pop(L, 1);
        const std::string key = lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2) : "";
        if (key == LuaBody::kMetatable || key == LuaWorld::kMetatable || key == LuaForceHandle::kMetatable ||
            key == LuaDraw::kMetatable) {
          ++metatables;
          lua_pushliteral(L, "__metatable");
          unlocked += lua_rawget(L, -2) == LUA_TNIL;
          lua_pop(L, 1);
        }
      }
      lua_pop(L, 1);
    }
  });
  CHECK_FALSE(error);
  CHECK(metatables == 4);  // body, world, force, draw
  CHECK(unlocked == 0);
  CHECK(finalizers == 0);
}

TEST_CASE("hostile: memory pressure at any point of loading ends in a located error, never an abort") {
  // 0 to 4 MiB kept alive by the main chunk, then a memory limit of 4 MiB set in the scene table:
  // the host runs out while reading the settings, making the world or its handles, in PopulateWorld.
  int refused = 0, loaded = 0;
  for (int kib = 0; kib <= 4096; kib += 128) {
    const std::string source = "keep = {}\nfor i = 1, " + std::to_string(kib) +
                               " do keep[i] = string.rep('x', 1000) .. i end\n"
                               "scene = { memory_limit = 4, title = 'pressure', gravity = {0, -1}, camera = {height = 3} }\n"
                               "function PopulateWorld(world)\n"
                               "  for i = 1, 200 do world:add_circle{ radius = 0.1, position = {i, 0}, name = 'n' .. i } end\n"
                               "end\n";
    CAPTURE(kib);
    try {
      auto scene = load(source);
      scene->step();
      ++loaded;
    } catch (const SceneError& e) {
      const std::string m = e.what();
      CHECK((contains(m, "memory") && m.starts_with("test.lua:")));
      ++refused;
    }
  }
  MESSAGE(loaded << " loaded, " << refused << " refused with a located memory error");
  CHECK(loaded > 0);
  CHECK(refused > 0);
}

TEST_CASE("hostile: a scene's strings count against its memory limit") {
  // The memory limit is what is tested, not the time: 40 000 bodies made (and removed) take over
  // the default 1 s budget under the sanitizers on a loaded machine, so the budget is wider.
  SceneOptions roomy;
  roomy.limits.hook_seconds = 30.0;
  // 40 000 bodies with 256-byte names are ~48 MB of host memory: over a 32 MiB limit.
  const Outcome o = timed([&] {
    load("scene = { memory_limit = 32 }\n"
         "local name = string.rep('n', 256)\n"
         "function PopulateWorld(world)\n"
         "  for i = 1, 40000 do world:add_circle{ radius = 0.1, position = {i, 0}, name = name } end\n"
         "end\n",
         roomy);
  });
  CHECK(o.message == "test.lua:4: add_circle: not enough memory (the scene's limit is 32 MiB); bodies, shapes, joints and "
                     "their names count against it");
  // Renaming counts too, and removing gives the memory back: the same 40 000 bodies fit when each
  // is removed after it is made.
  CHECK(timed([&] {
          load("scene = { memory_limit = 32 }\n"
               "local name = string.rep('n', 256)\n"
               "function PopulateWorld(world)\n"
               "  for i = 1, 40000 do local b = world:add_circle{ radius = 0.1 }; b.name = name; world:remove(b) end\n"
               "end\n",
               roomy);
        }).message == "(no error)");
}

TEST_CASE("hostile: OnDraw output is bounded per frame, and the report says when it was cut") {
  struct Counter final : OverlayDraw {
    int lines = 0, circles = 0, texts = 0;
    size_t longest = 0, bytes = 0;
    void line(const Vec2&, const Vec2&, const Color&) override { ++lines; }
    void circle(const Vec2&, double, const Color&) override { ++circles; }
    void text(const Vec2&, const std::string& t, const Color&) override {
      ++texts;
      longest = std::max(longest, t.size());
      bytes += t.size();
    }
  };
  auto scene = load(R"lua(
    function PopulateWorld(world) end
    local long = string.rep("t", 2048)
    function OnDraw(draw)
      for i = 1, 30000 do draw:line({0, 0}, {1, 1}) end
      for i = 1, 3000 do draw:circle({0, 0}, 1) end
      for i = 1, 600 do draw:text({0, 0}, long) end
    end)lua");
  Counter c;
  const Scene::DrawReport r = scene->onDraw(c);
  CHECK(r.truncated);
  CHECK(c.lines == Scene::kMaxDrawLines);
  CHECK(c.circles == Scene::kMaxDrawCircles);
  CHECK(c.longest <= kDrawTextBytes);
  CHECK(c.bytes <= Scene::kMaxDrawTextBytes);
  CHECK(c.texts == static_cast<int>(Scene::kMaxDrawTextBytes / kDrawTextBytes));  // 64 KiB in texts of 1 KiB
  // The next frame starts afresh, and a frame within the allowance is not reported as cut.
  auto small = load("function PopulateWorld(world) end\nfunction OnDraw(draw) draw:line({0, 0}, {1, 1}) end");
  Counter d;
  CHECK_FALSE(small->onDraw(d).truncated);
  CHECK(d.lines == 1);
}
