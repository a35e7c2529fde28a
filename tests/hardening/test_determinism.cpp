// Determinism (reliability.md test plan D1, D2; Box2D's test/test_determinism.c): every scene in
// scripts/scenes/ and tests/scenes/, loaded fresh and stepped kSteps steps of its own dt, has a
// state hash over every body's uid, position, angle, velocity and angular velocity bits. The hash
// must equal the golden value below, in this process and in 3 separate processes (each with its
// own randomised Lua string-hash seed and addresses).
//
// ANY CHANGE TO THE PHYSICS (or to a scene) CHANGES THESE HASHES: update them in the same commit.
// Regenerate the table with
//     build/tests/hardening/hardening_tests --print-hashes
// and paste its output over kGolden. A hash that changes without a physics change is a
// determinism bug (uninitialised memory, pairs() order, time or address dependence): find it.
#include <doctest/doctest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "util.h"

using namespace hardening;
using namespace rigidlab;
namespace fs = std::filesystem;

namespace {

constexpr int kSteps = 240;

struct Golden {
  const char* scene;  // relative to the source tree
  const char* hash;   // 16 hex digits
};

// clang-format off
const Golden kGolden[] = {
// Generated with --print-hashes after the soft step joined the contact solver (auto: large islands);
// regenerate with --print-hashes after every physics change.
    {"scripts/scenes/experiment1_two_circles.lua", "1ba25daf59194227"},
    {"scripts/scenes/experiment2_energy.lua", "7d4f2a9443d521c2"},
    {"scripts/scenes/experiment3_incline.lua", "ef0437924491de9d"},
    {"scripts/scenes/experiment4_springs.lua", "d6fd57cbc715d042"},
    {"scripts/scenes/free_fall.lua", "0e7c53772421e76e"},
    {"scripts/scenes/newtons_cradle.lua", "de7fa7ac2fe04a5d"},
    {"scripts/scenes/playground.lua", "b775aafef0929308"},
    {"scripts/scenes/pyramid.lua", "87f5db409082856a"},
    {"scripts/scenes/spring_chain.lua", "a6006e467d57afe5"},
    {"scripts/scenes/spring_pendulum.lua", "4356e1808a338acf"},
    {"tests/scenes/lua_api.lua", "c081df7e46e063da"},
    {"tests/scenes/lua_damper_twin.lua", "7367e7e70cd737d3"},
    {"tests/scenes/lua_spring_twin.lua", "ad804d90435d3a9c"},
    {"tests/scenes/regression_far_body.lua", "8b5d76f4f74135f6"},
    {"tests/scenes/vec2_api.lua", "31dd1a62c493ba98"},
};
// clang-format on

// FNV-1a, 64 bit, over the bytes of each value.
struct Hasher {
  uint64_t h = 1469598103934665603ull;
  template <typename T>
  void add(const T& v) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    for (unsigned char b : bytes) h = (h ^ b) * 1099511628211ull;
  }
};

uint64_t stateHash(const World& w) {
  Hasher hash;
  hash.add(w.stepCount());
  hash.add(w.time());
  for (BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    hash.add(b.uid);
    hash.add(b.position().x());
    hash.add(b.position().y());
    hash.add(b.angle);
    hash.add(b.velocity.x());
    hash.add(b.velocity.y());
    hash.add(b.angular_velocity);
  }
  return hash.h;
}

std::string hex(uint64_t h) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

const fs::path kRoot = RIGIDLAB_SOURCE_DIR;

std::vector<std::string> sceneFiles() {
  std::vector<std::string> files;
  for (const char* dir : {"scripts/scenes", "tests/scenes"})
    for (const auto& e : fs::directory_iterator(kRoot / dir))
      if (e.path().extension() == ".lua") files.push_back(fs::relative(e.path(), kRoot).string());
  std::sort(files.begin(), files.end());
  return files;
}

// Fresh load, kSteps steps (OnStep included), hash.
std::string hashOf(const std::string& relative, int steps = kSteps) {
  auto scene = Scene::loadFile(kRoot / relative, quiet());
  for (int i = 0; i < steps; ++i) scene->step();
  return hex(stateHash(scene->world()));
}

