// One configuration of the accuracy lab: the error pass and the timed runs (accuracy_run.h).
#include "accuracy_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include "rigidlab/lua/scene.h"

namespace rigidlab::app::accuracy {
namespace {

using Clock = std::chrono::steady_clock;

std::unique_ptr<lua::Scene> load(const Problem& problem, Integrator integrator) {
  auto scene = lua::Scene::loadFile(problem.file);
  scene->world().setIntegrator(integrator);
  return scene;
}

// Linear momentum Σ m v and angular momentum about the origin Σ (m c × v + I ω) of the dynamic bodies.
void momenta(const World& w, Vec2& p, double& l) {
  p = Vec2::Zero();
  l = 0.0;
  for (const BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    if (b.isStatic()) continue;
    p += b.mass * b.velocity;
    l += b.mass * cross(b.center, b.velocity) + b.inertia * b.angular_velocity;
  }
}

// The time in [0, h] where the cubic Hermite interpolant of an angle through (θa, ωa) at 0 and
// (θb, ωb) at h crosses 0 (θa and θb of opposite signs or one of them 0). The cubic is 4th-order
// accurate, so the crossing time does not hide RK4's order behind the interpolation's.
double crossing(double ta, double ya, double wa, double h, double yb, double wb) {
  const auto y = [&](double s) {  // s = t / h
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * ya + (s3 - 2 * s2 + s) * h * wa + (-2 * s3 + 3 * s2) * yb + (s3 - s2) * h * wb;
  };
  double lo = 0.0, hi = 1.0;  // bisection: the sign change is bracketed
  const bool rising = ya < yb;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((y(mid) < 0.0) == rising ? lo : hi) = mid;
  }
  return ta + 0.5 * (lo + hi) * h;
}

}  // namespace

double sweepDt(int k) { return 1.0 / (30.0 * std::ldexp(1.0, k)); }

long wholeSteps(double duration, double dt, const std::string& what) {
  const double n = duration / dt;
  const long steps = std::lround(n);
  if (std::abs(static_cast<double>(steps) * dt - duration) > 1e-9 * std::max(duration, dt))
    throw std::runtime_error(what + " (" + std::to_string(duration) + " s) is not a whole number of steps of " +
                             std::to_string(dt) + " s");
  return steps;
}

std::string ErrorPass::stages() const {
  std::string s = "integrate";
  if (force_evals > 0) s += lua_calls > 0 ? ", forces (Lua)" : ", forces";
  if (pairs_max > 0) s += contact_points_max > 0 ? ", pairs, contacts" : ", pairs (no contact)";
  if (impacts > 0) s += ", located impacts";
  return s;
}

