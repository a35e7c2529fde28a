// libFuzzer target: scene source text through the whole Lua path (sandbox, validators, world) and a
// few steps. A SceneError is the expected outcome for most inputs; anything else — a crash, a
// sanitizer report, another exception, a hang past libFuzzer's -timeout — is a bug. Budgets are
// short (250 ms) and the memory cap small (64 MiB) so runaways end quickly.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "rigidlab/lua/scene.h"

namespace {

struct NullDraw final : rigidlab::lua::OverlayDraw {
  void line(const rigidlab::Vec2&, const rigidlab::Vec2&, const rigidlab::Color&) override {}
  void circle(const rigidlab::Vec2&, double, const rigidlab::Color&) override {}
  void text(const rigidlab::Vec2&, const std::string&, const rigidlab::Color&) override {}
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const rigidlab::lua::SceneOptions options = [] {
    rigidlab::lua::SceneOptions o;
    o.log = [](const std::string&) {};
    o.limits.memory_bytes = size_t{64} << 20;
    o.limits.hook_seconds = 0.25;
    o.limits.force_seconds = 0.25;
    return o;
  }();
  const std::string_view source(reinterpret_cast<const char*>(data), size);
  try {
    auto scene = rigidlab::lua::Scene::loadString(source, "fuzz.lua", options);
    for (int i = 0; i < 10; ++i) scene->step();
    scene->runCheck();
    scene->onKey("space");
    scene->onMouse(rigidlab::lua::MouseEvent{});
    NullDraw draw;
    scene->onDraw(draw);
    scene->exact(0.5);
  } catch (const rigidlab::lua::SceneError&) {
  }
  return 0;
}
