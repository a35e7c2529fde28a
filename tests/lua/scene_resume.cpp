// scene_resume SCENE [FRACTION] [--check] [--differs REASON]: a run of SCENE resumed from a snapshot file gives the same bits as
// the uninterrupted run (docs/testing.md "Snapshots"). The scene runs its duration in whole steps,
// writing a snapshot (serializeSnapshot) at FRACTION of them (default 0.5) and hashing the state
// at the end; then a fresh load of the scene restores the file's state and runs the remaining
// steps. Exit 0 if both end in the same state (every body's uid, position, angle, velocities,
// sleep state, every contact's impulses, the clock), else 1 with the first body that differs.
// The snapshot carries the scene's own Lua state if it defines SaveState/LoadState (docs/lua-api.md
// "Snapshots"). With --check, the resumed scene's Check must pass too (its Lua variables came
// back). With --differs, the scene is a known limit (its hooks read Lua variables that it does not
// save): exit 0 if the runs differ, printing REASON, and 1 if they agree, so the list of limits in
// tests/lua/CMakeLists.txt cannot go stale.
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "rigidlab/lua/scene.h"
#include "rigidlab/world_snapshot.h"
#include "../state_hash.h"

using namespace rigidlab;
using rigidlab::test::Hash;

namespace {

uint64_t stateHash(const World& w) {
  Hash h;
  h.add(static_cast<uint64_t>(w.stepCount()));
  h.add(w.time());
  for (BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    h.add(uint64_t{b.uid});
    for (double x : {b.center.x(), b.center.y(), b.angle, b.velocity.x(), b.velocity.y(), b.angular_velocity})
      h.add(x);
    h.add(uint64_t{b.awake});
  }
  for (const ContactInfo& c : w.contacts())
    for (int k = 0; k < c.count; ++k) {
      h.add(c.normal_impulses[k]);
      h.add(c.tangent_impulses[k]);
    }
  return h.h;
}

std::unique_ptr<lua::Scene> load(const char* file) {
  lua::SceneOptions options;
  options.log = [](const std::string&) {};
  return lua::Scene::loadFile(file, options);
}

// The first body whose state differs, for the message.
std::string firstDifference(const World& a, const World& b) {
  const auto ia = a.bodyIds(), ib = b.bodyIds();
  if (ia.size() != ib.size())
    return std::to_string(ia.size()) + " bodies against " + std::to_string(ib.size());
  for (size_t i = 0; i < ia.size(); ++i) {
    const Body &x = a.body(ia[i]), &y = b.body(ib[i]);
    if (x.uid != y.uid || x.center != y.center || x.angle != y.angle || x.velocity != y.velocity ||
        x.angular_velocity != y.angular_velocity) {
      char text[256];
      std::snprintf(text, sizeof text, "body %u '%s': position (%.17g, %.17g) against (%.17g, %.17g)", x.uid,
                    x.name.c_str(), x.center.x(), x.center.y(), y.center.x(), y.center.y());
      return text;
    }
  }
  return "the bodies agree; contacts or awake flags differ";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: scene_resume SCENE [FRACTION] [--check] [--differs REASON]\n");
    return 2;
  }
  double fraction = 0.5;
  const char* differs = nullptr;
  bool check = false;
  for (int i = 2; i < argc; ++i) {
    if (std::strcmp(argv[i], "--differs") == 0 && i + 1 < argc) differs = argv[++i];
    else if (std::strcmp(argv[i], "--check") == 0) check = true;
    else fraction = std::atof(argv[i]);
  }
  try {
    auto whole = load(argv[1]);
    const double dt = whole->settings().dt;
    const long steps = std::lround(std::floor(whole->settings().duration / dt + 1e-9));
    const long at = std::lround(fraction * static_cast<double>(steps));
    std::string bytes;
    for (long i = 0; i < steps; ++i) {
      if (i == at) bytes = serializeSnapshot(whole->snapshot());
      whole->step();
    }
    if (at >= steps) bytes = serializeSnapshot(whole->snapshot());
    const uint64_t expected = stateHash(whole->world());

    auto resumed = load(argv[1]);
    const WorldSnapshot snapshot = deserializeSnapshot(bytes);
    resumed->restore(snapshot);
    for (long i = at; i < steps; ++i) resumed->step();
    const uint64_t got = stateHash(resumed->world());
    std::printf("%s: %ld steps, snapshot at step %ld (%zu bytes, %zu of them the scene's Lua state): %s\n", argv[1],
                steps, at, bytes.size(), snapshot.appData().size(),
                got == expected ? "resumed run has the same bits" : "resumed run DIFFERS");
    if (got != expected) std::printf("  %s\n", firstDifference(whole->world(), resumed->world()).c_str());
    if (differs) {
      std::printf("  known limit: %s\n", differs);
      if (got == expected) std::printf("  ... but it resumed exactly: remove it from the limits\n");
      return got == expected ? 1 : 0;
    }
    if (got != expected) return 1;
    if (check) {
      resumed->runCheck();  // SceneError if it fails
      std::printf("  Check passes after the resume\n");
    }
  } catch (const std::exception& e) {
    std::printf("%s: error: %s\n", argv[1], e.what());
    return 1;
  }
  return 0;
}
