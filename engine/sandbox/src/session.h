// The sandbox's state and the operations on it, independent of SDL, OpenGL and ImGui (so tests can
// drive it): the running scene (the Model, docs/design/thesis.md §11), the camera and draw settings (the View's
// state), and what the Controller keeps between frames — loop timing, pause, selection, undo
// history, hot reload, error overlays.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "camera.h"
#include "energy_plot.h"
#include "exact_readout.h"
#include "file_watcher.h"
#include "frame_clock.h"
#include "hot_reload.h"
#include "interpolation.h"
#include "profile_history.h"
#include "rigidlab/lua/scene.h"
#include "timeline.h"
#include "undo.h"

namespace rigidlab::sandbox {

struct DrawToggles {
  bool grid = true, shapes = true, springs = true, forces = true, joints = true;
  bool exact = true;  // ghosts of Exact(t)'s positions, for scenes that define it
  bool contacts = false, normals = false, impulses = false, aabbs = false, centers = false, velocities = false;
};

// World settings changed in the panel. They stay in force across hot reloads (the scene's values
// come back with "use the scene's values" or when another scene is opened).
struct WorldOverrides {
  std::optional<Vec2> gravity;
  std::optional<Integrator> integrator;
  std::optional<int> iterations;
  std::optional<double> dt;
  std::optional<bool> warm_starting;
  std::optional<bool> sleeping;
  std::optional<ContactSolver> solver;
  std::optional<int> substeps;
  bool any() const { return gravity || integrator || iterations || dt || warm_starting || sleeping || solver || substeps; }
};

enum class Tool { Select, Circle, Box, Polygon, Capsule, Joint };
// The joints the joint tool makes (joint_tool.cpp).
inline constexpr JointType kToolJoints[] = {JointType::Revolute, JointType::Weld, JointType::Distance,
                                            JointType::Prismatic, JointType::Wheel};

// What the mouse is doing (tools.cpp).
struct ToolState {
  Tool tool = Tool::Select;
  // Sizes and material of bodies made with a click (a drag sets the size instead).
  double circle_radius = 0.5, box_width = 1.0, box_height = 1.0;  // [m]
  double capsule_length = 1.5, capsule_radius = 0.25;              // [m]: length between the centres
  double density = 1.0;                                           // [kg/m²]
  double restitution = 0.2, friction = 0.6;
  bool make_static = false;

  enum class Gesture { None, Drag, Move, Rotate, Create, Pan };
  Gesture gesture = Gesture::None;
  Vec2 mouse_px = Vec2::Zero();  // last cursor position
  Vec2 press_px = Vec2::Zero();  // where the button went down
  Vec2 press_world = Vec2::Zero();
  JointId drag_joint;            // Drag: the motor joint pulling the body (running; mouse_drag.h)
  BodyId body;                   // Move/Rotate/Drag: the body
  BodyProps before;              // Move/Rotate: for undo
  Vec2 grab_offset = Vec2::Zero();  // Move: body origin − cursor
  double start_angle = 0.0, start_cursor_angle = 0.0;  // Rotate
  std::vector<Vec2> polygon;     // Polygon: the points clicked so far [m]

  // Joint tool: the kind to make and its options, and the first click (joint_tool.h).
  JointType joint_kind = JointType::Revolute;
  double joint_axis_degrees = 0.0;  // prismatic and wheel: the axis, from +x
  bool joint_collide = false;       // collide_connected
  bool joint_rope = false;          // distance: a rope (max length only) instead of a rod
  BodyId joint_body;                // the first body clicked; null: none yet
  Vec2 joint_point = Vec2::Zero();  // where it was clicked [m]
};

struct SaveDialog {
  bool open = false;
  std::string path;
  std::string message;        // why the last attempt was refused
  bool confirm_overwrite = false;
};

struct Session {
  using Clock = std::chrono::steady_clock;

  // --- model
  std::unique_ptr<lua::Scene> scene;  // never null after startSession
  std::filesystem::path file;         // the scene file (as given); empty: none
  bool scene_loaded = false;          // false while showing the empty placeholder after a failed start
  lua::SceneOptions scene_options;

  // --- view
  Camera camera;
  BodyId follow;  // the body the camera keeps in the middle of the view (camera_follow.h); null: none
  DrawToggles draw;
  bool show_panels = true, show_help = false, show_browser = false;

  // --- controller
  LoopSettings loop;
  FrameClock clock;
  RealTimeMeter meter;
  bool paused = false;
  bool behind = false;            // the last frame dropped simulated time
  int steps_last_frame = 0;
  double alpha = 1.0;
  double last_frame_ms = 0.0, last_steps_ms = 0.0;  // wall time of the last frame / its steps
  WorldOverrides overrides;
  WorldOverrides scene_values;  // the scene's own values of the overridable settings (all set)
  BodyId selected;         // at most one of these two is set
  JointId selected_joint;
  ToolState tools;
  UndoHistory undo;
  TransformHistory history;
  EnergyHistory energy;
  ProfileHistory profile;         // the step stages' times over the last seconds (Profile panel)
  Timeline timeline;              // recent states, for stepping back and scrubbing (rewind.cpp)
  size_t timeline_undo_mark = 0;  // undo.size() when the timeline last looked (syncTimeline)
  ExactReadout exact;
  size_t incidents_seen = 0;  // World::incidents() already reported
  SaveDialog save;

