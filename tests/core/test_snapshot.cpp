// Whole-simulation snapshots (world_snapshot.h): the steps after a restore give the same bits as the
// steps after the snapshot was taken, in memory and through the file format; a corrupt or truncated
// file is a SnapshotError.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <cstring>

#include "rigidlab/world_snapshot.h"
#include "../state_hash.h"
#include "test_util.h"

using namespace rigidlab;
using namespace rigidlab::test;

namespace {

constexpr double kDt = 1.0 / 60.0;

// Every body's state, every contact's impulses, every joint's state, the sensors' contents and
// the events: what a later step or a script could see.
uint64_t stateHash(const World& w) {
  Hash h;
  h.add(static_cast<uint64_t>(w.stepCount()));
  h.add(w.time());
  for (BodyId id : w.bodyIds()) {
    const Body& b = w.body(id);
    h.add(uint64_t{b.uid});
    h.add(b.center);
    h.add(b.angle);
    h.add(b.velocity);
    h.add(b.angular_velocity);
    h.add(uint64_t{b.awake} | uint64_t{b.frozen} << 1);
    h.add(b.sleep_time);
  }
  for (const ContactInfo& c : w.contacts()) {
    h.add(uint64_t{c.a.index} << 32 | c.b.index);
    for (int k = 0; k < c.count; ++k) {
      h.add(c.points[k]);
      h.add(c.normal_impulses[k]);
      h.add(c.tangent_impulses[k]);
    }
  }
  for (JointId j : w.jointIds()) {
    const JointState s = w.jointState(j);
    h.add(s.angle);
    h.add(s.translation);
    h.add(s.reaction_force);
    h.add(s.reaction_torque);
  }
  for (const auto& e : w.contactEvents()) h.add(e.normal_impulse);
  for (const auto& e : w.sensorEvents()) h.add(uint64_t{e.visitor.index} << 1 | e.begin);
  h.add(static_cast<uint64_t>(w.incidents().size()));
  return h.h;
}

// A scene with a bit of everything a snapshot must carry: a stack with warm-started contacts,
// a body asleep from the start and one that falls asleep, a kinematic platform, a sensor, joints
// (a motorised revolute, a distance spring, one that breaks), springs, a damper, a timed push, a
// mouse drag, a ball in free flight (located impacts) and a chain.
struct Scene {
  World w;
  BodyId platform, ball, grabbed;
  ShapeId sensor;
  Scene() {
    BodyDef g;
    g.type = BodyType::Static;
    const BodyId ground = w.createBody(g);
    World::ChainDef chain;
    chain.points = {{20, 0}, {5, 0}, {0, -0.2}, {-5, 0}, {-20, 0}};
    w.createChain(ground, chain);
    for (int i = 0; i < 5; ++i) addBox(w, 1.0, 1.0, {-3.0, 0.5 + i * 1.0});
    BodyDef asleep;
    asleep.shape = makeBox(1, 1);
    asleep.position = {8, 0.5};
    asleep.awake = false;
    w.createBody(asleep);
    BodyDef kin;
    kin.type = BodyType::Kinematic;
    kin.shape = makeBox(3, 0.2);
    kin.position = {3, 2};
    kin.velocity = {0.5, 0};
    platform = w.createBody(kin);
    addBox(w, 0.5, 0.5, {3, 2.5});
    BodyDef s;
    s.type = BodyType::Static;
    s.position = {-3, 3};
    const BodyId sensor_body = w.createBody(s);
    ShapeDef sd;
    sd.shape = makeBox(2, 8);
    sd.sensor = true;
    sensor = w.createShape(sensor_body, sd);
    ball = addCircle(w, 0.3, {0, 6});
    w.setVelocity(ball, {1.5, 0});
    const BodyId bob = addCircle(w, 0.2, {-8, 4});
    JointDef pin;
    pin.type = JointType::Revolute;
    pin.a = bob;
    pin.anchor_a = {-8, 5};
    pin.enable_motor = true;
    pin.motor_speed = 1.0;
    pin.max_motor_torque = 0.5;
    w.createJoint(pin);
    const BodyId a = addBox(w, 0.4, 0.4, {-12, 4});
    const BodyId b = addBox(w, 0.4, 0.4, {-12, 2.5});
    JointDef dist;
    dist.type = JointType::Distance;
    dist.a = a;
    dist.b = b;
    dist.anchor_a = {-12, 4};
    dist.anchor_b = {-12, 2.5};
    dist.enable_spring = true;
    dist.spring_hertz = 2.0;
    dist.spring_damping = 0.1;
    w.createJoint(dist);
    // A spinner whose motor winds it up until the pin's load breaks it (at step 47).
    const BodyId spinner = addBox(w, 0.4, 0.4, {-16, 4});
    JointDef weak;
    weak.type = JointType::Revolute;
    weak.a = spinner;
    weak.anchor_a = {-16, 4.5};
    weak.enable_motor = true;
    weak.motor_speed = 30.0;
    weak.max_motor_torque = 1.0;
    weak.break_force = 8.0;
    w.createJoint(weak);
    SpringDef spring;
    spring.a = addCircle(w, 0.25, {12, 5});
    spring.anchor = {12, 7};
    spring.stiffness = 40.0;
    spring.rest_length = 1.0;
    spring.damping = 0.2;
    w.addSpring(spring);
    w.addDamper({spring.a, 0.3, 0.01});
    grabbed = addBox(w, 0.6, 0.3, {14, 1});
    w.addForce(std::make_unique<ConstantForce>(Vec2(3.0, 0.0), Vec2(0.1, 0.0)), grabbed, {}, 0.75);
    MouseForceDef m = MouseForce::forBody(w.body(grabbed), {14, 1});
    m.target = {15, 3};
    w.addForce(std::make_unique<MouseForce>(m), grabbed);
  }
};

void run(World& w, int steps, std::vector<uint64_t>* hashes = nullptr) {
  for (int i = 0; i < steps; ++i) {
    w.step(kDt);
    if (hashes) hashes->push_back(stateHash(w));
  }
}

// FNV-1a as the format uses it, to re-sign a tampered payload.
uint64_t fnv1a(std::string_view bytes) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}
void resign(std::string& file) {
  const size_t start = 18 + 12;
  const uint64_t sum = fnv1a(std::string_view(file).substr(start, file.size() - start - 8));
  for (int i = 0; i < 8; ++i) file[file.size() - 8 + i] = static_cast<char>((sum >> (8 * i)) & 0xff);
}

