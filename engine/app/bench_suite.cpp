// Box2D v3's own benchmark suite, built in rigidlab: the same bodies, shapes, joints, materials,
// filters and step counts as its benchmark program creates (docs/performance.md "The Box2D v3
// suite" lists what each scene is for and the few places where rigidlab's vocabulary differs).
// Every scene reports the same engine-neutral figures (suiteMetrics), which the Box2D v3 peer
// program computes the same way, so quality is compared beside speed.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include "bench_scenes.h"
#include "rigidlab/portable_math.h"

namespace rigidlab::app {
namespace {

constexpr double kPi = std::numbers::pi;

BodyId addBody(World& w, BodyType type, Vec2 position, double linear_damping = 0.0, bool awake = true) {
  BodyDef d;
  d.type = type;
  d.position = position;
  d.linear_damping = linear_damping;
  d.awake = awake;
  return w.createBody(d);
}

ShapeId addShape(World& w, BodyId body, Shape shape, double density = 1.0, double friction = 0.6,
                 double restitution = 0.0, Filter filter = {}) {
  ShapeDef s;
  s.shape = std::move(shape);
  s.density = density;
  s.material.friction = friction;
  s.material.static_friction = friction;
  s.material.restitution = restitution;
  s.filter = filter;
  return w.createShape(body, s);
}

WorldDef suiteWorld(bool sleeping) {
  WorldDef def = benchSettings();
  def.gravity = Vec2(0.0, -10.0);
  def.sleeping = sleeping;
  return def;
}

BenchWorld emptyBench(bool sleeping) {
  BenchWorld b;
  b.world = std::make_unique<World>(suiteWorld(sleeping));
  return b;
}

// 100 × 100 discs (radius 0.4, 1 m apart) pinned to their neighbours by revolute joints, hanging
// from 7 static discs in the middle of the top row; discs do not collide with each other.
BenchWorld jointGrid() {
  BenchWorld b = emptyBench(false);
  World& w = *b.world;
  const int n = 100;
  Filter filter;
  filter.category = 2;
  filter.mask = ~uint64_t{2};
  std::vector<BodyId> bodies;
  bodies.reserve(n * n);
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < n; ++i) {
      const bool pinned = k >= n / 2 - 3 && k <= n / 2 + 3 && i == 0;
      const BodyId body = addBody(w, pinned ? BodyType::Static : BodyType::Dynamic, Vec2(k, -i));
      addShape(w, body, makeCircle(0.4), 1.0, 0.6, 0.0, filter);
      JointDef j;
      j.type = JointType::Revolute;
      // Box2D also joins the 7 static discs to each other (6 joints that do nothing); rigidlab
      // refuses a joint without a dynamic body, so those are left out.
      const bool left_pinned = k - 1 >= n / 2 - 3 && k - 1 <= n / 2 + 3 && i == 0;
      if (i > 0) {
        j.a = bodies.back();
        j.b = body;
        j.anchor_a = Vec2(k, -i + 0.5);
        w.createJoint(j);
      }
      if (k > 0 && !(pinned && left_pinned)) {
        j.a = bodies[bodies.size() - n];
        j.b = body;
        j.anchor_a = Vec2(k - 0.5, -i);
        w.createJoint(j);
      }
      bodies.push_back(body);
    }
  }
  return b;
}

// Box2D v3's large_pyramid: base 100 of 1 m boxes on a 200 m ground box (rigidlab's pyramid100
// with the peers' ground, 500 steps).
BenchWorld largePyramid() {
  BenchWorld b = emptyBench(false);
  World& w = *b.world;
  addShape(w, addBody(w, BodyType::Static, Vec2(0.0, -1.0)), makeBox(200.0, 2.0));
  const int base = 100;
  const double a = 0.5;
  for (int i = 0; i < base; ++i)
    for (int j = i; j < base; ++j)
      addShape(w, addBody(w, BodyType::Dynamic, Vec2((i + 1.0) * a + 2.0 * (j - i) * a - a * base, (2.0 * i + 1.0) * a)),
               makeBox(1.0, 1.0));
  return b;
}

