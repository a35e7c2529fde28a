// scenes.h - engine-agnostic scene descriptions, CLI parsing, timing statistics,
// stability metrics and JSON output shared by the peer benchmark programs.
//
// Every engine program does exactly the same thing:
//   1. parse Options from argv,
//   2. Scene sc = buildScene(opt)           (identical bodies for every engine),
//   3. for rep in reps: create world from sc, time each Step with steady_clock,
//      read back final body states,
//   4. print one JSON line via printResult().
//
// Units: meters, kilograms, seconds. Gravity (0,-10). dt = 1/60.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace peer {

// ---------------------------------------------------------------- options --

struct Options {
    std::string scene;        // pyramid | stack | rain | massratio | bullet
    int n = -1;               // scene size (-1: scene default)
    int steps = -1;           // steps to simulate (-1: scene default)
    int reps = 3;             // repetitions (fresh world each); medians reported
    bool sleep = false;       // allow sleeping (timing runs use false)
    std::string top = "heavy";  // massratio: which box is on top: heavy | light
    double offset = 0.0;      // stack: alternating +/- x offset of boxes (m)
    double heavyHalf = 1.0;   // massratio: heavy box half extent
    double heavyMass = 1000;  // massratio: heavy box mass, kg
    // Box2D 2.4
    int velIters = 8;
    int posIters = 3;
    bool bullet = false;      // b2BodyDef::bullet on the projectile
    bool continuous = true;   // b2World::SetContinuousPhysics
    // Box2D 3.x
    int subSteps = 4;
    int workers = 1;
    bool softening = false;   // b2WorldDef::enableContactSoftening (experimental, off by default)
    // Chipmunk
    int iterations = 10;      // cpSpaceSetIterations (Chipmunk default 10)
    double slop = -1.0;       // cpSpaceSetCollisionSlop (-1: keep Chipmunk default 0.1)
    int threads = 0;          // >0: use cpHastySpace with this many threads
    bool rawFriction = false; // Chipmunk: set shape friction = mu (pair mu*mu) instead of sqrt(mu)
};

inline void usage(const char* prog) {
    std::fprintf(stderr,
        "usage: %s <pyramid|stack|rain|massratio|bullet> [--n=N] [--steps=S] [--reps=R]\n"
        "       %s <large_pyramid|many_pyramids|joint_grid|ragdolls|smash|spinner|tumbler|\n"
        "           compounds|junkyard|washer> [--steps=S] [--reps=R]\n"
        "          (Box2D v3's benchmark suite, as rigidlab's engine/app/bench_suite.cpp builds it; suite.h)\n"
        "          [--sleep=0|1] [--top=heavy|light] [--heavy-half=1.0] [--heavy-mass=1000] [--offset=M]\n"
        "          box2d:    [--vel-iters=8] [--pos-iters=3] [--bullet=0|1] [--continuous=0|1]\n"
        "          box2d v3: [--substeps=4] [--workers=1] [--softening=0|1] [--bullet=0|1] [--continuous=0|1]\n"
        "          chipmunk: [--iterations=10] [--slop=0.1] [--threads=0] [--raw-friction=0|1]\n",
        prog, prog);
}

