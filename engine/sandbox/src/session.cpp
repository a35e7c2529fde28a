// Sandbox state operations: loading and swapping scenes, stepping, edits, saving (session.h).
#include "session.h"

#include <algorithm>
#include <cstdio>

#include "panel_layout.h"
#include "rigidlab/lua/scene_text.h"
#include "rigidlab/lua/scene_writer.h"

namespace rigidlab::sandbox {

namespace fs = std::filesystem;

std::string overlayText(std::string_view message, size_t max_bytes) {
  return lua::displayText(message, max_bytes, "\n");
}

void Session::setStatus(std::string message, double seconds) {
  status = overlayText(message, 512);  // one line at the bottom of the window
  status_until = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

namespace {

std::unique_ptr<lua::Scene> emptyScene(const lua::SceneOptions& options) {
  return lua::Scene::loadString("function PopulateWorld(world) end", "(no scene)", options);
}

fs::path comparable(const fs::path& p) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(fs::absolute(p, ec), ec);
  return ec ? p.lexically_normal() : r;
}

WorldOverrides currentValues(const lua::Scene& scene) {
  const WorldDef& def = scene.world().settings();
  return {def.gravity,      def.integrator, def.iterations,     scene.settings().dt,
          def.warm_starting, def.sleeping,  def.contact_solver, def.substeps};
}

// A scene's own view (scene.camera) shows, in the part of the window the panels leave free, the
// moving bodies it would show in the whole window: the view zooms out (never in) about the point
// at the free area's middle until they fit its width, so none starts behind a panel. Static
// bodies (a long ground) and moving ones outside that view do not count.
void keepMovingBodiesClearOfPanels(Session& s, const ScreenRect& area) {
  Camera& c = s.camera;
  const Vec2 lo = c.screenToWorld(Vec2(0, c.height_px)), hi = c.screenToWorld(Vec2(c.width_px, 0));
  const Vec2 focus = c.screenToWorld(area.middle());
  double reach = 0.0;  // the farthest x of a moving body's part in the view from the focus [m]
  const World& w = s.world();
  for (const BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    if (b.isStatic()) continue;
    for (const ShapeId sid : b.shapes) {
      const Aabb a = computeAabb(w.shape(sid).geometry, b.xf);
      if (a.upper.x() < lo.x() || a.lower.x() > hi.x() || a.upper.y() < lo.y() || a.lower.y() > hi.y()) continue;
      reach = std::max({reach, std::min(a.upper.x(), hi.x()) - focus.x(), focus.x() - std::max(a.lower.x(), lo.x())});
    }
  }
  const double room = 0.5 * 0.95 * area.width();  // px from the middle, 5 % kept as a margin
  if (reach * c.pixels_per_metre <= room) return;
  c.pixels_per_metre = std::max(room / reach, Camera::kMinPixelsPerMetre);
  c.placeAt(focus, area.middle());
}

// The scene's camera (its centre at the middle of the part of the window the panels leave free,
// as saved worlds store it); without one the bodies are framed there.
void placeCamera(Session& s) {
  const lua::SceneSettings& settings = s.scene->settings();
  const ScreenRect area = freeViewArea(s.camera.width_px, s.camera.height_px, s.show_panels);
  const auto box = worldBounds(s.world());
  if (box) {
    s.camera.fitIn(*box, area);
  } else {
    s.camera.center = Vec2::Zero();
    s.camera.setHeightMetres(20.0);
  }
  if (settings.camera_height) {
    s.camera.setHeightMetres(*settings.camera_height);
    if (box) s.camera.placeAt(0.5 * (box->lower + box->upper), area.middle());
  }
  if (settings.camera_center) s.camera.placeAt(*settings.camera_center, area.middle());
  if (settings.camera_center || settings.camera_height) keepMovingBodiesClearOfPanels(s, area);
}

// A script failed while running: the simulation pauses and says why (overlay and standard error).
void pauseOnScriptError(Session& s, const std::exception& e) {
  s.run_error = overlayText(e.what());
  std::fprintf(stderr, "rigidlab: paused: %s\n", s.run_error.c_str());
  std::fflush(stderr);
  setPaused(s, true);
}

void afterWorldChange(Session& s) {
  s.history.capture(s.world());  // an edited body is drawn where it is, not interpolated
}

}  // namespace

void startSession(Session& s, const fs::path& file) {
  s.file = file;
  s.scene_loaded = false;
  if (!file.empty()) {
    lua::removeStaleTemporaries(file.has_parent_path() ? file.parent_path() : fs::path("."));
    adoptScene(s, SceneLoader::loadNow(file, LoadPurpose::Open, s.scene_options));
  }
  if (!s.scene) {
    s.scene = emptyScene(s.scene_options);
    s.scene_values = currentValues(*s.scene);
    s.exact.reset(*s.scene);
    placeCamera(s);
  }
}

void adoptScene(Session& s, LoadResult r) {
  if (!r.scene) {
    s.load_error = overlayText(r.error);
    std::fprintf(stderr, "rigidlab: %s%s\n", r.purpose == LoadPurpose::Open ? "" : "reload failed: ", s.load_error.c_str());
    std::fflush(stderr);
    if (!s.scene_loaded) {
      // Nothing good to keep yet: watch the file the user is fixing.
      s.file = r.file;
      s.watcher.watch({r.file});
    }
    return;
  }
  if (s.scene) cancelGesture(s);  // its drag joint belongs to the old world
  const bool first = !s.scene_loaded;
  const bool keep_view = r.purpose != LoadPurpose::Open && !first;
  s.scene = std::move(r.scene);
  s.file = r.file;
  s.scene_loaded = true;
  s.last_load_ms = r.load_ms;
  s.load_error.clear();
  s.run_error.clear();
  s.draw_error.clear();
  s.rewind_error.clear();
  s.draw_truncated = false;
  s.scene_values = currentValues(*s.scene);
  if (keep_view) {
    applyOverrides(s);
  } else {
    s.overrides = {};
    s.paused = false;
    placeCamera(s);
  }
  s.undo.clear();
  s.history.clear();
  s.timeline.clear();
  recordState(s);
  s.timeline_undo_mark = 0;
  s.energy.clear();
  s.energy.sample(s.world());
  s.exact.reset(*s.scene);
  s.exact.update(*s.scene);
  s.incidents_seen = 0;
  s.profile.clear();
  s.follow = s.scene->settings().camera_follow.value_or(BodyId{});  // the scene's, also on a reload
  s.selected = {};
  s.selected_joint = {};
  s.tools.polygon.clear();
  s.tools.joint_body = {};
  s.clock.reset();
  s.meter.reset();
  s.watcher.watch(s.scene->sourceFiles());
  if (r.purpose != LoadPurpose::Open) ++s.reloads;
  // One line per load on standard output ("opened", "reloaded"): tests and tools wait for them.
  if (r.purpose == LoadPurpose::Reload || (first && r.purpose != LoadPurpose::Open)) {
    std::printf("reloaded %s\n", s.file.string().c_str());
    std::fflush(stdout);
  } else if (r.purpose == LoadPurpose::Open) {
    std::printf("opened %s\n", s.file.string().c_str());
    std::fflush(stdout);
  } else if (r.purpose == LoadPurpose::Reset) {
    s.setStatus("reset: " + s.file.filename().string());
  }
}

void requestLoad(Session& s, const fs::path& file, LoadPurpose purpose) {
  lua::SceneOptions options = s.scene_options;
  // A reload or reset keeps the scene's sliders where the user left them (scene.controls).
  if (purpose != LoadPurpose::Open && s.scene && s.scene_loaded) options.control_values = s.scene->controlValues();
  s.loader.start(file, purpose, options);
}

void updateHotReload(Session& s, Session::Clock::time_point now) {
  bool started = false;
  if (!s.file.empty() && s.watcher.poll(now)) {
    requestLoad(s, s.file, LoadPurpose::Reload);
    s.deferred_failure.reset();  // superseded by the newer content
    started = true;
  }
  // A typical scene loads in about a millisecond: wait a little for it (bounded, so a slow or
  // stuck PopulateWorld costs this frame at most 8 ms) instead of a whole frame.
  if (auto r = s.loader.poll(started ? std::chrono::milliseconds(8) : std::chrono::milliseconds(0))) {
    if (!r->scene && r->purpose == LoadPurpose::Reload && s.watcher.settling(now)) {
      s.deferred_failure = std::move(*r);  // the file is being written again: wait and see
    } else {
      adoptScene(s, std::move(*r));
    }
  }
  if (s.deferred_failure && !s.loader.busy() && !s.watcher.settling(now)) {
    LoadResult failure = std::move(*s.deferred_failure);
    s.deferred_failure.reset();
    adoptScene(s, std::move(failure));
  }
}

namespace {

// After steps: the readouts that follow the state (energy plot, live error against Exact(t)), and
// bodies the core's NaN firewall froze, which are reported once each.
void afterSteps(Session& s) {
  s.energy.sample(s.world());
  s.exact.update(*s.scene);
  const auto& incidents = s.world().incidents();
  for (; s.incidents_seen < incidents.size(); ++s.incidents_seen) {
    const std::string message = overlayText(incidents[s.incidents_seen].message());
    std::fprintf(stderr, "rigidlab: %s\n", message.c_str());
    s.setStatus(message, 8.0);
  }
}

// One step with the error policy of the issue: a failing script pauses the run and says why.
bool guardedStep(Session& s, double dt) {
  try {
    s.scene->step(dt);
    s.profile.add(s.world().stats(), std::chrono::duration<double>(Session::Clock::now().time_since_epoch()).count());
    return true;
  } catch (const std::exception& e) {
    pauseOnScriptError(s, e);
  }
  return false;
}

}  // namespace

void advance(Session& s, double frame_seconds) {
  s.steps_last_frame = 0;
  s.behind = false;
  if (s.paused) {
    s.alpha = 1.0;
    return;
  }
  const FramePlan plan = s.clock.plan(frame_seconds, s.dt(), s.loop);
  const auto t0 = Session::Clock::now();
  for (int i = 0; i < plan.steps; ++i) {
    s.history.capture(s.world());
    if (!guardedStep(s, plan.step_dt)) break;
    recordState(s);  // rewound: drops the states after the one shown first (timeline.h)
    ++s.steps_last_frame;
  }
  s.last_steps_ms = std::chrono::duration<double, std::milli>(Session::Clock::now() - t0).count();
  s.alpha = s.paused ? 1.0 : plan.alpha;
  s.behind = plan.behind;
  s.meter.add(frame_seconds, s.steps_last_frame * plan.step_dt);
  if (s.steps_last_frame > 0) afterSteps(s);
}

void stepOnce(Session& s) {
  setPaused(s, true);
  if (stepForward(s)) return;  // rewound: the next kept state
  s.history.capture(s.world());
  s.run_error.clear();
  if (guardedStep(s, s.dt())) {
    recordState(s);
    afterSteps(s);
  }
  s.alpha = 1.0;
}

void setPaused(Session& s, bool paused) {
  if (paused == s.paused) return;
  cancelGesture(s);
  if (!paused) {
    s.clock.reset();  // the paused time is not owed to the simulation
    s.run_error.clear();
  }
  s.paused = paused;
}

void applyOverrides(Session& s) {
  World& w = s.world();
  const WorldOverrides& o = s.overrides;
  try {
    if (o.gravity) w.setGravity(*o.gravity);
    if (o.integrator) w.setIntegrator(*o.integrator);
    if (o.iterations) w.setIterations(*o.iterations);
    if (o.warm_starting) w.setWarmStarting(*o.warm_starting);
    if (o.sleeping) w.setSleeping(*o.sleeping);
    if (o.solver) w.setContactSolver(*o.solver);
    if (o.substeps) w.setSubsteps(*o.substeps);
    if (o.dt) s.scene->setDt(*o.dt);
  } catch (const std::exception& e) {
    s.setStatus(std::string("setting refused: ") + e.what());
  }
}

void clearOverrides(Session& s) {
  s.overrides = s.scene_values;  // apply the scene's values once, then forget the overrides
  applyOverrides(s);
  s.overrides = {};
}

std::optional<Aabb> worldBounds(const World& world) {
  std::optional<Aabb> box;
  for (const BodyId id : world.bodyIds()) {
    const Body& b = world.body(id);
    for (const ShapeId sid : b.shapes) {
      const Aabb a = computeAabb(world.shape(sid).geometry, b.xf);
      if (!box) {
        box = a;
      } else {
        box->lower = box->lower.cwiseMin(a.lower);
        box->upper = box->upper.cwiseMax(a.upper);
      }
    }
  }
  return box;
}

bool runSceneHook(Session& s, const std::function<bool()>& hook) {
  try {
    const bool result = hook();
    s.history.capture(s.world());  // bodies it moved or made are drawn where they are
    return result;
  } catch (const std::exception& e) {
    pauseOnScriptError(s, e);
  }
  return false;
}

void fitCamera(Session& s) {
  s.follow = {};  // the whole scene, not one body
  if (const auto box = worldBounds(s.world()))
    s.camera.fitIn(*box, freeViewArea(s.camera.width_px, s.camera.height_px, s.show_panels));
}

std::string describe(const World& world, BodyId id) {
  const Body& b = world.body(id);
  const std::string shape = b.shapes.size() == 1 ? shapeTypeName(world.shape(b.shapes[0]).geometry.type)
                            : b.shapes.empty() ? "body" : "compound body";
  return b.name.empty() ? shape + " #" + std::to_string(b.uid) : "'" + b.name + "'";
}

std::string describe(const World& world, JointId id) {
  const JointDef& d = world.joint(id);
  return std::string(jointTypeName(d.type)) + " joint" + (d.name.empty() ? "" : " '" + d.name + "'");
}

void select(Session& s, BodyId body, JointId joint) {
  s.selected = body;
  s.selected_joint = joint;
}

BodyId addBody(Session& s, const BodyDef& def, const std::string& label) { return addCompound(s, def, {}, label); }

BodyId addCompound(Session& s, const BodyDef& def, const std::vector<ShapeDef>& more, const std::string& label) {
  World& w = s.world();
  BodyId id;
  try {
    id = w.createBody(def);
    for (const ShapeDef& shape : more) w.createShape(id, shape);
  } catch (const std::exception& e) {
    if (w.isValid(id)) w.destroyBody(id);  // all or nothing
    s.setStatus("cannot add " + label + ": " + e.what());
    return {};
  }
  s.undo.recordCreate(w, id, label);
  select(s, id);
  afterWorldChange(s);
  return id;
}

void deleteBody(Session& s, BodyId id) {
  if (!s.world().isValid(id)) return;
  if (s.tools.body == id) cancelGesture(s);
  const std::string label = "delete " + describe(s.world(), id);
  s.undo.destroy(s.world(), id, label);
  if (s.selected == id) s.selected = {};
  if (!s.world().isValid(s.selected_joint)) s.selected_joint = {};  // it went with the body
  if (!s.world().isValid(s.tools.joint_body)) s.tools.joint_body = {};
  afterWorldChange(s);
}

JointId addJoint(Session& s, const JointDef& def, const std::string& label) {
  try {
    const JointId id = s.world().createJoint(def);
    s.undo.recordCreateJoint(s.world(), id, label);
    select(s, {}, id);
    afterWorldChange(s);
    return id;
  } catch (const std::exception& e) {
    s.setStatus("cannot add " + label + ": " + e.what(), 5.0);
    return {};
  }
}

void deleteJoint(Session& s, JointId id) {
  if (!s.world().isValid(id) || id == s.tools.drag_joint) return;
  s.undo.destroyJoint(s.world(), id, "delete " + describe(s.world(), id));
  s.selected_joint = {};
  afterWorldChange(s);
}

void toggleStatic(Session& s, BodyId id) {
  if (!s.world().isValid(id)) return;
  if (s.tools.body == id) cancelGesture(s);
  const BodyProps before = captureProps(s.world(), id);
  const bool to_static = !s.world().body(id).isStatic();
  try {
    s.world().setType(id, to_static ? BodyType::Static : BodyType::Dynamic);
  } catch (const std::exception& e) {
    s.setStatus(std::string("cannot: ") + e.what(), 5.0);  // a body of segments cannot be dynamic
    return;
  }
  s.undo.recordModify(id, before, captureProps(s.world(), id),
                      std::string(to_static ? "make static " : "make dynamic ") + describe(s.world(), id));
  afterWorldChange(s);
}

void undo(Session& s) {
  cancelGesture(s);
  const std::string label = s.undo.undoLabel();
  try {
    if (s.undo.undo(s.world())) {
      select(s, s.undo.lastTouched(), s.undo.lastTouchedJoint());
      s.setStatus("undone: " + label);
    } else if (!label.empty()) {
      s.setStatus("cannot undo: the body or joint was removed by the scene; history cleared");
    }
  } catch (const std::exception& e) {
    s.setStatus(std::string("undo failed: ") + e.what());
  }
  afterWorldChange(s);
}

void redo(Session& s) {
  cancelGesture(s);
  const std::string label = s.undo.redoLabel();
  try {
    if (s.undo.redo(s.world())) {
      select(s, s.undo.lastTouched(), s.undo.lastTouchedJoint());
      s.setStatus("redone: " + label);
    } else if (!label.empty()) {
      s.setStatus("cannot redo: the body or joint was removed by the scene; history cleared");
    }
  } catch (const std::exception& e) {
    s.setStatus(std::string("redo failed: ") + e.what());
  }
  afterWorldChange(s);
}

void cancelGesture(Session& s) {
  ToolState& t = s.tools;
  World& w = s.world();
  switch (t.gesture) {
    case ToolState::Gesture::Drag:
      if (w.isValid(t.drag_joint)) w.destroyJoint(t.drag_joint);
      break;
    case ToolState::Gesture::Move:
    case ToolState::Gesture::Rotate:
      if (w.isValid(t.body))
        s.undo.recordModify(t.body, t.before, captureProps(w, t.body),
                            std::string(t.gesture == ToolState::Gesture::Move ? "move " : "rotate ") + describe(w, t.body));
      break;
    default:
      break;
  }
  t.gesture = ToolState::Gesture::None;
  t.drag_joint = {};
  t.body = {};
}

bool saveWorld(Session& s, const fs::path& path, std::string& message) {
  if (path.empty()) {
    message = "give a file name";
    return false;
  }
  cancelGesture(s);  // the drag joint is the mouse's, not the world's
  const fs::path target = comparable(path);
  std::vector<fs::path> protected_files = s.scene->sourceFiles();
  if (!s.file.empty()) protected_files.push_back(s.file);
  for (const fs::path& f : protected_files) {
    if (comparable(f) == target) {
      message = path.string() + " is the open scene (or a module it uses); choose a new name";
      return false;
    }
  }
  lua::SceneSettings settings = s.scene->settings();
  // The world point at the free area's middle, where the saved scene puts it again (placeCamera).
  settings.camera_center = s.camera.screenToWorld(freeViewArea(s.camera.width_px, s.camera.height_px, s.show_panels).middle());
  settings.camera_height = s.camera.heightMetres();
  try {
    lua::saveScene(s.world(), settings, path, s.scene_options.limits.source_bytes);
  } catch (const std::exception& e) {
    message = e.what();
    return false;
  }
  message.clear();
  s.setStatus("saved " + path.string());
  std::printf("saved %s\n", path.string().c_str());
  std::fflush(stdout);
  return true;
}

fs::path suggestSavePath(const Session& s) {
  const fs::path dir = s.file.has_parent_path() ? s.file.parent_path() : fs::path(".");
  const std::string stem = s.file.empty() ? "world" : s.file.stem().string();
  for (int i = 1;; ++i) {
    const fs::path candidate = dir / (stem + "_saved" + (i == 1 ? "" : "_" + std::to_string(i)) + ".lua");
    std::error_code ec;
    if (!fs::exists(candidate, ec)) return candidate;
  }
}

std::vector<fs::path> browsableScenes() {
  std::vector<fs::path> scenes;
  std::error_code ec;
  for (fs::directory_iterator it(lua::scriptsDirectory() / "scenes", ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    if (p.extension() == ".lua" && !lua::isTemporaryName(p)) scenes.push_back(p);
  }
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

}  // namespace rigidlab::sandbox
