// chipmunk_bench.cpp - Chipmunk2D 7.x peer benchmark (Debian libchipmunk-dev).
// usage: chipmunk_bench <scene> [options]   (see scenes.h / --help)
#include "scenes.h"
#include "suite.h"

#include <chipmunk/chipmunk.h>
#include <chipmunk/chipmunk_structs.h>  // cpBody::v, see dampedVelocity
#include <unistd.h>

#include <deque>
extern "C" {  // cpHastySpace.h has no C++ guards of its own
#include <chipmunk/cpHastySpace.h>
}

using namespace peer;

// Chipmunk combines friction as a*b (Box2D uses sqrt(a*b)). To give every
// contact pair the scene's pair coefficient mu, each shape gets sqrt(mu).
static double shapeFriction(double mu, const Options& o) { return o.rawFriction ? mu : std::sqrt(mu); }

static void countArbiter(cpBody* body, cpArbiter* arb, void* data) {
    int* n = static_cast<int*>(data);
    cpBody *a, *b;
    cpArbiterGetBodies(arb, &a, &b);
    cpBody* other = (a == body) ? b : a;
    if (cpArbiterGetCount(arb) == 0) return;
    if (cpBodyGetType(other) != CP_BODY_TYPE_DYNAMIC || body < other) ++*n;
}

static BodyState stateOf(cpBody* b) {
    BodyState st;
    cpVect p = cpBodyGetPosition(b), v = cpBodyGetVelocity(b);
    st.x = p.x;
    st.y = p.y;
    st.angle = cpBodyGetAngle(b);
    st.vx = v.x;
    st.vy = v.y;
    st.awake = !cpBodyIsSleeping(b);
    return st;
}

static RunResult runOnce(const Scene& sc, const Options& o) {
    RunResult rr;
    auto t0 = Clock::now();
    const bool hasty = o.threads > 0;
    cpSpace* space = hasty ? cpHastySpaceNew() : cpSpaceNew();
    if (hasty) cpHastySpaceSetThreads(space, (unsigned long)o.threads);
    cpSpaceSetGravity(space, cpv(sc.gx, sc.gy));
    cpSpaceSetIterations(space, o.iterations);
    if (o.slop >= 0) cpSpaceSetCollisionSlop(space, o.slop);
    // Chipmunk's default sleepTimeThreshold is INFINITY (sleeping off);
    // with --sleep=1 use 0.5 s like Box2D's b2_timeToSleep.
    if (o.sleep) cpSpaceSetSleepTimeThreshold(space, 0.5);

    std::vector<cpBody*> bodies(sc.bodies.size(), nullptr);
    std::vector<cpBody*> ownedBodies;
    std::vector<cpShape*> shapes;
    cpBody* staticBody = cpSpaceGetStaticBody(space);
    for (size_t i = 0; i < sc.bodies.size(); ++i) {
        const BodyDesc& d = sc.bodies[i];
        cpShape* shape = nullptr;
        if (d.isStatic) {
            // static geometry lives on the space's static body, at world coordinates
            bodies[i] = staticBody;
            if (d.shape == Shape::Box)
                shape = cpBoxShapeNew2(staticBody, cpBBNew(d.x - d.hx, d.y - d.hy, d.x + d.hx, d.y + d.hy), 0.0);
            else
                shape = cpCircleShapeNew(staticBody, d.r, cpv(d.x, d.y));
        } else {
            cpFloat mass, moment;
            if (d.shape == Shape::Box) {
                mass = d.density * 4.0 * d.hx * d.hy;
                moment = cpMomentForBox(mass, 2.0 * d.hx, 2.0 * d.hy);
            } else {
                mass = d.density * CP_PI * d.r * d.r;
                moment = cpMomentForCircle(mass, 0.0, d.r, cpvzero);
            }
            cpBody* body = cpSpaceAddBody(space, cpBodyNew(mass, moment));
            cpBodySetPosition(body, cpv(d.x, d.y));
            cpBodySetVelocity(body, cpv(d.vx, d.vy));
            bodies[i] = body;
            ownedBodies.push_back(body);
            if (d.shape == Shape::Box)
                shape = cpBoxShapeNew(body, 2.0 * d.hx, 2.0 * d.hy, 0.0);
            else
                shape = cpCircleShapeNew(body, d.r, cpvzero);
        }
        cpShapeSetFriction(shape, shapeFriction(d.friction, o));
        cpShapeSetElasticity(shape, 0.0);
        cpSpaceAddShape(space, shape);
        shapes.push_back(shape);
    }
    rr.setupMs = msSince(t0, Clock::now());

    const bool track = sc.name == "massratio";
    rr.stepMs.reserve(sc.steps);
    for (int s = 0; s < sc.steps; ++s) {
        auto a = Clock::now();
        if (hasty)
            cpHastySpaceStep(space, sc.dt);
        else
            cpSpaceStep(space, sc.dt);
        auto b = Clock::now();
        rr.stepMs.push_back(msSince(a, b));
        if (track) observeMassRatio(sc, rr.track, s, stateOf(bodies[sc.bottomIndex]), stateOf(bodies[sc.topIndex]));
        if (s == 0 && sc.name == "bullet") rr.track.vxAfterFirstStep = stateOf(bodies[sc.topIndex]).vx;
        if (sc.name == "stack") observeStack(sc, rr.track, s, stateOf(bodies[sc.topIndex]));
    }

    rr.final.resize(bodies.size());
    int contacts = 0;
    for (size_t i = 0; i < bodies.size(); ++i) {
        BodyState& st = rr.final[i];
        if (sc.bodies[i].isStatic) {
            st.x = sc.bodies[i].x;
            st.y = sc.bodies[i].y;
            st.awake = false;
            continue;
        }
        st = stateOf(bodies[i]);
        cpBodyEachArbiter(bodies[i], countArbiter, &contacts);
    }
    rr.contacts = contacts;

    for (cpShape* s : shapes) cpSpaceRemoveShape(space, s);
    for (cpBody* b : ownedBodies) cpSpaceRemoveBody(space, b);
    for (cpShape* s : shapes) cpShapeFree(s);
    for (cpBody* b : ownedBodies) cpBodyFree(b);
    if (hasty)
        cpHastySpaceFree(space);
    else
        cpSpaceFree(space);
    return rr;
}

