// suite.h - what the peer programs share for Box2D v3's benchmark suite (large_pyramid,
// many_pyramids, joint_grid, ragdolls, smash, spinner, tumbler, compounds, junkyard, washer): the
// scenes' sizes, step counts and
// sleeping, the engine-neutral quality figures and the JSON line. Each engine program builds the
// scenes as rigidlab's engine/app/bench_suite.cpp does, with its own API, and reports the figures
// rigidlab's suiteMetrics reports, computed the same way:
//   max_penetration_m   deepest touching contact point at the final positions
//   max_joint_gap_m     largest distance between a revolute (pivot) joint's two anchors at the end
//   moved_gt_0.25m      bodies more than 25 cm from where they were after the first step
//   mean_drop_m         mean fall of those bodies since the first step (a pile sinking)
//   top_height_loss_m   fall of the body that was highest after the first step
//   escaped             (compounds, junkyard, washer) bodies out of the scene's container at the end
#pragma once

#include "scenes.h"

namespace peer {

struct SuiteInfo {
    const char* name;
    int n;      // rigidlab's size figure for the scene (its bench's "n")
    int steps;  // default steps
    bool sleep; // sleeping allowed (Box2D v3's benchmark: off for the three piles of boxes and joints)
};

inline const SuiteInfo* suiteInfo(const std::string& name) {
    static const SuiteInfo kSuite[] = {
        {"large_pyramid", 5050, 500, false}, {"many_pyramids", 22000, 200, false}, {"joint_grid", 10000, 500, false},
        {"ragdolls", 11000, 1000, true},     {"smash", 9601, 300, true},          {"spinner", 6077, 500, true},
        {"tumbler", 2026, 750, true},        {"compounds", 3000, 500, true},      {"junkyard", 8001, 800, true},
        {"washer", 8101, 500, true},
    };
    for (const SuiteInfo& s : kSuite)
        if (name == s.name) return &s;
    return nullptr;
}

// One dynamic body as the figures see it: where it was after the first step (tracked) and now.
struct SuiteBody {
    bool tracked = false;  // existed after the first step and still exists at the end
    double x0 = 0, y0 = 0; // after the first step
    double x = 0, y = 0;   // at the end
};

struct SuiteFigures {
    int awake = 0, bodies = 0, joints = 0;  // at the end: awake dynamic bodies, dynamic bodies, joints
    double maxPenetration = 0.0;            // the engine computes it at the final positions
    double maxJointGap = 0.0;               // the engine computes it over its revolute/pivot joints
    int escaped = -1;                       // suiteEscaped; -1: the scene has no container
};

// Dynamic bodies out of the scene's container at the end, as rigidlab's escapedProbe counts them:
// compounds and junkyard, below the floor's middle (y < 0) or beyond a wall's middle (|x| > 40, 80);
// washer, farther than 16 m (the ring's inner face) from the drum's axis at (0, 10). -1 for the
// other scenes.
inline int suiteEscaped(const std::string& scene, const std::vector<SuiteBody>& dynamicBodies) {
    const double halfWidth = scene == "compounds" ? 40.0 : scene == "junkyard" ? 80.0 : 0.0;
    if (halfWidth == 0.0 && scene != "washer") return -1;
    int escaped = 0;
    for (const SuiteBody& b : dynamicBodies) {
        if (scene == "washer")
            escaped += std::sqrt(b.x * b.x + (b.y - 10.0) * (b.y - 10.0)) > 16.0 ? 1 : 0;
        else
            escaped += b.y < 0.0 || std::abs(b.x) > halfWidth ? 1 : 0;
    }
    return escaped;
}

inline std::string suiteMetricsJson(const SuiteFigures& f, const std::vector<SuiteBody>& dynamicBodies) {
    int moved = 0, tracked = 0;
    double drop = 0.0, topY0 = -1e300, topLoss = NAN;
    for (const SuiteBody& b : dynamicBodies) {
        if (!b.tracked) continue;
        ++tracked;
        const double dx = b.x - b.x0, dy = b.y - b.y0;
        moved += std::sqrt(dx * dx + dy * dy) > 0.25 ? 1 : 0;
        drop += b.y0 - b.y;
        if (b.y0 > topY0) {
            topY0 = b.y0;
            topLoss = b.y0 - b.y;
        }
    }
    Json j;
    j.integer("awake_at_end", f.awake);
    j.integer("bodies", f.bodies);
    j.integer("joints", f.joints);
    j.num("max_penetration_m", f.maxPenetration);
    j.num("max_joint_gap_m", f.maxJointGap);
    j.integer("moved_gt_0.25m", moved);
    j.num("mean_drop_m", tracked ? drop / tracked : NAN);
    j.num("top_height_loss_m", topLoss);
    if (f.escaped >= 0) j.integer("escaped", f.escaped);
    return j.done();
}

// One repetition of a suite scene.
struct SuiteRun {
    std::vector<double> stepMs;
    double setupMs = 0;
    int dynamicBodies = 0;
    int contacts = -1;    // touching contacts at the end (-1 unknown)
    std::string metrics;  // suiteMetricsJson
};

// One JSON line in the format of printResult (scenes.h), the last repetition's figures.
inline void printSuiteResult(const char* engine, const std::string& version, const SuiteInfo& info, int steps,
                             const std::string& settings, const std::vector<SuiteRun>& runs) {
    std::vector<double> meds, p95s, means, firsts, totals, setups;
    for (const auto& r : runs) {
        meds.push_back(median(r.stepMs));
        p95s.push_back(percentile(r.stepMs, 0.95));
        means.push_back(mean(r.stepMs));
        firsts.push_back(r.stepMs.empty() ? 0 : r.stepMs[0]);
        double tot = 0;
        for (double x : r.stepMs) tot += x;
        totals.push_back(tot);
        setups.push_back(r.setupMs);
    }
    Json j;
    j.str("engine", engine);
    j.str("version", version);
    j.str("build", PEER_BUILD);
    j.str("scene", info.name);
    j.integer("n", info.n);
    j.integer("dynamic_bodies", runs.empty() ? 0 : runs.back().dynamicBodies);
    j.integer("steps", steps);
    j.integer("reps", (long long)runs.size());
    j.boolean("sleep", info.sleep);
    j.raw("settings", settings);
    j.num("ms_median", median(meds));
    j.num("ms_median_best_rep", meds.empty() ? 0 : *std::min_element(meds.begin(), meds.end()));
    j.num("ms_p95", median(p95s));
    j.num("ms_mean", median(means));
    j.num("ms_first_step", median(firsts));
    j.num("ms_total", median(totals));
    j.num("ms_setup", median(setups));
    j.arr("rep_medians", meds);
    j.arr("rep_p95", p95s);
    if (!runs.empty() && runs.back().contacts >= 0) j.integer("contacts_at_end", runs.back().contacts);
    j.raw("metrics", runs.empty() ? "{}" : runs.back().metrics);
    std::printf("%s\n", j.done().c_str());
    std::fflush(stdout);
}

}  // namespace peer