// 20 rows × 20 columns of pyramids of base 10 (55 boxes each, 22 000 boxes), each row on its own
// ground segment.
BenchWorld manyPyramids() {
  BenchWorld b = emptyBench(false);
  World& w = *b.world;
  const int base = 10, rows = 20, columns = 20;
  const double extent = 0.5;
  const BodyId ground = addBody(w, BodyType::Static, Vec2::Zero());
  const double ground_dy = 2.0 * extent * (base + 1.0), ground_width = 2.0 * extent * columns * (base + 1.0);
  for (int i = 0; i < rows; ++i)
    addShape(w, ground, makeSegment(Vec2(-0.5 * ground_width, i * ground_dy), Vec2(0.5 * ground_width, i * ground_dy)));
  const double base_width = 2.0 * extent * base;
  for (int r = 0; r < rows; ++r) {
    const double base_y = r * ground_dy;
    for (int c = 0; c < columns; ++c) {
      const double center_x = -0.5 * ground_width + c * (base_width + 2.0 * extent) + 2.0 * extent;
      for (int i = 0; i < base; ++i)
        for (int j = i; j < base; ++j)
          addShape(w,
                   addBody(w, BodyType::Dynamic,
                           Vec2((i + 1.0) * extent + 2.0 * (j - i) * extent + center_x - 0.5, (2.0 * i + 1.0) * extent + base_y)),
                   makeBox(2 * extent, 2 * extent));
    }
  }
  return b;
}

// Box2D v3's ragdoll ("human"): 11 capsule bones, 10 revolute joints with limits, a friction motor
// and a soft spring towards the rest pose. Same-index humans of different groups share a negative
// group (they never collide); feet touch only the ground.
struct Human {
  std::vector<BodyId> bones;
};

Human addHuman(World& w, Vec2 position, int group) {
  const double s = 1.0, friction_torque = 0.05, hertz = 5.0, damping = 0.5;
  Filter body_filter;
  body_filter.group = -group;
  body_filter.category = 2;
  body_filter.mask = 1 | 2;
  Filter foot_filter = body_filter;
  foot_filter.mask = 1;
  Human h;
  // bone: centre height, capsule ends and radius, parent, pivot height, limits (× π), friction scale,
  // linear damping, reference angle.
  struct Bone {
    double y, y0, y1, r;
    int parent;
    double pivot, lower, upper, friction_scale, damping, reference;
    bool foot;
  };
  static const Bone kBones[] = {
      {0.95, -0.02, 0.02, 0.095, -1, 0, 0, 0, 1.0, 0.0, 0, false},              // hip
      {1.2, -0.135, 0.135, 0.09, 0, 1.0, -0.25, 0.0, 0.5, 0.0, 0, false},       // torso
      {1.475, -0.038, 0.039, 0.075, 1, 1.4, -0.3, 0.1, 0.25, 0.1, 0, false},    // head
      {0.775, -0.125, 0.125, 0.06, 0, 0.9, -0.05, 0.4, 1.0, 0.0, 0, false},     // upper left leg
      {0.475, -0.155, 0.125, 0.045, 3, 0.625, -0.5, -0.02, 0.5, 0.0, 0, true},  // lower left leg
      {0.775, -0.125, 0.125, 0.06, 0, 0.9, -0.05, 0.4, 1.0, 0.0, 0, false},     // upper right leg
      {0.475, -0.155, 0.125, 0.045, 5, 0.625, -0.5, -0.02, 0.5, 0.0, 0, true},  // lower right leg
      {1.225, -0.125, 0.125, 0.035, 1, 1.35, -0.1, 0.8, 0.5, 0.0, 0, false},    // upper left arm
      {0.975, -0.125, 0.125, 0.03, 7, 1.1, -0.2, 0.3, 0.1, 0.1, 0.25, false},  // lower left arm
      {1.225, -0.125, 0.125, 0.035, 1, 1.35, -0.1, 0.8, 0.5, 0.0, 0, false},    // upper right arm
      {0.975, -0.125, 0.125, 0.03, 9, 1.1, -0.2, 0.3, 0.1, 0.1, 0.25, false},  // lower right arm
  };
  const Vec2 foot[4] = {{-0.03 * s, -0.185 * s}, {0.11 * s, -0.185 * s}, {0.11 * s, -0.16 * s}, {-0.03 * s, -0.14 * s}};
  for (const Bone& bone : kBones) {
    const BodyId body = addBody(w, BodyType::Dynamic, position + Vec2(0.0, bone.y * s), bone.damping);
    addShape(w, body, makeCapsule(Vec2(0.0, bone.y0 * s), Vec2(0.0, bone.y1 * s), bone.r * s), 1.0, 0.2, 0.0, body_filter);
    if (bone.foot) addShape(w, body, makePolygon(foot), 1.0, 0.05, 0.0, foot_filter);
    if (bone.parent >= 0) {
      JointDef j;
      j.type = JointType::Revolute;
      j.a = h.bones[bone.parent];
      j.b = body;
      j.anchor_a = position + Vec2(0.0, bone.pivot * s);
      // Box2D turns the lower arms' frame on the upper arm by π/4: joint angle 0 (the spring's
      // rest, the limits' origin) is the elbow bent by π/4.
      j.reference_angle = bone.reference * kPi;
      j.enable_limit = true;
      j.lower = bone.lower * kPi;
      j.upper = bone.upper * kPi;
      j.enable_motor = true;
      j.max_motor_torque = bone.friction_scale * friction_torque * s;
      j.enable_spring = true;
      j.spring_hertz = hertz;
      j.spring_damping = damping;
      w.createJoint(j);
    }
    h.bones.push_back(body);
  }
  return h;
}