// ------------------------------------------------------------ Box2D v3 suite --
// The ten scenes of Box2D v3's benchmark suite (suite.h), built as rigidlab's
// engine/app/bench_suite.cpp builds them: the same bodies, shapes, densities, materials, filters,
// joints and step counts, each of rigidlab's words said in Chipmunk's where it is used.

// rigidlab's default Filter{category 1, mask all, group 0}: the grounds and every plain body are
// category 1, which the ragdolls' masks (1|2 and the feet's 1) see. Chipmunk tests masks both
// ways, as rigidlab and Box2D do.
static cpShapeFilter defaultFilter() { return cpShapeFilterNew(CP_NO_GROUP, 1, CP_ALL_CATEGORIES); }

// One dynamic body the figures follow (suite.h): removed ones stay, marked, so that the deque's
// addresses (a damped body's user data) stay valid.
struct SuiteDyn {
    cpBody* body = nullptr;
    double linearDamping = 0.0;  // rigidlab's BodyDef::linear_damping
    bool alive = true, tracked = false;
    double x0 = 0, y0 = 0;       // after the first step
};

struct SuiteSpace {
    cpSpace* space = nullptr;
    const Options* o = nullptr;
    std::deque<SuiteDyn> dyn;
    int joints = 0;  // rigidlab's joints alive: pivots only, not their limit/motor/spring helpers
    cpBody* pusher = nullptr;  // junkyard's kinematic pusher
    cpBody* ground() const { return cpSpaceGetStaticBody(space); }  // rigidlab's static body at the origin
};

// Chipmunk damps only space-wide (cpSpaceSetDamping); rigidlab damps single bodies (the ragdolls'
// heads and lower arms), as Box2D v3 does: the velocity the step starts with, implicitly,
// v <- v / (1 + dt c), before gravity is added (core/src/integrator.cpp). cpBodySetVelocity would
// reset the body's idle time (cpBodyActivate) every step and keep its ragdoll from sleeping, hence
// the direct write.
static void dampedVelocity(cpBody* body, cpVect gravity, cpFloat damping, cpFloat dt) {
    const SuiteDyn* d = static_cast<const SuiteDyn*>(cpBodyGetUserData(body));
    body->v = cpvmult(body->v, 1.0 / (1.0 + dt * d->linearDamping));
    cpBodyUpdateVelocity(body, gravity, damping, dt);
}

// A dynamic body whose mass and moment come from its shapes' densities (cpShapeSetDensity).
static cpBody* addDynamic(SuiteSpace& s, cpVect position, double linearDamping = 0.0) {
    cpBody* body = cpSpaceAddBody(s.space, cpBodyNew(0.0, 0.0));
    cpBodySetPosition(body, position);
    s.dyn.push_back(SuiteDyn{body, linearDamping});
    if (linearDamping > 0.0) {
        cpBodySetUserData(body, &s.dyn.back());
        cpBodySetVelocityUpdateFunc(body, dampedVelocity);
    }
    return body;
}

// rigidlab's addShape(density, friction, restitution, filter). Chipmunk multiplies the two
// shapes' friction and elasticity where rigidlab takes sqrt(fa fb) and max(ea, eb): each shape
// gets sqrt(mu) (shapeFriction) and sqrt(e), which gives pairs of equal materials their value.
static cpShape* addShape(SuiteSpace& s, cpShape* shape, double density = 1.0, double friction = 0.6,
                         double restitution = 0.0, cpShapeFilter filter = defaultFilter()) {
    if (cpBodyGetType(cpShapeGetBody(shape)) == CP_BODY_TYPE_DYNAMIC) cpShapeSetDensity(shape, density);
    cpShapeSetFriction(shape, shapeFriction(friction, *s.o));
    cpShapeSetElasticity(shape, std::sqrt(restitution));
    cpShapeSetFilter(shape, filter);
    return cpSpaceAddShape(s.space, shape);
}

// rigidlab's makeBox(width, height, center): FULL width and height, centre in body coordinates.
static cpShape* boxShape(cpBody* body, double width, double height, cpVect center = cpvzero) {
    return cpBoxShapeNew2(body, cpBBNewForExtents(center, 0.5 * width, 0.5 * height), 0.0);
}

// rigidlab's revolute joint (anchor in world coordinates): a pivot joint. Its limits, motor and
// spring are Chipmunk constraints of their own on the same two bodies (addMotor, addHuman).
static void addPivot(SuiteSpace& s, cpBody* a, cpBody* b, cpVect anchor) {
    cpSpaceAddConstraint(s.space, cpPivotJointNew(a, b, anchor));
    ++s.joints;
}

// rigidlab's revolute motor turns b at +speed relative to a (counter-clockwise positive); Chipmunk's
// simple motor drives w_b - w_a to -rate (cpSimpleMotor.c: wr = w_b - w_a + rate), hence -speed.
// Its max force is the torque bound: impulses clamped to dt * maxTorque, as rigidlab's.
static void addMotor(SuiteSpace& s, cpBody* a, cpBody* b, double speed, double maxTorque) {
    cpConstraint* motor = cpSimpleMotorNew(a, b, -speed);
    cpConstraintSetMaxForce(motor, maxTorque);
    cpSpaceAddConstraint(s.space, motor);
}