inline bool parseArgs(int argc, char** argv, Options& o) {
    if (argc < 2 || argv[1][0] == '-') return false;  // also -h / --help
    o.scene = argv[1];
    for (int i = 2; i < argc; ++i) {
        const char* a = argv[i];
        const char* eq = std::strchr(a, '=');
        if (std::strncmp(a, "--", 2) != 0 || !eq) {
            std::fprintf(stderr, "bad option '%s'\n", a);
            return false;
        }
        std::string key(a + 2, eq);
        const char* v = eq + 1;
        if (key == "n") o.n = std::atoi(v);
        else if (key == "steps") o.steps = std::atoi(v);
        else if (key == "reps") o.reps = std::max(1, std::atoi(v));
        else if (key == "sleep") o.sleep = std::atoi(v) != 0;
        else if (key == "top") o.top = v;
        else if (key == "offset") o.offset = std::atof(v);
        else if (key == "heavy-half") o.heavyHalf = std::atof(v);
        else if (key == "heavy-mass") o.heavyMass = std::atof(v);
        else if (key == "vel-iters") o.velIters = std::atoi(v);
        else if (key == "pos-iters") o.posIters = std::atoi(v);
        else if (key == "bullet") o.bullet = std::atoi(v) != 0;
        else if (key == "continuous") o.continuous = std::atoi(v) != 0;
        else if (key == "substeps") o.subSteps = std::atoi(v);
        else if (key == "workers") o.workers = std::atoi(v);
        else if (key == "softening") o.softening = std::atoi(v) != 0;
        else if (key == "iterations") o.iterations = std::atoi(v);
        else if (key == "slop") o.slop = std::atof(v);
        else if (key == "threads") o.threads = std::atoi(v);
        else if (key == "raw-friction") o.rawFriction = std::atoi(v) != 0;
        else {
            std::fprintf(stderr, "unknown option '--%s'\n", key.c_str());
            return false;
        }
    }
    const char* scenes[] = {"pyramid", "stack", "rain", "massratio", "bullet", "large_pyramid", "many_pyramids",
                            "joint_grid", "ragdolls", "smash", "spinner", "tumbler", "compounds", "junkyard", "washer"};
    for (const char* s : scenes)
        if (o.scene == s) return true;
    std::fprintf(stderr, "unknown scene '%s'\n", o.scene.c_str());
    return false;
}

// ------------------------------------------------------------------ scene --

enum class Shape { Box, Circle };

struct BodyDesc {
    Shape shape = Shape::Box;
    bool isStatic = false;
    double x = 0, y = 0;      // center (world)
    double hx = 0.5, hy = 0.5;  // box half extents
    double r = 0.5;           // circle radius
    double density = 1.0;
    double friction = 0.6;    // desired *pair* friction coefficient
    double vx = 0, vy = 0;    // initial linear velocity
    bool projectile = false;  // bullet scene: the fast circle
};

struct Scene {
    std::string name;
    int n = 0;
    int steps = 0;
    double dt = 1.0 / 60.0;
    double gx = 0.0, gy = -10.0;
    std::vector<BodyDesc> bodies;  // statics first, then dynamics
    // scene-specific bookkeeping for metrics
    int topIndex = -1;     // pyramid/stack: top box; massratio: top box
    int bottomIndex = -1;  // massratio: bottom box
    double wallX = 0, wallHx = 0;  // bullet
    double contMinX = 0, contMaxX = 0, contFloorY = 0;  // rain container interior
};

// Deterministic 32-bit xorshift PRNG (same sequence for every engine).
struct Rng {
    uint32_t s;
    explicit Rng(uint32_t seed) : s(seed ? seed : 0x9E3779B9u) {}
    uint32_t next() {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        return s;
    }
    double uniform() { return (next() >> 8) * (1.0 / 16777216.0); }  // [0,1)
    double range(double lo, double hi) { return lo + (hi - lo) * uniform(); }
};

inline BodyDesc staticBox(double cx, double cy, double hx, double hy, double friction = 0.6) {
    BodyDesc b;
    b.shape = Shape::Box;
    b.isStatic = true;
    b.x = cx; b.y = cy; b.hx = hx; b.hy = hy;
    b.density = 0.0;
    b.friction = friction;
    return b;
}

inline BodyDesc dynBox(double cx, double cy, double hx, double hy, double density, double friction = 0.6) {
    BodyDesc b;
    b.shape = Shape::Box;
    b.x = cx; b.y = cy; b.hx = hx; b.hy = hy;
    b.density = density;
    b.friction = friction;
    return b;
}

inline BodyDesc dynCircle(double cx, double cy, double r, double density, double friction = 0.6) {
    BodyDesc b;
    b.shape = Shape::Circle;
    b.x = cx; b.y = cy; b.r = r;
    b.density = density;
    b.friction = friction;
    return b;
}

