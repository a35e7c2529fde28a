// Loading a scene and running its hooks (docs/design/thesis.md §3 and §11: PopulateWorld builds the model).
#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>

#include "api_names.h"
#include "bindings.h"
#include "lua_args.h"
#include "lua_contact.h"
#include "lua_events.h"
#include "lua_snapshot.h"
#include "rigidlab/error.h"
#include "rigidlab/lua/bounded_file.h"
#include "rigidlab/lua/data_directory.h"
#include "rigidlab/lua/scene_text.h"
#include "scene_line.h"

namespace rigidlab::lua {
namespace {

using api::kSceneOptions;

// Lua reports a multi-line `scene = { ... }` assignment at its closing line; point at the line
// that starts the statement instead ("<file>:<line>: " in, the same form out).
std::string sceneStatementLine(std::string_view source, const std::string& at) {
  const size_t colon = at.rfind(':', at.size() >= 2 ? at.size() - 3 : 0);
  if (at.empty() || colon == std::string::npos) return at;
  const int reported = std::atoi(at.c_str() + colon + 1);
  std::vector<std::string_view> lines;
  for (size_t start = 0; start <= source.size();) {
    const size_t end = std::min(source.find('\n', start), source.size());
    lines.push_back(source.substr(start, end - start));
    start = end + 1;
  }
  for (int line = std::min<int>(reported, static_cast<int>(lines.size())); line >= 1; --line) {
    std::string_view l = lines[line - 1];
    l.remove_prefix(std::min(l.find_first_not_of(" \t"), l.size()));
    if (l.starts_with("scene") && l.substr(5).find_first_not_of(" \t") != std::string_view::npos &&
        l[l.find_first_not_of(" \t", 5)] == '=')
      return at.substr(0, colon) + ":" + std::to_string(line) + ": ";
  }
  return at;
}

// The fields `rigidlab test` reads (docs/testing.md). The golden name becomes a file name beside
// the scene, so it may not climb out of the golden/ folder or hide itself.
void readTestSettings(const Options& o, SceneSettings& settings) {
  if (o.has("golden")) {
    const std::string name = o.string("golden", std::nullopt, 128);
    const bool plain = !name.empty() && name[0] != '.' && std::all_of(name.begin(), name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
    });
    if (!plain)
      o.fail("golden", "must be a file name of letters, digits, '_', '-' and '.' (not starting with '.'), got " +
                           describe(o.get("golden")));
    settings.golden = name;
  }
  for (const std::string_view field : {"golden_every", "golden_tolerance"})
    if (o.has(field) && settings.golden.empty())
      o.fail(field, "needs scene.golden (the name of the recorded trajectory)");
  settings.golden_every = o.integer("golden_every", 1, 1000000, settings.golden_every);
  settings.golden_tolerance = o.nonNegative("golden_tolerance", settings.golden_tolerance);
  if (o.has("skip")) settings.skip = o.string("skip", std::nullopt, kTitleBytes);
}

// Reads the optional global `scene` table (inside ScriptHost::run). Errors read
// "<file>:<line>: scene: dt must be > 0, got 0".
void readSettings(Scene::Impl& s, WorldDef& def, const std::string& at) {
  lua_State* L = s.host->L();
  lua_pushglobaltable(L);
  lua_pushliteral(L, "scene");
  lua_rawget(L, -2);
  const sol::object table = sol::stack::pop<sol::object>(L);
  lua_pop(L, 1);
  s.settings.title = displayText(std::filesystem::path(s.name).stem().string(), kTitleBytes);
  if (table.get_type() == sol::type::lua_nil) return;
  try {
    if (table.get_type() != sol::type::table) fail(L, "scene", "must be a table of settings, got " + describe(table));
    const Options o(L, "scene", table, joined({&kSceneOptions, &api::kSceneModOptions}));
    if (o.has("memory_limit")) {
      const double cap = static_cast<double>(s.host->limits().memory_bytes >> 20);
      const auto bytes = static_cast<size_t>(o.inRange("memory_limit", 1, cap) * double(1 << 20));
      if (s.host->memoryUsed() > bytes) {
        char used[32];
        std::snprintf(used, sizeof used, "%.1f", static_cast<double>(s.host->memoryUsed()) / double(1 << 20));
        o.fail("memory_limit", "is " + describe(o.get("memory_limit")) + " MiB, less than the " + used +
                                   " MiB the scene already uses");
      }
      s.host->lowerMemoryLimit(bytes);
    }
    s.settings.title = o.string("title", s.settings.title, kTitleBytes);
    def.gravity = o.vec("gravity", def.gravity);
    s.settings.dt = o.positive("dt", s.settings.dt);
    s.settings.duration = o.nonNegative("duration", s.settings.duration);
    if (o.has("integrator")) {
      const std::string name = o.string("integrator");
      const auto integrator = parseIntegrator(name);
      if (!integrator) o.fail("integrator", "must be one of " + integratorNames() + ", got " + describe(o.get("integrator")));
      def.integrator = *integrator;
    }
    if (o.has("solver")) {
      const std::string name = o.string("solver");
      const auto solver = parseContactSolver(name);
      if (!solver) o.fail("solver", "must be one of " + contactSolverNames() + ", got " + describe(o.get("solver")));
      def.contact_solver = *solver;
    }
    if (o.has("impacts")) {
      const std::string name = o.string("impacts");
      const auto impacts = parseImpactHandling(name);
      if (!impacts) o.fail("impacts", "must be one of " + impactHandlingNames() + ", got " + describe(o.get("impacts")));
      def.impacts = *impacts;
    }
    def.iterations = o.integer("iterations", 1, 10000, def.iterations);
    def.substeps = o.integer("substeps", 1, 64, def.substeps);
    def.sleeping = o.boolean("sleeping", def.sleeping);
    def.exact_joints = o.boolean("exact_joints", def.exact_joints);
    s.settings.expect_incidents = o.boolean("expect_incidents", false);
    readTestSettings(o, s.settings);
    if (o.has("camera")) {
      const Options c(L, "scene.camera", o.get("camera"), {"center", "height", "follow"});
      if (c.has("center")) s.settings.camera_center = c.vec("center");
      if (c.has("height")) s.settings.camera_height = c.positive("height");
      // The body itself is read once PopulateWorld has made it (readCameraFollow).
      if (c.has("follow")) {
        const sol::object follow = c.get("follow");
        follow.push(L);
        const bool body = toHandle<LuaBody>(L, -1) != nullptr;
        lua_pop(L, 1);
        if (!body && follow.get_type() != sol::type::string)
          c.fail("follow", "must be a body or a body's name, got " + describe(follow));
      }
    }
    readModSettings(o, s.settings);  // scene.keys, scene.controls (scene_controls.cpp)
  } catch (const ScriptError& e) {
    throw SceneError((at.empty() ? s.name + ": " : at) + e.what());
  }
}

// scene.camera.follow once PopulateWorld has made the bodies (a scene sets it there to a body it
// made, or names one anywhere): the body the sandbox's camera keeps in the middle of the view.
void readCameraFollow(Scene::Impl& s) {
  lua_State* L = s.host->L();
  std::string problem;
  const auto error = s.host->run([&] {
    const auto field = [&](const char* key) {  // raw: no metamethod of the script's runs in the host
      lua_pushstring(L, key);
      return lua_rawget(L, -2);
    };
    lua_pushglobaltable(L);
    if (field("scene") != LUA_TTABLE || field("camera") != LUA_TTABLE || field("follow") == LUA_TNIL) return;
    if (const LuaBody* body = toHandle<LuaBody>(L, -1)) {
      if (body->scene == &s && s.world->isValid(body->id)) s.settings.camera_follow = body->id;
      else problem = "is a body that was removed";
    } else if (lua_type(L, -1) == LUA_TSTRING) {
      const std::string name = boundedString(L, -1, "scene.camera", "follow", kNameBytes);
      if (const auto id = s.world->findBody(std::string_view(name))) s.settings.camera_follow = *id;
      else problem = "names no body: " + describe(L, -1);
    } else {
      problem = "must be a body or a body's name, got " + describe(L, -1);
    }
  });
  if (error) throw SceneError(s.name + ": " + s.host->errorText(*error, ""));
  if (!problem.empty()) throw SceneError(s.name + ": scene.camera: follow " + problem);
}

// The global function `name` (read raw, inside ScriptHost::run), or nil.
sol::object hook(Scene::Impl& s, const char* name) {
  lua_State* L = s.host->L();
  lua_pushglobaltable(L);
  lua_pushstring(L, name);
  lua_rawget(L, -2);
  sol::object f = sol::stack::pop<sol::object>(L);
  lua_pop(L, 1);
  if (f.get_type() != sol::type::lua_nil && f.get_type() != sol::type::function)
    throw SceneError(s.name + ": " + name + " must be a function, got " + describe(f));
  return f;
}

bool defined(const sol::object& f) { return f.valid() && f.get_type() == sol::type::function; }

// Runs a hook under its budget; a Lua error becomes SceneError("<file>:<line>: <hook>: <message>").
// `read` gets the state with the hook's one result on top (inside the protected call).
template <typename Read, typename... Args>
void callReading(Scene::Impl& s, const sol::object& f, std::string_view name, Read read, const Args&... args) {
  ++s.host->calls;
  std::optional<std::string> error;
  {
    const Budget::Scope budget(s.host->budget(), Budget::Kind::Hook);
    error = s.host->run([&] {
      lua_State* L = s.host->L();
      f.push(L);
      (sol::stack::push(L, args), ...);
      lua_call(L, static_cast<int>(sizeof...(Args)), 1);
      read(L);
      lua_pop(L, 1);
    });
    if (error) error = s.host->errorText(std::move(*error), name);  // while the window is open (budget.h)
  }
  if (error) throw SceneError(*error);
}

template <typename... Args>
void call(Scene::Impl& s, const sol::object& f, std::string_view name, const Args&... args) {
  callReading(s, f, name, [](lua_State*) {}, args...);
}

double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// --- event hooks (lua_events.h): called after a step, before OnStep, each under its own budget.
// All of them in one protected call (a thousand contact events are common), each call in a budget
// window of its own, as call() opens for the other hooks.
void deliverEvents(Scene::Impl& s) {
  bool any = false;
  for (const EventHook& h : eventHooks()) any = any || defined(s.*h.slot);
  if (!any) return;  // no Lua call, nothing made
  ScriptHost& host = *s.host;
  // The window of one hook call; notes on closing whether it was spent, which errorText needs to
  // know after the protected call has closed it.
  struct Window {
    Window(Budget& b, bool& spent) : budget(b), spent(spent), scope(b, Budget::Kind::Hook) {}
    ~Window() { spent = budget.expired(); }
    Budget& budget;
    bool& spent;
    Budget::Scope scope;
  };
  std::vector<EventCall> calls;
  std::string_view running = "events";  // what an error happened in
  bool spent = false;
  auto error = host.run([&] {
    lua_State* L = host.L();
    pushEventCalls(s, calls);
    const int args = lua_gettop(L);
    // The world handle and each hook function from the registry once, not per call.
    s.world_handle.push(L);
    const int world = lua_gettop(L);
    std::array<std::pair<const sol::object*, int>, 6> hooks{};
    for (const EventCall& c : calls)
      for (auto& [hook, slot] : hooks) {
        if (hook == c.hook) break;
        if (hook) continue;
        hook = c.hook;
        c.hook->push(L);
        slot = lua_gettop(L);
        break;
      }
    for (const EventCall& c : calls) {
      running = c.name;
      ++host.calls;
      const Window window(host.budget(), spent);
      int slot = 0;
      for (const auto& [hook, at] : hooks)
        if (hook == c.hook) slot = at;
      lua_pushvalue(L, slot);
      lua_pushvalue(L, world);
      lua_rawgeti(L, args, c.first);
      if (c.second) lua_rawgeti(L, args, c.second);
      lua_call(L, c.second ? 3 : 2, 0);
    }
  });
  if (error) throw SceneError(host.errorText(std::move(*error), running, spent));
}

// The steps of load() that touch the state, each inside ScriptHost::run.
void setUp(Scene::Impl& s) {
  lua_State* L = s.host->L();
  registerBodyType(L);
  registerWorldType(L);
  registerDrawType(L);
  registerShapeType(L);
  registerJointType(L);
  registerControlsType(L);
  registerSnapshotType(L);
  registerContactTypes(L);
  s.handles = s.host->lua().create_table();
  s.user_data = s.host->lua().create_table();
  s.shape_user_data = s.host->lua().create_table();
  s.joint_user_data = s.host->lua().create_table();
  s.shape_handles = makeWeakTable(L);
  s.joint_handles = makeWeakTable(L);
}

void runMainChunk(Scene::Impl& s, std::string_view source, const std::string& name) {
  lua_State* L = s.host->L();
  s.host->pushChunk(source, name);
  watchSceneLine(L);
  lua_call(L, 0, 0);
  unwatchSceneLine(L);
}

std::unique_ptr<Scene::Impl> load(std::string_view source, const std::string& name, const std::filesystem::path& file,
                                  const SceneOptions& options) {
  auto s = std::make_unique<Scene::Impl>();
  s->name = name;
  s->file = file;
  const std::filesystem::path dir = file.empty() ? std::filesystem::current_path() : file.parent_path();
  s->host = std::make_unique<ScriptHost>(options, dir.empty() ? std::filesystem::path(".") : dir);
  ScriptHost& host = *s->host;
  lua_State* L = host.L();
  if (const auto error = host.run([&] { setUp(*s); })) throw SceneError(name + ": " + host.errorText(*error, ""));

  ++host.calls;
  std::optional<std::string> chunk_error;
  {
    const Budget::Scope budget(host.budget(), Budget::Kind::Hook);
    chunk_error = host.run([&] { runMainChunk(*s, source, name); });
    if (chunk_error) chunk_error = host.errorText(std::move(*chunk_error), "");
  }
  if (chunk_error) {
    if (!chunk_error->starts_with(name)) chunk_error = name + ": " + *chunk_error;
    throw SceneError(*chunk_error);
  }

  WorldDef def;
  std::string scene_line;
  if (auto error = host.run([&] {
        scene_line = sceneStatementLine(source, sceneLine(L));
        readSettings(*s, def, scene_line);
      })) {
    // An error of the host's own reading (out of memory) has no line of the scene's: the table's.
    if (!hasLocation(*error)) *error = (scene_line.empty() ? name + ": " : scene_line) + "scene: " + *error;
    throw SceneError(host.errorText(*error, ""));
  }
  sol::object populate;
  const auto error = host.run([&] {
    try {
      s->world = std::make_unique<World>(def);
    } catch (const InputError& e) {
      throw SceneError(name + ": scene: " + e.what());
    }
    pushHandle(L, LuaWorld{s.get()});
    s->world_handle = sol::stack::pop<sol::object>(L);
    pushDrawHandles(L, s->draw);
    s->draw_handle = sol::stack::pop<sol::object>(L);
    populate = hook(*s, "PopulateWorld");
    s->on_step = hook(*s, "OnStep");
    s->check = hook(*s, "Check");
    s->on_key = hook(*s, "OnKey");
    s->on_draw = hook(*s, "OnDraw");
    s->exact = hook(*s, "Exact");
    for (const EventHook& h : eventHooks()) (*s).*h.slot = hook(*s, h.name.data());
    s->should_collide = hook(*s, "ShouldCollide");
    installShouldCollide(*s);
    s->on_mouse = hook(*s, "OnMouse");
    s->on_control = hook(*s, "OnControl");
    s->save_state = hook(*s, "SaveState");
    s->load_state = hook(*s, "LoadState");
    s->control_values = initialControlValues(s->settings, options.control_values);
  });
  if (error) throw SceneError(name + ": " + host.errorText(*error, ""));
  if (!defined(populate))
    throw SceneError(name + ": PopulateWorld is not defined (a scene must define function PopulateWorld(world))");
  call(*s, populate, "PopulateWorld", s->world_handle);
  readCameraFollow(*s);
  for (const std::string& warning : unraisedEventWarnings(*s)) host.log(name + ": " + warning);
  return s;
}

std::string displayName(const std::filesystem::path& file) {
  std::error_code ec;
  const auto relative = std::filesystem::relative(file, std::filesystem::current_path(), ec);
  if (!ec && !relative.empty() && !relative.string().starts_with("..")) return relative.lexically_normal().string();
  return file.lexically_normal().string();
}

}  // namespace