// 100 x 100 discs (radius 0.4, 1 m apart) pinned to their neighbours, hanging from 7 static discs in
// the middle of the top row; discs do not collide with each other (category 2, mask ~2).
static void suiteJointGrid(SuiteSpace& s) {
    const int n = 100;
    const cpShapeFilter filter = cpShapeFilterNew(CP_NO_GROUP, 2, CP_ALL_CATEGORIES & ~cpBitmask(2));
    std::vector<cpBody*> bodies;
    bodies.reserve(n * n);
    for (int k = 0; k < n; ++k) {
        for (int i = 0; i < n; ++i) {
            const bool pinned = k >= n / 2 - 3 && k <= n / 2 + 3 && i == 0;
            cpBody* body;
            if (pinned) {  // a static body of its own, placed before its shape is added
                body = cpBodyNewStatic();
                cpBodySetPosition(body, cpv(k, -i));
                cpSpaceAddBody(s.space, body);
            } else {
                body = addDynamic(s, cpv(k, -i));
            }
            addShape(s, cpCircleShapeNew(body, 0.4, cpvzero), 1.0, 0.6, 0.0, filter);
            // as rigidlab: no joints between two of the static discs
            const bool leftPinned = k - 1 >= n / 2 - 3 && k - 1 <= n / 2 + 3 && i == 0;
            if (i > 0) addPivot(s, bodies.back(), body, cpv(k, -i + 0.5));
            if (k > 0 && !(pinned && leftPinned)) addPivot(s, bodies[bodies.size() - n], body, cpv(k - 0.5, -i));
            bodies.push_back(body);
        }
    }
}

// Pyramid of base 100 of 1 m boxes on a 200 m x 2 m ground box whose top is y = 0.
static void suiteLargePyramid(SuiteSpace& s) {
    addShape(s, boxShape(s.ground(), 200.0, 2.0, cpv(0.0, -1.0)));
    const int base = 100;
    const double a = 0.5;
    for (int i = 0; i < base; ++i)
        for (int j = i; j < base; ++j)
            addShape(s, boxShape(addDynamic(s, cpv((i + 1.0) * a + 2.0 * (j - i) * a - a * base, (2.0 * i + 1.0) * a)),
                                 1.0, 1.0));
}

// 20 rows x 20 columns of pyramids of base 10, each row on its own ground segment.
static void suiteManyPyramids(SuiteSpace& s) {
    const int base = 10, rows = 20, columns = 20;
    const double extent = 0.5;
    const double groundDy = 2.0 * extent * (base + 1.0), groundWidth = 2.0 * extent * columns * (base + 1.0);
    for (int i = 0; i < rows; ++i)  // rigidlab's makeSegment: a segment of radius 0
        addShape(s, cpSegmentShapeNew(s.ground(), cpv(-0.5 * groundWidth, i * groundDy),
                                      cpv(0.5 * groundWidth, i * groundDy), 0.0));
    const double baseWidth = 2.0 * extent * base;
    for (int r = 0; r < rows; ++r) {
        const double baseY = r * groundDy;
        for (int c = 0; c < columns; ++c) {
            const double centerX = -0.5 * groundWidth + c * (baseWidth + 2.0 * extent) + 2.0 * extent;
            for (int i = 0; i < base; ++i)
                for (int j = i; j < base; ++j)
                    addShape(s, boxShape(addDynamic(s, cpv((i + 1.0) * extent + 2.0 * (j - i) * extent + centerX - 0.5,
                                                           (2.0 * i + 1.0) * extent + baseY)),
                                         2 * extent, 2 * extent));
        }
    }
}

// Box2D v3's ragdoll ("human"): 11 capsule bones, 10 revolute joints with limits, a friction motor
// and a soft spring towards the rest pose.
struct SuiteHuman {
    std::vector<SuiteDyn*> bones;
};

