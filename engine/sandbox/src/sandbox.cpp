// The sandbox's life cycle (docs/design/thesis.md §3 Algorithm 1 and §11): open the window → load the scene
// (PopulateWorld builds the model) → per frame: handle events, pick up file changes, simulate,
// draw the world and the panels, sleep to the frame cap. Built on Dear ImGui's
// example_sdl2_opengl3/main.cpp: SDL2 window + OpenGL 3.3 core context + ImGui's SDL2/OpenGL3
// backends, with the world drawn by our own renderer underneath the panels.
//
// Automation (--frames N): at most N frames; with --screenshot, the last frame drawn (the Nth, or the
// one during which the window was closed or SIGTERM arrived) is written as a PNG. The simulation clock advances exactly 1/60 s per frame instead of the
// measured frame time, so the picture after N frames is the same on a fast machine and under a
// software renderer; frames are still paced at the frame cap in real time, so file changes made
// during the run (the hot reload tests) are seen as a user would see them.
#include "rigidlab/sandbox/sandbox.h"

#include <SDL.h>
#include <imgui.h>
#include <backends/imgui_impl_opengl3.h>
#include <backends/imgui_impl_sdl.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <thread>

#include "assets.h"
#include "camera_follow.h"
#include "gl.h"
#include "panel_layout.h"
#include "panels.h"
#include "renderer.h"
#include "screenshot.h"
#include "session.h"
#include "tools.h"
#include "world_view.h"

namespace rigidlab::sandbox {

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kAutomationFrameSeconds = 1.0 / 60.0;

bool explicitVideoDriver() {
  const char* driver = std::getenv("SDL_VIDEODRIVER");
  return driver && *driver;
}

// Without a display server SDL 2.26 quietly falls back to its "offscreen" (EGL) or "dummy" driver:
// a window nobody can see. That counts as no display unless the user asked for the driver.
bool displayAvailable() {
#ifdef __linux__
  if (!explicitVideoDriver() && !std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) return false;
#endif
  return true;
}

// Multisampling: 4× by default, RIGIDLAB_MSAA=N to choose. On a software renderer (Mesa llvmpipe,
// as under Xvfb or in a VM without a GPU) it is off unless asked for: measured under Xvfb on the
// playground scene, 4× costs 27 ms of CPU per frame against 7 ms without, which is the difference
// between 36 and 60 frames per second and doubles the hot-reload latency.
std::optional<int> requestedSamples() {
  const char* env = std::getenv("RIGIDLAB_MSAA");
  if (!env || !*env) return std::nullopt;
  return std::max(0, std::atoi(env));
}

bool softwareRenderer() {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (!renderer) return false;
  const std::string name = renderer;
  for (const char* soft : {"llvmpipe", "softpipe", "swrast", "SWR"})
    if (name.find(soft) != std::string::npos) return true;
  return false;
}

struct Window {
  SDL_Window* window = nullptr;
  SDL_GLContext gl = nullptr;
  ~Window() {
    if (gl) SDL_GL_DeleteContext(gl);
    if (window) SDL_DestroyWindow(window);
    SDL_Quit();
  }
};

// A window with an OpenGL 3.3 core context, multisampled if the system offers it (see above).
bool openWindow(Window& w, int width, int height, std::string& error) {
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_CORE);
  SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
  SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 0);
  SDL_GL_SetAttribute(SDL_GL_STENCIL_SIZE, 8);
  const auto flags = static_cast<SDL_WindowFlags>(SDL_WINDOW_OPENGL | SDL_WINDOW_RESIZABLE);
  const std::optional<int> requested = requestedSamples();
  for (const int samples : {requested.value_or(4), 0}) {
    SDL_GL_SetAttribute(SDL_GL_MULTISAMPLEBUFFERS, samples > 0 ? 1 : 0);
    SDL_GL_SetAttribute(SDL_GL_MULTISAMPLESAMPLES, samples);
    w.window = SDL_CreateWindow("rigidlab", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, width, height, flags);
    if (w.window) w.gl = SDL_GL_CreateContext(w.window);
    if (w.gl && samples > 0 && !requested && softwareRenderer()) {
      SDL_GL_DeleteContext(w.gl);  // software GL: try again without multisampling
      w.gl = nullptr;
    }
    if (w.gl) return true;
    error = SDL_GetError();
    if (w.window) SDL_DestroyWindow(w.window);
    w.window = nullptr;
    if (samples == 0) break;
  }
  return false;
}