// Restores the bytes into a new world and steps it once: the error's message ("input: " before an
// InputError's), or "(no error)".
std::string restoreError(std::string_view bytes) {
  try {
    World w;
    w.restore(deserializeSnapshot(bytes));
    w.step(kDt);
  } catch (const SnapshotError& e) {
    return std::string(e.what());
  } catch (const InputError& e) {
    return std::string("input: ") + e.what();
  }
  return std::string("(no error)");
}

}  // namespace

TEST_CASE("snapshot: restore in memory gives the same bits, step by step, as the run it was taken from") {
  Scene s;
  run(s.w, 30);
  const WorldSnapshot snap = s.w.snapshot();
  CHECK(snap.stepCount() == 30);
  CHECK(s.w.jointIds().size() == 3);
  CHECK(snap.time() == s.w.time());
  std::vector<uint64_t> a, b;
  run(s.w, 200, &a);
  // Edits after the snapshot are undone too.
  s.w.destroyBody(s.ball);
  addBox(s.w, 1, 1, {0, 10});
  s.w.setGravity({0, 3});
  s.w.restore(snap);
  CHECK(s.w.stepCount() == 30);
  CHECK(s.w.isValid(s.ball));
  run(s.w, 200, &b);
  CHECK(a == b);
  // The scene did what the snapshot must carry: something slept, the weak joint broke, the sensor
  // saw bodies, contacts were warm-started.
  CHECK(s.w.jointIds().size() == 2);
  bool slept = false;
  for (BodyId id : s.w.bodyIds()) slept |= s.w.body(id).isDynamic() && !s.w.body(id).awake;
  CHECK(slept);
  CHECK(!s.w.contacts().empty());
  // A snapshot can be restored again and again.
  s.w.restore(snap);
  std::vector<uint64_t> c;
  run(s.w, 200, &c);
  CHECK(a == c);
}