static SuiteHuman addHuman(SuiteSpace& s, cpVect position, int group) {
    const double scale = 1.0, frictionTorque = 0.05, hertz = 5.0, dampingRatio = 0.5;
    // rigidlab's Filter{group -group, category 2, mask 1|2}: its negative group means "never
    // collide within the group", which is what any non-zero Chipmunk group means; the same group
    // number for the same-index humans of every group of five, as rigidlab's.
    const cpShapeFilter bodyFilter = cpShapeFilterNew(cpGroup(group), 2, 1 | 2);
    const cpShapeFilter footFilter = cpShapeFilterNew(cpGroup(group), 2, 1);  // feet touch only the ground
    struct Bone {
        double y, y0, y1, r;
        int parent;
        double pivot, lower, upper, frictionScale, damping, reference;
        bool foot;
    };
    // rigidlab's table: centre height, capsule ends and radius, parent, pivot height, limits (x pi),
    // friction scale, linear damping, reference angle (x pi), foot.
    static const Bone kBones[] = {
        {0.95, -0.02, 0.02, 0.095, -1, 0, 0, 0, 1.0, 0.0, 0, false},              // hip
        {1.2, -0.135, 0.135, 0.09, 0, 1.0, -0.25, 0.0, 0.5, 0.0, 0, false},       // torso
        {1.475, -0.038, 0.039, 0.075, 1, 1.4, -0.3, 0.1, 0.25, 0.1, 0, false},    // head
        {0.775, -0.125, 0.125, 0.06, 0, 0.9, -0.05, 0.4, 1.0, 0.0, 0, false},     // upper left leg
        {0.475, -0.155, 0.125, 0.045, 3, 0.625, -0.5, -0.02, 0.5, 0.0, 0, true},  // lower left leg
        {0.775, -0.125, 0.125, 0.06, 0, 0.9, -0.05, 0.4, 1.0, 0.0, 0, false},     // upper right leg
        {0.475, -0.155, 0.125, 0.045, 5, 0.625, -0.5, -0.02, 0.5, 0.0, 0, true},  // lower right leg
        {1.225, -0.125, 0.125, 0.035, 1, 1.35, -0.1, 0.8, 0.5, 0.0, 0, false},    // upper left arm
        {0.975, -0.125, 0.125, 0.03, 7, 1.1, -0.2, 0.3, 0.1, 0.1, 0.25, false},  // lower left arm
        {1.225, -0.125, 0.125, 0.035, 1, 1.35, -0.1, 0.8, 0.5, 0.0, 0, false},    // upper right arm
        {0.975, -0.125, 0.125, 0.03, 9, 1.1, -0.2, 0.3, 0.1, 0.1, 0.25, false},  // lower right arm
    };
    const cpVect foot[4] = {cpv(-0.03 * scale, -0.185 * scale), cpv(0.11 * scale, -0.185 * scale),
                            cpv(0.11 * scale, -0.16 * scale), cpv(-0.03 * scale, -0.14 * scale)};
    SuiteHuman h;
    for (const Bone& bone : kBones) {
        cpBody* body = addDynamic(s, cpvadd(position, cpv(0.0, bone.y * scale)), bone.damping);
        // rigidlab's capsule: a segment shape with a radius
        addShape(s, cpSegmentShapeNew(body, cpv(0.0, bone.y0 * scale), cpv(0.0, bone.y1 * scale), bone.r * scale), 1.0,
                 0.2, 0.0, bodyFilter);
        if (bone.foot) addShape(s, cpPolyShapeNew(body, 4, foot, cpTransformIdentity, 0.0), 1.0, 0.05, 0.0, footFilter);
        if (bone.parent >= 0) {
            cpBody* a = h.bones[bone.parent]->body;
            addPivot(s, a, body, cpvadd(position, cpv(0.0, bone.pivot * scale)));
            // rigidlab's limits apply to angle_b - angle_a - reference; Chipmunk's rotary limit to
            // angle_b - angle_a: the reference (the lower arms' pi/4) shifts the range
            cpSpaceAddConstraint(s.space, cpRotaryLimitJointNew(a, body, (bone.lower + bone.reference) * CP_PI,
                                                                (bone.upper + bone.reference) * CP_PI));
            // rigidlab's friction motor: speed 0, torque bounded
            addMotor(s, a, body, 0.0, bone.frictionScale * frictionTorque * scale);
            // rigidlab's (Box2D v3's) spring is given in hertz and damping ratio for the pair's
            // effective inertia I = 1 / (1/Ia + 1/Ib); Chipmunk's in stiffness k = I w^2 and damping
            // c = 2 zeta I w (its damping decays w_a - w_b at c (1/Ia + 1/Ib)). Chipmunk 7.0.3 measures
            // the spring's angle as angle_a - angle_b (cpDampedRotarySpring.c), so the rest angle
            // angle_b - angle_a = reference is -reference.
            const double inertia = 1.0 / (1.0 / cpBodyGetMoment(a) + 1.0 / cpBodyGetMoment(body));
            const double omega = 2.0 * CP_PI * hertz;
            cpSpaceAddConstraint(s.space, cpDampedRotarySpringNew(a, body, -bone.reference * CP_PI, inertia * omega * omega,
                                                                  2.0 * dampingRatio * inertia * omega));
        }
        h.bones.push_back(&s.dyn.back());
    }
    return h;
}

// Removes a human's bodies with their shapes and constraints (rigidlab's destroyBody).
static void removeHuman(SuiteSpace& s, SuiteHuman& h) {
    std::vector<cpConstraint*> constraints;
    std::vector<cpShape*> shapes;
    for (SuiteDyn* d : h.bones) {
        constraints.clear();
        shapes.clear();
        cpBodyEachConstraint(
            d->body, [](cpBody*, cpConstraint* c, void* v) { static_cast<std::vector<cpConstraint*>*>(v)->push_back(c); },
            &constraints);
        cpBodyEachShape(
            d->body, [](cpBody*, cpShape* sh, void* v) { static_cast<std::vector<cpShape*>*>(v)->push_back(sh); }, &shapes);
        for (cpConstraint* c : constraints) {
            s.joints -= cpConstraintIsPivotJoint(c) ? 1 : 0;
            cpSpaceRemoveConstraint(s.space, c);
            cpConstraintFree(c);
        }
        for (cpShape* sh : shapes) {
            cpSpaceRemoveShape(s.space, sh);
            cpShapeFree(sh);
        }
        cpSpaceRemoveBody(s.space, d->body);
        cpBodyFree(d->body);
        d->body = nullptr;
        d->alive = false;
    }
    h.bones.clear();
}

// Box2D v3's rain: ragdolls in groups of 5 rain onto 5 floors of 501 small static boxes, a column
// of groups (one per floor) every 8 steps; after 40 columns (11 000 bodies) the oldest column is
// removed as a new one falls in its place.
struct SuiteRain {
    static constexpr int kRows = 5, kGroup = 5, kGridCount = 500, kColumns = 40;
    static constexpr double kGrid = 0.5;
    std::vector<std::vector<SuiteHuman>> groups = std::vector<std::vector<SuiteHuman>>(kRows * kColumns);
    int columnCount = 0, columnIndex = 0;