// Box2D v3's rain: ragdolls in groups of 5 rain onto 5 floors of 501 small static boxes, a column of
// groups (one per floor) every 8 steps; after `columns` columns (the suite's 40: 11 000 bodies at
// most) the oldest column is removed as a new one falls.
BenchWorld ragdollRain(int columns) {
  BenchWorld b = emptyBench(true);
  World& w = *b.world;
  constexpr int kRows = 5, kGroup = 5, kGridCount = 500;
  constexpr double kGrid = 0.5;
  const BodyId ground = addBody(w, BodyType::Static, Vec2::Zero());
  for (int i = 0; i < kRows; ++i) {
    double x = -0.5 * kGridCount * kGrid;
    for (int j = 0; j <= kGridCount; ++j, x += kGrid) addShape(w, ground, makeBox(kGrid, kGrid, Vec2(x, 45.0 * i)));
  }
  struct Rain {
    int columns;
    std::vector<std::vector<Human>> groups = std::vector<std::vector<Human>>(kRows * columns);
    int column_count = 0, column_index = 0;
  };
  auto rain = std::make_shared<Rain>(Rain{columns});
  const auto create = [rain](World& world, int row, int column) {
    const double span = kGridCount * kGrid, distance = span / rain->columns;
    Vec2 p(-0.5 * span + distance * (column + 0.5), 40.0 + 45.0 * row);
    std::vector<Human>& g = rain->groups[row * rain->columns + column];
    for (int i = 0; i < kGroup; ++i, p.x() += 0.5) g.push_back(addHuman(world, p, i + 1));
  };
  b.before_step = [rain, create](World& world, int step) {
    if ((step & 7) != 0) return;
    if (rain->column_count < rain->columns) {
      for (int i = 0; i < kRows; ++i) create(world, i, rain->column_count);
      ++rain->column_count;
      return;
    }
    for (int i = 0; i < kRows; ++i) {
      std::vector<Human>& g = rain->groups[i * rain->columns + rain->column_index];
      for (const Human& h : g)
        for (BodyId bone : h.bones) world.destroyBody(bone);  // its joints go with it
      g.clear();
      create(world, i, rain->column_index);
    }
    rain->column_index = (rain->column_index + 1) % rain->columns;
  };
  return b;
}

// Box2D v3's smash: a heavy 8 m box at 40 m/s into a wall of 120 × 80 small boxes created asleep,
// without gravity.
BenchWorld smash() {
  BenchWorld b = emptyBench(true);
  World& w = *b.world;
  w.setGravity(Vec2::Zero());
  {
    BodyDef d;
    d.position = Vec2(-20.0, 0.0);
    d.velocity = Vec2(40.0, 0.0);
    addShape(w, w.createBody(d), makeBox(8.0, 8.0), 8.0);
  }
  const double size = 0.4;
  const int columns = 120, rows = 80;
  for (int i = 0; i < columns; ++i)
    for (int j = 0; j < rows; ++j)
      addShape(w, addBody(w, BodyType::Dynamic, Vec2(i * size + 30.0, (j - rows / 2.0) * size), 0.0, false),
               makeBox(size, size));
  return b;
}