void updateTitle(SDL_Window* window, const Session& s, std::string& shown) {
  const std::string title = "rigidlab - " + overlayText(s.scene->settings().title, 256) + (s.paused ? " (paused)" : "");
  if (title != shown) SDL_SetWindowTitle(window, title.c_str());
  shown = title;
}

void drawWorld(Session& s, Renderer& renderer) {
  renderer.begin(s.camera);
  if (s.draw.grid) renderer.drawGrid();
  DrawOptions options;
  options.shapes = s.draw.shapes;
  options.springs = s.draw.springs;
  options.forces = s.draw.forces;
  options.joints = s.draw.joints;
  options.contacts = s.draw.contacts;
  options.normals = s.draw.normals;
  options.impulses = s.draw.impulses;
  options.aabbs = s.draw.aabbs;
  options.centers = s.draw.centers;
  options.velocities = s.draw.velocities;
  options.selected = s.selected;
  if (!s.paused) {
    options.transforms = s.history.interpolate(s.world(), s.alpha);
    options.springs = options.forces = false;  // drawn below, at the same poses
  }
  s.world().draw(renderer, options);
  if (!options.transforms.empty()) drawForces(s.world(), options.transforms, s.draw, renderer);
  if (s.draw.exact && s.exact.active) {
    // Where Exact(t) puts each body origin (at the time of the last step, like the drawn state).
    const Color ghost{1.0f, 0.6f, 0.1f, 0.9f};
    const double arm = s.camera.metres(7.0);
    for (const BodyError& e : s.exact.bodies) {
      const Vec2& p = e.exact_position;
      renderer.drawSegment(p - Vec2(arm, arm), p + Vec2(arm, arm), ghost);
      renderer.drawSegment(p - Vec2(arm, -arm), p + Vec2(arm, -arm), ghost);
    }
  }
  drawToolOverlay(s, renderer);
  if (s.scene->hasOnDraw() && s.draw_error.empty()) {
    try {
      s.draw_truncated = s.scene->onDraw(renderer).truncated;
    } catch (const std::exception& e) {
      s.draw_error = overlayText(e.what());
      std::fprintf(stderr, "rigidlab: %s\n", s.draw_error.c_str());
    }
  }
  renderer.flush();
}

// --layout-file: the windows' rectangles (panel_dock.h), and where the camera is and the
// followed body is drawn.
bool writeLayout(const std::filesystem::path& file, Session& s, const Renderer& renderer, std::string& error) {
  const Camera& c = s.camera;
  std::vector<ScreenRect> hud;
  if (const auto r = renderer.hud()) hud.push_back(*r);
  char line[256];
  std::vector<std::string> extra;
  std::snprintf(line, sizeof line, "camera %.6g %.6g %.6g", c.pixels_per_metre, c.center.x(), c.center.y());
  extra.push_back(line);
  if (s.world().isValid(s.follow)) {
    const Vec2 at = c.worldToScreen(drawnCenter(s, s.follow));
    std::snprintf(line, sizeof line, "follow %.1f %.1f %s", at.x(), at.y(), describe(s.world(), s.follow).c_str());
    extra.push_back(line);
  }
  return writeWindowRects(file.string(), ImGui::GetIO().DisplaySize,
                          freeViewArea(c.width_px, c.height_px, s.show_panels), hud, extra, error);
}

}  // namespace