    void build(SuiteSpace& s) {
        for (int i = 0; i < kRows; ++i) {
            double x = -0.5 * kGridCount * kGrid;
            for (int j = 0; j <= kGridCount; ++j, x += kGrid)
                addShape(s, boxShape(s.ground(), kGrid, kGrid, cpv(x, 45.0 * i)));
        }
    }
    void create(SuiteSpace& s, int row, int column) {
        const double span = kGridCount * kGrid, distance = span / kColumns;
        cpVect p = cpv(-0.5 * span + distance * (column + 0.5), 40.0 + 45.0 * row);
        std::vector<SuiteHuman>& g = groups[row * kColumns + column];
        for (int i = 0; i < kGroup; ++i, p.x += 0.5) g.push_back(addHuman(s, p, i + 1));
    }
    // rigidlab's before_step
    void beforeStep(SuiteSpace& s, int step) {
        if ((step & 7) != 0) return;
        if (columnCount < kColumns) {
            for (int i = 0; i < kRows; ++i) create(s, i, columnCount);
            ++columnCount;
            return;
        }
        for (int i = 0; i < kRows; ++i) {
            std::vector<SuiteHuman>& g = groups[i * kColumns + columnIndex];
            for (SuiteHuman& h : g) removeHuman(s, h);
            g.clear();
            create(s, i, columnIndex);
        }
        columnIndex = (columnIndex + 1) % kColumns;
    }
};

// A heavy 8 m box at 40 m/s into a wall of 120 x 80 small boxes created asleep, without gravity.
static void suiteSmash(SuiteSpace& s) {
    cpBody* heavy = addDynamic(s, cpv(-20.0, 0.0));
    addShape(s, boxShape(heavy, 8.0, 8.0), 8.0);
    cpBodySetVelocity(heavy, cpv(40.0, 0.0));
    const double size = 0.4;
    const int columns = 120, rows = 80;
    for (int i = 0; i < columns; ++i)
        for (int j = 0; j < rows; ++j) {
            cpBody* body = addDynamic(s, cpv(i * size + 30.0, (j - rows / 2.0) * size));
            addShape(s, boxShape(body, size, size));
            // rigidlab's BodyDef::awake = false: Chipmunk sleeps a body only once it is in the space
            // with its shapes; each in a component of its own, as Box2D v3 gives each its own island.
            // Slept as it is made: cpBodySleep drops it from the space's awake list by a linear search.
            cpBodySleep(body);
        }
}

// 6076 capsules, discs and squares in a 40 m ring (a closed chain of 360 points) stirred by a
// 40 m paddle on a motor (5 rad/s, unlimited torque).
static void suiteSpinner(SuiteSpace& s) {
    // rigidlab's joints leave the two bodies they join out of each other's contacts (collide_connected
    // false): the paddle, jointed to the ground, passes through the ground's ring. Chipmunk collides
    // jointed bodies, so the ring and the paddle share a group.
    const cpShapeFilter jointed = cpShapeFilterNew(cpGroup(1), 1, CP_ALL_CATEGORIES);
    // Every shape of the scene gets elasticity sqrt(0.1): rigidlab's pairs take max(ea, eb) = 0.1
    // (the bodies' 0.1 against the ring's and paddle's 0), Chipmunk's take the product.
    const double restitution = 0.1;
    {
        // rigidlab's chain (a loop): static segments of radius 0 between consecutive points,
        // two-sided where rigidlab's (Box2D's) chain is one-sided. Not told their neighbours
        // (cpSegmentShapeSetNeighbors, Chipmunk's ghost vertices): Chipmunk then rejects end-point
        // contacts on the concave side of a corner, the side the ring's bodies are on, and about
        // twice as many bodies left the ring in 500 steps (2581 against 1433). rigidlab computes
        // the points with its portableCos/Sin, which may differ from the C library in the last bit.
        constexpr int kPoints = 360;
        std::vector<cpVect> p(kPoints);
        for (int i = 0; i < kPoints; ++i) {
            const double t = -2.0 * CP_PI * i / kPoints;
            p[i] = cpv(40.0 * std::cos(t), 40.0 * std::sin(t) + 32.0);
        }
        for (int i = 0; i < kPoints; ++i)
            addShape(s, cpSegmentShapeNew(s.ground(), p[i], p[(i + 1) % kPoints], 0.0), 0.0, 0.1, restitution, jointed);
    }
    // rigidlab's paddle is the box enclosing Box2D's (a 0.8 x 40 box rounded by 0.2 m): 1.2 x 40.4,
    // friction 0.
    cpBody* paddle = addDynamic(s, cpv(0.0, 12.0));
    addShape(s, boxShape(paddle, 2.0 * (0.4 + 0.2), 2.0 * (20.0 + 0.2)), 1.0, 0.0, restitution, jointed);
    addPivot(s, s.ground(), paddle, cpv(0.0, 12.0));
    addMotor(s, s.ground(), paddle, 5.0, INFINITY);
    const int count = 2 * 3038;
    double x = -23.0, y = 2.0;
    for (int i = 0; i < count; ++i) {
        cpBody* body = addDynamic(s, cpv(x, y));
        cpShape* shape = i % 3 == 0 ? cpSegmentShapeNew(body, cpv(-0.25, 0.0), cpv(0.25, 0.0), 0.25)  // capsule
                         : i % 3 == 1 ? cpCircleShapeNew(body, 0.35, cpvzero)
                                      : boxShape(body, 0.7, 0.7);
        addShape(s, shape, 0.25, 0.1, restitution);
        x += 0.5;
        if (x >= 23.0) {
            x = -23.0;
            y += 0.5;
        }
    }
}