TEST_CASE("snapshot: through the file format, in a fresh world, the same bits") {
  Scene s;
  run(s.w, 30);
  const std::string bytes = serializeSnapshot(s.w.snapshot());
  std::vector<uint64_t> a, b;
  run(s.w, 200, &a);
  World fresh;
  fresh.restore(deserializeSnapshot(bytes));
  run(fresh, 200, &b);
  CHECK(a == b);
  // Serializing is itself exact: the read state writes the same bytes.
  World again;
  again.restore(deserializeSnapshot(bytes));
  CHECK(serializeSnapshot(again.snapshot()) == bytes);
}

TEST_CASE("snapshot: a kinematic platform's last velocity travels through the file (RK4 carried crate)") {
  // Under RK4 a crate carried by a kinematic platform whose velocity is set between steps takes
  // the change as a jump (the velocity the platform moved with last step is part of the state):
  // without it, the resumed run would see no jump at its first step and the crate would slip.
  const auto build = [](World& w) {
    BodyDef p;
    p.type = BodyType::Kinematic;
    p.shape = makeBox(3.0, 0.2);
    p.friction = 0.8;
    w.createBody(p);
    BodyDef c;
    c.shape = makeBox(0.6, 0.6);
    c.position = Vec2(0.0, 0.4);
    c.friction = 0.8;
    w.createBody(c);
  };
  const double h = 1.0 / 60.0;
  const auto drive = [&](World& w, int from, int to, std::vector<uint64_t>& hashes) {
    const BodyId platform = w.bodyIds()[0];
    for (int i = from; i < to; ++i) {
      w.setVelocity(platform, Vec2(3.0 * i * h, 0.0));
      w.step(h);
      hashes.push_back(stateHash(w));
    }
  };
  World w;  // RK4
  build(w);
  std::vector<uint64_t> straight, resumed;
  drive(w, 1, 21, straight);
  const std::string bytes = serializeSnapshot(w.snapshot());
  drive(w, 21, 41, straight);
  World fresh;
  fresh.restore(deserializeSnapshot(bytes));
  drive(fresh, 21, 41, resumed);
  REQUIRE(resumed.size() == 20);
  CHECK(std::equal(resumed.begin(), resumed.end(), straight.end() - 20));
}

TEST_CASE("snapshot: a label travels through the file") {
  World w;
  addCircle(w, 1, {0, 0});
  WorldSnapshot s = w.snapshot();
  s.setLabel("scripts/scenes/pyramid.lua");
  CHECK(deserializeSnapshot(serializeSnapshot(s)).label() == "scripts/scenes/pyramid.lua");
  CHECK(deserializeSnapshot(serializeSnapshot(s)).bodyCount() == 1);
}

// Version 1 of the format is version 2 without the application data (snapshot_format.cpp): the
// u64 length after the label is dropped, the version and the payload length rewritten, re-signed.
std::string asVersion1(std::string file, size_t label_bytes) {
  REQUIRE(file[18] == 2);
  const size_t length_at = 18 + 4, payload_at = 18 + 12;
  const size_t app_at = payload_at + 8 + label_bytes;
  for (int i = 0; i < 8; ++i) REQUIRE(file[app_at + i] == 0);  // no application data to drop
  file.erase(app_at, 8);
  file[18] = 1;
  const uint64_t length = file.size() - payload_at - 8;
  for (int i = 0; i < 8; ++i) file[length_at + i] = static_cast<char>((length >> (8 * i)) & 0xff);
  resign(file);
  return file;
}