std::unique_ptr<Scene> Scene::loadFile(const std::filesystem::path& file, const SceneOptions& options) {
  const std::string name = displayName(file);
  if (!std::filesystem::is_regular_file(file)) throw SceneError(name + ": no such scene file");
  // Read within the limit first (the size before reading, and no further while reading): the
  // state does not exist yet.
  std::string text;
  try {
    text = readBoundedFile(file, options.limits.source_bytes, name, "a scene file");
  } catch (const std::runtime_error& e) {
    throw SceneError(e.what());
  }
  return std::unique_ptr<Scene>(new Scene(load(text, name, file, options)));
}

std::unique_ptr<Scene> Scene::loadString(std::string_view source, const std::string& name, const SceneOptions& options) {
  if (source.size() > options.limits.source_bytes)
    throw SceneError(name + ": source is " + std::to_string(source.size()) + " bytes, larger than the limit of " +
                     std::to_string(options.limits.source_bytes));
  return std::unique_ptr<Scene>(new Scene(load(source, name, {}, options)));
}

Scene::Impl::~Impl() {
  // The world first (its Lua forces release their references), then the host's other references,
  // then the state. From here on a handle sees no world and refuses to work ("the scene is
  // closed") instead of touching a destroyed one, whatever Lua code might run while the state
  // closes.
  world.reset();
  snapshots.clear();  // they share the Lua forces, which release their references now
  on_step = check = on_key = on_draw = exact = sol::object();
  for (const EventHook& h : eventHooks()) this->*h.slot = sol::object();
  pre_solve_functions = sol::table();
  on_mouse = on_control = sol::object();
  save_state = load_state = sol::object();
  handles = user_data = shape_handles = joint_handles = shape_user_data = joint_user_data = sol::table();
  should_collide = sol::object();
  world_handle = draw_handle = sol::object();
  draw = nullptr;
  host.reset();
}