  // --- hot reload and errors
  FileWatcher watcher;
  SceneLoader loader;
  // A reload that failed while its file was being rewritten again: probably a half-written file.
  // Shown only if the writes settle without bringing a new load (then it was a real error).
  std::optional<LoadResult> deferred_failure;
  // Messages are stored as overlayText() makes them, so they are safe and small enough to draw.
  std::string load_error;  // the last load failed: shown until the next good load
  std::string run_error;   // a script failed while running: the simulation paused
  std::string draw_error;  // OnDraw failed: it is not called again until the scene is reloaded
  std::string rewind_error;  // SaveState failed: no state is recorded until the scene is reloaded
  bool draw_truncated = false;  // the last OnDraw asked for more than a frame draws (Scene::DrawReport)
  std::string status;      // a transient message (saved, undone, refused edit, ...)
  Clock::time_point status_until{};
  int reloads = 0;
  double last_load_ms = 0.0;

  void setStatus(std::string message, double seconds = 3.0);
  World& world() { return scene->world(); }
  const World& world() const { return scene->world(); }
  double dt() const { return scene->settings().dt; }
};

// A message as the sandbox shows and prints it: control characters escaped, at most
// kOverlayBytes. Dear ImGui draws 4 vertices per character and a window's vertices must number
// under 65 536 (16-bit indices): an error of 20 000 characters aborted it on an assertion.
inline constexpr size_t kOverlayBytes = 4096;
std::string overlayText(std::string_view message, size_t max_bytes = kOverlayBytes);

// Loads `file` (empty: an empty world) on this thread and starts watching it. On failure the
// session shows an empty world with the error overlay and watches the file, so fixing it loads it.
void startSession(Session& s, const std::filesystem::path& file);
// Puts a finished load in place (see LoadPurpose) or shows its error. Prints one line to standard
// output per successful load: `opened <file>` (a scene opened) or `reloaded <file>` (hot reload,
// reset); failures go to standard error.
void adoptScene(Session& s, LoadResult result);
// Starts loading `file` beside the running scene (the browser, reset, F5, the file watcher).
void requestLoad(Session& s, const std::filesystem::path& file, LoadPurpose purpose);
// Per frame: file changes → loads, finished loads → adoptScene.
void updateHotReload(Session& s, Session::Clock::time_point now = Session::Clock::now());

// Runs the world steps of one frame that took `frame_seconds` (frame_clock.h). A script error
// pauses the simulation and sets run_error; the world stays as before the failed step.
void advance(Session& s, double frame_seconds);
// One step now (the single-step key); pauses first.
void stepOnce(Session& s);
void setPaused(Session& s, bool paused);

// Runs a hook of the scene's that may edit the world between steps (OnKey, OnMouse, OnControl); a
// script error pauses the simulation with the error shown. Returns what `hook` returned, false
// after an error.
bool runSceneHook(Session& s, const std::function<bool()>& hook);

void applyOverrides(Session& s);
void clearOverrides(Session& s);  // and restore the scene's own values (by reloading)
void fitCamera(Session& s);       // the whole scene in view
// Bounds of all bodies; nothing for an empty world.
std::optional<Aabb> worldBounds(const World& world);

// --- edits (all undoable)
BodyId addBody(Session& s, const BodyDef& def, const std::string& label);  // BodyId{} if refused (status says why)
// A body of several shapes: def's shape (if any) and then `more`, in body coordinates.
BodyId addCompound(Session& s, const BodyDef& def, const std::vector<ShapeDef>& more, const std::string& label);
void deleteBody(Session& s, BodyId id);  // with its joints
JointId addJoint(Session& s, const JointDef& def, const std::string& label);  // JointId{} if refused
void deleteJoint(Session& s, JointId id);
// Selects a body or a joint (the other is deselected); null ids: nothing.
void select(Session& s, BodyId body, JointId joint = {});
// "'name'", "polygon #3", "compound body #4"; for joints "revolute joint 'hinge'" or "revolute joint".
std::string describe(const World& world, BodyId id);
std::string describe(const World& world, JointId id);
void toggleStatic(Session& s, BodyId id);
void undo(Session& s);
void redo(Session& s);
// Ends whatever the mouse was doing (drag joint removed, move committed) — before a swap, a pause.
void cancelGesture(Session& s);

// Saves the world as a scene file (scene_writer.h). Refuses the open scene and its modules (they
// would be overwritten by data and reloaded). Returns false with the reason in `message`.
bool saveWorld(Session& s, const std::filesystem::path& path, std::string& message);
// A file name next to the scene that does not exist yet: "<stem>_saved.lua", "<stem>_saved_2.lua", ...
std::filesystem::path suggestSavePath(const Session& s);

// --- rewind (rewind.cpp; docs/sandbox.md "Rewind")
// After a step or a load: the world's state into the timeline, if due.
void recordState(Session& s);
// Shift+N: pauses and shows the kept state before the one shown (false if there is none).
bool stepBack(Session& s);
// Rewound, N: the kept state after the one shown (false at the newest: then N steps anew).
bool stepForward(Session& s);
// The timeline slider: shows kept state `index` (0 = oldest), paused.
void seekState(Session& s, size_t index);
// Per frame: an edit made while rewound drops the states after the one shown.
void syncTimeline(Session& s);
// Writes the world's state as a snapshot file (`rigidlab run --load-state` reads it), for a bug
// report. False with the reason in `message`.
bool saveState(Session& s, const std::filesystem::path& path, std::string& message);
// "<stem>_state.snap" next to the scene, "<stem>_state_2.snap", ... (a name not taken yet).
std::filesystem::path suggestStatePath(const Session& s);

// Scene files offered by the browser: scripts/scenes/*.lua, sorted.
std::vector<std::filesystem::path> browsableScenes();

}  // namespace rigidlab::sandbox
