// The interactive sandbox: SDL2 window, OpenGL 3.3 drawing, Dear ImGui panels, hot reload.
#pragma once

#include <filesystem>
#include <optional>

namespace rigidlab::sandbox {

struct SandboxOptions {
  std::filesystem::path scene;        // empty: the default scene, with the scene browser open
  // Run at most this many frames, then exit (automation). The simulation then advances exactly
  // 1/60 s per frame whatever the machine, so the picture after N frames is reproducible; frames are
  // still paced in real time, so file edits during the run are seen as a user would see them.
  std::optional<int> frames;
  std::filesystem::path screenshot;   // with `frames`: a PNG of the last frame drawn (the Nth, or the one when the window closed)
  int width = 1280, height = 720;     // the window's size at start [px]
  // With `frames`: where every panel was in the last frame drawn, as text (lines "panel X0 Y0 X1
  // Y1 NAME", the free view area, the scene's HUD, the camera and the followed body), for tests of
  // the layout (docs/sandbox.md "Automation").
  std::filesystem::path layout_file;
};

// Returned by runSandbox when no window can be opened (no display): the caller runs headless.
inline constexpr int kNoDisplay = -100;

// Runs the sandbox until the window closes (or `frames` have been drawn). Returns the process exit
// code, or kNoDisplay.
int runSandbox(const SandboxOptions& options);

}  // namespace rigidlab::sandbox