Scene::Scene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Scene::~Scene() = default;

World& Scene::world() { return *impl_->world; }
const World& Scene::world() const { return *impl_->world; }
const SceneSettings& Scene::settings() const { return impl_->settings; }
void Scene::setDt(double dt) {
  if (!(dt > 0) || !std::isfinite(dt)) throw SceneError("dt must be > 0, got " + formatNumber(dt));
  impl_->settings.dt = dt;
}
const std::filesystem::path& Scene::file() const { return impl_->file; }

std::vector<std::filesystem::path> Scene::sourceFiles() const {
  std::vector<std::filesystem::path> files;
  if (!impl_->file.empty()) files.push_back(impl_->file);
  for (const auto& f : impl_->host->requiredFiles()) files.push_back(f);
  return files;
}

void Scene::step() { step(impl_->settings.dt); }

void Scene::step(double dt) {
  try {
    const Budget::Scope forces(impl_->host->budget(), Budget::Kind::Force, /*lazy=*/true);
    impl_->world->step(dt);
  } catch (const ScriptError& e) {  // a Lua force failed; the world is as before the step
    throw SceneError(e.what());
  } catch (const InputError& e) {
    throw SceneError(impl_->name + ": step: " + e.what());
  }
  noteJointBreaks(*impl_);
  const auto events_start = std::chrono::steady_clock::now();
  const double cpu_start = threadCpuSeconds();
  deliverEvents(*impl_);
  impl_->event_cpu_seconds = threadCpuSeconds() - cpu_start;
  impl_->event_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - events_start).count();
  if (defined(impl_->on_step)) call(*impl_, impl_->on_step, "OnStep", impl_->world_handle, dt);
}

