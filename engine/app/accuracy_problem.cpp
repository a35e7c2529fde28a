// Reading a reference problem's `accuracy` table (accuracy_problem.h).
#include "accuracy_problem.h"

#include <lua5.4/lua.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "rigidlab/lua/scene.h"
#include "text_file.h"

namespace rigidlab::app::accuracy {

const char* groupName(Group g) {
  switch (g) {
    case Group::Smooth: return "smooth";
    case Group::Impact: return "impact";
    case Group::Contact: return "contact";
    case Group::Sanity: return "sanity";
    case Group::Mechanism: return "mechanism";
  }
  return "?";
}

std::optional<double> defaultOrder(const std::string& integrator) {
  if (integrator == "euler" || integrator == "semi_implicit_euler" || integrator == "implicit_euler") return 1.0;
  if (integrator == "rk4") return 4.0;
  return std::nullopt;
}

// A plain Lua state that ran the problem file once. Only the libraries a table of numbers and an
// energy function need. `require` loads the pure Lua modules of the scripts folder (elliptic, for
// the closed forms of mechanisms) into this state too; a name that is not a file there answers an
// empty table, so module-level code that only stores a module (local x = require "forces.x") runs.
class ProblemScript {
 public:
  ProblemScript(const std::string& source, const std::string& name) : L_(luaL_newstate()), name_(name) {
    if (!L_) throw std::runtime_error(name + ": cannot create a Lua state");
    const std::pair<const char*, lua_CFunction> libs[] = {
        {"_G", luaopen_base}, {LUA_MATHLIBNAME, luaopen_math}, {LUA_STRLIBNAME, luaopen_string}, {LUA_TABLIBNAME, luaopen_table}};
    for (const auto& [lib, open] : libs) {
      luaL_requiref(L_, lib, open, 1);
      lua_pop(L_, 1);
    }
    for (const char* unsafe : {"dofile", "loadfile", "load", "collectgarbage"}) {
      lua_pushnil(L_);
      lua_setglobal(L_, unsafe);
    }
    lua_pushcfunction(L_, requireModule);
    lua_setglobal(L_, "require");
    lua_pushcfunction(L_, [](lua_State*) -> int { return 0; });
    lua_setglobal(L_, "print");
    // A budget of instructions per call (the file's main chunk, each energy call), so a script that
    // never returns is an error here as it is in the scene's own state.
    lua_sethook(L_, [](lua_State* L, lua_Debug*) {
      lua_getfield(L, LUA_REGISTRYINDEX, "rigidlab.accuracy.ticks");
      const lua_Integer ticks = lua_tointeger(L, -1) + 1;
      lua_pop(L, 1);
      lua_pushinteger(L, ticks);
      lua_setfield(L, LUA_REGISTRYINDEX, "rigidlab.accuracy.ticks");
      if (ticks > kTickBudget) luaL_error(L, "ran for more than %d million instructions", static_cast<int>(kTickBudget));
    }, LUA_MASKCOUNT, 1000000);
    resetBudget();
    if (luaL_loadbuffer(L_, source.data(), source.size(), ("@" + name).c_str()) != LUA_OK ||
        lua_pcall(L_, 0, 0, 0) != LUA_OK)
      throw std::runtime_error(popError());
  }
  static constexpr lua_Integer kTickBudget = 100;  // × 1e6 instructions (about 0.3 s)