// A version 2 file, written by the program before version 3 (at commit 501d831), labelled
// "bouncers": 6 steps of a world solved by sequential impulses with impacts handled per step, on a
// static ground box (20 × 1 m, centred at (0, −0.5)): six bodies of restitution 0.6 let go from rest,
// alternately 0.5 m boxes and 0.25 m discs, at x = −4 + i m, y = 0.27 + 0.012 i m, angle 0.01 i rad
// (i = 0..5), and a stack of three 0.8 m boxes at x = 5 m. At step 6 some of its contact points
// have just bounced, which version 3 keeps as a flag and version 2 as their target velocity.
std::string version2File() {
  const std::string path = std::string(RIGIDLAB_TEST_DATA_DIR) + "/snapshot_v2_bouncers.snap";
  std::FILE* f = std::fopen(path.c_str(), "rb");
  REQUIRE_MESSAGE(f != nullptr, "cannot open " << path);
  std::string bytes;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, f)) > 0;) bytes.append(buffer, n);
  std::fclose(f);
  return bytes;
}
// The state hash 40 steps after restoring that file, as the program that wrote it gave it. Reading
// a bounced point's flag wrongly either way changes it (checked by making the reader set the flag to
// false, then to true). Like the golden hashes (hardening/test_determinism.cpp), it changes when
// the step's behaviour does: then the new value is taken, with the golden hashes, explained.
constexpr uint64_t kVersion2Resumed = 0x92bfc713a528c18bull;

TEST_CASE("snapshot: the application data travels through the file (since version 2) unread by the world") {
  Scene s;
  run(s.w, 30);
  WorldSnapshot snap = s.w.snapshot();
  CHECK(snap.appData().empty());
  std::string data;
  for (int i = 0; i < 256; ++i) data += static_cast<char>(i);  // every byte value, zeros included
  data += std::string(1000, '\0');
  snap.setLabel("scene: x.lua\n");
  snap.setAppData(data);
  const std::string bytes = serializeSnapshot(snap);
  CHECK(bytes[18] == 5);
  const WorldSnapshot read = deserializeSnapshot(bytes);
  CHECK(read.appData() == data);
  CHECK(read.label() == "scene: x.lua\n");
  CHECK(serializeSnapshot(read) == bytes);
  // The data does not touch the world: restoring either snapshot gives the same steps.
  World a, b;
  a.restore(read);
  b.restore(s.w.snapshot());
  run(a, 30);
  run(b, 30);
  CHECK(stateHash(a) == stateHash(b));
  // Cleared again, it reads back empty.
  snap.setAppData("");
  CHECK(deserializeSnapshot(serializeSnapshot(snap)).appData().empty());
}

TEST_CASE("snapshot: version 1 and 2 files still load and resume the same bits as the program that wrote them") {
  const std::string v2 = version2File();
  const std::string v1 = asVersion1(v2, std::string("bouncers").size());
  CHECK(v1.size() == v2.size() - 8);
  for (const std::string* file : {&v2, &v1}) {
    CAPTURE(int{(*file)[18]});
    const WorldSnapshot old = deserializeSnapshot(*file);
    CHECK(old.label() == "bouncers");
    CHECK(old.appData().empty());
    CHECK(old.stepCount() == 6);
    CHECK(old.bodyCount() == 10);
    World w;
    w.restore(old);
    // Its writer solved every joint in the contact solvers (WorldDef::exact_joints came later).
    CHECK_FALSE(w.settings().exact_joints);
    run(w, 40);
    CHECK(stateHash(w) == kVersion2Resumed);
    // Written again, it is a version 5 file, which resumes the same.
    const std::string v5 = serializeSnapshot(old);
    CHECK(v5[18] == 5);
    World again;
    again.restore(deserializeSnapshot(v5));
    run(again, 40);
    CHECK(stateHash(again) == kVersion2Resumed);
  }
  // Versions outside 1..5 are refused, naming both.
  for (char version : {0, 6}) {
    std::string t = v2;
    t[18] = version;
    try {
      (void)deserializeSnapshot(t);
      FAIL("version " << int{version} << " was read");
    } catch (const SnapshotError& e) {
      CHECK(std::string(e.what()) == "snapshot: version " + std::to_string(version) + ", this program reads versions 1 to 5");
    }
  }
}