inline Scene buildScene(const Options& o) {
    Scene sc;
    sc.name = o.scene;

    if (o.scene == "pyramid") {
        // Ground: static box, top surface at y = 0. Pyramid of unit boxes, base N,
        // rows exactly 1 m apart (touching), same layout as Box2D v3 large_pyramid.
        int N = o.n > 0 ? o.n : 20;
        sc.n = N;
        sc.steps = o.steps > 0 ? o.steps : (N <= 40 ? 500 : 300);
        double groundHalf = std::max(50.0, 0.5 * N + 10.0);
        sc.bodies.push_back(staticBox(0.0, -1.0, groundHalf, 1.0));
        const double a = 0.5;
        for (int i = 0; i < N; ++i) {
            double y = (2.0 * i + 1.0) * a;
            for (int j = i; j < N; ++j) {
                double x = (i + 1.0) * a + 2.0 * (j - i) * a - a * N;
                sc.bodies.push_back(dynBox(x, y, a, a, 1.0, 0.6));
            }
        }
        sc.topIndex = (int)sc.bodies.size() - 1;
    } else if (o.scene == "stack") {
        // Vertical column of N unit boxes on static ground, touching.
        // --offset=d shifts boxes alternately by +d/-d in x (default 0: perfectly aligned).
        int N = o.n > 0 ? o.n : 10;
        sc.n = N;
        sc.steps = o.steps > 0 ? o.steps : 600;  // 10 s
        sc.bodies.push_back(staticBox(0.0, -1.0, 20.0, 1.0));
        for (int i = 0; i < N; ++i) {
            double dx = (i % 2 == 0 ? 1.0 : -1.0) * o.offset;
            sc.bodies.push_back(dynBox(dx, 0.5 + i, 0.5, 0.5, 1.0, 0.6));
        }
        sc.topIndex = (int)sc.bodies.size() - 1;
    } else if (o.scene == "rain") {
        // Container: 40 m wide interior, floor top at y = 0, walls 150 m tall.
        // N circles, radius U(0.25,0.5), placed on a jittered grid (pitch 1.05 m,
        // 36 columns) starting 1 m above the floor, all released at t = 0.
        int N = o.n > 0 ? o.n : 1000;
        sc.n = N;
        sc.steps = o.steps > 0 ? o.steps : 600;
        const double W = 40.0, wallH = 150.0, t = 0.5;
        sc.bodies.push_back(staticBox(0.0, -t, 0.5 * W + 2 * t, t));                // floor
        sc.bodies.push_back(staticBox(-0.5 * W - t, 0.5 * wallH, t, 0.5 * wallH));  // left wall
        sc.bodies.push_back(staticBox(0.5 * W + t, 0.5 * wallH, t, 0.5 * wallH));   // right wall
        sc.contMinX = -0.5 * W;
        sc.contMaxX = 0.5 * W;
        sc.contFloorY = 0.0;
        Rng rng(12345u);
        const int cols = 36;
        const double pitch = 1.05;
        for (int k = 0; k < N; ++k) {
            int row = k / cols, col = k % cols;
            double r = rng.range(0.25, 0.5);
            double jx = rng.range(-0.02, 0.02);
            double x = -0.5 * (cols - 1) * pitch + col * pitch + jx;
            double y = 1.0 + row * pitch;
            sc.bodies.push_back(dynCircle(x, y, r, 1.0, 0.6));
        }
    } else if (o.scene == "massratio") {
        // Light box: 1 m x 1 m, density 1 -> 1 kg.
        // Heavy box: 2 m x 2 m, density 250 -> 1000 kg (--heavy-half=h: 2h x 2h;
        // --heavy-mass=M: M kg).
        // --top=heavy: light box on the ground, heavy box on top (the hard case).
        // --top=light: heavy box on the ground, light box on top.
        sc.n = 2;
        sc.steps = o.steps > 0 ? o.steps : 300;  // 5 s
        sc.bodies.push_back(staticBox(0.0, -1.0, 20.0, 1.0));
        BodyDesc light = dynBox(0, 0, 0.5, 0.5, 1.0, 0.6);
        double hh = o.heavyHalf > 0 ? o.heavyHalf : 1.0;
        BodyDesc heavy = dynBox(0, 0, hh, hh, o.heavyMass / (4.0 * hh * hh), 0.6);
        BodyDesc bot = (o.top == "light") ? heavy : light;
        BodyDesc top = (o.top == "light") ? light : heavy;
        bot.y = bot.hy;
        top.y = 2.0 * bot.hy + top.hy;
        sc.bodies.push_back(bot);
        sc.bottomIndex = 1;
        sc.bodies.push_back(top);
        sc.topIndex = 2;
    } else if (o.scene == "bullet") {
        // 0.1 m radius circle at (0,0) moving at +500 m/s toward a static wall,
        // 0.1 m thick, whose near face is 10 m away. 1 s simulated.
        // --n=K (K>1) adds a phase sweep: projectile i starts at x = -i*(v*dt)/K and
        // y = 0, +0.5, -0.5, +1, ... (non-interacting), so the K projectiles reach the
        // wall at K different sub-step phases. Projectile 0 is always the spec case.
        int K = o.n > 0 ? o.n : 1;
        sc.n = K;
        sc.steps = o.steps > 0 ? o.steps : 60;
        sc.wallHx = 0.05;
        sc.wallX = 10.0 + sc.wallHx;
        const double v = 500.0;
        sc.bodies.push_back(staticBox(sc.wallX, 0.0, sc.wallHx, 0.5 * K + 5.0));
        sc.topIndex = 1;
        for (int i = 0; i < K; ++i) {
            double y = (i % 2 ? 1.0 : -1.0) * 0.5 * ((i + 1) / 2);
            BodyDesc b = dynCircle(-i * v * sc.dt / K, y, 0.1, 1.0, 0.6);
            b.vx = v;
            b.projectile = true;
            sc.bodies.push_back(b);
        }
    }
    return sc;
}