// Output of a command (one process).
std::string run(const std::string& command) {
  std::string out;
  FILE* p = ::popen(command.c_str(), "r");
  REQUIRE(p != nullptr);
  char buffer[4096];
  while (size_t n = std::fread(buffer, 1, sizeof buffer, p)) out.append(buffer, n);
  const int status = ::pclose(p);
  CHECK(status == 0);
  return out;
}

std::string self() { return fs::read_symlink("/proc/self/exe").string(); }

// A scene that reads a string-keyed table with pairs() (whose order follows the per-process hash
// seed), but creates its bodies in sorted order with host-seeded math.random: the trace must not
// depend on the seed.
const char* kSeedScene = R"lua(
  scene = { gravity = {0, -9.81} }
  function PopulateWorld(world)
    world:add_box{ width = 40, height = 1, position = {0, -0.5}, static = true }
    local sizes = { alpha = 0.3, bravo = 0.4, charlie = 0.5, delta = 0.35, echo = 0.45, foxtrot = 0.25,
                    golf = 0.3, hotel = 0.55, india = 0.2, juliett = 0.4 }
    local order = {}
    for name in pairs(sizes) do order[#order + 1] = name end
    print("pairs order: " .. table.concat(order, " "))
    table.sort(order)
    for i, name in ipairs(order) do
      world:add_circle{ name = name, radius = sizes[name], position = {math.random(-8, 8) + 0.1 * i, 1 + 2 * math.random()},
                        velocity = {math.random() - 0.5, 0}, restitution = 0.3 }
    end
  end)lua";

}  // namespace

// Helper modes for the separate processes (main.cpp).
int hardeningHelperMain(int argc, char** argv) {
  const std::string mode = argv[1];
  if (mode == "--print-hashes") {
    for (const std::string& f : sceneFiles()) std::printf("    {\"%s\", \"%s\"},\n", f.c_str(), hashOf(f).c_str());
    return 0;
  }
  if (mode == "--state-hash" && argc == 3) {
    std::printf("%s\n", hashOf(argv[2]).c_str());
    return 0;
  }
  if (mode == "--seed-scene") {
    std::string pairs_order;
    SceneOptions options;
    options.log = [&](const std::string& line) { pairs_order = line; };
    auto scene = Scene::loadString(kSeedScene, "seed.lua", options);
    for (int i = 0; i < 300; ++i) scene->step();
    std::printf("%s\n%s\n", hex(stateHash(scene->world())).c_str(), pairs_order.c_str());
    return 0;
  }
  return -1;
}

TEST_CASE("determinism: every scene matches its golden state hash after 240 steps (D1)") {
  std::set<std::string> golden;
  for (const Golden& g : kGolden) golden.insert(g.scene);
  for (const std::string& f : sceneFiles()) {
    CAPTURE(f);
    CHECK_MESSAGE(golden.count(f) == 1, "no golden hash for this scene: run hardening_tests --print-hashes");
  }
  for (const Golden& g : kGolden) {
    const std::string scene = g.scene;
    CAPTURE(scene);
    CHECK(hashOf(g.scene) == g.hash);
  }
}

TEST_CASE("determinism: the same hashes in 3 separate processes") {
  for (const Golden& g : kGolden) {
    const std::string scene = g.scene;
    CAPTURE(scene);
    for (int i = 0; i < 3; ++i) CHECK(run(self() + " --state-hash " + scene) == std::string(g.hash) + "\n");
  }
}

TEST_CASE("determinism: processes with different Lua hash seeds give the same trace (D2)") {
  std::set<std::string> hashes, orders;
  for (int i = 0; i < 6; ++i) {
    const std::string out = run(self() + " --seed-scene");
    const size_t nl = out.find('\n');
    REQUIRE(nl != std::string::npos);
    hashes.insert(out.substr(0, nl));
    orders.insert(out.substr(nl + 1));
  }
  MESSAGE(orders.size() << " different pairs() orders in 6 processes, " << hashes.size() << " state hash(es)");
  CHECK(orders.size() >= 2);  // the seeds did differ (pairs() order follows them) ...
  CHECK(hashes.size() == 1);  // ... and the simulation did not
}

TEST_CASE("determinism: a scene hashed twice in one process gives the same value (no leftover state)") {
  const std::string f = "scripts/scenes/pyramid.lua";
  CHECK(hashOf(f, 60) == hashOf(f, 60));
}