TEST_CASE("snapshot: a force that cannot be copied is kept in memory and taken from the world from a file") {
  World w;
  const BodyId b = addCircle(w, 0.5, {2, 0});
  w.setGravity({0, 0});
  const ForceId f = w.addForce(std::make_unique<HookeToOrigin>(4.0), b);
  run(w, 10);
  const WorldSnapshot snap = w.snapshot();
  const std::string bytes = serializeSnapshot(snap);
  std::vector<uint64_t> a, b2, c;
  run(w, 60, &a);
  w.removeForce(f);
  w.restore(snap);  // in memory: the snapshot kept the object
  CHECK(w.isValid(f));
  run(w, 60, &b2);
  CHECK(a == b2);
  // From the file, a world without that force cannot take it ...
  World fresh;
  const std::string message = [&] {
    try {
      fresh.restore(deserializeSnapshot(bytes));
    } catch (const SnapshotError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  }();
  CHECK(message.find("test_hooke") != std::string::npos);
  CHECK(fresh.bodyCount() == 0);  // left as it was
  // ... a world that made it the same way can.
  World same;
  same.setGravity({0, 0});
  same.addForce(std::make_unique<HookeToOrigin>(4.0), addCircle(same, 0.5, {2, 0}));
  same.restore(deserializeSnapshot(bytes));
  run(same, 60, &c);
  CHECK(a == c);
}

TEST_CASE("snapshot: not while stepping, not empty") {
  World w;
  CHECK_THROWS_AS(w.restore(WorldSnapshot{}), SnapshotError);
  CHECK_THROWS_AS(serializeSnapshot(WorldSnapshot{}), SnapshotError);
}

TEST_CASE("snapshot: a truncated, extended, corrupt or foreign file is a SnapshotError") {
  Scene s;
  run(s.w, 30);
  const std::string bytes = serializeSnapshot(s.w.snapshot());
  CHECK(restoreError(bytes) == "(no error)");
  CHECK(restoreError("") .find("not a rigidlab snapshot") != std::string::npos);
  CHECK(restoreError("hello world, this is not a snapshot at all").find("not a rigidlab snapshot") != std::string::npos);
  for (size_t n = 0; n < bytes.size(); n += 1 + n / 7) CHECK(restoreError(bytes.substr(0, n)).starts_with("snapshot: "));
  CHECK(restoreError(bytes + "x").find("truncated or extended") != std::string::npos);
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x40;
  CHECK(restoreError(flipped).find("checksum") != std::string::npos);
  std::string version = bytes;
  version[18] = 9;
  CHECK(restoreError(version).find("version 9") != std::string::npos);
  // Tampered bytes with a valid checksum: every one is refused or gives a world that steps.
  int refused = 0;
  for (size_t i = 30; i + 8 < bytes.size(); i += 1 + i / 97) {
    for (unsigned char bit : {0x01, 0x80}) {
      std::string t = bytes;
      t[i] = static_cast<char>(t[i] ^ bit);
      resign(t);
      const std::string e = restoreError(t);
      CHECK((e == "(no error)" || e.starts_with("snapshot: ") || e.starts_with("input: ")));
      refused += e.starts_with("snapshot: ") ? 1 : 0;
    }
  }
  CHECK(refused > 0);
}

TEST_CASE("snapshot: a non-finite body state or shape in a file is refused, naming what") {
  // A step never leaves a body's state non-finite (its firewall puts the body back where the step
  // began), so a file that holds one was not written by a step: the NaN would have nowhere finite
  // to go back to. Each value below is written once in the file (an angle and a half width no other
  // field holds); it is replaced by a NaN and an infinity and the checksum signed again.
  World w;
  BodyDef def;
  def.shape = makeBox(2.75, 1);  // full sizes: corners at ±1.375, ±0.5
  def.position = {2, 3};
  def.angle = 0.123456789;
  w.createBody(def);
  const std::string bytes = serializeSnapshot(w.snapshot());
  const auto replaced = [&](double from, double to) {
    std::string t = bytes;
    int n = 0;
    for (size_t i = 30; i + 8 + 8 <= t.size(); ++i) {
      double x;
      std::memcpy(&x, t.data() + i, 8);
      if (x != from) continue;
      std::memcpy(t.data() + i, &to, 8);
      ++n;
    }
    REQUIRE(n > 0);
    resign(t);
    return t;
  };
  for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    CHECK(restoreError(replaced(0.123456789, bad)) == "snapshot: body 1 has a non-finite position, angle, velocity or mass");
    CHECK(restoreError(replaced(1.375, bad)) == "snapshot: shape 0 has a non-finite vertex, normal or radius");
    CHECK(restoreError(replaced(-1.375, bad)) == "snapshot: shape 0 has a non-finite vertex, normal or radius");
  }
  CHECK(restoreError(replaced(0.123456789, 0.25)) == "(no error)");  // a finite change is the file's own business
}