// A 20 m box drum of four walls (density 50) turned at 25 deg/s by a motor, tumbling 45 x 45 small
// boxes.
static void suiteTumbler(SuiteSpace& s) {
    cpBody* drum = addDynamic(s, cpv(0.0, 10.0));
    // rigidlab's makeBox(w, h, offset): boxes off the body's origin
    addShape(s, boxShape(drum, 1.0, 20.0, cpv(10.0, 0.0)), 50.0);
    addShape(s, boxShape(drum, 1.0, 20.0, cpv(-10.0, 0.0)), 50.0);
    addShape(s, boxShape(drum, 20.0, 1.0, cpv(0.0, 10.0)), 50.0);
    addShape(s, boxShape(drum, 20.0, 1.0, cpv(0.0, -10.0)), 50.0);
    addPivot(s, s.ground(), drum, cpv(0.0, 10.0));
    addMotor(s, s.ground(), drum, CP_PI / 180.0 * 25.0, 1e8);
    const int grid = 45;
    double y = -0.2 * grid + 10.0;
    for (int i = 0; i < grid; ++i, y += 0.4) {
        double x = -0.2 * grid;
        for (int k = 0; k < grid; ++k, x += 0.4) addShape(s, boxShape(addDynamic(s, cpv(x, y)), 0.25, 0.25));
    }
}

// The static container of compounds and junkyard: a floor of 1.1 x 1 m boxes 1 m apart along y = 0
// from x = -half to half, and at x = +-half a wall of `wall` 1 x 1.1 m boxes stacked from y = 1.
static void addBoxContainer(SuiteSpace& s, int half, int wall) {
    for (int i = 0; i <= 2 * half; ++i) addShape(s, boxShape(s.ground(), 1.1, 1.0, cpv(i - half, 0.0)));
    for (int side : {-1, 1})
        for (int i = 0; i < wall; ++i) addShape(s, boxShape(s.ground(), 1.0, 1.1, cpv(side * half, i + 1.0)));
}

// rigidlab's makePolygon: Chipmunk takes the points' convex hull, radius 0.
static cpShape* polyShape(cpBody* body, const std::vector<cpVect>& points) {
    return cpPolyShapeNew(body, (int)points.size(), points.data(), cpTransformIdentity, 0.0);
}

// A kinematic body (Chipmunk's turn about its centre of gravity, the origin here, as v3's about
// their origin).
static cpBody* addKinematic(SuiteSpace& s, cpVect position) {
    cpBody* body = cpSpaceAddBody(s.space, cpBodyNewKinematic());
    cpBodySetPosition(body, position);
    return body;
}

// Box2D v3's compounds: 20 x 150 bodies of two overlapping triangles (density 1, friction 0.5)
// fall into an 80 m container with 100 m walls; a 1600 m segment 80 m below catches what falls out.
static void suiteCompounds(SuiteSpace& s) {
    addBoxContainer(s, 40, 100);
    addShape(s, cpSegmentShapeNew(s.ground(), cpv(-800.0, -80.0), cpv(800.0, -80.0), 0.0), 0.0);
    const std::vector<cpVect> left = {cpv(-1.0, 0.0), cpv(0.5, 1.0), cpv(0.0, 2.0)};
    const std::vector<cpVect> right = {cpv(1.0, 0.0), cpv(-0.5, 1.0), cpv(0.0, 2.0)};
    const int columns = 20, rows = 150;
    const double shift = 2.0, extraY = 0.25, centerX = shift * columns / 2.0 - 1.0, centerY = 1.15 / 2.0, yStart = 5.0;
    double side = 0.25;
    for (int i = 0; i < columns; ++i)
        for (int j = 0; j < rows; ++j, side = -side) {
            cpBody* body = addDynamic(s, cpv(i * shift - centerX + side, j * (shift + extraY) + centerY + yStart));
            addShape(s, polyShape(body, left), 1.0, 0.5);
            addShape(s, polyShape(body, right), 1.0, 0.5);
        }
}

// Box2D v3's junkyard: 200 x 40 pentagons (radius 0.25 m) fall into a 160 m container with 50 m
// walls, swept by a kinematic 4 x 8 m pusher whose velocity is set before each step (junkyardPush).
static void suiteJunkyard(SuiteSpace& s) {
    addBoxContainer(s, 80, 50);
    const double radius = 0.25, phi = CP_PI * (std::sqrt(5.0) - 1.0);
    std::vector<cpVect> pentagon;
    for (int k = 0; k < 5; ++k) pentagon.push_back(cpv(radius * std::cos(phi * k), radius * std::sin(phi * k)));
    const int columns = 200, rows = 40;
    double side = -0.1;
    for (int i = 0; i < columns; ++i)
        for (int j = 0; j < rows; ++j, side = -side)
            addShape(s, polyShape(addDynamic(s, cpv(1.5 * (2.0 * i - columns) * radius + side, 4.0 * j * radius + 15.0)), pentagon));
    s.pusher = addKinematic(s, cpvzero);
    addShape(s, boxShape(s.pusher, 4.0, 8.0, cpv(0.0, 4.0)));
}

// Before step k: the velocity that takes the pusher to x = 60 sin(0.2 k dt) in one step (Box2D v3's
// b2Body_SetTargetTransform, rigidlab's World::setTarget).
static void junkyardPush(SuiteSpace& s, int step, double dt) {
    const cpVect p = cpBodyGetPosition(s.pusher);
    cpBodySetVelocity(s.pusher, cpv((60.0 * std::sin(0.2 * dt * step) - p.x) / dt, -p.y / dt));
}

