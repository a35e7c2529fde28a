// The coordinates of a mechanism (mechanism.h): value, rate, Jacobian and J̇ v of each measure.
//
// Between bodies A and B with anchors r = R(θ) s from the centres of mass, the anchors' separation
// d = P_B − P_A moves as
//   ḋ = v_B + ω_B × r_B − v_A − ω_A × r_A,     d̈ = (terms linear in a, α) + k,   k = ω_A² r_A − ω_B² r_B
// (ω × r = ω r⊥ with r⊥ = (−r_y, r_x); (ω × (ω × r)) = −ω² r). With x = measure, ẍ = J a + J̇ v:
//   point x, y   x = d_x, d_y;   J_A = (−1, 0, r_Ay), (0, −1, −r_Ax),  J_B = (1, 0, −r_By), (0, 1, r_Bx)
//                J̇ v = k_x, k_y
//   angle        x = θ_B − θ_A − θ_ref;  J_A = (0, 0, −1), J_B = (0, 0, 1);  J̇ v = 0
//   axis         x = n · d with n = R(θ_A) n₀ turning with A (ṅ = ω_A n⊥):
//                J_A = (−n, −(d + r_A) × n), J_B = (n, r_B × n)
//                J̇ v = n · k + 2 ω_A n⊥ · ḋ − ω_A² n · d
//   distance     x = |d|, u = d/|d|:  J_A = (−u, −r_A × u), J_B = (u, r_B × u)
//                J̇ v = u · k + (|ḋ|² − (u · ḋ)²)/|d|
// Rotations R(θ) come from the caller, one per body and state (rotationsOf: a sine and a cosine
// that every machine rounds alike, portable_math.h), not one per measure.
// The same sign conventions as the joints' rows (joint_rows.cpp): a multiplier λ on a row pulls B
// by +λ J_B and A by λ J_A, so a row's λ is the joint's force on B along it.
#include <cmath>

#include "mechanism.h"

