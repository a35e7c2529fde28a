// libFuzzer target: snapshot files (world_snapshot.h). The bytes are either a whole file (last
// byte even: FuzzedDataProvider takes integers from the end) or mutations of a valid file: of a
// snapshot of a small world with contacts, joints, a sensor, springs and a sleeping body (last byte
// odd, below 128), or of the version 2 file the core tests read, whose contact points have the
// older layout (odd, from 129). A mutation is pairs of (offset, xor mask),
// after which the checksum is recomputed, so the mutations reach the reader's checks behind it. The result is
// deserialized (its application data written back the same), restored into a world and stepped.
// Only SnapshotError and InputError may come out; nothing may crash or trip a sanitizer.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "rigidlab/error.h"
#include "rigidlab/world.h"

using namespace rigidlab;

namespace {

std::string baseSnapshot() {
  World w;
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = makeBox(20, 1);
  ground.position = {0, -0.5};
  w.createBody(ground);
  BodyId last;
  for (int i = 0; i < 3; ++i) {
    BodyDef box;
    box.shape = makeBox(1, 1);
    box.position = {0, 0.5 + i};
    last = w.createBody(box);
  }
  BodyDef ball;
  ball.shape = makeCircle(0.3);
  ball.position = {3, 3};
  const BodyId b = w.createBody(ball);
  JointDef pin;
  pin.a = b;
  pin.anchor_a = {3, 4};
  w.createJoint(pin);
  SpringDef s;
  s.a = last;
  s.anchor = {0, 6};
  s.stiffness = 5;
  s.rest_length = 2;
  w.addSpring(s);
  BodyDef sensor;
  sensor.type = BodyType::Static;
  sensor.shape = makeBox(2, 2);
  sensor.sensor = true;
  sensor.position = {3, 2};
  w.createBody(sensor);
  BodyDef asleep;
  asleep.shape = makeBox(1, 1);
  asleep.position = {-5, 0.5};
  asleep.awake = false;
  w.createBody(asleep);
  for (int i = 0; i < 20; ++i) w.step(1.0 / 60.0);
  WorldSnapshot snapshot = w.snapshot();
  // Application data (format version 2): opaque to the core, any bytes; here a scene's saved
  // state as the Lua layer writes it (scene_state.cpp), so mutations reach its length too.
  snapshot.setAppData(std::string("RLSS\x01\x06\x01\0\0\0\0\0\0\0\x05\x01\0\0\0\0\0\0\0k\x02", 25));
  return serializeSnapshot(snapshot);
}

// tests/core/data/snapshot_v2_bouncers.snap (test_snapshot.cpp says what it holds).
std::string version2Snapshot() {
  std::FILE* f = std::fopen(RIGIDLAB_SNAPSHOT_V2, "rb");
  if (!f) {
    std::fprintf(stderr, "fuzz_snapshot: cannot open %s\n", RIGIDLAB_SNAPSHOT_V2);
    std::abort();
  }
  std::string bytes;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, f)) > 0;) bytes.append(buffer, n);
  std::fclose(f);
  return bytes;
}

uint64_t fnv1a(std::string_view bytes) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string base = baseSnapshot(), version2 = version2Snapshot();
  FuzzedDataProvider in(data, size);
  std::string bytes;
  const uint8_t mode = in.ConsumeIntegral<uint8_t>();
  if (mode % 2 == 0) {
    bytes = in.ConsumeRemainingBytesAsString();
  } else {
    bytes = mode < 128 ? base : version2;
    constexpr size_t kHeader = 18 + 12;
    while (in.remaining_bytes() >= 3) {
      const size_t at = kHeader + in.ConsumeIntegralInRange<size_t>(0, bytes.size() - kHeader - 9);
      bytes[at] = static_cast<char>(bytes[at] ^ in.ConsumeIntegral<uint8_t>());
    }
    const uint64_t sum = fnv1a(std::string_view(bytes).substr(kHeader, bytes.size() - kHeader - 8));
    for (int i = 0; i < 8; ++i) bytes[bytes.size() - 8 + i] = static_cast<char>((sum >> (8 * i)) & 0xff);
  }
  try {
    World w;
    const WorldSnapshot read = deserializeSnapshot(bytes);
    // What was read is written back the same (the application data included).
    if (deserializeSnapshot(serializeSnapshot(read)).appData() != read.appData()) __builtin_trap();
    w.restore(read);
    for (int i = 0; i < 20; ++i) w.step(1.0 / 60.0);
    (void)w.contacts();
    (void)w.impacts();
    (void)w.snapshot();
  } catch (const SnapshotError&) {
  } catch (const InputError&) {
  }
  return 0;
}