// ------------------------------------------------------------ body states --

struct BodyState {
    double x = 0, y = 0, angle = 0, vx = 0, vy = 0;
    bool awake = true;
};

// Per-step observation (outside the timed region) for the mass-ratio scene:
// first time the stack counts as collapsed and the worst box-box penetration.
struct Tracker {
    double collapseTime = -1.0;
    double maxBoxPen = -1e30;
    double maxGroundPen = -1e30;
    double vxAfterFirstStep = NAN;  // bullet: projectile 0 speed after step 1
    double leanTime = -1.0;         // stack: first time |top box dx| > 0.1 m
};

inline void observeStack(const Scene& sc, Tracker& t, int step, const BodyState& top) {
    if (t.leanTime < 0 && std::fabs(top.x - sc.bodies[sc.topIndex].x) > 0.1) t.leanTime = (step + 1) * sc.dt;
}

inline bool massRatioCollapsed(const BodyDesc& bd, const BodyDesc& td, const BodyState& bs, const BodyState& ts,
                               double* boxPenOut = nullptr) {
    double boxPen = (bd.hy + td.hy) - (ts.y - bs.y);
    if (boxPenOut) *boxPenOut = boxPen;
    bool slidOff = std::fabs(ts.x - bs.x) > bd.hx + td.hx;
    // collapsed: top box sank > 25% of the smaller box height into the bottom one,
    // slid off, or ended up below it
    return slidOff || boxPen > 0.5 * std::min(bd.hy, td.hy) || ts.y < bs.y;
}

inline double boxBottom(const BodyDesc& d, const BodyState& s);

inline void observeMassRatio(const Scene& sc, Tracker& t, int step, const BodyState& bs, const BodyState& ts) {
    const auto& bd = sc.bodies[sc.bottomIndex];
    const auto& td = sc.bodies[sc.topIndex];
    double boxPen;
    bool c = massRatioCollapsed(bd, td, bs, ts, &boxPen);
    if (c && t.collapseTime < 0) t.collapseTime = (step + 1) * sc.dt;
    t.maxBoxPen = std::max(t.maxBoxPen, boxPen);
    t.maxGroundPen = std::max(t.maxGroundPen, 0.0 - boxBottom(bd, bs));
}