  // require(name): scripts/<name with dots as folders>.lua, run once and kept.
  static int requireModule(lua_State* L) {
    const std::string name = luaL_checkstring(L, 1);
    lua_getfield(L, LUA_REGISTRYINDEX, "rigidlab.accuracy.modules");
    if (lua_isnil(L, -1)) {
      lua_pop(L, 1);
      lua_newtable(L);
      lua_pushvalue(L, -1);
      lua_setfield(L, LUA_REGISTRYINDEX, "rigidlab.accuracy.modules");
    }
    lua_getfield(L, -1, name.c_str());
    if (!lua_isnil(L, -1)) return 1;
    lua_pop(L, 1);
    const bool plain = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
    }) && name.find("..") == std::string::npos && name.front() != '.';
    std::string relative = name;
    std::replace(relative.begin(), relative.end(), '.', '/');
    const std::filesystem::path file = lua::scriptsDirectory() / (relative + ".lua");
    std::error_code error;
    if (!plain || !std::filesystem::is_regular_file(file, error)) {
      lua_newtable(L);
      return 1;
    }
    std::string source;
    try {
      source = readFile(file, lua::ScriptLimits{}.source_bytes, "a module");
    } catch (const std::exception& e) {
      return luaL_error(L, "%s", e.what());
    }
    if (luaL_loadbuffer(L, source.data(), source.size(), ("@" + file.string()).c_str()) != LUA_OK) return lua_error(L);
    lua_call(L, 0, 1);
    if (lua_isnil(L, -1)) {
      lua_pop(L, 1);
      lua_newtable(L);
    }
    lua_pushvalue(L, -1);
    lua_setfield(L, -3, name.c_str());
    return 1;
  }

  void resetBudget() {
    lua_pushinteger(L_, 0);
    lua_setfield(L_, LUA_REGISTRYINDEX, "rigidlab.accuracy.ticks");
  }
  ~ProblemScript() { lua_close(L_); }
  ProblemScript(const ProblemScript&) = delete;
  ProblemScript& operator=(const ProblemScript&) = delete;

  lua_State* L() const { return L_; }
  const std::string& name() const { return name_; }

  std::string popError() {
    std::string message = lua_type(L_, -1) == LUA_TSTRING ? lua_tostring(L_, -1) : "error";
    lua_pop(L_, 1);
    return message;
  }

  // accuracy.energy(bodies, t); bodies[name] = {x, y, vx, vy, angle, omega, mass, inertia}.
  bool hasEnergy() {
    pushAccuracyField("energy");
    const bool is_function = lua_type(L_, -1) == LUA_TFUNCTION;
    lua_pop(L_, 1);
    return is_function;
  }

  double energy(const World& world, double t) {
    resetBudget();
    pushAccuracyField("energy");
    lua_createtable(L_, 0, 4);
    for (const BodyId id : world.bodyIds()) {
      const Body& b = world.body(id);
      if (b.name.empty()) continue;
      lua_createtable(L_, 0, 8);
      const auto set = [&](const char* k, double v) {
        lua_pushnumber(L_, v);
        lua_setfield(L_, -2, k);
      };
      set("x", b.position().x());
      set("y", b.position().y());
      set("vx", b.velocity.x());
      set("vy", b.velocity.y());
      set("angle", b.angle);
      set("omega", b.angular_velocity);
      set("mass", b.mass);
      set("inertia", b.inertia);
      lua_setfield(L_, -2, b.name.c_str());
    }
    lua_pushnumber(L_, t);
    if (lua_pcall(L_, 2, 1, 0) != LUA_OK) throw std::runtime_error(name_ + ": accuracy.energy: " + popError());
    int is_number = 0;
    const double e = lua_tonumberx(L_, -1, &is_number);
    lua_pop(L_, 1);
    if (!is_number) throw std::runtime_error(name_ + ": accuracy.energy must return a number");
    return e;
  }

  // Pushes accuracy[field] (nil if absent).
  void pushAccuracyField(const char* field) {
    lua_getglobal(L_, "accuracy");
    if (lua_type(L_, -1) != LUA_TTABLE) {
      lua_pop(L_, 1);
      lua_pushnil(L_);
      return;
    }
    lua_getfield(L_, -1, field);
    lua_remove(L_, -2);
  }

 private:
  lua_State* L_;
  std::string name_;
};

namespace {

// Typed reads of accuracy.<field> with messages naming the field and the bad value.
class Fields {
 public:
  Fields(ProblemScript& s, std::string file) : s_(s), L_(s.L()), file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw std::runtime_error(file_ + ": accuracy." + field + " " + what);
  }

  std::optional<double> number(const char* field) {
    s_.pushAccuracyField(field);
    std::optional<double> v;
    if (lua_type(L_, -1) == LUA_TNUMBER) {
      v = lua_tonumber(L_, -1);
    } else if (lua_type(L_, -1) != LUA_TNIL) {
      const std::string type = luaL_typename(L_, -1);
      lua_pop(L_, 1);
      fail(field, "must be a number, got a " + type);
    }
    lua_pop(L_, 1);
    if (v && !std::isfinite(*v)) fail(field, "must be finite");
    return v;
  }