namespace rigidlab::mechanism {
namespace {

Vec2 perp(const Vec2& r) { return Vec2(-r.y(), r.x()); }

// One term, into its two Jacobian blocks (A, B), value, rate and J̇ v.
struct TermValue {
  double x, xdot, jdotv;
  Eigen::Vector3d ja, jb;
};

TermValue evaluateTerm(const Term& t, const State* states, const Rot* rotations) {
  const State& A = states[t.a];
  const State& B = states[t.b];
  TermValue out;
  if (t.measure == Measure::Angle) {
    out.x = B.angle - A.angle - t.offset;
    out.xdot = B.w - A.w;
    out.jdotv = 0.0;
    out.ja = Eigen::Vector3d(0.0, 0.0, -1.0);
    out.jb = Eigen::Vector3d(0.0, 0.0, 1.0);
    return out;
  }
  const Vec2 ra = rotations[t.a].apply(t.sa), rb = rotations[t.b].apply(t.sb);
  const Vec2 d = (B.c + rb) - (A.c + ra);
  const Vec2 ddot = B.v + B.w * perp(rb) - A.v - A.w * perp(ra);
  const Vec2 k = A.w * A.w * ra - B.w * B.w * rb;
  // A direction u through the anchors (lever arms la on A, rb on B): J_A = (−u, −la × u), J_B = (u, rb × u).
  const auto along = [&](const Vec2& u, const Vec2& la) {
    out.ja = Eigen::Vector3d(-u.x(), -u.y(), -cross(la, u));
    out.jb = Eigen::Vector3d(u.x(), u.y(), cross(rb, u));
  };
  switch (t.measure) {
    case Measure::PointX:
      out.x = d.x();
      out.xdot = ddot.x();
      out.jdotv = k.x();
      along(Vec2(1.0, 0.0), ra);
      break;
    case Measure::PointY:
      out.x = d.y();
      out.xdot = ddot.y();
      out.jdotv = k.y();
      along(Vec2(0.0, 1.0), ra);
      break;
    case Measure::Axis: {
      const Vec2 n = rotations[t.a].apply(t.axis);
      out.x = n.dot(d);
      out.xdot = n.dot(ddot) + A.w * perp(n).dot(d);
      out.jdotv = n.dot(k) + 2.0 * A.w * perp(n).dot(ddot) - A.w * A.w * n.dot(d);
      along(n, d + ra);
      break;
    }
    case Measure::Distance: {
      const double length = d.norm();
      // Coincident anchors have no direction: the measure is then taken along x (a rigid distance
      // of zero is a pin, which the joint makes of point rows instead).
      const Vec2 u = length > 0.0 ? Vec2(d / length) : Vec2(1.0, 0.0);
      out.x = length;
      out.xdot = u.dot(ddot);
      const double across = ddot.squaredNorm() - out.xdot * out.xdot;
      out.jdotv = u.dot(k) + (length > 0.0 ? std::max(across, 0.0) / length : 0.0);
      along(u, ra);
      break;
    }
    case Measure::Angle: break;
  }
  return out;
}

void add(Evaluated& e, uint32_t body, const Eigen::Vector3d& j) {
  for (int i = 0; i < e.count; ++i)
    if (e.body[i] == body) {
      e.j[i] += j;
      return;
    }
  e.body[e.count] = body;
  e.j[e.count++] = j;
}

// A pin's two point terms (the same bodies and anchors) at once: what evaluate() gives for each,
// with the anchors, their separation and its rates computed once.
void pinRows(const Term& t, const State* states, const Rot* rotations, Evaluated& ex, Evaluated& ey) {
  const State& A = states[t.a];
  const State& B = states[t.b];
  const Vec2 ra = rotations[t.a].apply(t.sa), rb = rotations[t.b].apply(t.sb);
  const Vec2 d = (B.c + rb) - (A.c + ra);
  const Vec2 ddot = B.v + B.w * perp(rb) - A.v - A.w * perp(ra);
  const Vec2 k = A.w * A.w * ra - B.w * B.w * rb;
  const auto fill = [&](Evaluated& e, const Vec2& u, double x, double xdot, double jdotv) {
    // As evaluate() sums its one term of weight 1 into zeros (0 + x: the same bits, −0 made +0).
    e.x = 0.0 + x;
    e.xdot = 0.0 + xdot;
    e.jdotv = 0.0 + jdotv;
    e.count = 2;
    e.body[0] = t.a;
    e.body[1] = t.b;
    e.j[0] = Eigen::Vector3d(-u.x(), -u.y(), -cross(ra, u));
    e.j[1] = Eigen::Vector3d(u.x(), u.y(), cross(rb, u));
  };
  fill(ex, Vec2(1.0, 0.0), d.x(), ddot.x(), k.x());
  fill(ey, Vec2(0.0, 1.0), d.y(), ddot.y(), k.y());
}

}  // namespace

bool isPinPair(const Coordinate& x, const Coordinate& y) {
  if (x.terms != 1 || y.terms != 1) return false;
  const Term& a = x.term[0];
  const Term& b = y.term[0];
  return a.measure == Measure::PointX && b.measure == Measure::PointY && a.weight == 1.0 && b.weight == 1.0 &&
         a.a == b.a && a.b == b.b && a.a != a.b && a.sa == b.sa && a.sb == b.sb;
}

void evaluatePin(const Coordinate& x, const State* states, const Rot* rotations, Evaluated& ex, Evaluated& ey) {
  pinRows(x.term[0], states, rotations, ex, ey);
}

void rotationsOf(const std::vector<State>& states, std::vector<Rot>& out) {
  out.resize(states.size());
  for (size_t k = 0; k < states.size(); ++k) out[k] = Rot::fromAngle(states[k].angle);
}

Evaluated evaluate(const Coordinate& c, const State* states, const Rot* rotations) {
  Evaluated e;
  if (c.terms == 1 && c.term[0].weight == 1.0 && c.term[0].a != c.term[0].b) {
    // One term of weight 1 on two bodies (nearly every row): the sums below without their loops,
    // the same bits (0 + 1 · x is 0 + x; 1 · j is j).
    const Term& t = c.term[0];
    const TermValue v = evaluateTerm(t, states, rotations);
    e.x = 0.0 + v.x;
    e.xdot = 0.0 + v.xdot;
    e.jdotv = 0.0 + v.jdotv;
    e.count = 2;
    e.body[0] = t.a;
    e.body[1] = t.b;
    e.j[0] = v.ja;
    e.j[1] = v.jb;
    return e;
  }
  for (int k = 0; k < c.terms; ++k) {
    const Term& t = c.term[k];
    const TermValue v = evaluateTerm(t, states, rotations);
    e.x += t.weight * v.x;
    e.xdot += t.weight * v.xdot;
    e.jdotv += t.weight * v.jdotv;
    add(e, t.a, t.weight * v.ja);
    add(e, t.b, t.weight * v.jb);
  }
  return e;
}

}  // namespace rigidlab::mechanism
