// Loading a scene and running its hooks (origin.md §3 and §11: PopulateWorld builds the model).
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "api_names.h"
#include "bindings.h"
#include "lua_args.h"
#include "rigidlab/error.h"

namespace rigidlab::lua {
namespace {

using api::kSceneOptions;

// Records the line where the main chunk assigns the global `scene`, so errors in the settings
// table can point at it: a temporary __newindex on the globals, removed after the chunk ran.
int recordSceneLine(lua_State* L) {
  if (lua_type(L, 2) == LUA_TSTRING && std::string_view(lua_tostring(L, 2)) == "scene") {
    const std::string at = where(L, 1);
    lua_pushlstring(L, at.data(), at.size());
    lua_setfield(L, LUA_REGISTRYINDEX, "rigidlab.scene_line");
  }
  lua_rawset(L, 1);
  return 0;
}

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

// Reads the optional global `scene` table. Errors read "<file>:<line>: scene: dt must be > 0, got 0".
void readSettings(Scene::Impl& s, WorldDef& def, const std::string& at) {
  lua_State* L = s.host->L();
  const sol::object table = s.host->lua().globals().raw_get<sol::object>("scene");
  s.settings.title = std::filesystem::path(s.name).stem().string();
  if (table.get_type() == sol::type::lua_nil) return;
  try {
    if (table.get_type() != sol::type::table) fail(L, "scene", "must be a table of settings, got " + describe(table));
    const Options o(L, "scene", table, kSceneOptions);
    if (o.has("memory_limit")) {
      const double cap = static_cast<double>(s.host->limits().memory_bytes >> 20);
      s.host->lowerMemoryLimit(static_cast<size_t>(o.inRange("memory_limit", 1, cap) * double(1 << 20)));
    }
    s.settings.title = o.string("title", s.settings.title);
    def.gravity = o.vec("gravity", def.gravity);
    s.settings.dt = o.positive("dt", s.settings.dt);
    s.settings.duration = o.nonNegative("duration", s.settings.duration);
    if (o.has("integrator")) {
      const std::string name = o.string("integrator");
      const auto integrator = parseIntegrator(name);
      if (!integrator) o.fail("integrator", "must be one of " + integratorNames() + ", got \"" + name + "\"");
      def.integrator = *integrator;
    }
    if (o.has("solver")) {
      const std::string name = o.string("solver");
      const auto solver = parseContactSolver(name);
      if (!solver) o.fail("solver", "must be one of " + contactSolverNames() + ", got \"" + name + "\"");
      def.contact_solver = *solver;
    }
    def.iterations = o.integer("iterations", 1, 10000, def.iterations);
    def.substeps = o.integer("substeps", 1, 64, def.substeps);
    def.sleeping = o.boolean("sleeping", def.sleeping);
    if (o.has("camera")) {
      const Options c(L, "scene.camera", o.get("camera"), {"center", "height"});
      if (c.has("center")) s.settings.camera_center = c.vec("center");
      if (c.has("height")) s.settings.camera_height = c.positive("height");
    }
  } catch (const ScriptError& e) {
    throw SceneError((at.empty() ? s.name + ": " : at) + e.what());
  }
}

sol::protected_function hook(Scene::Impl& s, const char* name) {
  const sol::object f = s.host->lua().globals().raw_get<sol::object>(name);
  if (f.get_type() == sol::type::lua_nil) return {};
  if (f.get_type() != sol::type::function)
    throw SceneError(s.name + ": " + name + " must be a function, got " + describe(f));
  return s.host->protect(f);
}

bool defined(const sol::protected_function& f) { return f.valid() && f.get_type() == sol::type::function; }

// Runs a hook; a Lua error becomes SceneError("<file>:<line>: <hook>: <message>").
template <typename... Args>
void call(Scene::Impl& s, const sol::protected_function& f, std::string_view name, Args&&... args) {
  ++s.host->calls;
  std::string error;
  {
    const Budget::Scope budget(s.host->budget(), Budget::Kind::Hook);
    auto result = f(std::forward<Args>(args)...);
    if (!result.valid()) error = s.host->errorText(result, name);
  }
  if (!error.empty()) throw SceneError(error);
}

std::unique_ptr<Scene::Impl> load(std::string_view source, const std::string& name, const std::filesystem::path& file,
                                  const SceneOptions& options) {
  auto s = std::make_unique<Scene::Impl>();
  s->name = name;
  s->file = file;
  const std::filesystem::path dir = file.empty() ? std::filesystem::current_path() : file.parent_path();
  s->host = std::make_unique<ScriptHost>(options, dir.empty() ? std::filesystem::path(".") : dir);
  sol::state& lua = s->host->lua();
  registerBodyType(lua);
  registerWorldType(lua);
  registerDrawType(lua);
  s->handles = lua.create_table();

  sol::protected_function chunk = s->host->compile(source, name);
  lua_State* L = s->host->L();
  lua_pushglobaltable(L);
  lua_createtable(L, 0, 1);
  lua_pushcfunction(L, guarded<recordSceneLine>);
  lua_setfield(L, -2, "__newindex");
  lua_setmetatable(L, -2);
  lua_pop(L, 1);
  ++s->host->calls;
  std::string chunk_error;
  {
    const Budget::Scope budget(s->host->budget(), Budget::Kind::Hook);
    auto ran = chunk();
    if (!ran.valid()) chunk_error = s->host->errorText(ran, "");
  }
  lua_pushglobaltable(L);
  lua_pushnil(L);
  lua_setmetatable(L, -2);
  lua_pop(L, 1);
  if (!chunk_error.empty()) {
    if (!chunk_error.starts_with(name)) chunk_error = name + ": " + chunk_error;
    throw SceneError(chunk_error);
  }
  lua_getfield(L, LUA_REGISTRYINDEX, "rigidlab.scene_line");
  const std::string scene_line = sceneStatementLine(source, lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "");
  lua_pop(L, 1);

  WorldDef def;
  readSettings(*s, def, scene_line);
  try {
    s->world = std::make_unique<World>(def);
  } catch (const InputError& e) {
    throw SceneError(name + ": scene: " + e.what());
  }
  s->world_handle = sol::make_object(s->host->L(), LuaWorld{s.get()});
  s->draw_handle = sol::make_object(s->host->L(), LuaDraw{});

  const sol::protected_function populate = hook(*s, "PopulateWorld");
  if (!defined(populate))
    throw SceneError(name + ": PopulateWorld is not defined (a scene must define function PopulateWorld(world))");
  s->on_step = hook(*s, "OnStep");
  s->check = hook(*s, "Check");
  s->on_key = hook(*s, "OnKey");
  s->on_draw = hook(*s, "OnDraw");
  s->exact = hook(*s, "Exact");
  call(*s, populate, "PopulateWorld", s->world_handle);
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
  // Read with a host-independent limit first: the state does not exist yet.
  ScriptLimits limits = options.limits;
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (!ec && size > limits.source_bytes)
    throw SceneError(name + ": file is " + std::to_string(size) + " bytes, larger than the limit of " +
                     std::to_string(limits.source_bytes));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(name + ": cannot read the file");
  std::ostringstream text;
  text << in.rdbuf();
  return std::unique_ptr<Scene>(new Scene(load(text.str(), name, file, options)));
}

std::unique_ptr<Scene> Scene::loadString(std::string_view source, const std::string& name, const SceneOptions& options) {
  if (source.size() > options.limits.source_bytes)
    throw SceneError(name + ": source is " + std::to_string(source.size()) + " bytes, larger than the limit of " +
                     std::to_string(options.limits.source_bytes));
  return std::unique_ptr<Scene>(new Scene(load(source, name, {}, options)));
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
void Scene::onDraw(OverlayDraw& draw) {
  if (!hasOnDraw()) return;
  LuaDraw& d = impl_->draw_handle.as<LuaDraw&>();
  d.target = &draw;
  try {
    call(*impl_, impl_->on_draw, "OnDraw", impl_->draw_handle);
  } catch (...) {
    d.target = nullptr;
    throw;
  }
  d.target = nullptr;
}

bool Scene::hasExact() const { return defined(impl_->exact); }

std::vector<Scene::ExactState> Scene::exact(double t) {
  std::vector<ExactState> states;
  if (!hasExact()) return states;
  Impl& s = *impl_;
  ++s.host->calls;
  const Budget::Scope budget(s.host->budget(), Budget::Kind::Hook);
  auto result = s.exact(t);
  if (!result.valid()) throw SceneError(s.host->errorText(result, "Exact"));
  lua_State* L = s.host->L();
  const sol::object answer = result;
  const auto bad = [&](const std::string& what) { throw SceneError(s.name + ": Exact: " + what); };
  if (answer.get_type() != sol::type::table) bad("must return a table {body name = {position = {x, y}, ...}}, got " + describe(answer));
  answer.push(L);
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    sol::stack_object key(L, -2), value(L, -1);
    std::optional<BodyId> id;
    if (key.get_type() == sol::type::string) {
      id = s.world->findBody(std::string_view(key.as<std::string>()));
      if (!id) {
        const std::string name = key.as<std::string>();
        lua_pop(L, 3);
        bad("no body is named \"" + name + "\"");
      }
    } else if (key.is<LuaBody>() && s.world->isValid(key.as<const LuaBody&>().id)) {
      id = key.as<const LuaBody&>().id;
    } else {
      const std::string k = describe(key);
      lua_pop(L, 3);
      bad("keys must be body names or bodies, got " + k);
    }
    ExactState e;
    e.uid = s.world->body(*id).uid;
    try {
      const Options o(L, "Exact", sol::object(value), {"position", "velocity", "angle", "angular_velocity"});
      e.position = o.vec("position");
      if (o.has("velocity")) e.velocity = o.vec("velocity");
      if (o.has("angle")) e.angle = o.number("angle");
      if (o.has("angular_velocity")) e.angular_velocity = o.number("angular_velocity");
    } catch (const ScriptError& err) {
      lua_pop(L, 3);
      throw SceneError(s.name + ": " + err.what());
    }
    states.push_back(e);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  std::sort(states.begin(), states.end(), [](const ExactState& a, const ExactState& b) { return a.uid < b.uid; });
  return states;
}

long Scene::luaCalls() const { return impl_->host->calls; }

std::filesystem::path scriptsDirectory() {
  if (const char* env = std::getenv("RIGIDLAB_SCRIPTS"); env && *env) return env;
  return RIGIDLAB_SCRIPTS_DIR;
}

}  // namespace rigidlab::lua
