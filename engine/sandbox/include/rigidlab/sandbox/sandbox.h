// The interactive sandbox: SDL2 window, OpenGL 3.3 drawing, Dear ImGui panels, hot reload.
#pragma once

#include <filesystem>
#include <optional>

namespace rigidlab::sandbox {

struct SandboxOptions {
  std::filesystem::path scene;        // empty: the default scene, with the scene browser open
  std::optional<int> frames;          // run this many frames, then exit (automation)
  std::filesystem::path screenshot;   // with `frames`: write a PNG of the last frame here
};

// Returned by runSandbox when no window can be opened (no display): the caller runs headless.
inline constexpr int kNoDisplay = -100;

// Runs the sandbox until the window closes (or `frames` have been drawn). Returns the process exit
// code, or kNoDisplay.
int runSandbox(const SandboxOptions& options);

}  // namespace rigidlab::sandbox