bool Scene::hasCheck() const { return defined(impl_->check); }
void Scene::runCheck() {
  if (hasCheck()) call(*impl_, impl_->check, "Check", impl_->world_handle);
}
bool Scene::hasOnStep() const { return defined(impl_->on_step); }
bool Scene::hasOnKey() const { return defined(impl_->on_key); }
void Scene::onKey(const std::string& key) {
  if (hasOnKey()) call(*impl_, impl_->on_key, "OnKey", impl_->world_handle, key);
}
bool Scene::hasOnDraw() const { return defined(impl_->on_draw); }
Scene::DrawReport Scene::onDraw(OverlayDraw& draw) {
  LuaDraw& d = *impl_->draw;
  d.report = {};
  d.text_bytes = 0;
  if (!hasOnDraw()) return {};
  d.target = &draw;
  try {
    call(*impl_, impl_->on_draw, "OnDraw", impl_->draw_handle, impl_->world_handle);
  } catch (...) {
    d.target = nullptr;
    throw;
  }
  d.target = nullptr;
  return d.report;
}

bool Scene::hasExact() const { return defined(impl_->exact); }

// --- sandbox mod hooks: OnMouse, OnControl (the controls themselves: scene_controls.cpp)

bool Scene::hasOnMouse() const { return defined(impl_->on_mouse); }