// Box2D v3's spinner: 6076 capsules, discs and squares in a 40 m ring (a closed chain of 360
// points) stirred by a 40 m paddle on a motor (5 rad/s, unlimited torque). Box2D's paddle is a box
// rounded by 0.2 m; rigidlab's polygons are not rounded, so here it is the box that encloses it.
BenchWorld spinner() {
  BenchWorld b = emptyBench(true);
  World& w = *b.world;
  const BodyId ground = addBody(w, BodyType::Static, Vec2::Zero());
  {
    constexpr int kPoints = 360;
    World::ChainDef chain;
    for (int i = 0; i < kPoints; ++i) {
      // portableCos and portableSin (what a Lua scene's math.cos and math.sin are): the same bits on
      // every machine, where the C library's differ in the last bit with the processor.
      const double t = -2.0 * kPi * i / kPoints;
      chain.points.push_back(Vec2(40.0 * portableCos(t), 40.0 * portableSin(t) + 32.0));
    }
    chain.loop = true;
    chain.material.friction = chain.material.static_friction = 0.1;
    w.createChain(ground, chain);
  }
  const BodyId paddle = addBody(w, BodyType::Dynamic, Vec2(0.0, 12.0));
  addShape(w, paddle, makeBox(2.0 * (0.4 + 0.2), 2.0 * (20.0 + 0.2)), 1.0, 0.0);
  JointDef j;
  j.type = JointType::Revolute;
  j.a = ground;
  j.b = paddle;
  j.anchor_a = Vec2(0.0, 12.0);
  j.enable_motor = true;
  j.motor_speed = 5.0;
  j.max_motor_torque = std::numeric_limits<double>::infinity();
  w.createJoint(j);
  const int count = 2 * 3038;
  double x = -23.0, y = 2.0;
  for (int i = 0; i < count; ++i) {
    const BodyId body = addBody(w, BodyType::Dynamic, Vec2(x, y));
    Shape shape = i % 3 == 0 ? makeCapsule(Vec2(-0.25, 0.0), Vec2(0.25, 0.0), 0.25)
                  : i % 3 == 1 ? makeCircle(0.35)
                               : makeBox(0.7, 0.7);
    addShape(w, body, std::move(shape), 0.25, 0.1, 0.1);
    x += 0.5;
    if (x >= 23.0) {
      x = -23.0;
      y += 0.5;
    }
  }
  return b;
}

// Box2D v3's tumbler: a 20 m box drum of four walls (density 50) turned at 25°/s by a motor,
// tumbling 45 × 45 small boxes.
BenchWorld tumbler() {
  BenchWorld b = emptyBench(true);
  World& w = *b.world;
  const BodyId ground = addBody(w, BodyType::Static, Vec2::Zero());
  const BodyId drum = addBody(w, BodyType::Dynamic, Vec2(0.0, 10.0));
  addShape(w, drum, makeBox(1.0, 20.0, Vec2(10.0, 0.0)), 50.0);
  addShape(w, drum, makeBox(1.0, 20.0, Vec2(-10.0, 0.0)), 50.0);
  addShape(w, drum, makeBox(20.0, 1.0, Vec2(0.0, 10.0)), 50.0);
  addShape(w, drum, makeBox(20.0, 1.0, Vec2(0.0, -10.0)), 50.0);
  JointDef j;
  j.type = JointType::Revolute;
  j.a = ground;
  j.b = drum;
  j.anchor_a = Vec2(0.0, 10.0);
  j.enable_motor = true;
  j.motor_speed = kPi / 180.0 * 25.0;
  j.max_motor_torque = 1e8;
  w.createJoint(j);
  const int grid = 45;
  double y = -0.2 * grid + 10.0;
  for (int i = 0; i < grid; ++i, y += 0.4) {
    double x = -0.2 * grid;
    for (int k = 0; k < grid; ++k, x += 0.4) addShape(w, addBody(w, BodyType::Dynamic, Vec2(x, y)), makeBox(0.25, 0.25));
  }
  return b;
}

// The static container that v3's compounds and junkyard share: a floor of boxes 1.1 m × 1 m, 1 m
// apart along y = 0 (top at 0.5, each overlapping its neighbours by 10 cm) from x = −half to half,
// and at x = ±half a wall of `wall` boxes 1 m × 1.1 m stacked from y = 1.
void addBoxContainer(World& w, BodyId ground, int half, int wall) {
  for (int i = 0; i <= 2 * half; ++i) addShape(w, ground, makeBox(1.1, 1.0, Vec2(i - half, 0.0)));
  for (int side : {-1, 1})
    for (int i = 0; i < wall; ++i) addShape(w, ground, makeBox(1.0, 1.1, Vec2(side * half, i + 1.0)));
}

