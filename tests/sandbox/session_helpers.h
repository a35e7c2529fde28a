// Helpers of the session tests (test_session.cpp, test_mod_input.cpp): a scratch directory, atomic
// file writes, pumping the hot reload, synthetic SDL events.
#pragma once

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <SDL.h>

#include "session.h"
#include "tools.h"
#include "temp_dir.h"

namespace rigidlab::sandbox::testing {

using test_support::TempDir;

namespace fs = std::filesystem;
using namespace std::chrono_literals;

inline void write(const fs::path& f, const std::string& text) {
  const fs::path tmp = f.string() + ".new";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
  }
  fs::rename(tmp, f);  // as an editor that saves atomically
}

// Polls the session like the frame loop until `done` or the timeout.
template <typename Done>
inline bool pump(Session& s, Done done, std::chrono::milliseconds timeout = 2000ms) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    updateHotReload(s);
    if (done()) return true;
    std::this_thread::sleep_for(5ms);
  }
  return false;
}

inline SDL_Event mouse(Uint32 type, Vec2 px, Uint8 button = SDL_BUTTON_LEFT) {
  SDL_Event e{};
  e.type = type;
  if (type == SDL_MOUSEMOTION) {
    e.motion.x = static_cast<Sint32>(px.x());
    e.motion.y = static_cast<Sint32>(px.y());
  } else {
    e.button.button = button;
    e.button.x = static_cast<Sint32>(px.x());
    e.button.y = static_cast<Sint32>(px.y());
  }
  return e;
}

inline SDL_Event key(SDL_Keycode k, Uint16 mod = 0) {
  SDL_Event e{};
  e.type = SDL_KEYDOWN;
  e.key.keysym.sym = k;
  e.key.keysym.mod = mod;
  return e;
}

inline void click(Session& s, Vec2 world_point) {
  const Vec2 px = s.camera.worldToScreen(world_point);
  handleEvent(s, mouse(SDL_MOUSEMOTION, px), {});
  handleEvent(s, mouse(SDL_MOUSEBUTTONDOWN, px), {});
  handleEvent(s, mouse(SDL_MOUSEBUTTONUP, px), {});
}

// Writes `source` to `file` and starts a 1280×720 session on it.
inline void startOn(Session& s, const fs::path& file, const std::string& source) {
  write(file, source);
  s.camera.resize(1280, 720);
  startSession(s, file);
}

}  // namespace rigidlab::sandbox::testing