  double positive(const char* field, std::optional<double> fallback) {
    const auto v = number(field);
    if (!v && !fallback) fail(field, "is required (a number > 0)");
    const double x = v.value_or(fallback.value_or(0.0));
    if (!(x > 0)) fail(field, "must be > 0, got " + std::to_string(x));
    return x;
  }

  std::optional<std::string> string(const char* field) {
    s_.pushAccuracyField(field);
    std::optional<std::string> v;
    if (lua_type(L_, -1) == LUA_TSTRING) {
      v = lua_tostring(L_, -1);
    } else if (lua_type(L_, -1) != LUA_TNIL) {
      lua_pop(L_, 1);
      fail(field, "must be a string");
    }
    lua_pop(L_, 1);
    return v;
  }

  std::vector<std::string> stringList(const char* field) {
    std::vector<std::string> out;
    s_.pushAccuracyField(field);
    if (lua_type(L_, -1) == LUA_TTABLE) {
      const lua_Integer n = luaL_len(L_, -1);
      for (lua_Integer i = 1; i <= n; ++i) {
        lua_geti(L_, -1, i);
        if (lua_type(L_, -1) != LUA_TSTRING) {
          lua_pop(L_, 2);
          fail(field, "must be a list of strings");
        }
        out.emplace_back(lua_tostring(L_, -1));
        lua_pop(L_, 1);
      }
    } else if (lua_type(L_, -1) != LUA_TNIL) {
      lua_pop(L_, 1);
      fail(field, "must be a list of strings");
    }
    lua_pop(L_, 1);
    return out;
  }

  // accuracy.expected_order = {rk4 = 4, euler = "exact", ...}
  std::map<std::string, Expected> expectations() {
    std::map<std::string, Expected> out;
    s_.pushAccuracyField("expected_order");
    if (lua_type(L_, -1) == LUA_TTABLE) {
      lua_pushnil(L_);
      while (lua_next(L_, -2) != 0) {
        if (lua_type(L_, -2) != LUA_TSTRING) {
          lua_pop(L_, 3);
          fail("expected_order", "keys must be integrator names");
        }
        const std::string key = lua_tostring(L_, -2);
        Expected e;
        e.known = true;
        if (lua_type(L_, -1) == LUA_TNUMBER) {
          e.order = lua_tonumber(L_, -1);
        } else if (lua_type(L_, -1) == LUA_TSTRING && std::string(lua_tostring(L_, -1)) == "exact") {
          e.exact = true;
        } else if (lua_type(L_, -1) == LUA_TSTRING && std::string(lua_tostring(L_, -1)) == "none") {
          e.known = false;  // reported, not expected (its asymptotic range lies beyond the sweep)
        } else {
          lua_pop(L_, 3);
          fail("expected_order." + key, "must be a number, \"exact\" or \"none\"");
        }
        out[key] = e;
        lua_pop(L_, 1);
      }
    } else if (lua_type(L_, -1) != LUA_TNIL) {
      lua_pop(L_, 1);
      fail("expected_order", "must be a table {integrator = order}");
    }
    lua_pop(L_, 1);
    return out;
  }

 private:
  ProblemScript& s_;
  lua_State* L_;
  std::string file_;
};

}  // namespace

Expected Problem::expectedFor(const std::string& integrator) const {
  if (const auto it = expected.find(integrator); it != expected.end()) return it->second;
  Expected e;
  if (const auto order = defaultOrder(integrator)) {
    e.known = true;
    e.order = *order;
  }
  return e;
}

bool Problem::hasCustomEnergy() const { return script && script->hasEnergy(); }

double Problem::energyOf(const World& world, double t) const {
  if (hasCustomEnergy()) return script->energy(world, t);
  return world.kineticEnergy() + world.potentialEnergy();
}