// Box2D v3's washer: a kinematic drum turning at 25 deg/s about (0, 10), drifting at (0.001, -0.002)
// m/s, of 36 ring pieces (16 to 18 m, 10 deg plus 1 deg over each neighbour) and 4 fins (14 to 16 m)
// holds 90 x 90 boxes of 0.2 m. v3 (and rigidlab) report hit events of the boxes; Chipmunk has none
// of its own (a post-solve callback would be the nearest, and would cost what v3's events do not):
// left out. Chipmunk wakes whatever touches a kinematic body at every step (cpSpaceComponent.c).
static void suiteWasher(SuiteSpace& s) {
    cpBody* drum = addKinematic(s, cpv(0.0, 10.0));
    cpBodySetAngularVelocity(drum, CP_PI / 180.0 * 25.0);
    cpBodySetVelocity(drum, cpv(0.001, -0.002));
    const double r0 = 14.0, r1 = 16.0, r2 = 18.0, step = CP_PI / 18.0;
    const auto at = [](double r, double angle) { return cpv(r * std::cos(angle), r * std::sin(angle)); };
    for (int i = 0; i < 36; ++i) {
        const double t1 = i * step, t2 = (i + 1) * step;
        addShape(s, polyShape(drum, {at(r1, t1 - 0.1 * step), at(r2, t1 - 0.1 * step), at(r2, t2 + 0.1 * step),
                                     at(r1, t2 + 0.1 * step)}));
        if (i % 9 == 0) addShape(s, polyShape(drum, {at(r0, t1), at(r1, t1), at(r1, t2), at(r0, t2)}));
    }
    const int grid = 90;
    const double a = 0.1;
    double y = -1.1 * a * grid + 10.0;
    for (int i = 0; i < grid; ++i, y += 2.1 * a) {
        double x = -1.1 * a * grid;
        for (int j = 0; j < grid; ++j, x += 2.1 * a) addShape(s, boxShape(addDynamic(s, cpv(x, y)), 2.0 * a, 2.0 * a));
    }
}

// The deepest touching point of each of a body's arbiters (each pair once, as countArbiter),
// recomputed with cpShapesCollide. Chipmunk integrates positions before it finds its contacts
// (cpSpaceStep), so the last step's contacts are where the bodies are now; recomputing them reads
// the shapes' cached transforms of that same moment, and does not depend on which arbiters
// Chipmunk keeps for sleeping bodies.
static void deepestArbiter(cpBody* body, cpArbiter* arb, void* data) {
    cpBody *a, *b;
    cpArbiterGetBodies(arb, &a, &b);
    cpBody* other = (a == body) ? b : a;
    if (cpBodyGetType(other) == CP_BODY_TYPE_DYNAMIC && other < body) return;
    cpShape *sa, *sb;
    cpArbiterGetShapes(arb, &sa, &sb);
    const cpContactPointSet set = cpShapesCollide(sa, sb);
    double& deepest = *static_cast<double*>(data);
    for (int i = 0; i < set.count; ++i) deepest = std::max(deepest, -set.points[i].distance);  // distance < 0: overlap
}

// A body's constraints, each once: every constraint here has a dynamic body b. Through the bodies,
// since Chipmunk takes a sleeping body's constraints out of cpSpaceEachConstraint's list.
static void widestPivot(cpBody* body, cpConstraint* c, void* data) {
    if (cpConstraintGetBodyB(c) != body || !cpConstraintIsPivotJoint(c)) return;
    const cpVect pa = cpBodyLocalToWorld(cpConstraintGetBodyA(c), cpPivotJointGetAnchorA(c));
    const cpVect pb = cpBodyLocalToWorld(cpConstraintGetBodyB(c), cpPivotJointGetAnchorB(c));
    double& widest = *static_cast<double*>(data);
    widest = std::max(widest, cpvdist(pa, pb));
}

// Sleep settings of the suite's spaces (also reported in the settings JSON).
static double suiteSleepTime(const SuiteInfo& info) { return info.sleep ? 0.5 : INFINITY; }  // Box2D's time to sleep
// Chipmunk's idle speed 0 means |gravity| * dt (1/6 m/s here), which without gravity (smash) is 0:
// nothing woken would sleep again. There it is rigidlab's sleep_linear_speed, 0.01 m/s.
static double suiteIdleSpeed(const SuiteInfo& info) { return std::string(info.name) == "smash" ? 0.01 : 0.0; }