ErrorPass errorPass(const Problem& problem, Integrator integrator, double dt, double duration, bool record_energy) {
  ErrorPass r;
  const long steps = wholeSteps(duration, dt, problem.name + ": duration");
  const long every = wholeSteps(problem.sample_dt, dt, problem.name + ": sample_dt");
  auto scene = load(problem, integrator);
  World& world = scene->world();

  std::vector<BodyId> dynamic;
  for (const BodyId id : world.bodyIds())
    if (!world.body(id).isStatic()) dynamic.push_back(id);

  const double e0 = problem.energyOf(world, 0.0);
  Vec2 p0;
  double l0;
  momenta(world, p0, l0);

  double sum_sq = 0.0;
  long samples = 0;
  // Least-squares sums for the energy trend: E/E0 against t.
  double st = 0, se = 0, stt = 0, ste = 0;
  long ne = 0;

  // Errors against Exact(t) at the current state; false if the state is not finite.
  // The energy error: |E/E0 − 1|, or |E − E0| / energy_scale when the problem gives a scale.
  const auto energyError = [&](double e) {
    return problem.energy_scale ? std::abs(e - e0) / *problem.energy_scale : std::abs(e / e0 - 1.0);
  };
  const auto sample = [&](double t, bool final) {
    double err = 0.0, verr = 0.0;
    if (problem.fit_energy) err = energyError(problem.energyOf(world, t));
    for (const lua::Scene::ExactState& e : problem.fit_energy ? std::vector<lua::Scene::ExactState>{} : scene->exact(t)) {
      const auto id = world.findBody(e.uid);
      if (!id) continue;
      const Body& b = world.body(*id);
      err = std::max(err, (b.position() - e.position).norm() / problem.reference_length);
      if (e.velocity) verr = std::max(verr, (b.velocity - *e.velocity).norm() / problem.reference_speed);
    }
    if (!std::isfinite(err)) err = std::numeric_limits<double>::infinity();
    r.err_linf = std::max(r.err_linf, err);
    sum_sq += err * err;
    ++samples;
    if (final) {
      r.err_final = err;
      r.vel_err_final = verr;
    }
    const double e = problem.energyOf(world, t);
    if (problem.energy && (e0 != 0.0 || problem.energy_scale)) r.energy_drift_max = std::max(r.energy_drift_max, energyError(e));
    if (e0 != 0.0) {
      const double ratio = e / e0;
      if (std::isfinite(ratio)) {
        st += t, se += ratio, stt += t * t, ste += t * ratio;
        ++ne;
      }
      if (record_energy) {
        r.energy_t.push_back(t);
        r.energy_ratio.push_back(ratio);
      }
      if (!problem.energy_scale && std::abs(e) > 1e6 * std::abs(e0) && r.status == "ok") r.status = "unstable";
    }
    if (problem.energy_scale && !(energyError(e) <= 1e6) && r.status == "ok") r.status = "unstable";
    Vec2 p;
    double l;
    momenta(world, p, l);
    r.mom_err = std::max(r.mom_err, (p - p0).norm());
    if (l0 != 0.0) r.angmom_err = std::max(r.angmom_err, std::abs(l - l0) / std::abs(l0));
  };

  // The period: the times the body's angle crosses 0, T = 2 (t_last − t_first) / (crossings − 1).
  std::optional<BodyId> period_id;
  if (problem.period)
    for (const BodyId id : dynamic)
      if (world.body(id).name == problem.period_body) period_id = id;
  if (problem.period && !period_id) throw std::runtime_error(problem.name + ": no body named " + problem.period_body);
  std::vector<double> crossings;
  double last_angle = period_id ? world.body(*period_id).angle : 0.0;
  double last_omega = period_id ? world.body(*period_id).angular_velocity : 0.0;

  sample(0.0, steps == 0);
  for (long n = 1; n <= steps; ++n) {
    const long calls = scene->luaCalls();
    scene->step(dt);
    r.lua_calls += scene->luaCalls() - calls;
    ++r.steps;
    const StepStats& s = world.stats();
    r.force_evals += s.force_evaluations;
    r.pairs_max = std::max(r.pairs_max, s.pairs);
    r.contact_points_max = std::max(r.contact_points_max, s.contact_points);
    r.impacts += s.impacts_located;
    r.integrate_ms += s.integrate_ms;
    r.broad_ms += s.broad_phase_ms;
    r.narrow_ms += s.narrow_phase_ms;
    r.solve_ms += s.solve_ms;
    r.correct_ms += s.correct_ms;
    const double t = static_cast<double>(n) * dt;
    // A state that is not finite, or a body the engine froze (made static) to contain one.
    for (const BodyId id : dynamic) {
      const Body& b = world.body(id);
      if (!isFinite(b.center) || !isFinite(b.velocity) || !std::isfinite(b.angular_velocity) || b.isStatic()) {
        r.status = "nan";
        break;
      }
    }
    if (r.status == "nan") {
      r.err_linf = r.err_final = std::numeric_limits<double>::infinity();
      r.stopped_at = t;
      break;
    }
    if (period_id) {
      const Body& b = world.body(*period_id);
      if ((last_angle < 0.0 && b.angle >= 0.0) || (last_angle > 0.0 && b.angle <= 0.0))
        crossings.push_back(crossing(t - dt, last_angle, last_omega, dt, b.angle, b.angular_velocity));
      last_angle = b.angle;
      last_omega = b.angular_velocity;
    }
    if (n % every == 0 || n == steps) sample(t, n == steps);
    if (r.status != "ok") {
      r.stopped_at = t;
      break;
    }
  }
  if (problem.period) {
    r.period_err = crossings.size() < 2 ? std::numeric_limits<double>::infinity()
                                        : std::abs(2.0 * (crossings.back() - crossings.front()) /
                                                       static_cast<double>(crossings.size() - 1) / *problem.period -
                                                   1.0);
  }
  r.err_l2 = samples > 0 ? std::sqrt(sum_sq / static_cast<double>(samples)) : 0.0;
  if (problem.energy && ne >= 2) {
    const double n = static_cast<double>(ne), den = n * stt - st * st;
    r.energy_drift_trend = den != 0.0 ? (n * ste - st * se) / den : 0.0;
  }
  if (r.status != "ok" && r.steps < steps) r.err_final = std::numeric_limits<double>::infinity();
  return r;
}

Timing timeRuns(const Problem& problem, Integrator integrator, double dt, long steps, const TimingOptions& o) {
  Timing t;
  // Runs `batch` fresh scenes (loaded untimed) of `steps` steps each; returns seconds per run.
  const auto timed = [&](int batch) {
    std::vector<std::unique_ptr<lua::Scene>> scenes;
    scenes.reserve(batch);
    for (int i = 0; i < batch; ++i) scenes.push_back(load(problem, integrator));
    const auto start = Clock::now();
    for (auto& scene : scenes)
      for (long n = 0; n < steps; ++n) scene->step(dt);
    const double s = std::chrono::duration<double>(Clock::now() - start).count();
    return s / batch;
  };

  const double warm = timed(1);  // warm-up, also the estimate of one run
  if (warm > o.single_run_above_s) {
    t.min_s = t.median_s = warm;
    t.repeats = 1;
    return t;
  }
  if (warm < o.batch_below_s)
    t.batch = static_cast<int>(std::clamp(std::ceil(o.batch_below_s / std::max(warm, 1e-7)), 1.0, 1000.0));
  // The budget counts the loading of the scenes too: for short runs that is most of the cost.
  std::vector<double> times;
  const auto begin = Clock::now();
  while (static_cast<int>(times.size()) < o.max_repeats) {
    times.push_back(timed(t.batch));
    const double spent = std::chrono::duration<double>(Clock::now() - begin).count();
    if (static_cast<int>(times.size()) >= o.min_repeats && spent > o.budget_s) break;
  }
  std::sort(times.begin(), times.end());
  const auto quantile = [&](double q) {
    const double pos = q * static_cast<double>(times.size() - 1);
    const size_t i = static_cast<size_t>(pos);
    const double f = pos - static_cast<double>(i);
    return i + 1 < times.size() ? times[i] * (1 - f) + times[i + 1] * f : times[i];
  };
  t.min_s = times.front();
  t.median_s = quantile(0.5);
  t.iqr_s = quantile(0.75) - quantile(0.25);
  t.repeats = static_cast<int>(times.size());
  return t;
}

}  // namespace rigidlab::app::accuracy
