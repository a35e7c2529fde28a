// Stage 4 of the step: the soft step (WorldDef::contact_solver = SoftStep, and the auto solver's
// choice for islands of many contact points).
// E. Catto, "Solver2D" (2024) and Box2D v3's solver: sub-stepping with soft contact constraints
// and relaxation. Why: sequential impulses with a separate position pass (contact_solver.cpp,
// position_correction.cpp) cannot carry the weight of a hundred rows of boxes to the ground within
// one step, so tall piles sink and spread (a pyramid of base 100 collapses within 5 s at 10
// iterations, measured); cutting the step into sub-steps, each of which applies its share of
// gravity and solves the contacts right after, makes each sub-step's problem small and lets the
// solver see the positions move.
//
// How it fits the pipeline. Integration has already moved every body by the step's forces (RK4 by
// default), and the contacts were found at those positions. Bodies that take part in a contact are
// put back at the start of the step; their velocity change from the integrator, Δv, is handed out
// in n equal kicks (Δv/n per sub-step). Each sub-step of h = dt/n then:
//   1. kick:       v += Δv/n, plus the warm start: each point's impulse of the previous sub-step
//                  (or the previous step)
//   2. solve:      soft contact impulses with a push out of overlap
//   3. move:       c += h v, θ += h ω
//   4. relax:      the same without the push, so that the push moves positions but leaves no
//                  velocity behind (no bounce from resolving an overlap)
// and after the last sub-step, restitution. Bodies that no impulse touched keep the integrator's
// result exactly, so free flight near a surface is as accurate as free flight anywhere.
//
// Separation without collision detection: the normal n is held fixed and the contact anchors r_A,
// r_B (from the centres at detection) turn with their bodies:
//   s = s₀ + (Δc_B + q_B r_B − Δc_A − q_A r_A)·n − (r_B − r_A)·n        (Box2D v3 contact_solver.c)
// where Δc, q are the displacement and rotation since detection.
//
// Soft constraint (Catto, "Soft Step", GDC 2011; Solver2D): a contact behaves like a spring of
// frequency f and damping ratio ζ integrated with the implicit sub-step h. With ω = 2πf,
//   a₁ = 2ζ + hω,  a₂ = hω a₁,  a₃ = 1/(1 + a₂),  bias rate β = ω/a₁
// and for each point the complementarity problem
//   w = v_n + b + γ P ≥ 0,  P ≥ 0,  w·P = 0
// with b = β s and γ = K/a₂ (K = 1/m_n) while overlapping (s ≤ 0) in the solve; b = s/h, γ = 0
// for a gap (speculative: the points may close it in this sub-step, not more); b = γ = 0 in the
// relax pass. One point's update is λ = −w/(K + γ); written with Box2D's mass and impulse scales
// a₂a₃ and a₃ it is λ = −m_n (a₂a₃ v_n + a₂a₃ β s) − a₃ P. The push −β s is capped at
// WorldDef::contact_push_speed; contacts with a static or sleeping body are twice as stiff.
//
// Layout: contacts are coloured so that no two of a colour move the same body, and solved four at
// a time (SoftLanes): each stage of the solve runs over the four lanes, whose dependency chains
// are independent, so the processor overlaps them instead of waiting on one chain of loads, a
// division and stores per contact.
//
// Stiffness and sub-steps (measured on the bench scenes, see docs/performance.md): the contacts
// are springs, so a column of boxes buckles if they are too soft (a 20-box stack with boxes
// staggered by 1 cm topples at 30 Hz and stands from about 55 Hz), and with one pass per sub-step
// the iteration stops converging once f·h exceeds about 1/8 (pyramids creep sideways). Hence the
// defaults 60 Hz and 8 sub-steps, and the hertz is capped at 1/8 of the sub-step rate as in Box2D
// v3.2.
#include "rigidlab/portable_math.h"
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "joint_solver.h"
#include "softness.h"
#include "stages.h"
#include "task_pool.h"
#include "world_impl.h"