static SuiteRun runSuiteOnce(const SuiteInfo& info, int steps, const Options& o) {
    SuiteRun run;
    const std::string name = info.name;
    const double dt = 1.0 / 60.0;
    auto t0 = Clock::now();
    const bool hasty = o.threads > 0;
    SuiteSpace s;
    s.o = &o;
    s.space = hasty ? cpHastySpaceNew() : cpSpaceNew();
    if (hasty) cpHastySpaceSetThreads(s.space, (unsigned long)o.threads);
    cpSpaceSetGravity(s.space, name == "smash" ? cpvzero : cpv(0.0, -10.0));
    cpSpaceSetIterations(s.space, o.iterations);
    if (o.slop >= 0) cpSpaceSetCollisionSlop(s.space, o.slop);
    // before any body: smash's wall sleeps as it is made
    if (info.sleep) cpSpaceSetSleepTimeThreshold(s.space, suiteSleepTime(info));
    cpSpaceSetIdleSpeedThreshold(s.space, suiteIdleSpeed(info));

    SuiteRain rain;
    if (name == "large_pyramid") suiteLargePyramid(s);
    else if (name == "many_pyramids") suiteManyPyramids(s);
    else if (name == "joint_grid") suiteJointGrid(s);
    else if (name == "ragdolls") rain.build(s);
    else if (name == "smash") suiteSmash(s);
    else if (name == "spinner") suiteSpinner(s);
    else if (name == "tumbler") suiteTumbler(s);
    else if (name == "compounds") suiteCompounds(s);
    else if (name == "junkyard") suiteJunkyard(s);
    else if (name == "washer") suiteWasher(s);
    run.setupMs = msSince(t0, Clock::now());

    // rigidlab times the scene's own edits before a step (its before_step: the rain's spawning and
    // removal) with the step (app/bench_run.cpp), so they are timed here too.
    run.stepMs.reserve(steps);
    for (int i = 0; i < steps; ++i) {
        auto a = Clock::now();
        if (name == "ragdolls") rain.beforeStep(s, i);
        if (name == "junkyard") junkyardPush(s, i, dt);
        if (hasty)
            cpHastySpaceStep(s.space, dt);
        else
            cpSpaceStep(s.space, dt);
        run.stepMs.push_back(msSince(a, Clock::now()));
        if (i == 0)  // the figures' start: where the bodies are after the first step
            for (SuiteDyn& d : s.dyn) {
                if (!d.alive) continue;
                const cpVect p = cpBodyGetPosition(d.body);
                d.tracked = true;
                d.x0 = p.x;
                d.y0 = p.y;
            }
    }

    SuiteFigures f;
    std::vector<SuiteBody> figures;
    int contacts = 0;
    for (const SuiteDyn& d : s.dyn) {
        if (!d.alive) continue;
        ++f.bodies;
        f.awake += cpBodyIsSleeping(d.body) ? 0 : 1;
        cpBodyEachArbiter(d.body, countArbiter, &contacts);
        cpBodyEachArbiter(d.body, deepestArbiter, &f.maxPenetration);
        cpBodyEachConstraint(d.body, widestPivot, &f.maxJointGap);
        if (!d.tracked) continue;
        const cpVect p = cpBodyGetPosition(d.body);
        SuiteBody b;
        b.tracked = true;
        b.x0 = d.x0;
        b.y0 = d.y0;
        b.x = p.x;
        b.y = p.y;
        figures.push_back(b);
    }
    f.joints = s.joints;
    f.escaped = suiteEscaped(name, figures);
    run.contacts = contacts;
    run.dynamicBodies = f.bodies;
    run.metrics = suiteMetricsJson(f, figures);

    // Free the space first, then what was in it: removing 40 000 constraints one by one costs a
    // linear search of Chipmunk's arrays each. cpSpaceFree reads the bodies (it wakes them), so
    // they are freed after it. The constraints are found through their bodies b (all dynamic
    // here), as in widestPivot: a sleeping body's constraints are not in the space's list.
    std::vector<cpConstraint*> constraints;
    std::vector<cpShape*> shapes;
    std::vector<cpBody*> bodies;
    cpSpaceEachShape(s.space, [](cpShape* sh, void* v) { static_cast<std::vector<cpShape*>*>(v)->push_back(sh); },
                     &shapes);
    cpSpaceEachBody(s.space, [](cpBody* b, void* v) { static_cast<std::vector<cpBody*>*>(v)->push_back(b); }, &bodies);
    for (cpBody* b : bodies)
        cpBodyEachConstraint(
            b,
            [](cpBody* body, cpConstraint* c, void* v) {
                if (cpConstraintGetBodyB(c) == body) static_cast<std::vector<cpConstraint*>*>(v)->push_back(c);
            },
            &constraints);
    // Woken first: cpSpaceFree wakes the sleeping components while it walks their array, skips
    // some, and their saved contacts leak (AddressSanitizer, ragdolls).
    for (cpBody* b : bodies)
        if (cpBodyGetType(b) == CP_BODY_TYPE_DYNAMIC) cpBodyActivate(b);
    cpBody* spaceStatic = s.ground();
    if (hasty)
        cpHastySpaceFree(s.space);
    else
        cpSpaceFree(s.space);
    for (cpConstraint* c : constraints) cpConstraintFree(c);
    for (cpShape* sh : shapes) cpShapeFree(sh);
    for (cpBody* b : bodies)
        if (b != spaceStatic) cpBodyFree(b);
    return run;
}

int main(int argc, char** argv) {
    Options o;
    if (!parseArgs(argc, argv, o)) {
        usage(argv[0]);
        return 2;
    }
    Scene sc = buildScene(o);

    // A Chipmunk built without NDEBUG (the Debian one) printf()s a one-time
    // "Debug Enabled" banner on the first cpSpaceInit. Create a scratch space with
    // stdout pointed at stderr so stdout stays one JSON line; also read defaults.
    std::fflush(stdout);
    int savedOut = dup(1);
    dup2(2, 1);
    cpSpace* probe = cpSpaceNew();
    std::fflush(stdout);
    dup2(savedOut, 1);
    close(savedOut);
    double slop = o.slop >= 0 ? o.slop : cpSpaceGetCollisionSlop(probe);
    double bias = cpSpaceGetCollisionBias(probe);
    cpSpaceFree(probe);

    if (const SuiteInfo* info = suiteInfo(o.scene)) {
        const int steps = o.steps > 0 ? o.steps : info->steps;
        std::vector<SuiteRun> runs;
        for (int r = 0; r < o.reps; ++r) runs.push_back(runSuiteOnce(*info, steps, o));
        std::string settings = settingsJson({{"dt", 1.0 / 60.0},
                                             {"iterations", (double)o.iterations},
                                             {"collisionSlop", slop},
                                             {"collisionBias", bias},
                                             {"hastyThreads", (double)o.threads},
                                             {"shapeFrictionIsSqrt", o.rawFriction ? 0.0 : 1.0},
                                             {"sleepTimeThreshold", suiteSleepTime(*info)},
                                             {"idleSpeedThreshold", suiteIdleSpeed(*info)},
                                             {"cpFloatBytes", (double)sizeof(cpFloat)}});
        printSuiteResult("chipmunk", cpVersionString, *info, steps, settings, runs);
        return 0;
    }

    std::vector<RunResult> runs;
    for (int r = 0; r < o.reps; ++r) runs.push_back(runOnce(sc, o));

    std::string settings = settingsJson({{"dt", sc.dt},
                                         {"iterations", (double)o.iterations},
                                         {"collisionSlop", slop},
                                         {"collisionBias", bias},
                                         {"hastyThreads", (double)o.threads},
                                         {"shapeFrictionIsSqrt", o.rawFriction ? 0.0 : 1.0},
                                         {"cpFloatBytes", (double)sizeof(cpFloat)}});
    printResult("chipmunk", cpVersionString, o, sc, settings, runs);
    return 0;
}