// Box2D v3's compounds (its samples' barrel of compound shapes): 20 columns × 150 rows of bodies of
// two overlapping triangles each (density 1, friction 0.5; 3000 bodies, 6000 shapes) fall into an
// 80 m container with 100 m walls; a 1600 m segment 80 m below catches what falls out.
BenchWorld compounds() {
  BenchWorld b = emptyBench(true);
  World& w = *b.world;
  const BodyId ground = addBody(w, BodyType::Static, Vec2::Zero());
  addBoxContainer(w, ground, 40, 100);
  addShape(w, ground, makeSegment(Vec2(-800.0, -80.0), Vec2(800.0, -80.0)));
  const Vec2 left[3] = {{-1.0, 0.0}, {0.5, 1.0}, {0.0, 2.0}};
  const Vec2 right[3] = {{1.0, 0.0}, {-0.5, 1.0}, {0.0, 2.0}};
  const int columns = 20, rows = 150;
  // v3's sample's layout: columns 2 m apart centred on x = 0, rows 2.25 m apart from y = 5.575,
  // every other body (counted across the columns) 0.25 m to the right, the others to the left.
  const double shift = 2.0, extra_y = 0.25, center_x = shift * columns / 2.0 - 1.0, center_y = 1.15 / 2.0, y_start = 5.0;
  double side = 0.25;
  for (int i = 0; i < columns; ++i) {
    for (int j = 0; j < rows; ++j, side = -side) {
      const BodyId body = addBody(w, BodyType::Dynamic, Vec2(i * shift - center_x + side, j * (shift + extra_y) + center_y + y_start));
      addShape(w, body, makePolygon(left), 1.0, 0.5);
      addShape(w, body, makePolygon(right), 1.0, 0.5);
    }
  }
  return b;
}

// Box2D v3's junkyard: 200 columns × 40 rows of pentagons (radius 0.25 m, 8000 bodies) fall into a
// 160 m container with 50 m walls, and a kinematic pusher (a 4 × 8 m box standing on the floor)
// sweeps them: before each step k its velocity is set to reach x = 60 sin(0.2 k dt) in one step
// (b2Body_SetTargetTransform; World::setTarget).
BenchWorld junkyard() {
  BenchWorld b = emptyBench(true);
  World& w = *b.world;
  addBoxContainer(w, addBody(w, BodyType::Static, Vec2::Zero()), 80, 50);
  // v3's pentagon: 5 points of the circle of radius 0.25 at the angles k φ, φ = π(√5 − 1) (2π less
  // the golden angle: a Fibonacci spiral's step), taken in angular order (k = 0, 2, 4, 1, 3) for makePolygon. v3
  // computes the cosines and sines with its own approximation (b2ComputeCosSin, about 1e-3 rad
  // off); here they are portableCos and portableSin (a Lua scene's math.cos and math.sin).
  const double radius = 0.25, phi = kPi * (std::sqrt(5.0) - 1.0);
  std::vector<Vec2> pentagon;
  for (int k : {0, 2, 4, 1, 3}) pentagon.push_back(Vec2(radius * portableCos(phi * k), radius * portableSin(phi * k)));
  const Shape shape = makePolygon(pentagon);
  const int columns = 200, rows = 40;
  double side = -0.1;  // every other body (counted across the columns) 0.1 m left, the others right
  for (int i = 0; i < columns; ++i)
    for (int j = 0; j < rows; ++j, side = -side)
      addShape(w, addBody(w, BodyType::Dynamic, Vec2(1.5 * (2.0 * i - columns) * radius + side, 4.0 * j * radius + 15.0)), shape);
  const BodyId pusher = addBody(w, BodyType::Kinematic, Vec2::Zero());
  addShape(w, pusher, makeBox(4.0, 8.0, Vec2(0.0, 4.0)));
  b.before_step = [pusher](World& world, int step) {
    const double dt = 1.0 / 60.0;
    world.setTarget(pusher, Vec2(60.0 * portableSin(0.2 * dt * step), 0.0), 0.0, dt);
  };
  return b;
}

