// rigidlab against other engines on the same scenes (bench_compare.cpp), as ratios measured in one
// run: timings depend on the machine and its load, ratios much less.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bench_scenes.h"

namespace rigidlab::app {

// One configuration of another engine: a peer program of the command line of
// engine/peers/scenes.h (Box2D 2.4.1, Chipmunk 7, Box2D v3) and the arguments it is run with.
struct PeerProgram {
  std::string label;    // "Box2D v3, 2 threads"
  std::string program;  // path
  std::string extra;    // e.g. " --workers=2"
};

// Box2D 2.4.1 and Chipmunk 7 from the peer programs' sources in `dir` (engine/peers), built by its
// run.sh into `build_dir` (it installs the two Debian packages when they are missing). Throws a
// UsageError when `dir` has no run.sh, a std::runtime_error when the build fails.
std::vector<PeerProgram> buildPeerPrograms(const std::filesystem::path& dir, const std::filesystem::path& build_dir);

// Box2D v3 through an existing build of the peers' bench_v3.c: one thread, and `threads` > 1.
std::vector<PeerProgram> v3Programs(const std::filesystem::path& program, int threads);

// Each scene for `rounds` rounds, every round alternating rigidlab (once per entry of `substeps`, a
// row each, so that its default and the sub-steps at which its results are as good as a peer's are
// compared in one run) with every peer program, so that a change in the machine's load hits every
// configuration; a peer five times slower than every rigidlab row runs in the first round only, and
// one run of a peer that takes more than `timeout_s` seconds (0: no limit) is stopped, reported as
// at least that time over the steps a step, and not run again.
// Prints each configuration's median over the rounds with its spread [min-max], the
// ratios rigidlab ÷ peer and every engine's quality figures. Scenes the peers do not have are
// reported as such.
int comparePeers(const std::vector<BenchScene>& scenes, const std::vector<PeerProgram>& peers, int rounds,
                 const std::vector<int>& substeps, int timeout_s, bool json);

}  // namespace rigidlab::app
