// Golden trajectories (`scene.golden`, docs/testing.md): the state of every body sampled every K
// steps of a run, kept as a text file beside the scene, and the comparison of a later run with it.
//
// The file, one line per body per sample, every number with 17 significant digits so that it
// reads back bit for bit:
//   # rigidlab golden trajectory: ...
//   scene pyramid.lua
//   dt 0.016666666666666666
//   steps 600
//   every 10
//   sample 0 0                                   (step, time)
//   0 1 0 -0.5 0 0 0 0 ground                    (step, uid, x, y, angle, vx, vy, omega, name)
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rigidlab/world.h"

namespace rigidlab::app {

// The largest golden trajectory file read or written (docs/security.md "Files"). A run whose
// trajectory would be larger stops with an error (sampleBytesBound), so that a scene can
// neither make the runner hold an unbounded trajectory nor write a golden it would not read again.
inline constexpr size_t kMaxGoldenBytes = size_t{64} << 20;

struct BodySample {
  uint32_t uid = 0;
  std::string name;
  double x = 0, y = 0, angle = 0, vx = 0, vy = 0, omega = 0;
};

struct TrajectorySample {
  long step = 0;  // steps of the run before the sample (0: the state after PopulateWorld)
  double time = 0.0;
  std::vector<BodySample> bodies;  // by uid
};

struct Trajectory {
  std::string scene;  // the scene's file name
  double dt = 0.0;
  long steps = 0;  // of the whole run
  long every = 1;
  std::vector<TrajectorySample> samples;
};

// Every body of `world` now, after `step` steps of the run.
TrajectorySample sampleWorld(const World& world, long step);

std::string formatTrajectory(const Trajectory& trajectory);
// At least the bytes formatTrajectory writes for `sample` (its lines with every number at its
// longest, names escaped at their longest), so that a running total bounds the file before it exists.
size_t sampleBytesBound(const TrajectorySample& sample);
// Throws std::runtime_error("<path>:<line>: <what is wrong>").
Trajectory parseTrajectory(const std::string& text, const std::string& path);

// Where a scene's golden trajectory `name` lives: <scene dir>/golden/<name>.txt.
std::filesystem::path goldenPath(const std::filesystem::path& scene, const std::string& name);

// The first difference of `actual` from `expected` beyond `tolerance` (0: bit for bit), said as
// which body diverged at which step and time, by how much; nullopt if they agree.
std::optional<std::string> compareTrajectories(const Trajectory& expected, const Trajectory& actual, double tolerance);

// `rigidlab test --update`: writes the trajectory into the scene's golden file `name` (making its
// golden/ folder) and returns its path. Throws std::runtime_error on a write error.
std::filesystem::path writeGolden(const std::filesystem::path& scene, const std::string& name,
                                  const Trajectory& trajectory);

// A run of `scene` against its golden file `name`: nullopt if it matches; else why not — a
// missing, unreadable or too large (kMaxGoldenBytes) file, or the first difference, in which case both trajectories are
// written into `diff_dir` (expected.txt, actual.txt) and the message names them.
std::optional<std::string> checkGolden(const std::filesystem::path& scene, const std::string& name,
                                       const Trajectory& actual, double tolerance,
                                       const std::filesystem::path& diff_dir);

}  // namespace rigidlab::app