// Box2D v3's washer: a kinematic drum turning at 25°/s about (0, 10) (and drifting at
// (0.001, −0.002) m/s, as v3 sets it) holds 90 × 90 boxes of 0.2 m (8100, hit events on). The drum
// is a ring from 16 to 18 m of 36 quadrilaterals, each 10° wide plus 1° over each neighbour, and 4
// fins from 14 to 16 m, 10° wide, every 90°: 40 shapes.
BenchWorld washer() {
  BenchWorld b = emptyBench(true);
  World& w = *b.world;
  addBody(w, BodyType::Static, Vec2::Zero());  // v3 makes a ground body without shapes
  BodyDef d;
  d.type = BodyType::Kinematic;
  d.position = Vec2(0.0, 10.0);
  d.angular_velocity = kPi / 180.0 * 25.0;
  d.velocity = Vec2(0.001, -0.002);
  const BodyId drum = w.createBody(d);
  const double r0 = 14.0, r1 = 16.0, r2 = 18.0, step = kPi / 18.0;
  const auto unit = [](double angle) { return Vec2(portableCos(angle), portableSin(angle)); };
  for (int i = 0; i < 36; ++i) {
    const double t1 = i * step, t2 = (i + 1) * step;
    const Vec2 a1 = unit(t1 - 0.1 * step), a2 = unit(t2 + 0.1 * step);
    const Vec2 quad[4] = {r1 * a1, r2 * a1, r2 * a2, r1 * a2};  // counter-clockwise
    addShape(w, drum, makePolygon(quad));
    if (i % 9 == 0) {
      const Vec2 u1 = unit(t1), u2 = unit(t2);
      const Vec2 fin[4] = {r0 * u1, r1 * u1, r1 * u2, r0 * u2};
      addShape(w, drum, makePolygon(fin));
    }
  }
  const int grid = 90;
  const double a = 0.1;
  ShapeDef box;
  box.shape = makeBox(2.0 * a, 2.0 * a);
  box.hit_events = true;  // as v3 sets them (its default threshold, 1 m/s, is rigidlab's hit_speed)
  double y = -1.1 * a * grid + 10.0;
  for (int i = 0; i < grid; ++i, y += 2.1 * a) {
    double x = -1.1 * a * grid;
    for (int j = 0; j < grid; ++j, x += 2.1 * a) w.createShape(addBody(w, BodyType::Dynamic, Vec2(x, y)), box);
  }
  return b;
}

// Bodies out of the scene's container at the end (the figure `escaped`): for compounds and junkyard
// below the floor's middle (y < 0) or beyond a wall's middle; for the washer farther than 16 m
// (the ring's inner face) from the drum's axis at (0, 10). Computed after every step, kept the last.
BenchScene::Probe escapedProbe(double half_width, double drum_radius) {
  return [half_width, drum_radius](BenchWorld& bw, int, BenchSamples& out) {
    int escaped = 0;
    World& w = bw.get();
    for (BodyId id : w.bodyIds()) {
      const Body& body = w.body(id);
      if (!body.isDynamic()) continue;
      const Vec2 p = body.position();
      escaped += drum_radius > 0 ? (p - Vec2(0.0, 10.0)).norm() > drum_radius : p.y() < 0.0 || std::abs(p.x()) > half_width;
    }
    out.figures["escaped"] = escaped;
  };
}

}  // namespace

BenchWorld suiteRagdolls(int columns) { return ragdollRain(columns); }

void addSuiteScenes(std::vector<BenchScene>& scenes) {
  const auto add = [&](const char* name, int n, const char* description, int steps, BenchWorld (*build)()) {
    scenes.push_back({name, name, n, description, steps, 1.0 / 60.0, build});
  };
  add("large_pyramid", 5050, "Box2D v3 suite: pyramid of base 100 (5050 boxes), 500 steps", 500, largePyramid);
  add("many_pyramids", 22000, "Box2D v3 suite: 400 pyramids of base 10 (22 000 boxes), 200 steps", 200, manyPyramids);
  add("joint_grid", 10000, "Box2D v3 suite: 100 x 100 discs on 19 800 revolute joints, 500 steps", 500, jointGrid);
  add("ragdolls", 11000, "Box2D v3 suite (its \"rain\"): 1000 ragdolls rain on 5 floors, 1000 steps", 1000,
      [] { return ragdollRain(40); });
  add("smash", 9601, "Box2D v3 suite: a heavy box into 9600 sleeping boxes, no gravity, 300 steps", 300, smash);
  add("spinner", 6077, "Box2D v3 suite: 6076 bodies in a ring stirred by a motor paddle, 500 steps", 500, spinner);
  add("tumbler", 2026, "Box2D v3 suite: 2025 boxes in a turning drum, 750 steps", 750, tumbler);
  add("compounds", 3000, "Box2D v3 suite: 3000 bodies of two triangles fall into a container, 500 steps", 500, compounds);
  scenes.back().probe = escapedProbe(40.0, 0.0);
  add("junkyard", 8001, "Box2D v3 suite: 8000 pentagons swept by a kinematic pusher, 800 steps", 800, junkyard);
  scenes.back().probe = escapedProbe(80.0, 0.0);
  add("washer", 8101, "Box2D v3 suite: 8100 small boxes in a kinematic drum turning at 25 deg/s, 500 steps", 500, washer);
  scenes.back().probe = escapedProbe(0.0, 16.0);
}

