// Running one benchmark scene in its own process and reading its result (bench_command.cpp,
// bench_compare.cpp).
#pragma once

#include <string>
#include <vector>

#include "bench_scenes.h"
#include "json_value.h"

namespace rigidlab::app {

double median(std::vector<double> v);
std::string fmt(double x);  // %.6g, or null when not finite (JSON)
// The scene run `reps` times in a child process: its JSON line (the peers' format plus rigidlab's
// fields and the child's peak memory). Throws when the child fails.
std::string runIsolated(const BenchScene& scene, int reps);
void printHuman(const JsonValue& r);

}  // namespace rigidlab::app