Problem loadProblem(const std::filesystem::path& file) {
  Problem p;
  p.file = file;
  p.name = file.stem().string();
  const std::string shown = file.lexically_normal().string();
  // The scene itself first: its errors (syntax, bad options, PopulateWorld) are reported by the
  // scene loader, under the scene's own limits.
  try {
    lua::Scene::loadFile(file);
  } catch (const lua::SceneError& e) {
    throw std::runtime_error(e.what());
  }
  p.script = std::make_shared<ProblemScript>(readFile(file, lua::ScriptLimits{}.source_bytes, "a scene file"), shown);
  lua_State* L = p.script->L();
  lua_getglobal(L, "accuracy");
  const bool has_table = lua_type(L, -1) == LUA_TTABLE;
  lua_pop(L, 1);
  if (!has_table)
    throw std::runtime_error(shown + ": no `accuracy` table (a reference problem needs accuracy = {t_end = ..., ...}; "
                                     "see scripts/accuracy/README.md)");
  lua_getglobal(L, "Exact");
  const bool has_exact = lua_type(L, -1) == LUA_TFUNCTION;
  lua_pop(L, 1);

  // The title as the scene table gives it (a string field only; the Scene validates the rest).
  lua_getglobal(L, "scene");
  if (lua_type(L, -1) == LUA_TTABLE) {
    lua_getfield(L, -1, "title");
    if (lua_type(L, -1) == LUA_TSTRING) p.title = lua_tostring(L, -1);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  if (p.title.empty()) p.title = p.name;

  Fields f(*p.script, shown);
  p.t_end = f.positive("t_end", std::nullopt);
  p.sample_dt = f.positive("sample_dt", 0.1);
  p.reference_length = f.positive("reference_length", 1.0);
  p.reference_speed = f.positive("reference_speed", 1.0);
  const double samples = p.t_end / p.sample_dt;
  if (std::abs(samples - std::round(samples)) > 1e-9 * samples)
    f.fail("t_end", "must be a multiple of sample_dt (" + std::to_string(p.sample_dt) + " s)");
  if (const auto g = f.string("group")) {
    if (*g == "smooth") p.group = Group::Smooth;
    else if (*g == "impact") p.group = Group::Impact;
    else if (*g == "contact") p.group = Group::Contact;
    else if (*g == "sanity") p.group = Group::Sanity;
    else if (*g == "mechanism") p.group = Group::Mechanism;
    else f.fail("group", "must be one of smooth, impact, contact, sanity, mechanism, got \"" + *g + "\"");
  }
  if (const auto fit = f.string("fit")) {
    if (*fit != "position" && *fit != "energy") f.fail("fit", "must be \"position\" or \"energy\", got \"" + *fit + "\"");
    p.fit_energy = *fit == "energy";
  }
  if (!has_exact && !p.fit_energy)
    throw std::runtime_error(shown + ": no Exact(t) function (see scripts/accuracy/README.md)");
  if (const auto e = f.number("energy_scale")) {
    if (!(*e > 0)) f.fail("energy_scale", "must be > 0");
    p.energy_scale = *e;
  }
  if (p.fit_energy && !p.energy_scale) f.fail("energy_scale", "is required with fit = \"energy\" (the energy errors are divided by it) [J]");
  if (const auto a = f.number("asymptotic_below")) {
    if (!(*a > 0)) f.fail("asymptotic_below", "must be > 0");
    p.asymptotic_below = *a;
  }
  if (const auto t = f.number("order_tolerance")) {
    if (!(*t > 0)) f.fail("order_tolerance", "must be > 0");
    p.order_tolerance = *t;
  }
  static const std::set<std::string> kMetrics = {"energy", "momentum", "angmom", "velocity", "pos_linf", "pos_final"};
  for (const std::string& m : f.stringList("metrics")) {
    if (!kMetrics.contains(m)) f.fail("metrics", "has an unknown metric \"" + m + "\" (energy, momentum, angmom, velocity)");
    p.energy |= m == "energy";
    p.momentum |= m == "momentum";
    p.angmom |= m == "angmom";
    p.velocity |= m == "velocity";
  }
  p.expected = f.expectations();
  if (const auto l = f.number("long_run")) {
    if (!(*l > 0)) f.fail("long_run", "must be > 0");
    p.long_run = *l;
  }
  if (const auto t = f.number("period")) {
    if (!(*t > 0)) f.fail("period", "must be > 0");
    p.period = *t;
    p.period_body = f.string("period_body").value_or("");
    if (p.period_body.empty()) f.fail("period_body", "must name the body whose period `period` is");
  }
  p.note = f.string("note").value_or("");
  return p;
}

std::vector<std::filesystem::path> problemFiles(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".lua") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::filesystem::path problemDirectory() { return lua::scriptsDirectory() / "accuracy"; }

}  // namespace rigidlab::app::accuracy