// Result of one repetition.
struct RunResult {
    Tracker track;
    std::vector<double> stepMs;        // wall time of each Step, ms
    std::vector<BodyState> final;      // indexed like Scene::bodies (statics too)
    int contacts = -1;                 // engine-reported contact count at end (-1 unknown)
    double setupMs = 0;
};

// --------------------------------------------------------------- statistics --

inline double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

inline double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    size_t idx = (size_t)std::ceil(p * v.size());
    if (idx > 0) --idx;
    return v[std::min(idx, v.size() - 1)];
}

inline double mean(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0 : s / v.size();
}

using Clock = std::chrono::steady_clock;
inline double msSince(Clock::time_point t0, Clock::time_point t1) {
    return std::chrono::duration<double, std::milli>(t1 - t0).count();
}

// ------------------------------------------------------------------- JSON --

struct Json {
    std::string s;
    bool first = true;
    void sep() { if (!first) s += ", "; first = false; }
    void key(const char* k) { sep(); s += '"'; s += k; s += "\": "; }
    void num(const char* k, double v) {
        key(k);
        char buf[64];
        if (std::isfinite(v)) std::snprintf(buf, sizeof buf, "%.6g", v);
        else std::snprintf(buf, sizeof buf, "null");
        s += buf;
    }
    void integer(const char* k, long long v) { key(k); s += std::to_string(v); }
    void boolean(const char* k, bool v) { key(k); s += v ? "true" : "false"; }
    void str(const char* k, const std::string& v) { key(k); s += '"'; s += v; s += '"'; }
    void raw(const char* k, const std::string& v) { key(k); s += v; }
    void arr(const char* k, const std::vector<double>& v) {
        key(k);
        s += '[';
        char buf[64];
        for (size_t i = 0; i < v.size(); ++i) {
            std::snprintf(buf, sizeof buf, "%s%.6g", i ? ", " : "", v[i]);
            s += buf;
        }
        s += ']';
    }
    std::string done() const { return "{" + s + "}"; }
};

// ---------------------------------------------------------------- metrics --

inline double boxBottom(const BodyDesc& d, const BodyState& s) {
    // lowest point of an (possibly rotated) box
    double c = std::fabs(std::cos(s.angle)), sn = std::fabs(std::sin(s.angle));
    return s.y - (d.hx * sn + d.hy * c);
}

