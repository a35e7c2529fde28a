// What a headless run prints: a short human summary, or one JSON document; and the CSV trace.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "rigidlab/lua/scene.h"

namespace rigidlab::app {

struct RunInfo {
  long steps = 0;
  double wall_ms = 0.0;
  std::string check;  // "passed", "failed", "none"
  // The first step after which the world's energy was not finite (0: it stayed finite), and that
  // energy.
  long energy_blowup_step = 0;
  double energy_blowup_time = 0.0, blowup_kinetic = 0.0, blowup_potential = 0.0;
  bool expect_incidents = false;  // scene.expect_incidents
};

// What went wrong in a run that did not fail (RunInfo, World::incidents): one message per frozen
// body, and one for a non-finite energy. Empty for a clean run.
std::vector<std::string> incidents(const World& world, const RunInfo& info);

void printSummary(std::FILE* out, const lua::Scene& scene, const RunInfo& info);
void printJson(std::FILE* out, const lua::Scene& scene, const RunInfo& info);

// CSV with header time,id,name,x,y,angle,vx,vy,omega; one row per body per written step.
class Trace {
 public:
  Trace(const std::string& path);  // throws std::runtime_error("<path>: <reason>")
  ~Trace();
  void write(const World& world);

 private:
  std::FILE* file_;
  std::string path_;
};

// 17 significant digits; null for a non-finite value (JSON has no NaN).
std::string jsonNumber(double x);
std::string jsonString(const std::string& s);

}  // namespace rigidlab::app