TEST_CASE("snapshot: version 4's state travels through the file: own gravity, surfaces, local anchors, a body gear, a torque, the filter's answers") {
  World w;
  BodyDef floor_def;
  floor_def.type = BodyType::Static;
  floor_def.shape = makeBox(40, 1);
  floor_def.position = {0, -0.5};
  const BodyId floor = w.createBody(floor_def);
  w.setShapeSurface(w.body(floor).shapes[0], 1.5, 0.0);  // a conveyor
  addBox(w, 1, 1, {-5, 0.5});                            // carried by it
  BodyDef ball;
  ball.shape = makeCircle(0.5);
  ball.position = {5, 0.5};
  ball.velocity = {2, 0};
  ball.angular_velocity = -4;
  ball.gravity = Vec2(0.0, -20.0);
  ball.sleeping_allowed = false;
  const BodyId rolling = w.createBody(ball);
  w.setShapeSurface(w.body(rolling).shapes[0], 0.0, 0.2);
  w.setInertia(rolling, 0.3);
  const BodyId a = addBox(w, 1, 0.2, {10, 5}), b = addBox(w, 1, 0.2, {11.5, 5});
  JointDef pin;
  pin.type = JointType::Revolute;
  pin.a = a;
  pin.b = b;
  pin.local_anchor_a = Vec2(0.5, 0.0);
  pin.local_anchor_b = Vec2(-0.5, 0.0);  // apart at creation: pulled together
  w.createJoint(pin);
  const BodyId c = addCircle(w, 0.5, {20, 5}), d = addCircle(w, 0.3, {22, 5});
  for (const BodyId wheel : {c, d}) {
    JointDef axle;
    axle.type = JointType::Revolute;
    axle.a = wheel;
    axle.anchor_a = w.body(wheel).center;
    w.createJoint(axle);
  }
  JointDef gear;
  gear.type = JointType::Gear;
  gear.a = c;
  gear.b = d;
  gear.ratio = 2.0;
  w.createJoint(gear);
  w.addForce(std::make_unique<ConstantForce>(Vec2::Zero(), std::nullopt, 3.0), c, {}, 2.0);
  // A ghost that the filter lets through the floor; the answers are counted.
  const BodyId ghost = addCircle(w, 0.3, {-10, 2});
  long asked = 0;
  const ShapeId ghost_shape = w.body(ghost).shapes[0];
  w.setShouldCollide([&](ShapeId x, ShapeId y) {
    ++asked;
    return !(x == ghost_shape || y == ghost_shape);
  });
  run(w, 30);
  const std::string bytes = serializeSnapshot(w.snapshot());
  const long asked_before = asked;
  std::vector<uint64_t> first, second;
  run(w, 100, &first);
  const long asked_after = asked - asked_before;
  World fresh;
  fresh.restore(deserializeSnapshot(bytes));
  long asked_again = 0;
  fresh.setShouldCollide([&](ShapeId x, ShapeId y) {
    ++asked_again;
    return !(x == ghost_shape || y == ghost_shape);
  });
  run(fresh, 100, &second);
  CHECK(first == second);
  CHECK(asked_again == asked_after);  // the pairs overlapping at the snapshot were not asked again
  CHECK(w.body(ghost).center.y() < -1.0);  // it fell through the floor
  const Body& r = fresh.body(rolling);
  CHECK(r.own_gravity);
  CHECK(r.gravity == Vec2(0.0, -20.0));
  CHECK(!r.sleeping_allowed);
  CHECK(r.inertia == 0.3);
  CHECK(fresh.shape(fresh.body(floor).shapes[0]).tangent_speed == 1.5);
  CHECK(asked_after >= 1);
}