// Scene-specific stability metrics, computed from the last repetition's final
// state (all engines here are deterministic single-threaded, reps agree).
inline std::string sceneMetrics(const Scene& sc, const RunResult& r) {
    Json j;
    const auto& B = sc.bodies;
    const auto& F = r.final;
    int awake = 0, dyn = 0;
    for (size_t i = 0; i < B.size(); ++i)
        if (!B[i].isStatic) { ++dyn; awake += F[i].awake ? 1 : 0; }
    j.integer("awake_at_end", awake);

    if (sc.name == "pyramid" || sc.name == "stack") {
        double maxDisp = 0, sumDisp = 0, maxY = -1e30;
        int moved = 0;
        for (size_t i = 0; i < B.size(); ++i) {
            if (B[i].isStatic) continue;
            double dx = F[i].x - B[i].x, dy = F[i].y - B[i].y;
            double d = std::sqrt(dx * dx + dy * dy);
            maxDisp = std::max(maxDisp, d);
            sumDisp += d;
            if (d > 0.25) ++moved;
            if ((int)i != sc.topIndex) maxY = std::max(maxY, F[i].y);
        }
        const auto& t0 = B[sc.topIndex];
        const auto& t1 = F[sc.topIndex];
        bool topOnTop = t1.y > maxY + 0.5 && std::fabs(t1.x - t0.x) < 0.5;
        j.num("max_disp_m", maxDisp);
        j.num("mean_disp_m", sumDisp / std::max(1, dyn));
        j.integer("moved_gt_0.25m", moved);
        j.boolean("top_on_top", topOnTop);
        j.num("top_dx_m", t1.x - t0.x);
        j.num("top_height_loss_m", t0.y - t1.y);
        j.num("top_angle_rad", t1.angle);
        double maxAbsDx = 0, maxAbsAngle = 0;
        for (size_t i = 0; i < B.size(); ++i) {
            if (B[i].isStatic) continue;
            maxAbsDx = std::max(maxAbsDx, std::fabs(F[i].x - B[i].x));
            maxAbsAngle = std::max(maxAbsAngle, std::fabs(F[i].angle));
        }
        j.num("max_abs_dx_m", maxAbsDx);
        j.num("max_abs_angle_rad", maxAbsAngle);
        if (sc.name == "stack") {
            j.num("lean_0.1m_time_s", r.track.leanTime);
            j.boolean("toppled", t0.y - t1.y > 0.5);
        }
    } else if (sc.name == "rain") {
        int escaped = 0;
        double maxTop = -1e30, maxSpeed = 0, sumSpeed = 0, maxBoundaryPen = 0;
        std::vector<int> circles;
        for (size_t i = 0; i < B.size(); ++i) {
            if (B[i].isStatic) continue;
            circles.push_back((int)i);
            const auto& s = F[i];
            double r = B[i].r;
            // escaped: center left the container interior (or non-finite)
            if (!(s.x > sc.contMinX && s.x < sc.contMaxX && s.y > sc.contFloorY)) ++escaped;
            double bpen = std::max({sc.contMinX - (s.x - r), (s.x + r) - sc.contMaxX, sc.contFloorY - (s.y - r)});
            maxBoundaryPen = std::max(maxBoundaryPen, bpen);
            maxTop = std::max(maxTop, s.y + r);
            double sp = std::sqrt(s.vx * s.vx + s.vy * s.vy);
            maxSpeed = std::max(maxSpeed, sp);
            sumSpeed += sp;
        }
        // pairwise circle overlap (uniform grid, cell = 1 m = max diameter)
        double maxPen = 0, sumPen = 0;
        int overlapping = 0;
        {
            const double cell = 1.0;
            double minX = -25, minY = -5;
            int gw = 60, gh = 2000;
            std::vector<std::vector<int>> grid((size_t)gw * gh);
            auto cellOf = [&](double x, double y, int& cx, int& cy) {
                cx = std::clamp((int)std::floor((x - minX) / cell), 0, gw - 1);
                cy = std::clamp((int)std::floor((y - minY) / cell), 0, gh - 1);
            };
            for (int i : circles) {
                int cx, cy;
                cellOf(F[i].x, F[i].y, cx, cy);
                grid[(size_t)cy * gw + cx].push_back(i);
            }
            for (int i : circles) {
                int cx, cy;
                cellOf(F[i].x, F[i].y, cx, cy);
                for (int yy = std::max(0, cy - 1); yy <= std::min(gh - 1, cy + 1); ++yy)
                    for (int xx = std::max(0, cx - 1); xx <= std::min(gw - 1, cx + 1); ++xx)
                        for (int k : grid[(size_t)yy * gw + xx]) {
                            if (k <= i) continue;
                            double dx = F[k].x - F[i].x, dy = F[k].y - F[i].y;
                            double pen = B[i].r + B[k].r - std::sqrt(dx * dx + dy * dy);
                            if (pen > 0) {
                                maxPen = std::max(maxPen, pen);
                                sumPen += pen;
                                ++overlapping;
                            }
                        }
            }
        }
        j.integer("escaped", escaped);
        j.num("pile_top_m", maxTop);
        j.num("mean_speed_mps", sumSpeed / std::max(1, dyn));
        j.num("max_speed_mps", maxSpeed);
        j.num("max_boundary_overlap_m", maxBoundaryPen);
        j.integer("overlapping_pairs", overlapping);
        j.num("max_overlap_m", maxPen);
        j.num("mean_overlap_m", overlapping ? sumPen / overlapping : 0.0);
    } else if (sc.name == "massratio") {
        const auto& bd = B[sc.bottomIndex];
        const auto& td = B[sc.topIndex];
        const auto& bs = F[sc.bottomIndex];
        const auto& ts = F[sc.topIndex];
        // penetration > 0 means overlap of the *core* geometry (Box2D 2.4 keeps a
        // 2 x 0.01 m polygon skin, so a resting Box2D 2.4 contact shows a negative value)
        double groundPen = 0.0 - boxBottom(bd, bs);
        double boxPen;
        bool collapsed = massRatioCollapsed(bd, td, bs, ts, &boxPen);
        j.num("top_mass_kg", td.density * 4 * td.hx * td.hy);
        j.num("bottom_mass_kg", bd.density * 4 * bd.hx * bd.hy);
        j.num("ground_penetration_m", groundPen);
        j.num("box_box_penetration_m", boxPen);
        j.num("max_box_box_penetration_m", r.track.maxBoxPen);
        j.num("max_ground_penetration_m", r.track.maxGroundPen);
        j.num("collapse_time_s", r.track.collapseTime);
        j.num("top_dx_m", ts.x - td.x);
        j.num("top_height_loss_m", td.y - ts.y);
        j.num("bottom_angle_rad", bs.angle);
        j.boolean("collapsed", collapsed);
    } else if (sc.name == "bullet") {
        int passedCount = 0;
        for (size_t i = 0; i < B.size(); ++i)
            if (B[i].projectile && F[i].x - B[i].r > sc.wallX + sc.wallHx) ++passedCount;
        const auto& s = F[sc.topIndex];
        double rad = B[sc.topIndex].r;
        bool passed = s.x - rad > sc.wallX + sc.wallHx;
        j.boolean("passed_through", passed);
        j.num("final_x_m", s.x);
        j.num("final_vx_mps", s.vx);
        j.num("vx_after_step1_mps", r.track.vxAfterFirstStep);
        j.num("wall_near_face_x_m", sc.wallX - sc.wallHx);
        j.integer("projectiles", sc.n);
        j.integer("passed_count", passedCount);
    }
    return j.done();
}