int runSandbox(const SandboxOptions& options) {
  if (!displayAvailable()) return kNoDisplay;
  if (SDL_Init(SDL_INIT_VIDEO | SDL_INIT_TIMER) != 0) return kNoDisplay;
  const char* driver = SDL_GetCurrentVideoDriver();
  if (!explicitVideoDriver() && driver && (std::strcmp(driver, "offscreen") == 0 || std::strcmp(driver, "dummy") == 0)) {
    SDL_Quit();
    return kNoDisplay;
  }
  Window w;
  std::string error;
  if (!openWindow(w, options.width, options.height, error)) {
    std::fprintf(stderr, "rigidlab: cannot open an OpenGL 3.3 window: %s\n", error.c_str());
    return kNoDisplay;
  }
  SDL_GL_MakeCurrent(w.window, w.gl);
  const bool automated = options.frames.has_value();
  SDL_GL_SetSwapInterval(automated ? 0 : 1);  // vsync when interactive; the frame cap paces either way

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini: nothing is written into a (possibly watched) directory
  ImGui::StyleColorsDark();
  ImGui::GetStyle().Alpha = 0.95f;
  ImGui_ImplSDL2_InitForOpenGL(w.window, w.gl);
  ImGui_ImplOpenGL3_Init("#version 330");

  int exit_code = 0;
  {
    Renderer renderer;
    if (!renderer.init(assetsDirectory(), error)) {
      std::fprintf(stderr, "rigidlab: %s\n", error.c_str());
      exit_code = 1;
    } else {
      Session s;
      int width = 0, height = 0;
      SDL_GL_GetDrawableSize(w.window, &width, &height);
      s.camera.resize(width, height);
      std::filesystem::path file = options.scene;
      if (file.empty()) {
        s.show_browser = true;
        const auto playground = lua::scriptsDirectory() / "scenes" / "playground.lua";
        if (std::filesystem::exists(playground)) file = playground;
      }
      startSession(s, file);
      PanelState panels;
      std::string title;

      auto last = Clock::now();
      for (int frame = 1; !options.frames || frame <= *options.frames; ++frame) {
        const auto frame_start = Clock::now();
        const double measured = std::chrono::duration<double>(frame_start - last).count();
        last = frame_start;

        bool quit = false;
        SDL_Event event;
        while (SDL_PollEvent(&event)) {
          ImGui_ImplSDL2_ProcessEvent(&event);
          if (event.type == SDL_QUIT) quit = true;
          if (event.type == SDL_WINDOWEVENT && event.window.event == SDL_WINDOWEVENT_CLOSE &&
              event.window.windowID == SDL_GetWindowID(w.window))
            quit = true;
          handleEvent(s, event, {io.WantCaptureMouse, io.WantCaptureKeyboard});
        }
        // Closed early (window, SIGTERM) under --frames: this frame is still drawn, for the screenshot
        // and the layout file.
        const bool last_frame = (options.frames && frame == *options.frames) || quit;
        if (quit && !(automated && (!options.screenshot.empty() || !options.layout_file.empty()))) break;

        updateHotReload(s);
        syncTimeline(s);  // rewind.cpp: an edit at a past state drops its future
        advance(s, automated ? kAutomationFrameSeconds : measured);
        updateTools(s);

        SDL_GL_GetDrawableSize(w.window, &width, &height);
        s.camera.resize(width, height);
        updateFollow(s);
        drawWorld(s, renderer);

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplSDL2_NewFrame();
        ImGui::NewFrame();
        renderer.drawTexts(ImGui::GetBackgroundDrawList());
        drawPanels(s, panels, renderer);
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (automated && last_frame && !options.layout_file.empty() && !writeLayout(options.layout_file, s, renderer, error)) {
          std::fprintf(stderr, "rigidlab: layout file: %s\n", error.c_str());
          exit_code = 1;
        }

        if (automated && last_frame && !options.screenshot.empty()) {
          if (!writeScreenshot(options.screenshot, width, height, error)) {
            std::fprintf(stderr, "rigidlab: screenshot: %s\n", error.c_str());
            exit_code = 1;
          }
        }
        SDL_GL_SwapWindow(w.window);
        updateTitle(w.window, s, title);
        if (quit) break;

        s.last_frame_ms = std::chrono::duration<double, std::milli>(Clock::now() - frame_start).count();
        if (s.loop.frame_cap_hz > 0.0) {
          const auto next = frame_start + std::chrono::duration_cast<Clock::duration>(
                                              std::chrono::duration<double>(1.0 / s.loop.frame_cap_hz));
          std::this_thread::sleep_until(next);
        }
      }
      // A scene that never loaded is a failure for automation (scripts check the exit status).
      if (!s.scene_loaded && !file.empty()) exit_code = 1;
      // A load still running on its worker thread must not outlive main()'s statics; a script stuck
      // in PopulateWorld is given a second, then left (the process exits around it).
      if (s.loader.busy()) s.loader.poll(std::chrono::milliseconds(1000));
    }
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplSDL2_Shutdown();
  ImGui::DestroyContext();
  return exit_code;
}

}  // namespace rigidlab::sandbox