bool Scene::onMouse(const MouseEvent& event) {
  if (!hasOnMouse()) return false;
  bool consumed = false;
  std::string bad;
  const auto read = [&](lua_State* L) {
    const int type = lua_type(L, -1);
    if (type == LUA_TBOOLEAN) consumed = lua_toboolean(L, -1);
    else if (type != LUA_TNIL) bad = describe(L, -1);
  };
  const auto pushEvent = [&] {
    pushMouseEvent(impl_->host->L(), event);
    return sol::stack::pop<sol::object>(impl_->host->L());
  };
  sol::object table;
  if (const auto error = impl_->host->run([&] { table = pushEvent(); }))
    throw SceneError(impl_->name + ": " + impl_->host->errorText(*error, "OnMouse"));
  callReading(*impl_, impl_->on_mouse, "OnMouse", read, impl_->world_handle, table);
  if (!bad.empty()) throw SceneError(impl_->name + ": OnMouse: must return true (the event is consumed), false or nothing, got " + bad);
  return consumed;
}

void Scene::onControl(const std::string& name) {
  if (defined(impl_->on_control)) call(*impl_, impl_->on_control, "OnControl", impl_->world_handle, name);
}

namespace {

// Exact(t)'s answer, read raw (inside ScriptHost::run): the table at the top of the stack.
std::vector<Scene::ExactState> readExact(Scene::Impl& s) {
  lua_State* L = s.host->L();
  std::vector<Scene::ExactState> states;
  const sol::object answer(L, -1);
  const auto bad = [&](const std::string& what) { throw SceneError(s.name + ": Exact: " + what); };
  if (answer.get_type() != sol::type::table) bad("must return a table {body name = {position = {x, y}, ...}}, got " + describe(answer));
  const int table = lua_gettop(L);
  lua_pushnil(L);
  while (lua_next(L, table) != 0) {
    sol::stack_object key(L, -2), value(L, -1);
    std::optional<BodyId> id;
    if (key.get_type() == sol::type::string) {
      id = s.world->findBody(std::string_view(lua_tostring(L, -2)));
      if (!id) bad("no body is named " + describe(L, -2));
    } else if (const LuaBody* b = toHandle<LuaBody>(L, -2); b && s.world->isValid(b->id)) {
      id = b->id;
    } else {
      bad("keys must be body names or bodies, got " + describe(key));
    }
    Scene::ExactState e;
    e.uid = s.world->body(*id).uid;
    try {
      const Options o(L, "Exact", sol::object(value), {"position", "velocity", "angle", "angular_velocity"});
      e.position = o.vec("position");
      if (o.has("velocity")) e.velocity = o.vec("velocity");
      if (o.has("angle")) e.angle = o.number("angle");
      if (o.has("angular_velocity")) e.angular_velocity = o.number("angular_velocity");
    } catch (const ScriptError& err) {
      throw SceneError(s.name + ": " + err.what());
    }
    states.push_back(e);
    lua_pop(L, 1);
  }
  return states;
}

}  // namespace

std::vector<Scene::ExactState> Scene::exact(double t) {
  std::vector<ExactState> states;
  if (!hasExact()) return states;
  Impl& s = *impl_;
  ++s.host->calls;
  std::optional<std::string> error;
  {
    const Budget::Scope budget(s.host->budget(), Budget::Kind::Hook);
    error = s.host->run([&] {
      lua_State* L = s.host->L();
      s.exact.push(L);
      lua_pushnumber(L, t);
      lua_call(L, 1, 1);
      states = readExact(s);
    });
    if (error) error = s.host->errorText(std::move(*error), "Exact");
  }
  if (error) throw SceneError(*error);
  std::sort(states.begin(), states.end(), [](const ExactState& a, const ExactState& b) { return a.uid < b.uid; });
  return states;
}

long Scene::luaCalls() const { return impl_->host->calls; }
double Scene::eventSeconds() const { return impl_->event_seconds; }
double Scene::eventCpuSeconds() const { return impl_->event_cpu_seconds; }

std::filesystem::path scriptsDirectory() { return dataDirectory("scripts", "RIGIDLAB_SCRIPTS"); }

}  // namespace rigidlab::lua