inline std::string settingsJson(const std::vector<std::pair<std::string, double>>& kv) {
    Json j;
    for (auto& p : kv) j.num(p.first.c_str(), p.second);
    return j.done();
}

// Aggregate reps and print one JSON line.
#ifndef PEER_BUILD
#define PEER_BUILD "debian-pkg"  // which library build this binary links (see Makefile)
#endif

inline void printResult(const char* engine, const std::string& version, const Options& o, const Scene& sc,
                        const std::string& settings, const std::vector<RunResult>& runs) {
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
    int dyn = 0;
    for (auto& b : sc.bodies) dyn += b.isStatic ? 0 : 1;

    Json j;
    j.str("engine", engine);
    j.str("version", version);
    j.str("build", PEER_BUILD);
    j.str("scene", sc.name);
    j.integer("n", sc.n);
    if (sc.name == "massratio") {
        j.str("top", o.top);
        j.num("heavy_half", o.heavyHalf);
        j.num("heavy_mass", o.heavyMass);
    }
    if (sc.name == "stack") j.num("offset", o.offset);
    j.integer("dynamic_bodies", dyn);
    j.integer("steps", sc.steps);
    j.integer("reps", (long long)runs.size());
    j.boolean("sleep", o.sleep);
    j.raw("settings", settings);
    j.num("ms_median", median(meds));
    j.num("ms_median_best_rep", *std::min_element(meds.begin(), meds.end()));
    j.num("ms_p95", median(p95s));
    j.num("ms_mean", median(means));
    j.num("ms_first_step", median(firsts));
    j.num("ms_total", median(totals));
    j.num("ms_setup", median(setups));
    j.arr("rep_medians", meds);
    j.arr("rep_p95", p95s);
    if (!runs.empty() && runs.back().contacts >= 0) j.integer("contacts_at_end", runs.back().contacts);
    j.raw("metrics", runs.empty() ? "{}" : sceneMetrics(sc, runs.back()));
    std::printf("%s\n", j.done().c_str());
    std::fflush(stdout);
}

}  // namespace peer