bool isSuiteScene(const std::string& kind) {
  for (const char* k : {"large_pyramid", "many_pyramids", "joint_grid", "ragdolls", "smash", "spinner", "tumbler",
                        "compounds", "junkyard", "washer"})
    if (kind == k) return true;
  return false;
}

void SuiteTracker::observe(World& w, int step) {
  if (step != 0) return;  // positions after the first step: the start of the figures below
  for (BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    if (b.isDynamic()) start[b.uid] = b.position();
  }
}

// The deepest contact point (−separation) where the bodies are now. A step finds its contacts at
// the positions its integration predicts, before its solve moves the bodies (world.cpp), so the
// contacts of the last step describe where the bodies were heading, not where they are: a ragdoll
// leg landing at a few m/s shows 9 cm of overlap there and 1.7 cm where it ends. One more step of
// 1e-12 s finds the contacts at the final positions (its integration moves nothing measurable); it
// is the world's last, so it is taken after every other figure, and the world itself is stepped (a
// copy would add to the scene's peak memory). Box2D v3 finds its contacts at the start of a step, so
// the peer's figure is taken after b2World_Step(world, 0, n), which finds them without solving.
double deepestContactNow(World& w) {
  w.step(1e-12);
  double max_pen = 0.0;
  for (const ContactInfo& c : w.contacts())
    for (int k = 0; k < c.count; ++k) max_pen = std::max(max_pen, -c.separations[k]);
  return max_pen;
}

// Engine-neutral figures, computed the same way by the Box2D v3 peer:
//   max_penetration_m   deepest touching contact point (−separation) at the final positions
//   max_joint_gap_m     largest distance between a revolute joint's two anchors at the end
//   moved_gt_0.25m      bodies more than 25 cm from where they were after the first step
//   mean_drop_m         mean fall of the bodies since the first step (a pile sinking)
//   top_height_loss_m   fall of the body that was highest after the first step
std::string suiteMetrics(World& w, const SuiteTracker& t) {
  double max_gap = 0.0;
  int joints = 0;
  for (JointId id : w.jointIds()) {
    ++joints;
    if (w.joint(id).type != JointType::Revolute) continue;
    const JointState s = w.jointState(id);
    max_gap = std::max(max_gap, (s.world_anchor_a - s.world_anchor_b).norm());
  }
  int dynamic = 0, moved = 0, tracked = 0;
  double drop = 0.0, top_y0 = -1e300, top_loss = NAN;
  for (BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    if (!b.isDynamic()) continue;
    ++dynamic;
    const auto it = t.start.find(b.uid);
    if (it == t.start.end()) continue;
    ++tracked;
    moved += (b.position() - it->second).norm() > 0.25 ? 1 : 0;
    drop += it->second.y() - b.position().y();
    if (it->second.y() > top_y0) {
      top_y0 = it->second.y();
      top_loss = it->second.y() - b.position().y();
    }
  }
  const int awake = w.stats().awake_bodies;
  const double max_pen = deepestContactNow(w);  // steps the world: after every other figure
  const auto num = [](double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, std::isfinite(x) ? "%.6g" : "null", x);
    return std::string(buf);
  };
  return "{\"awake_at_end\": " + std::to_string(awake) + ", \"bodies\": " + std::to_string(dynamic) +
         ", \"joints\": " + std::to_string(joints) + ", \"max_penetration_m\": " + num(max_pen) +
         ", \"max_joint_gap_m\": " + num(max_gap) + ", \"moved_gt_0.25m\": " + std::to_string(moved) +
         ", \"mean_drop_m\": " + num(tracked ? drop / tracked : NAN) + ", \"top_height_loss_m\": " + num(top_loss) + "}";
}

}  // namespace rigidlab::app