namespace rigidlab {

// The soft step's scratch (WorldImpl::soft_step holds it, opaque to the other stages). Nothing in
// it is simulation state: every field is written before it is read in each step, except the
// colouring kept between steps (graph_*, slot, source, color_first, lanes' serial flags), which is
// a cache: a function of this step's contacts and moving bodies (sameGraph), so a copy of the world
// (World::snapshot), which starts without this scratch, colours again and gets the same groups
// (RIGIDLAB_VERIFY_CACHES builds check it).
struct SoftStepScratch {
  std::vector<SoftBody> bodies;
  std::vector<SoftLanes> lanes;
  std::vector<SoftTally> tally;      // per lane of lanes
  std::vector<SoftTotals> totals;    // per group of lanes
  std::vector<SoftSurfaceLanes> surfaces;  // per group of lanes when some has surface effects, else empty
  std::vector<uint32_t> source;      // per lane: index into contacts, or UINT32_MAX if empty
  std::vector<uint32_t> slot;        // per soft contact: its lane (group · L + lane)
  std::vector<uint32_t> colors_used; // per slot: colours of the contacts that move the body
  std::vector<uint8_t> color;        // per soft contact
  std::vector<uint32_t> color_order; // the soft contacts in the order they are coloured
  std::vector<uint8_t> color_bucket; // per soft contact: its place in that order (hash bucket)
  std::vector<uint32_t> color_first; // per colour, then the serial groups, then the end: first group
  std::vector<SoftKick> kick;        // per slot: velocity the step's forces add per sub-step
  std::vector<SoftKick> warm;        // per slot: the next sub-step's warm start
  std::vector<double> angle;         // per slot: angle minus the angle at detection
  std::vector<char> moved;           // per slot: 1 in contact and awake, 2 if also pushed
  std::vector<uint32_t> list;        // the slots with moved ≠ 0
  std::vector<JointBodies> joint_bodies;  // per entry of WorldImpl::soft_joints: its bodies' SoftBody
  // What the last colouring was made from (sameGraph): each soft contact's bodies, and moved;
  // graph_valid is false until the first colouring.
  struct GraphPair {
    uint32_t a, b;
  };
  std::vector<GraphPair> graph_pairs;
  std::vector<char> graph_moved;
  bool graph_valid = false;
};

namespace {

constexpr int L = kSoftLanes;

// A contact's softness as the passes use it. There are two (SoftLanes::stiff picks one), so the
// contacts store a flag rather than these four numbers each: the lanes are streamed from memory in
// every pass, 4 MB of them for a pile of 5 000 boxes.
struct Level {
  double bias_rate;   // β
  double bias_floor;  // the push −β s is at most WorldDef::contact_push_speed
  double compliance;  // γ/K = 1/a₂
  double mass_scale;  // K/(K + γ) = a₂a₃
};

Level levelOf(const Softness& s, double push_speed) {
  return {s.bias_rate, -push_speed / s.mass_scale, s.impulse_scale / s.mass_scale, s.mass_scale};
}

// A contact point's anchors: the point from each centre at detection [m].
struct Anchor {
  double rax, ray, rbx, rby;
};

inline Anchor anchorOf(const SoftLanes& c, int i, int l) { return {c.rax[i][l], c.ray[i][l], c.rbx[i][l], c.rby[i][l]}; }

// The impulse (px, py) at a point: −P on A, +P on B.
inline void apply(SoftBody& a, SoftBody& b, const Anchor& r, double px, double py) {
  a.vx -= a.im * px;
  a.vy -= a.im * py;
  a.w -= a.ii * (r.rax * py - r.ray * px);
  b.vx += b.im * px;
  b.vy += b.im * py;
  b.w += b.ii * (r.rbx * py - r.rby * px);
}

// ((v_B + ω_B × r_B) − (v_A + ω_A × r_A))·d
inline double relative(const SoftBody& a, const SoftBody& b, const Anchor& r, double dx, double dy) {
  const double rvx = b.vx - b.w * r.rby - a.vx + a.w * r.ray;
  const double rvy = b.vy + b.w * r.rbx - a.vy - a.w * r.rax;
  return rvx * dx + rvy * dy;
}

// Current separation of a point: the anchors' displacement since detection along the fixed normal.
inline double separation(const SoftBody& a, const SoftBody& b, const Anchor& r, double base, double nx, double ny) {
  const double sx = b.dx - a.dx + (b.qc * r.rbx - b.qs * r.rby) - (a.qc * r.rax - a.qs * r.ray);
  const double sy = b.dy - a.dy + (b.qs * r.rbx + b.qc * r.rby) - (a.qs * r.rax + a.qc * r.ray);
  return base + sx * nx + sy * ny;
}

// What a pass does besides the solve: both passes record impact speeds for restitution (the normal
// velocity of a point before the first solve that gives it an impulse); the relax pass adds the
// final impulses to the next sub-step's warm start and to the step's totals.
struct PassContext {
  double inv_h;
  int substep;
  const Level* levels;           // [0] soft, [1] stiff (a static or sleeping body)
  SoftTally* tallies;            // of this group's lanes
  SoftTotals* totals;            // of this group
  std::vector<SoftKick>* warm;   // relax pass, not the last sub-step: the next warm start
};

// The warm start of the next sub-step: the velocity change the lane's final impulses cause, added
// up per body and applied with the next kick (velocity changes add, so this is the same as applying
// the impulses again at the start of the next sub-step, without another pass).
inline void addWarmStart(const SoftBody& a, const SoftBody& b, const SoftLanes& c, int l, SoftKick& wa, SoftKick& wb) {
  const double nx = c.nx[l], ny = c.ny[l], tx = ny, ty = -nx;
  for (int i = 0; i < c.count[l]; ++i) {
    const double px = c.pn[i][l] * nx + c.pt[i][l] * tx, py = c.pn[i][l] * ny + c.pt[i][l] * ty;
    wa.vx -= a.im * px;
    wa.vy -= a.im * py;
    wa.w -= a.ii * (c.rax[i][l] * py - c.ray[i][l] * px);
    wb.vx += b.im * px;
    wb.vy += b.im * py;
    wb.w += b.ii * (c.rbx[i][l] * py - c.rby[i][l] * px);
  }
}

// One pass over the contact in lane l, which has N points: normal impulses first, then friction
// against the new normal impulses (Box2D v3's order: the normal impulse is this sub-step's load,
// which friction should see). kSoft: the soft solve with the push; otherwise the rigid relax pass.
// Everything is read into locals first (N is a constant, so they live in registers): the pass is
// bound by instructions, not memory (callgrind: 660 instructions per contact and pass when it
// worked on the lane arrays in place, reloading them after every store).
template <bool kSoft, int N>
inline void solveContact(std::vector<SoftBody>& bodies, SoftLanes& c, int l, const PassContext& ctx, SoftSurfaceLanes* surface) {
  SoftBody a = bodies[c.a[l]], b = bodies[c.b[l]];
  const double nx = c.nx[l], ny = c.ny[l];
  Anchor r[N];
  double pn[N], vn[N], bias[N], g[N], k[N], inv_m[N];
  for (int i = 0; i < N; ++i) {
    r[i] = anchorOf(c, i, l);
    pn[i] = c.pn[i][l];
    k[i] = c.k[i][l];
    // A gap (s > 0) may close in this sub-step, not more (speculative); an overlap is pushed
    // apart by the soft pass. Selected without branches (see below).
    const double s = separation(a, b, r[i], c.base[i][l], nx, ny);
    const bool gap = s > 0.0;
    const Level& lv = ctx.levels[c.stiff[l] != 0];
    const double push = kSoft ? std::max(lv.bias_rate * s, lv.bias_floor) : 0.0;
    bias[i] = gap ? s * ctx.inv_h : push;
    g[i] = gap || !kSoft ? 0.0 : k[i] * lv.compliance;
    inv_m[i] = gap || !kSoft ? c.inv_k[i][l] : c.inv_k[i][l] * lv.mass_scale;  // 1/(K + γ)
    vn[i] = relative(a, b, r[i], nx, ny);
  }
  if (N == 2 && c.block[l]) {
    // The normal impulses of both points together, as a 2×2 linear complementarity problem (as
    // contact_solver.cpp's block solver, with the compliances on the diagonal): find P ≥ 0 with
    // w = (K + diag γ) P + q ≥ 0, w·P = 0, trying both points pushing, one, the other, none.
    // Solving the points one after the other instead leaves the first with a residual in every
    // pass, which turns the bodies: pyramids walk sideways (measured). All four cases are computed
    // and the first that fits is selected without branches: near rest the fitting case changes
    // from pass to pass, and mispredicted branches cost more than the arithmetic (relax passes of
    // a 100-row pyramid: 6.7 → 5.6 ms per step, measured).
    const double k12 = c.k12[l], p1 = pn[0], p2 = pn[N - 1];
    const double q1 = vn[0] + bias[0] - (k[0] * p1 + k12 * p2);
    const double q2 = vn[N - 1] + bias[N - 1] - (k12 * p1 + k[N - 1] * p2);
    const double m11 = k[0] + g[0], m22 = k[N - 1] + g[N - 1];
    const double inv_det = kSoft ? 1.0 / (m11 * m22 - k12 * k12) : c.inv_det[l];
    const double both1 = (k12 * q2 - m22 * q1) * inv_det, both2 = (k12 * q1 - m11 * q2) * inv_det;
    const double only1 = -q1 * inv_m[0], only2 = -q2 * inv_m[N - 1];
    const bool fits_both = (both1 >= 0.0) & (both2 >= 0.0);
    const bool fits_first = (only1 >= 0.0) & (k12 * only1 + q2 >= 0.0);
    const bool fits_second = (only2 >= 0.0) & (k12 * only2 + q1 >= 0.0);
    const bool fits_none = (q1 >= 0.0) & (q2 >= 0.0);  // both separating
    // No case fits only through round-off: then the impulses stay as they are.
    const double x1 = fits_both ? both1 : fits_first ? only1 : (fits_second | fits_none) ? 0.0 : p1;
    const double x2 = fits_both ? both2 : fits_first ? 0.0 : fits_second ? only2 : fits_none ? 0.0 : p2;
    const double d1 = x1 - p1, d2 = x2 - p2;
    pn[0] = x1;
    pn[N - 1] = x2;
    apply(a, b, r[0], d1 * nx, d1 * ny);
    apply(a, b, r[N - 1], d2 * nx, d2 * ny);
  } else {
    // One point, or two whose K is ill-conditioned: one after the other.
    for (int i = 0; i < N; ++i) {
      const double v = i == 0 ? vn[0] : relative(a, b, r[i], nx, ny);
      const double total = std::max(pn[i] - (v + bias[i] + g[i] * pn[i]) * inv_m[i], 0.0);
      const double lambda = total - pn[i];
      pn[i] = total;
      apply(a, b, r[i], lambda * nx, lambda * ny);
    }
  }
  if (c.bounce[l]) {  // both passes: a gap can close in the relax pass, after the move
    SoftTally& t = ctx.tallies[l];
    for (int i = 0; i < N; ++i)
      if (t.impact[i] < 0 && pn[i] > 0.0) {
        t.impact[i] = ctx.substep;
        t.approach[i] = vn[i];
      }
  }
  const double tx = ny, ty = -nx;  // t = n × 1
  double pt[N];
  bool acted = false;
  // A surface's own tangent speed (a conveyor), which friction aims for instead of 0.
  const double tangent_speed = surface ? surface->tangent_speed[l] : 0.0;
  for (int i = 0; i < N; ++i) {
    const double limit = c.friction[i][l] * pn[i];
    const double old = c.pt[i][l];
    pt[i] = std::clamp(old - c.tangent_mass[i][l] * (relative(a, b, r[i], tx, ty) - tangent_speed), -limit, limit);
    const double lambda = pt[i] - old;
    apply(a, b, r[i], lambda * tx, lambda * ty);
    acted |= (pn[i] != 0.0) | (pt[i] != 0.0);
  }
  if (surface && surface->rolling[l] > 0.0) {
    // Rolling resistance (contact_solver.cpp solveRolling), from zero at each sub-step's soft pass.
    SoftSurfaceLanes& sl = *surface;
    double total = 0.0;
    for (int i = 0; i < N; ++i) total += pn[i];
    const double limit = sl.rolling[l] * total, old = kSoft ? 0.0 : sl.rolling_impulse[l];
    sl.rolling_impulse[l] = std::clamp(old - sl.rolling_mass[l] * (b.w - a.w), -limit, limit);
    const double lambda = sl.rolling_impulse[l] - old;
    a.w -= a.ii * lambda;
    b.w += b.ii * lambda;
    acted |= sl.rolling_impulse[l] != 0.0;
  }
  for (int i = 0; i < N; ++i) {
    c.pn[i][l] = pn[i];
    c.pt[i][l] = pt[i];
  }
  c.acted[l] |= acted;
  // Immovable bodies (static, asleep) are not written: several lanes may share one.
  if (a.im != 0.0 || a.ii != 0.0) bodies[c.a[l]] = a;
  if (b.im != 0.0 || b.ii != 0.0) bodies[c.b[l]] = b;
  if (!kSoft) {
    if (ctx.warm) addWarmStart(a, b, c, l, (*ctx.warm)[c.a[l]], (*ctx.warm)[c.b[l]]);
    for (int i = 0; i < N; ++i) {  // each sub-step applies its final impulses in all
      ctx.totals->n[i][l] += pn[i];
      ctx.totals->t[i][l] += pt[i];
    }
  }
}

template <bool kSoft>
void solveGroup(std::vector<SoftBody>& bodies, SoftLanes& c, const PassContext& ctx, SoftSurfaceLanes* surface) {
  for (int l = 0; l < L; ++l) {
    if (c.count[l] == 2) {
      solveContact<kSoft, 2>(bodies, c, l, ctx, surface);
    } else if (c.count[l] == 1) {
      solveContact<kSoft, 1>(bodies, c, l, ctx, surface);
    }
  }
}

// --- The same pass on the four lanes of a group at once, in vectors of four doubles (GCC vector
// extensions: one AVX instruction each where the processor has AVX2, two SSE2 instructions
// otherwise; both give the same bits). Lanes hold contacts that share no moving body, so they do
// not interact within the pass. A one-point contact has a neutral second point (no anchors, an
// enormous gap) and an empty lane two of them, on a body that cannot move; both then compute
// impulses of zero. Everything else as solveContact, which serial groups still use.
static_assert(L == 4, "the vector code below spells out four lanes");
// GCC warns that passing these vectors by value would change the ABI without AVX; every function
// that does so is internal to this file and inlined, so no ABI is involved.
#pragma GCC diagnostic ignored "-Wpsabi"
typedef double V __attribute__((vector_size(8 * L)));
typedef long long M __attribute__((vector_size(8 * L)));

// Loads and stores through an unaligned, aliasing vector type rather than memcpy: this file's
// helpers are compiled for the baseline, where GCC splits a 32-byte memcpy into two 16-byte moves
// before they are inlined into the AVX2 passes, which then put the halves on the stack and read
// them back as one, stalling on every load (perf: 7 % of the soft pass on one such reload).
typedef double VU __attribute__((vector_size(8 * L), aligned(8), may_alias));
inline V load(const double* p) { return *reinterpret_cast<const VU*>(p); }
inline void store(double* p, V v) { *reinterpret_cast<VU*>(p) = v; }
inline V splat(double x) { return V{x, x, x, x}; }
typedef long long MU __attribute__((vector_size(8 * L), aligned(8), may_alias));
static_assert(sizeof(long long) == sizeof(int64_t));
inline M loadMask(const int64_t* p) { return *reinterpret_cast<const MU*>(p); }
inline void storeMask(int64_t* p, M m) { *reinterpret_cast<MU*>(p) = m; }
inline V vmax(V a, V b) { return a < b ? b : a; }  // std::max
inline V vmin(V a, V b) { return b < a ? b : a; }  // std::min

struct WideBody {
  V vx, vy, w, dx, dy, qc, qs, im, ii;
  M still;  // cannot move and does not move (static, asleep): several lanes may share it
};

// Four rows of four doubles to four columns (a 4×4 transpose): unpacks and lane swaps, which for
// AVX2 are a few instructions, where reading the fields one by one into vectors takes an insert each.
// __builtin_shufflevector: the spelling GCC (12 and later) and clang share.
[[gnu::always_inline]] inline void transpose(V r0, V r1, V r2, V r3, V& c0, V& c1, V& c2, V& c3) {
  const V t0 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6), t1 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
  const V t2 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6), t3 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
  c0 = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  c1 = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  c2 = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  c3 = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

// Four consecutive fields of a SoftBody, from the field `first` on.
static_assert(sizeof(SoftBody) == 9 * sizeof(double), "gather reads a SoftBody as nine doubles");
[[gnu::always_inline]] inline V row(const SoftBody& b, int first) {
  return *reinterpret_cast<const VU*>(reinterpret_cast<const double*>(&b) + first);
}

[[gnu::always_inline]] inline WideBody gather(const std::vector<SoftBody>& bodies, const uint32_t index[L]) {
  const SoftBody &b0 = bodies[index[0]], &b1 = bodies[index[1]], &b2 = bodies[index[2]], &b3 = bodies[index[3]];
  WideBody v;
  transpose(row(b0, 0), row(b1, 0), row(b2, 0), row(b3, 0), v.vx, v.vy, v.w, v.dx);  // vx vy w dx
  transpose(row(b0, 4), row(b1, 4), row(b2, 4), row(b3, 4), v.dy, v.qc, v.qs, v.im);  // dy qc qs im
  v.ii = V{b0.ii, b1.ii, b2.ii, b3.ii};
  // Still: immovable (im = ii = 0) and not a moving kinematic body, which softStep marks with
  // ii = −0.0 (the bits of +0.0 are all zero, those of −0.0 are not; as a factor both give zero).
  // A moving kinematic body is in one lane of a colour at most, like a dynamic one, and its
  // velocity is written back; a still body may be shared by several lanes.
  v.still = (v.im == splat(0.0)) & (__builtin_bit_cast(M, v.ii) == M{0, 0, 0, 0});
  return v;
}

// Writes the velocities back as whole rows of four doubles (vx vy w dx), so that the next gather
// of the same body reads what one store wrote (three scalar stores followed by a 32-byte load
// cannot be forwarded and stall). Still bodies, which several lanes may share, keep velocity zero
// (their impulses change nothing unless they are not finite); kinematic ones keep theirs (an
// impulse times their zero inverse mass changes nothing either).
template <bool kThreaded>
[[gnu::always_inline]] inline void scatter(std::vector<SoftBody>& bodies, const uint32_t index[L], const WideBody& v) {
  const V zero = splat(0.0);
  const M still = v.still;
  V r[4];
  transpose(still ? zero : v.vx, still ? zero : v.vy, still ? zero : v.w, v.dx, r[0], r[1], r[2], r[3]);
  // With threads a still body is not written at all: it already holds these values (zero
  // velocity, its dx), and another thread may be reading it for a lane of another group of the
  // colour. With one, the unconditional store is cheaper than a test per lane (rain of 4000: about
  // 5 % of the pass, measured).
  for (int l = 0; l < L; ++l)
    if (!kThreaded || !still[l]) store(&bodies[index[l]].vx, r[l]);
}

struct WideAnchor {
  V rax, ray, rbx, rby;
};

inline void applyWide(WideBody& a, WideBody& b, const WideAnchor& r, V px, V py) {
  a.vx -= a.im * px;
  a.vy -= a.im * py;
  a.w -= a.ii * (r.rax * py - r.ray * px);
  b.vx += b.im * px;
  b.vy += b.im * py;
  b.w += b.ii * (r.rbx * py - r.rby * px);
}

inline V relativeWide(const WideBody& a, const WideBody& b, const WideAnchor& r, V dx, V dy) {
  const V rvx = b.vx - b.w * r.rby - a.vx + a.w * r.ray;
  const V rvy = b.vy + b.w * r.rbx - a.vy - a.w * r.rax;
  return rvx * dx + rvy * dy;
}

struct WideKick {
  V vx, vy, w;
};

static_assert(sizeof(SoftKick) == 4 * sizeof(double), "the kicks are read and written as rows of four doubles");
[[gnu::always_inline]] inline WideKick gatherKick(const std::vector<SoftKick>& kicks, const uint32_t index[L]) {
  WideKick k;
  V unused;
  transpose(load(&kicks[index[0]].vx), load(&kicks[index[1]].vx), load(&kicks[index[2]].vx), load(&kicks[index[3]].vx), k.vx, k.vy,
            k.w, unused);
  return k;
}

// Still bodies' lanes are not written: their warm start is never applied (see warmStartWide), and
// several groups of a colour, on different threads, may share one.
template <bool kThreaded>
[[gnu::always_inline]] inline void scatterKick(std::vector<SoftKick>& kicks, const uint32_t index[L], const WideKick& k, M still) {
  V r[4];
  transpose(k.vx, k.vy, k.w, splat(0.0), r[0], r[1], r[2], r[3]);
  for (int l = 0; l < L; ++l)
    if (!kThreaded || !still[l]) store(&kicks[index[l]].vx, r[l]);
}

// addWarmStart on the four lanes at once, with the same operations in the same order per lane
// (point 1 only where there are two points). Movable bodies appear in one lane at most. The
// immovable ones, which several lanes may share, are not written: their warm start is never
// applied (the kick loop runs over the moving bodies only).
template <int NP, bool kThreaded>
[[gnu::always_inline]] inline void warmStartWide(const WideBody& a, const WideBody& b, const SoftLanes& c, M two, V nx, V ny,
                                                  const V pn[2], const V pt[2], std::vector<SoftKick>& warm) {
  const V tx = ny, ty = -nx;
  WideKick wa = gatherKick(warm, c.a), wb = gatherKick(warm, c.b);
  for (int i = 0; i < NP; ++i) {
    const V px = pn[i] * nx + pt[i] * tx, py = pn[i] * ny + pt[i] * ty;
    const V rax = load(c.rax[i]), ray = load(c.ray[i]), rbx = load(c.rbx[i]), rby = load(c.rby[i]);
    const WideKick na{wa.vx - a.im * px, wa.vy - a.im * py, wa.w - a.ii * (rax * py - ray * px)};
    const WideKick nb{wb.vx + b.im * px, wb.vy + b.im * py, wb.w + b.ii * (rbx * py - rby * px)};
    if (i == 0) {
      wa = na;
      wb = nb;
    } else {
      wa = {two ? na.vx : wa.vx, two ? na.vy : wa.vy, two ? na.w : wa.w};
      wb = {two ? nb.vx : wb.vx, two ? nb.vy : wb.vy, two ? nb.w : wb.w};
    }
  }
  scatterKick<kThreaded>(warm, c.a, wa, a.still);
  scatterKick<kThreaded>(warm, c.b, wb, b.still);
}

// NP: the most points of any lane (SoftLanes::points); groups of one-point contacts (circles) skip
// the second point's work, half of the pass. kSurface: the group has surface effects (surface),
// a separate instance so that the others compile as they did without them.
template <bool kSoft, int NP, bool kThreaded, bool kSurface>
[[gnu::always_inline]] inline void solveWide(std::vector<SoftBody>& bodies, SoftLanes& c, const PassContext& ctx, SoftSurfaceLanes* surface) {
  WideBody a = gather(bodies, c.a), b = gather(bodies, c.b);
  const V nx = load(c.nx), ny = load(c.ny);
  const V zero = splat(0.0);
  WideAnchor r[2];
  V pn[2], vn[2], bias[2], g[2], inv_m[2];
  // K is read outside the loop: in it, GCC turns the two loads into a memcpy of 16-byte moves
  // through the stack, and each 32-byte read of the result stalls (as for the impulses below).
  const V k[2] = {load(c.k[0]), load(c.k[1])};
  V rate = zero, floor = zero, compliance = zero, mass_scale = zero;  // the lanes' Level
  if (kSoft) {
    const M stiff = loadMask(c.stiff);
    const Level &soft = ctx.levels[0], &hard = ctx.levels[1];
    rate = stiff ? splat(hard.bias_rate) : splat(soft.bias_rate);
    floor = stiff ? splat(hard.bias_floor) : splat(soft.bias_floor);
    compliance = stiff ? splat(hard.compliance) : splat(soft.compliance);
    mass_scale = stiff ? splat(hard.mass_scale) : splat(soft.mass_scale);
  }
  for (int i = 0; i < NP; ++i) {
    r[i] = {load(c.rax[i]), load(c.ray[i]), load(c.rbx[i]), load(c.rby[i])};
    const V sx = b.dx - a.dx + (b.qc * r[i].rbx - b.qs * r[i].rby) - (a.qc * r[i].rax - a.qs * r[i].ray);
    const V sy = b.dy - a.dy + (b.qs * r[i].rbx + b.qc * r[i].rby) - (a.qs * r[i].rax + a.qc * r[i].ray);
    const V s = load(c.base[i]) + sx * nx + sy * ny;
    const M gap = s > zero;
    const V push = kSoft ? vmax(rate * s, floor) : zero;
    bias[i] = gap ? s * splat(ctx.inv_h) : push;
    g[i] = kSoft ? (gap ? zero : k[i] * compliance) : zero;
    const V inv_k = load(c.inv_k[i]);
    inv_m[i] = kSoft ? (gap ? inv_k : inv_k * mass_scale) : inv_k;  // 1/(K + γ)
    vn[i] = relativeWide(a, b, r[i], nx, ny);
  }
  // Block solution (see solveContact), and the sequential one: point 0, then point 1 seeing point
  // 0's new impulse through K's coupling, v_n1 += k12 Δp0 (what applying it would give).
  // The impulses are read here, not into pn[] in the loop above: pn[] is indexed by lane below, so
  // it lives on the stack, and GCC filled it with 16-byte copies that each 32-byte read waited on.
  const V k12 = load(c.k12), p1 = load(c.pn[0]), p2 = load(c.pn[1]);
  // Each solution only where some lane takes it (SoftLanes::blocks): piles of boxes are nearly all
  // block contacts, piles of circles all one-point contacts.
  V block1 = zero, block2 = zero, seq1 = zero, seq2 = zero;
  if (NP == 2 && c.blocks != SoftLanes::kNoBlock) {
    const V q1 = vn[0] + bias[0] - (k[0] * p1 + k12 * p2);
    const V q2 = vn[1] + bias[1] - (k12 * p1 + k[1] * p2);
    const V m11 = k[0] + g[0], m22 = k[1] + g[1];
    // The relax pass's matrix is the same in every pass (no compliance): its inverse determinant
    // was computed once, as the reciprocals 1/(K + γ). Divisions are the longest links of this chain.
    const V inv_det = kSoft ? splat(1.0) / (m11 * m22 - k12 * k12) : load(c.inv_det);
    const V both1 = (k12 * q2 - m22 * q1) * inv_det, both2 = (k12 * q1 - m11 * q2) * inv_det;
    const V only1 = -q1 * inv_m[0], only2 = -q2 * inv_m[1];
    const M fits_both = (both1 >= zero) & (both2 >= zero);
    const M fits_first = (only1 >= zero) & (k12 * only1 + q2 >= zero);
    const M fits_second = (only2 >= zero) & (k12 * only2 + q1 >= zero);
    const M fits_none = (q1 >= zero) & (q2 >= zero);
    block1 = fits_both ? both1 : fits_first ? only1 : (fits_second | fits_none) ? zero : p1;
    block2 = fits_both ? both2 : fits_first ? zero : fits_second ? only2 : fits_none ? zero : p2;
  }
  if (NP == 1 || c.blocks != SoftLanes::kAllBlock) {
    seq1 = vmax(p1 - (vn[0] + bias[0] + g[0] * p1) * inv_m[0], zero);
    if (NP == 2) {
      const V vn2 = vn[1] + k12 * (seq1 - p1);
      seq2 = vmax(p2 - (vn2 + bias[1] + g[1] * p2) * inv_m[1], zero);
    }
  }
  const M block = M{c.block[0], c.block[1], c.block[2], c.block[3]} != 0;
  const V x1 = NP == 1 ? seq1 : (block ? block1 : seq1), x2 = block ? block2 : seq2;
  applyWide(a, b, r[0], (x1 - p1) * nx, (x1 - p1) * ny);
  pn[0] = x1;
  if (NP == 2) {
    applyWide(a, b, r[1], (x2 - p2) * nx, (x2 - p2) * ny);
    pn[1] = x2;
  }
  uint32_t bouncing;  // any lane: one test for the common case of none
  std::memcpy(&bouncing, c.bounce, sizeof bouncing);
  if (bouncing != 0) {  // impact speeds, in both passes (see solveContact)
    for (int l = 0; l < L; ++l) {
      if (!c.bounce[l]) continue;
      SoftTally& t = ctx.tallies[l];
      for (int i = 0; i < c.count[l]; ++i)
        if (t.impact[i] < 0 && pn[i][l] > 0.0) {
          t.impact[i] = ctx.substep;
          t.approach[i] = vn[i][l];
        }
    }
  }
  const V tx = ny, ty = -nx;  // t = n × 1
  V pt[2];
  // Surface effects (SoftSurfaceLanes) only in groups that have them (SoftLanes::surface, a byte
  // of the group's first line).
  for (int i = 0; i < NP; ++i) {
    const V limit = load(c.friction[i]) * pn[i];
    const V old = load(c.pt[i]);
    V slip = relativeWide(a, b, r[i], tx, ty);
    if constexpr (kSurface) slip -= load(surface->tangent_speed);
    pt[i] = vmin(vmax(old - load(c.tangent_mass[i]) * slip, -limit), limit);
    applyWide(a, b, r[i], (pt[i] - old) * tx, (pt[i] - old) * ty);
    store(c.pn[i], pn[i]);
    store(c.pt[i], pt[i]);
  }
  [[maybe_unused]] M rolled;  // kSurface only
  if constexpr (kSurface) {
    // Rolling resistance on the four lanes (solveContact's), lanes without it bounded by zero.
    const V total = NP == 2 ? pn[0] + pn[1] : pn[0];
    const V limit = load(surface->rolling) * total, old = kSoft ? zero : load(surface->rolling_impulse);
    const V rolling = vmin(vmax(old - load(surface->rolling_mass) * (b.w - a.w), -limit), limit);
    store(surface->rolling_impulse, rolling);
    a.w -= a.ii * (rolling - old);
    b.w += b.ii * (rolling - old);
    rolled = rolling != zero;
  }
  scatter<kThreaded>(bodies, c.a, a);
  scatter<kThreaded>(bodies, c.b, b);
  // Only real points count (a neutral one's impulses are zero unless the velocities are not finite).
  const M two = M{c.count[0], c.count[1], c.count[2], c.count[3]} == 2;
  M acted = (pn[0] != zero) | (pt[0] != zero);
  if constexpr (kSurface) acted |= rolled;
  if (NP == 2) acted |= two & ((pn[1] != zero) | (pt[1] != zero));
  // Empty lanes may record anything: the write-back reads real contacts only.
  storeMask(c.acted, loadMask(c.acted) | acted);
  if (!kSoft) {
    if (ctx.warm) warmStartWide<NP, kThreaded>(a, b, c, two, nx, ny, pn, pt, *ctx.warm);
    SoftTotals& t = *ctx.totals;
    for (int i = 0; i < NP; ++i) {  // each sub-step applies its final impulses in all
      store(t.n[i], load(t.n[i]) + pn[i]);
      store(t.t[i], load(t.t[i]) + pt[i]);
    }
  }
}

bool& onePointPass() {
  static bool on = true;
  return on;
}

// One pass over the groups g0 … g1. kThreaded: other groups of the colour may be solved on other
// threads at the same time, so bodies that several lanes share are not written (see scatter);
// fixed at compile time so that the serial pass stores without a test per lane. kSurfaces: some
// group has surface effects (SoftLanes::surface); a separate instance, so that steps without them
// run the code they ran before them (with the test per group inside, the pass of a 40-row pyramid
// took 3 % more instructions, cachegrind).
template <bool kSoft, bool kThreaded, bool kSurfaces>
[[gnu::always_inline]] inline void passGroups(std::vector<SoftBody>& bodies, std::vector<SoftLanes>& groups, std::vector<SoftTally>& tallies,
                                              std::vector<SoftTotals>& totals, std::vector<SoftSurfaceLanes>* surfaces, double inv_h, int substep, std::vector<SoftKick>* warm,
                                              const Level* levels, size_t g0, size_t g1) {
  for (size_t g = g0; g < g1; ++g) {
    SoftSurfaceLanes* const surface = kSurfaces && groups[g].surface ? &(*surfaces)[g] : nullptr;
    const PassContext ctx{inv_h, substep, levels, &tallies[g * L], &totals[g], warm};
    if (groups[g].serial) {
      solveGroup<kSoft>(bodies, groups[g], ctx, surface);
    } else if (groups[g].points <= 1 && onePointPass()) {
      if (kSurfaces && surface) solveWide<kSoft, 1, kThreaded, kSurfaces>(bodies, groups[g], ctx, surface);
      else solveWide<kSoft, 1, kThreaded, false>(bodies, groups[g], ctx, nullptr);
    } else {
      if (kSurfaces && surface) solveWide<kSoft, 2, kThreaded, kSurfaces>(bodies, groups[g], ctx, surface);
      else solveWide<kSoft, 2, kThreaded, false>(bodies, groups[g], ctx, nullptr);
    }
  }
}

template <bool kSoft, bool kSurfaces>
[[gnu::always_inline]] inline void passBody(std::vector<SoftBody>& bodies, std::vector<SoftLanes>& groups, std::vector<SoftTally>& tallies,
                                            std::vector<SoftTotals>& totals, std::vector<SoftSurfaceLanes>* surfaces, double inv_h, int substep, std::vector<SoftKick>* warm,
                                            const Level* levels, size_t g0, size_t g1, bool threaded) {
  if (threaded) {
    passGroups<kSoft, true, kSurfaces>(bodies, groups, tallies, totals, surfaces, inv_h, substep, warm, levels, g0, g1);
  } else {
    passGroups<kSoft, false, kSurfaces>(bodies, groups, tallies, totals, surfaces, inv_h, substep, warm, levels, g0, g1);
  }
}

// The passes compiled twice on x86-64: for AVX2 and for the baseline (SSE2), chosen once per
// process (softStepUseAvx2). The default build stays portable, and both give the same bits (only
// additions, multiplications, divisions and comparisons; no fused multiply-add), which
// tests/core/test_soft_step.cpp checks. Other processors (aarch64) compile the baseline only, with
// their own vector unit for the same generic vector code.
#if defined(__x86_64__) || defined(__i386__)
#define RIGIDLAB_SOFT_STEP_AVX2 1
bool cpuHasAvx2() { return __builtin_cpu_supports("avx2"); }
#else
#define RIGIDLAB_SOFT_STEP_AVX2 0
bool cpuHasAvx2() { return false; }
#endif

#if RIGIDLAB_SOFT_STEP_AVX2
template <bool kSoft, bool kSurfaces>
__attribute__((target("avx2"))) void passAvx2(std::vector<SoftBody>& bodies, std::vector<SoftLanes>& groups, std::vector<SoftTally>& tallies,
                                              std::vector<SoftTotals>& totals, std::vector<SoftSurfaceLanes>* surfaces, double inv_h, int substep, std::vector<SoftKick>* warm,
                  const Level* levels, size_t g0, size_t g1, bool threaded) {
  passBody<kSoft, kSurfaces>(bodies, groups, tallies, totals, surfaces, inv_h, substep, warm, levels, g0, g1, threaded);
}
#endif

template <bool kSoft, bool kSurfaces>
void passBaseline(std::vector<SoftBody>& bodies, std::vector<SoftLanes>& groups, std::vector<SoftTally>& tallies,
                  std::vector<SoftTotals>& totals, std::vector<SoftSurfaceLanes>* surfaces, double inv_h, int substep, std::vector<SoftKick>* warm,
                  const Level* levels, size_t g0, size_t g1, bool threaded) {
  passBody<kSoft, kSurfaces>(bodies, groups, tallies, totals, surfaces, inv_h, substep, warm, levels, g0, g1, threaded);
}

bool& avx2Selected() {
  static bool on = cpuHasAvx2();
  return on;
}

template <bool kSoft>
void pass(std::vector<SoftBody>& bodies, std::vector<SoftLanes>& groups, std::vector<SoftTally>& tallies, std::vector<SoftTotals>& totals,
          std::vector<SoftSurfaceLanes>* surfaces,
          double inv_h, int substep, std::vector<SoftKick>* warm, const Level* levels, size_t g0, size_t g1,
          bool threaded) {
#if RIGIDLAB_SOFT_STEP_AVX2
  if (avx2Selected()) {
    if (surfaces) passAvx2<kSoft, true>(bodies, groups, tallies, totals, surfaces, inv_h, substep, warm, levels, g0, g1, threaded);
    else passAvx2<kSoft, false>(bodies, groups, tallies, totals, nullptr, inv_h, substep, warm, levels, g0, g1, threaded);
    return;
  }
#endif
  if (surfaces) passBaseline<kSoft, true>(bodies, groups, tallies, totals, surfaces, inv_h, substep, warm, levels, g0, g1, threaded);
  else passBaseline<kSoft, false>(bodies, groups, tallies, totals, nullptr, inv_h, substep, warm, levels, g0, g1, threaded);
}

// Restitution after the sub-steps (Box2D v3's b2ApplyRestitution), for points that pushed and
// were approaching faster than the threshold when they first did. The target is the bounce of the
// impact speed less what the step's forces took away after the impact (they kept pressing the
// bodies together for the remaining sub-steps):
//   v_target = −e v_impact + (n − 1 − k) · kick      (kick: the forces' normal velocity per sub-step)
// Friction acts on the restitution impulse too (Coulomb over the whole collision, docs/design/thesis.md §10;
// docs/design/accuracy.md §3.11: experiment 1's friction impulse is f times the full normal impulse).
void restitute(std::vector<SoftBody>& bodies, const SoftLanes& c, int l, SoftTally& t, SoftTotals& totals, double threshold,
               int substeps, double tangent_speed) {
  SoftBody& a = bodies[c.a[l]];
  SoftBody& b = bodies[c.b[l]];
  const double nx = c.nx[l], ny = c.ny[l], tx = ny, ty = -nx;
  for (int i = 0; i < c.count[l]; ++i) {
    if (t.impact[i] < 0 || t.approach[i] > -threshold) continue;
    const double target = -t.restitution * t.approach[i] + (substeps - 1 - t.impact[i]) * t.kick[i];
    const Anchor r = anchorOf(c, i, l);
    const double vn = relative(a, b, r, nx, ny);
    const double normal = std::max(-(vn - target) / c.k[i][l], -c.pn[i][l]);
    if (normal <= 0.0) continue;
    apply(a, b, r, normal * nx, normal * ny);
    totals.n[i][l] += normal;
    const double limit = c.friction[i][l] * normal;
    const double tangent = std::clamp(-c.tangent_mass[i][l] * (relative(a, b, r, tx, ty) - tangent_speed), -limit, limit);
    apply(a, b, r, tangent * tx, tangent * ty);
    totals.t[i][l] += tangent;
  }
}

// A well-mixed 64-bit hash of a contact's pair of bodies (the finaliser of splitmix64, Steele,
// Lea and Flood 2014): its top byte picks the contact's place in the colouring order.
inline uint64_t mixPair(uint32_t a, uint32_t b) {
  uint64_t x = ((static_cast<uint64_t>(a) << 32) | b) + 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// The order the contacts are coloured in: by a hash of their pair of bodies (256 buckets, a counting
// sort; (a, b) order within a bucket). Why not the (a, b) order itself: greedy colouring in that
// order gives the colours, and so the Gauss–Seidel sweep, the build order of the scene (a pile built
// row by row from the left is met left to right in every colour), and with one pass per sub-step
// the unconverged part of the friction then pushes every row the same way: pyramids walk sideways,
// and a pile built in mirror order walks the other way. In hash order the sweep has no direction.
// Measured (bench, 2026-12-05; largest sideways move of a box, pyramid of base 100): 0.886 → 0.253 m
// at 4 sub-steps, 0.072 → 0.034 m at the default 8 (Box2D v3 at its 4: 0.181 m); heights move by a
// few per cent, the deepest contact and largest overlap by up to about 20 %, either way
// (docs/performance.md).
void colouringOrder(WorldImpl& w) {
  SoftStepScratch& own = w.soft_step.get();
  const size_t n = w.soft_solved.size();
  auto& bucket = own.color_bucket;
  auto& order = own.color_order;
  bucket.resize(n);
  order.resize(n);
  uint32_t first[257] = {};
  for (size_t k = 0; k < n; ++k) {
    bucket[k] = static_cast<uint8_t>(mixPair(w.soft_refs[k].a, w.soft_refs[k].b) >> 56);
    ++first[bucket[k] + 1];
  }
  for (int i = 0; i < 256; ++i) first[i + 1] += first[i];
  for (size_t k = 0; k < n; ++k) order[first[bucket[k]]++] = static_cast<uint32_t>(k);
}

// The colouring is a function of the contacts' pairs of bodies (in order) and of which bodies move,
// and nothing else: when both are those of the last step, as in a pile at rest, so is the colouring,
// and it is kept (Box2D v3 keeps its constraint graph between steps instead of colouring again).
// Only the lanes' contact indices are written again. Checked pair by pair, stopping at the first
// difference, so a scene whose contacts change pays little for the check.
bool sameGraph(WorldImpl& w) {
  SoftStepScratch& own = w.soft_step.get();
  auto& last = own.graph_pairs;
  const auto& refs = w.soft_refs;
  bool same = own.graph_valid && last.size() == refs.size() && own.graph_moved == own.moved;
  for (size_t k = 0; same && k < refs.size(); ++k) same = last[k].a == refs[k].a && last[k].b == refs[k].b;
  if (same) return true;
  last.resize(refs.size());
  for (size_t k = 0; k < refs.size(); ++k) last[k] = {refs[k].a, refs[k].b};
  own.graph_moved = own.moved;
  own.graph_valid = true;
  return false;
}

// Colours the contacts greedily, in colouringOrder's order, so that no two contacts of a colour move
// the same body (static and sleeping bodies do not count), as Box2D v3's constraint graph does, and
// packs each colour into groups of L lanes, in the contacts' (a, b) order within a colour. Contacts
// that find no free colour among kColors (a body touching dozens of others) go to serial groups.
void colourGroups(WorldImpl& w) {
  SoftStepScratch& own = w.soft_step.get();
  constexpr int kColors = 32;
  const auto& solved = w.soft_solved;
  const auto& moved = own.moved;
  auto& used = own.colors_used;
  used.assign(w.bodies.size(), 0u);
  auto& color = own.color;
  color.resize(solved.size());
  colouringOrder(w);
  int count[kColors + 1] = {};
  for (const uint32_t k : own.color_order) {
    const SolvedRef& c = w.soft_refs[k];
    const uint32_t busy = (moved[c.a] ? used[c.a] : 0u) | (moved[c.b] ? used[c.b] : 0u);
    const int free = busy == ~0u ? kColors : std::countr_one(busy);  // lowest colour not busy
    color[k] = static_cast<uint8_t>(free);
    ++count[free];
    if (free < kColors) {
      if (moved[c.a]) used[c.a] |= 1u << free;
      if (moved[c.b]) used[c.b] |= 1u << free;
    }
  }
  // Lane slots: each colour rounded up to whole groups.
  int first[kColors + 2];
  first[0] = 0;
  for (int c = 0; c <= kColors; ++c) first[c + 1] = first[c] + (count[c] + L - 1) / L * L;
  auto& source = own.source;
  auto& slot = own.slot;
  source.assign(static_cast<size_t>(first[kColors + 1]), UINT32_MAX);
  slot.resize(solved.size());
  int next[kColors + 1];
  for (int c = 0; c <= kColors; ++c) next[c] = first[c];
  for (size_t k = 0; k < solved.size(); ++k) {
    slot[k] = static_cast<uint32_t>(next[color[k]]++);
    source[slot[k]] = solved[k];
  }
  own.lanes.resize(source.size() / L);
  for (size_t g = 0; g < own.lanes.size(); ++g) own.lanes[g].serial = static_cast<int>(g * L) >= first[kColors];
  // Each colour's first group, then the serial groups' first, then the end.
  own.color_first.resize(kColors + 2);
  for (int c = 0; c <= kColors + 1; ++c) own.color_first[c] = static_cast<uint32_t>(first[c] / L);
}

// The groups of this step's soft contacts: the last step's colouring when sameGraph says it still
// holds, a new one otherwise.
void buildGroups(WorldImpl& w) {
  SoftStepScratch& own = w.soft_step.get();
  if (!sameGraph(w)) {
    colourGroups(w);
    return;
  }
  for (size_t k = 0; k < w.soft_solved.size(); ++k) own.source[own.slot[k]] = w.soft_solved[k];
#ifdef RIGIDLAB_VERIFY_CACHES
  // Sanitizer and fuzz builds: the kept colouring must be the one colouring again gives.
  const std::vector<uint32_t> slot = own.slot, source = own.source, first = own.color_first;
  colourGroups(w);
  if (slot != own.slot || source != own.source || first != own.color_first) {
    std::fprintf(stderr, "rigidlab: the kept colouring of the soft contacts differs from a new one\n");
    std::abort();
  }
#endif
}

// Asks for the cache lines of the contact `ahead` entries further down the list. The loops over a
// large pile's contacts are bound by loading them (a Contact spans four or five lines, and the hardware
// prefetcher does not keep up while the loop also writes lanes and tallies in colour order):
// prepare took 17 % of the soft step's own time waiting for one field (perf). Always inlined: GCC
// finds a function that only prefetches free of side effects and drops the calls.
[[gnu::always_inline]] inline void prefetchContact(const WorldImpl& w, size_t k, size_t ahead) {
  if (k + ahead >= w.soft_solved.size()) return;
  const char* p = reinterpret_cast<const char*>(&w.contacts[w.soft_solved[k + ahead]]);
  for (size_t offset = 0; offset < sizeof(Contact); offset += 64) __builtin_prefetch(p + offset);
  __builtin_prefetch(p + sizeof(Contact) - 1);
}

// The same for the centres of its bodies, which prepare reads (a Body is large and they are far
// apart in memory).
[[gnu::always_inline]] inline void prefetchCenters(const WorldImpl& w, size_t k, size_t ahead) {
  if (k + ahead >= w.soft_refs.size()) return;
  const SolvedRef& r = w.soft_refs[k + ahead];
  __builtin_prefetch(&w.bodies[r.a].center);
  __builtin_prefetch(&w.bodies[r.b].center);
}

// And for the write-back: the contact's impulses and its lane's.
[[gnu::always_inline]] inline void prefetchWriteBack(const WorldImpl& w, const SoftStepScratch& own, size_t k, size_t ahead) {
  if (k + ahead >= w.soft_solved.size()) return;
  const Contact& c = w.contacts[w.soft_solved[k + ahead]];
  __builtin_prefetch(&c.points[0].normal_impulse, 1);
  __builtin_prefetch(&c.points[0].step_tangent_impulse, 1);
  __builtin_prefetch(&c.points[1].normal_impulse, 1);
  __builtin_prefetch(&c.points[1].step_tangent_impulse, 1);
  const SoftLanes& sc = own.lanes[own.slot[k + ahead] / L];
  __builtin_prefetch(&sc.pn[0][0]);
  __builtin_prefetch(&sc.pn[1][3]);
  __builtin_prefetch(&sc.pt[1][3]);
}

}  // namespace

// Work per thread below which a loop stays in the calling thread (task_pool.h): a hand-off costs
// a few microseconds, a group's pass about 0.1 µs, a body's kick or move a few nanoseconds.
constexpr size_t kGroupGrain = 16;
constexpr size_t kContactGrain = 256;
constexpr size_t kBodyGrain = 1024;

void softStepOnePointPass(bool on) { onePointPass() = on; }

bool softStepUseAvx2(bool on) {
  const bool can = cpuHasAvx2();
  avx2Selected() = on && can;
  return avx2Selected() == on;
}

namespace {
// A contact's surface effects in its lane of the group's SoftSurfaceLanes; returns its tangent speed.
[[gnu::noinline]] double surfaceLane(const ContactSurface& surface, const SoftBody& a, const SoftBody& b, SoftSurfaceLanes& sl, int l) {
  if (!surface.any()) return 0.0;
  const double k_roll = a.ii + b.ii;
  sl.tangent_speed[l] = surface.tangent_speed;
  sl.rolling[l] = surface.rolling_resistance;
  sl.rolling_mass[l] = k_roll > 0.0 ? 1.0 / k_roll : 0.0;
  return surface.tangent_speed;
}
}  // namespace

void softStep(WorldImpl& w, const StepContext& ctx) {
  SoftStepScratch& own = w.soft_step.get();
  const uint32_t n = static_cast<uint32_t>(w.bodies.size());
  const int substeps = ctx.settings.substeps;
  const double h = ctx.dt / substeps, inv_h = 1.0 / h;
  // The contacts and joints were chosen by solveContacts (contact_solver.cpp).
  if (w.soft_solved.empty() && w.soft_joints.empty()) return;

  // Bodies: the moving ones of those contacts go back to the start of the step.
  auto& bodies = own.bodies;
  auto& kick = own.kick;
  auto& warm = own.warm;
  auto& moved = own.moved;
  auto& angle = own.angle;
  auto& list = own.list;
  bodies.resize(n + 1);  // slot n: an immovable body for the empty lanes
  bodies[n] = {0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0};
  kick.resize(n);
  angle.resize(n);
  warm.assign(n + 1, SoftKick{0.0, 0.0, 0.0, 0.0});
  moved.assign(n, 0);
  for (const SolvedRef& r : w.soft_refs) {
    // Awake dynamic bodies, and kinematic ones that move: both are sub-stepped.
    if (r.active & 1 || w.isMovingKinematic(r.a)) moved[r.a] = 1;
    if (r.active & 2 || w.isMovingKinematic(r.b)) moved[r.b] = 1;
  }
  for (uint32_t k : w.soft_joints) {  // jointed bodies are always acted on
    const Joint& j = w.joints[k];
    for (uint32_t slot : {j.a, j.b, j.c, j.d})
      if (slot != kWorldSlot && (w.isActive(slot) || w.isMovingKinematic(slot))) moved[slot] = 2;
  }
  list.clear();
  for (uint32_t i = 0; i < n; ++i) {
    if (!moved[i]) {
      bodies[i] = {0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0};  // static, asleep or not in contact
      kick[i] = {0.0, 0.0, 0.0, 0.0};
      continue;
    }
    list.push_back(i);
    const Body& b = w.bodies[i];
    const Vec2 v0 = w.start_velocity[i];
    const double w0 = w.start_angular_velocity[i];
    const Vec2 d = w.start_center[i] - b.center;
    angle[i] = w.start_angle[i] - b.angle;
    double sin_angle = 0.0, cos_angle = 1.0;
    portableSinCos(angle[i], sin_angle, cos_angle);
    bodies[i] = {v0.x(), v0.y(), w0, d.x(), d.y(), cos_angle, sin_angle, b.inv_mass, b.inv_inertia};
    if (b.isKinematic()) bodies[i].ii = -0.0;  // moves, though no impulse moves it (gather's still)
    kick[i] = {(b.velocity.x() - v0.x()) / substeps, (b.velocity.y() - v0.y()) / substeps,
               (b.angular_velocity - w0) / substeps, 0.0};
  }

  // Worker threads (WorldDef::threads): nullptr for one, and for a small step, which then never
  // starts them. Only loops whose iterations write their own slots are split (task_pool.h), so
  // every thread count gives the same bits.
  TaskPool* pool = w.soft_solved.size() >= 2 * kContactGrain || list.size() >= 2 * kBodyGrain ? w.taskPool() : nullptr;
  const auto forEach = [pool](size_t count, size_t grain, auto&& fn) {
    if (pool) pool->parallelFor(count, grain, fn);
    else if (count > 0) fn(size_t{0}, count);
  };

  // Constraints, in groups of L lanes.
  buildGroups(w);
  const double hertz = std::min(ctx.settings.contact_hertz, 0.125 * inv_h);
  const Softness soft = makeSoft(hertz, ctx.settings.contact_damping_ratio, h);
  const Softness stiff = makeSoft(2.0 * hertz, ctx.settings.contact_damping_ratio, h);
  const Level levels[2] = {levelOf(soft, ctx.settings.contact_push_speed), levelOf(stiff, ctx.settings.contact_push_speed)};
  auto& groups = own.lanes;
  auto& tallies = own.tally;
  const auto& source = own.source;
  tallies.resize(source.size());
  auto& totals = own.totals;
  totals.assign(groups.size(), SoftTotals{});
  // Surface effects (pre_solve.cpp): lanes for them only when some contact of the step has them.
  auto& surfaces = own.surfaces;
  surfaces.clear();
  if (!w.contact_surfaces.empty()) surfaces.assign(groups.size(), SoftSurfaceLanes{});
  // Empty lanes and the second point of one-point contacts: neutral, so that the vector code can
  // run them with the others and compute impulses of zero (an enormous gap, no anchors, no friction,
  // the immovable body n).
  const auto neutral = [](SoftLanes& sc, int i, int l) {
    sc.rax[i][l] = sc.ray[i][l] = sc.rbx[i][l] = sc.rby[i][l] = 0.0;
    sc.base[i][l] = 1e30;
    sc.k[i][l] = sc.inv_k[i][l] = 1.0;
    sc.tangent_mass[i][l] = sc.friction[i][l] = sc.pn[i][l] = sc.pt[i][l] = 0.0;
  };
  for (size_t g = 0; g < groups.size(); ++g)
    for (int l = 0; l < L; ++l)
      if (source[g * L + l] == UINT32_MAX) {
        SoftLanes& sc = groups[g];
        sc.a[l] = sc.b[l] = n;
        sc.count[l] = sc.bounce[l] = 0;
        sc.block[l] = 1;  // either solution gives an empty lane zero; this one lets a group skip the other
        sc.acted[l] = 0;
        sc.nx[l] = 0.0;
        sc.ny[l] = 1.0;
        sc.stiff[l] = 0;
        sc.k12[l] = sc.inv_det[l] = 0.0;
        neutral(sc, 0, l);
        neutral(sc, 1, l);
      }
  // In the contacts' own order: a Contact is large, and reading them in colour order misses the
  // cache on nearly every one (this loop took 40 % of the soft step's own time that way).
  // With several threads, each range of contacts is prepared on its own thread and the warm starts,
  // sums over each body's contacts, are added afterwards serially in the same order.
  const bool any_surface = !surfaces.empty();
  const auto prepare = [&](size_t k) {
    prefetchContact(w, k, 8);
    prefetchCenters(w, k, 8);
    const size_t g = own.slot[k] / L;
    const int l = static_cast<int>(own.slot[k] % L);
    SoftLanes& sc = groups[g];
    {  // one contact
      sc.acted[l] = 0;
      const Contact& c = w.contacts[w.soft_solved[k]];
      const SoftBody& a = bodies[c.a];
      const SoftBody& b = bodies[c.b];
      const bool fixed = (a.im == 0.0 && a.ii == 0.0) || (b.im == 0.0 && b.ii == 0.0);
      SoftTally& t = tallies[g * L + l];
      sc.a[l] = c.a;
      sc.b[l] = c.b;
      sc.count[l] = static_cast<uint8_t>(c.count);
      sc.bounce[l] = c.restitution > 0.0;
      sc.nx[l] = c.normal.x();
      sc.ny[l] = c.normal.y();
      sc.stiff[l] = fixed ? -1 : 0;
      if (sc.bounce[l]) t.restitution = c.restitution;  // the tallies are read for bouncing contacts only
      const double tangent_speed = any_surface ? surfaceLane(w.contact_surfaces[w.soft_solved[k]], a, b, surfaces[g], l) : 0.0;
      const Vec2 nrm = c.normal, tan = cross(c.normal, 1.0);
      const Vec2 ca = w.bodies[c.a].center, cb = w.bodies[c.b].center;
      const SoftKick ka = kick[c.a], kb = kick[c.b];
      for (int i = 0; i < c.count; ++i) {
        const ContactPoint& cp = c.points[i];
        const Vec2 ra = cp.point - ca, rb = cp.point - cb;
        sc.rax[i][l] = ra.x();
        sc.ray[i][l] = ra.y();
        sc.rbx[i][l] = rb.x();
        sc.rby[i][l] = rb.y();
        sc.base[i][l] = cp.separation - (rb - ra).dot(nrm);
        const double rna = cross(ra, nrm), rnb = cross(rb, nrm), rta = cross(ra, tan), rtb = cross(rb, tan);
        const double kn = a.im + b.im + a.ii * rna * rna + b.ii * rnb * rnb;
        const double kt = a.im + b.im + a.ii * rta * rta + b.ii * rtb * rtb;
        sc.k[i][l] = kn;
        sc.tangent_mass[i][l] = kt > 0.0 ? 1.0 / kt : 0.0;
        sc.inv_k[i][l] = 1.0 / kn;
        // f_s or f_d from the slip at the start of the step (docs/design/thesis.md §10), against the
        // surface's own motion; the bodies still hold the velocities of the start of the step.
        const double slip = relative(a, b, anchorOf(sc, i, l), tan.x(), tan.y()) - tangent_speed;
        sc.friction[i][l] = std::abs(slip) < ctx.settings.static_friction_speed ? c.static_friction : c.friction;
        sc.pn[i][l] = ctx.settings.warm_starting ? cp.normal_impulse : 0.0;
        sc.pt[i][l] = ctx.settings.warm_starting ? cp.tangent_impulse : 0.0;
        sc.acted[l] |= (sc.pn[i][l] != 0.0) | (sc.pt[i][l] != 0.0);
        if (!sc.bounce[l]) continue;
        t.approach[i] = 0.0;
        t.impact[i] = -1;
        t.kick[i] = (kb.vx - kb.w * rb.y() - ka.vx + ka.w * ra.y()) * nrm.x() +
                    (kb.vy + kb.w * rb.x() - ka.vy - ka.w * ra.x()) * nrm.y();
      }
      // Two points: k12 = 1/m_A + 1/m_B + (r_A1×n)(r_A2×n)/I_A + (r_B1×n)(r_B2×n)/I_B; solved
      // together when K is well conditioned (Box2D 2.4's rule, as contact_solver.cpp).
      sc.block[l] = 0;
      sc.k12[l] = sc.inv_det[l] = 0.0;
      if (c.count == 1) neutral(sc, 1, l);
      if (c.count == 2) {
        const double rn1a = sc.rax[0][l] * nrm.y() - sc.ray[0][l] * nrm.x();
        const double rn1b = sc.rbx[0][l] * nrm.y() - sc.rby[0][l] * nrm.x();
        const double rn2a = sc.rax[1][l] * nrm.y() - sc.ray[1][l] * nrm.x();
        const double rn2b = sc.rbx[1][l] * nrm.y() - sc.rby[1][l] * nrm.x();
        sc.k12[l] = a.im + b.im + a.ii * rn1a * rn2a + b.ii * rn1b * rn2b;
        const double k11 = sc.k[0][l], k22 = sc.k[1][l];
        sc.block[l] = k11 * k11 < 1000.0 * (k11 * k22 - sc.k12[l] * sc.k12[l]);
        if (sc.block[l]) sc.inv_det[l] = 1.0 / (k11 * k22 - sc.k12[l] * sc.k12[l]);
      }
    }
  };
  // The first sub-step's warm start: the impulses carried over from the previous step.
  const auto warmStart = [&](size_t k) {
    const uint32_t at = own.slot[k];
    const SoftLanes& sc = groups[at / L];
    const int l = static_cast<int>(at % L);
    addWarmStart(bodies[sc.a[l]], bodies[sc.b[l]], sc, l, warm[sc.a[l]], warm[sc.b[l]]);
  };
  if (!pool) {
    for (size_t k = 0; k < w.soft_solved.size(); ++k) {
      prepare(k);
      warmStart(k);
    }
  } else {
    pool->parallelFor(w.soft_solved.size(), kContactGrain, [&](size_t begin, size_t end) {
      for (size_t k = begin; k < end; ++k) prepare(k);
    });
    for (size_t k = 0; k < w.soft_solved.size(); ++k) warmStart(k);
  }

  for (size_t g = 0; g < groups.size(); ++g) {
    SoftLanes& sc = groups[g];
    const int blocks = (sc.block[0] != 0) + (sc.block[1] != 0) + (sc.block[2] != 0) + (sc.block[3] != 0);
    sc.blocks = blocks == 0 ? SoftLanes::kNoBlock : blocks == L ? SoftLanes::kAllBlock : SoftLanes::kSomeBlocks;
    sc.points = std::max({sc.count[0], sc.count[1], sc.count[2], sc.count[3]});
    sc.surface = 0;
    if (!surfaces.empty())
      for (int l = 0; l < L; ++l) sc.surface |= surfaces[g].tangent_speed[l] != 0.0 || surfaces[g].rolling[l] > 0.0;
  }
  std::vector<SoftSurfaceLanes>* const surface_lanes = surfaces.empty() ? nullptr : &surfaces;

  // Joints (joint.h): prepared at the detection state, solved serially before the contacts of each
  // pass, with the joints' own soft bias.
  JointStep joint_step;
  joint_step.h = h;
  joint_step.inv_h = inv_h;
  joint_step.soft = makeSoft(std::min(ctx.settings.joint_hertz, 0.25 * inv_h), ctx.settings.joint_damping_ratio, h);
  joint_step.warm_starting = ctx.settings.warm_starting;
  for (uint32_t k : w.soft_joints) prepareJointAt(w, w.joints[k], joint_step);
  // Each joint's bodies, found once for the step's 3 × substeps passes over the joints.
  auto& joint_bodies = own.joint_bodies;
  joint_bodies.resize(w.soft_joints.size());
  for (size_t q = 0; q < w.soft_joints.size(); ++q) {
    const Joint& j = w.joints[w.soft_joints[q]];
    const auto at = [&](uint32_t slot) { return &bodies[slot == kWorldSlot ? n : slot]; };
    joint_bodies[q] = JointBodies{at(j.a), at(j.b), at(j.c), at(j.d)};
  }
  const auto forEachJoint = [&](auto&& fn) {
    for (size_t q = 0; q < w.soft_joints.size(); ++q) fn(w.joints[w.soft_joints[q]], joint_bodies[q]);
  };

  // Sub-steps.
  // A pass: with several threads, colour by colour (the groups of one colour share no moving body,
  // so they are independent), then the serial groups in the caller; in group order otherwise.
  const auto& color_first = own.color_first;
  const auto runPass = [&](auto soft, int step, std::vector<SoftKick>* next) {
    constexpr bool kSoft = decltype(soft)::value;
    if (!pool) {
      pass<kSoft>(bodies, groups, tallies, totals, surface_lanes, inv_h, step, next, levels, 0, groups.size(), false);
      return;
    }
    const size_t colors = color_first.size() - 2;
    for (size_t c = 0; c < colors; ++c) {
      const size_t g0 = color_first[c], g1 = color_first[c + 1];
      pool->parallelFor(g1 - g0, kGroupGrain, [&](size_t begin, size_t end) {
        pass<kSoft>(bodies, groups, tallies, totals, surface_lanes, inv_h, step, next, levels, g0 + begin, g0 + end, true);
      });
    }
    pass<kSoft>(bodies, groups, tallies, totals, surface_lanes, inv_h, step, next, levels, color_first[colors], color_first[colors + 1], false);
  };
  for (int step = 0; step < substeps; ++step) {
    forEach(list.size(), kBodyGrain, [&](size_t begin, size_t end) {
      for (size_t j = begin; j < end; ++j) {  // kick and warm start
        const uint32_t i = list[j];
        SoftBody& b = bodies[i];
        b.vx += kick[i].vx + warm[i].vx;
        b.vy += kick[i].vy + warm[i].vy;
        b.w += kick[i].w + warm[i].w;
        warm[i] = {0.0, 0.0, 0.0, 0.0};
      }
    });
    forEachJoint([&](Joint& j, const JointBodies& jb) { warmStartJoint(j, jb); });
    forEachJoint([&](Joint& j, const JointBodies& jb) { solveJoint(j, jb, joint_step, true); });
    runPass(std::true_type{}, step, nullptr);
    forEach(list.size(), kBodyGrain, [&](size_t begin, size_t end) {
     for (size_t j = begin; j < end; ++j) {  // move
      const uint32_t i = list[j];
      SoftBody& b = bodies[i];
      b.dx += h * b.vx;
      b.dy += h * b.vy;
      angle[i] += h * b.w;
      // q ← normalise(q + hω q⊥): the rotation by hω to second order (Box2D v3 b2IntegrateRotation).
      const double c = b.qc - h * b.w * b.qs, s = b.qs + h * b.w * b.qc;
      const double inv = 1.0 / std::sqrt(c * c + s * s);
      b.qc = c * inv;
      b.qs = s * inv;
     }
    });
    std::vector<SoftKick>* next = step + 1 < substeps ? &warm : nullptr;
    forEachJoint([&](Joint& j, const JointBodies& jb) { solveJoint(j, jb, joint_step, false); });  // relax
    runPass(std::false_type{}, step, next);
  }
  for (size_t g = 0; g < groups.size(); ++g)
    for (int l = 0; l < L; ++l)
      if (groups[g].bounce[l])
        restitute(bodies, groups[g], l, tallies[g * L + l], totals[g], ctx.settings.restitution_threshold, substeps,
                  groups[g].surface ? surfaces[g].tangent_speed[l] : 0.0);

  // Write back: impulses for warm starting and reports; bodies that some impulse acted on take the
  // sub-stepped state, the others keep the integrator's.
  // Counts and bodies from the lanes: the Contact is written, not read.
  const auto writeBack = [&](size_t k) {
    prefetchWriteBack(w, own, k, 8);
    const uint32_t at = own.slot[k];
    const SoftLanes& sc = groups[at / L];
    const int l = static_cast<int>(at % L);
    const SoftTotals& t = totals[at / L];
    ContactPoint* points = w.contacts[w.soft_solved[k]].points;
    for (int i = 0; i < sc.count[l]; ++i) {
      ContactPoint& cp = points[i];
      cp.normal_impulse = sc.pn[i][l];
      cp.tangent_impulse = sc.pt[i][l];
      cp.step_normal_impulse = t.n[i][l];
      cp.step_tangent_impulse = t.t[i][l];
    }
  };
  const auto markPushed = [&](size_t k) {  // several contacts may mark one body: serially
    const uint32_t at = own.slot[k];
    const SoftLanes& sc = groups[at / L];
    const int l = static_cast<int>(at % L);
    if (!sc.acted[l]) return;
    if (moved[sc.a[l]]) moved[sc.a[l]] = 2;
    if (moved[sc.b[l]]) moved[sc.b[l]] = 2;
  };
  if (!pool) {
    for (size_t k = 0; k < w.soft_solved.size(); ++k) {
      writeBack(k);
      markPushed(k);
    }
  } else {
    pool->parallelFor(w.soft_solved.size(), kContactGrain, [&](size_t begin, size_t end) {
      for (size_t k = begin; k < end; ++k) writeBack(k);
    });
    for (size_t k = 0; k < w.soft_solved.size(); ++k) markPushed(k);
  }
  forEach(list.size(), kBodyGrain, [&](size_t begin, size_t end) {
    for (size_t j = begin; j < end; ++j) {
      const uint32_t i = list[j];
      if (moved[i] != 2 || !w.bodies[i].isDynamic()) continue;  // kinematic bodies keep the integrator's
      Body& b = w.bodies[i];
      const SoftBody& s = bodies[i];
      b.center += Vec2(s.dx, s.dy);
      b.angle += angle[i];
      b.velocity = Vec2(s.vx, s.vy);
      b.angular_velocity = s.w;
      WorldImpl::syncTransform(b);
    }
  });
}

}  // namespace rigidlab
