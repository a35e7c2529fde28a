// What a headless run prints: a short human summary, or one JSON document; and the CSV trace.
#pragma once

#include <cstdio>
#include <string>

#include "rigidlab/lua/scene.h"

namespace rigidlab::app {

struct RunInfo {
  long steps = 0;
  double wall_ms = 0.0;
  std::string check;  // "passed", "failed", "none"
};

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
