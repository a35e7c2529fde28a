// Contact constraints: one per touching pair, up to two points, solved by sequential impulses
// (contact_solver.cpp) and then separated (position_correction.cpp).
#pragma once

#include <cstdint>

#include "manifold.h"

namespace rigidlab {

// Kept small and packed (no padding between fields): every stage from the narrow phase on walks the
// whole array, and a pile of 12 500 contacts is several megabytes, so each byte is paid for in cache
// misses several times per step (callgrind/perf, pyramid of base 100). What only sequential
// impulses need (anchors, effective masses, target velocities, the 2×2 K) lives in their
// SolverPrepared and SolverContact, not here: the soft step's contacts never need it.
// Unaligned 2-vectors: an aligned Vec2 pads ContactPoint to 128 bytes and Contact to 336.
using Vec2u = Eigen::Matrix<double, 2, 1, Eigen::DontAlign>;

struct ContactPoint {
  Vec2u point = Vec2::Zero();     // world [m]
  double separation = 0.0;        // [m] < 0 overlap
  uint32_t id = 0;                // feature id (manifold.h)
  bool persisted = false;         // the same features touched in the previous step
  // Sequential impulses aimed at a separating normal velocity this step (restitution,
  // contact_solver.cpp): its impulse was an impact's, which says nothing about the next step's
  // contact force, so the next step does not start from it (narrow_phase.cpp).
  bool bounced = false;
  double normal_impulse = 0.0;    // accumulated, ≥ 0 [N·s]; the next step starts from it (the soft
                                  //   step's is that of its last sub-step)
  double tangent_impulse = 0.0;   // accumulated, |·| ≤ friction · normal_impulse [N·s]
  double step_normal_impulse = 0.0;   // what the step applied in all [N·s] (World::contacts)
  double step_tangent_impulse = 0.0;
};

struct Contact {
  uint32_t a = 0, b = 0;  // body slots
  uint32_t shape_a = 0, shape_b = 0;  // shape slots: the contact's key (shape_a < shape_b)
  int count = 0;
  bool block = false;     // sequential impulses solve the two points together (contact_solver.cpp)
  // Events (contact_events.cpp): the shapes touch (from the first step a point overlapped until the
  // contact ends, so that a resting contact does not flicker); a one-way platform let the other
  // shape through, and keeps doing so until the contact ends (pre_solve.cpp).
  bool touching = false;
  bool passing = false;
  Vec2u normal = Vec2::Zero();
  ContactPoint points[2];
  double restitution = 0.0;
  double friction = 0.0;         // combined dynamic friction
  double static_friction = 0.0;  // combined static friction
  double slop = 0.0;             // penetration left alone by the position pass [m]
};
static_assert(sizeof(ContactPoint) <= 64 && sizeof(Contact) <= 208, "packed: see the comment above ContactPoint");

// Overlap beyond a contact's slop that keeps its bodies awake [m] (sleep.cpp).
constexpr double kDeepOverlapMargin = 0.005;

// Per contact, in the same order as WorldImpl::contacts: what the walks that need only the bodies
// read (choosing the solvers, islands, sleep), so that they do not load each 200-byte Contact again
// (a pile of 16 000 contacts is 6 MB, far beyond the cache). Written by the narrow phase.
struct ContactKey {
  uint32_t a, b;      // body slots
  uint8_t count;      // contact points
  bool deep_overlap;  // some point overlaps by more than slop + kDeepOverlapMargin
  bool disabled;      // by a one-way platform or a pre-solve callback, for this step (pre_solve.cpp)
};

// A solved contact's bodies, noted once when the solvers are chosen (contact_solver.cpp), so that
// the loops that only need them do not load the Contact again (each load of a large pile's
// contacts misses the cache).
struct SolvedRef {
  uint32_t a, b;   // body slots
  uint8_t count;   // contact points
  uint8_t active;  // bit 0: A is awake and dynamic (WorldImpl::isActive), bit 1: B
};

// The contact solver's working copies: its iterations read and write only these, in plain doubles
// (contact_solver.cpp), and its prepare step writes them directly. A SolverContact is about half a
// Contact, so a pass stays in cache and takes about half the instructions (callgrind, pyramid of
// base 40). Impulses are copied back to the Contacts afterwards, for warm starting and drawing.
struct SolverPoint {
  double rax, ray, rbx, rby;  // lever arms r_A, r_B
  double normal_mass, tangent_mass, target, friction;
  double pn, pt;              // accumulated impulses
};

// A contact's surface effects (ShapeDef::tangent_speed, rolling_resistance), for the contacts that
// have them: kept out of the contacts themselves, which piles stream through every pass.
struct ContactSurface {
  double tangent_speed = 0.0;       // the relative tangent velocity friction aims for [m/s]
  double rolling_resistance = 0.0;  // the rolling torque's bound per unit of normal force [m]
  bool any() const { return tangent_speed != 0.0 || rolling_resistance > 0.0; }
};

// Sequential impulses' working copy of a contact's surface effects (SolverContact::surface).
struct SolverSurface {
  double tangent_speed, rolling, rolling_mass, rolling_impulse;
};
constexpr uint32_t kNoSurface = UINT32_MAX;

struct SolverContact {
  uint32_t a, b;
  uint8_t count;
  bool block;
  uint32_t surface;  // index into WorldImpl::solver_surfaces, or kNoSurface (in what was padding)
  double nx, ny;
  double k11, k12, k22, i11, i12, i22;  // K and K⁻¹ of a block contact
  SolverPoint p[2];
};

// What the solver's prepare step finds that only its iterations need, per solved contact: kept out
// of the Contact, which every stage walks, and copied into the SolverContact.
struct SolverPrepared {
  Vec2 ra[2] = {Vec2::Zero(), Vec2::Zero()};  // from A's centre of mass to each point [m]
  Vec2 rb[2] = {Vec2::Zero(), Vec2::Zero()};  // from B's
  double target_velocity[2] = {0.0, 0.0};     // normal relative velocity the solver aims for (restitution) [m/s]
  double overlap_time[2] = {0.0, 0.0};        // how long the point has overlapped this step [s] (position_correction.cpp)
  double friction[2] = {0.0, 0.0};            // f_s or f_d, chosen from the slip at the start of the step
  double normal_mass[2] = {0.0, 0.0}, tangent_mass[2] = {0.0, 0.0};
  double k11 = 0.0, k12 = 0.0, k22 = 0.0, i11 = 0.0, i12 = 0.0, i22 = 0.0;  // K and K⁻¹ of a block contact
  // For the nonlinear position pass (position_correction.cpp), in body coordinates at detection
  // (nothing has moved the bodies between the narrow phase and this): the normal in A's, and the
  // points on A's and B's surfaces, p ∓ (s/2) n.
  Vec2 local_normal = Vec2::Zero();
  Vec2 local_a[2] = {Vec2::Zero(), Vec2::Zero()}, local_b[2] = {Vec2::Zero(), Vec2::Zero()};
};

struct SolverBody {  // velocity and inverse mass of a body, as plain doubles
  double vx, vy, w, im, ii;
};

// The soft step's working copies (soft_step.cpp). Positions are tracked relative to the state in
// which the contacts were found, so that a point's separation can be updated without collision
// detection: s = s₀ + (Δc_B + q_B r_B − Δc_A − q_A r_A)·n with the normal held fixed.
struct SoftBody {
  double vx, vy, w;    // velocity
  double dx, dy;       // centre minus the centre at detection [m]
  double qc, qs;       // rotation since detection (cos, sin)
  double im, ii;       // inverse mass and inertia; 0 for static and sleeping bodies
};

struct SoftKick {  // a velocity change of a body; four doubles, so the vector passes read and write it whole
  double vx, vy, w, unused;
};

// Contacts solved side by side: kSoftLanes contacts of one colour, which share no moving body
// (soft_step.cpp colours them), so the processor can work on all of them at once. Fields are
// arrays over the lanes; points 0 and 1 of each contact are the first index where there are two.
// What every pass reads and writes: 944 bytes for 4 contacts, so a pass over a hundred-row pyramid
// (16 000 contacts) streams 3.8 MB.
constexpr int kSoftLanes = 4;
struct SoftLanes {
  static constexpr int L = kSoftLanes;
  uint32_t a[L], b[L];  // body slots
  uint8_t count[L];     // contact points; 0 for an empty lane
  uint8_t block[L];     // two points solved together: K = [[k[0], k12], [k12, k[1]]]
  uint8_t bounce[L];    // restitution > 0: record impact speeds
  bool serial;          // lanes may share a body (contacts left over by the colouring): one by one
  enum : uint8_t { kNoBlock, kSomeBlocks, kAllBlock };
  uint8_t blocks;       // how many lanes are block contacts (empty lanes count as block)
  uint8_t points;       // the most contact points of any lane
  uint8_t surface;      // some lane has surface effects: its group's SoftSurfaceLanes (in what was padding)
  int64_t acted[L];     // not 0: some impulse was non-zero during the step (a vector mask, or'ed per pass)
  double nx[L], ny[L];
  int64_t stiff[L];     // −1: the stiffer softness (a static or sleeping body), 0: the soft one
  double k12[L];
  double rax[2][L], ray[2][L], rbx[2][L], rby[2][L];  // anchors: the point from each centre at detection [m]
  double base[2][L];                   // separation at detection − (r_B − r_A)·n [m]
  double k[2][L];                      // K = 1/m_n = 1/m_A + 1/m_B + (r_A×n)²/I_A + (r_B×n)²/I_B
  double inv_k[2][L];                  // 1/K
  double inv_det[L];                   // block contacts: 1/det K (the relax pass's matrix)
  double tangent_mass[2][L], friction[2][L];
  double pn[2][L], pt[2][L];           // impulses of the current sub-step, warm-started [N·s]
};

// Per group of SoftLanes, when some soft contact has surface effects (ContactSurface): the lanes'
// tangent speeds, rolling resistances (bound per unit normal impulse [m]), rolling masses
// 1/(1/I_A + 1/I_B) and the rolling impulse of the current sub-step; zero in the other lanes.
struct SoftSurfaceLanes {
  double tangent_speed[kSoftLanes], rolling[kSoftLanes], rolling_mass[kSoftLanes], rolling_impulse[kSoftLanes];
};

// Per group of SoftLanes: the impulses applied during the step [N·s], for reports. Lanes side by
// side, so that the relax pass adds a group's four contacts in one go.
struct SoftTotals {
  double n[2][kSoftLanes], t[2][kSoftLanes];
};

// Per contact, touched once per sub-step or less: what restitution needs.
struct SoftTally {
  double approach[2];             // normal velocity when the point first pushed (< 0 closing) [m/s]
  double kick[2];                 // normal velocity the step's forces add per sub-step [m/s]
  int impact[2];                  // sub-step of that first push, −1 before it
  double restitution;
};

}  // namespace rigidlab
