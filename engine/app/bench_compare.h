// rigidlab against other engines on the same scenes (bench_compare.cpp), as ratios measured in one
// run: timings depend on the machine and its load, ratios much less.
#pragma once

#include <filesystem>
#include <vector>

#include "bench_scenes.h"
#include "json_value.h"

namespace rigidlab::app {

// Box2D 2.4.1 and Chipmunk 7 (DIR/run.sh builds and runs them), after rigidlab's own results.
int comparePeers(const std::vector<JsonValue>& ours, const std::filesystem::path& peers);

// Box2D v3 through an existing program of the peers' command line (docs/performance.md), one
// thread and `threads` > 1, alternated with rigidlab scene by scene for `rounds` rounds; prints
// each engine's median over the rounds with the spread, the ratios and the quality figures side by
// side. rigidlab runs once per entry of `substeps` in each round (a row each), so that its default
// and the sub-steps at which its results are as good as v3's are compared in one alternated run.
// Scenes the program does not know are reported as such.
int compareV3(const std::vector<BenchScene>& scenes, const std::filesystem::path& program, int rounds, int threads,
              const std::vector<int>& substeps, bool json);

}  // namespace rigidlab::app
