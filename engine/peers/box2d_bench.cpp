// box2d_bench.cpp - Box2D 2.4.x peer benchmark (Debian libbox2d-dev).
// usage: box2d_bench <scene> [options]   (see scenes.h / --help)
#include "scenes.h"
#include "suite.h"

#include <box2d/box2d.h>

#include <cfloat>
#include <functional>
#include <memory>

using namespace peer;

static BodyState stateOf(const b2Body* b) {
    BodyState st;
    st.x = b->GetPosition().x;
    st.y = b->GetPosition().y;
    st.angle = b->GetAngle();
    st.vx = b->GetLinearVelocity().x;
    st.vy = b->GetLinearVelocity().y;
    st.awake = b->IsAwake();
    return st;
}

static RunResult runOnce(const Scene& sc, const Options& o) {
    RunResult rr;
    auto t0 = Clock::now();
    auto world = std::make_unique<b2World>(b2Vec2((float)sc.gx, (float)sc.gy));
    world->SetAllowSleeping(o.sleep);
    world->SetContinuousPhysics(o.continuous);

    std::vector<b2Body*> bodies;
    bodies.reserve(sc.bodies.size());
    for (const BodyDesc& d : sc.bodies) {
        b2BodyDef bd;
        bd.type = d.isStatic ? b2_staticBody : b2_dynamicBody;
        bd.position.Set((float)d.x, (float)d.y);
        bd.linearVelocity.Set((float)d.vx, (float)d.vy);
        bd.bullet = d.projectile && o.bullet;
        b2Body* body = world->CreateBody(&bd);

        b2FixtureDef fd;
        b2PolygonShape poly;
        b2CircleShape circle;
        if (d.shape == Shape::Box) {
            poly.SetAsBox((float)d.hx, (float)d.hy);
            fd.shape = &poly;
        } else {
            circle.m_radius = (float)d.r;
            fd.shape = &circle;
        }
        fd.density = (float)d.density;
        fd.friction = (float)d.friction;  // Box2D mixes sqrt(a*b): pair = d.friction
        fd.restitution = 0.0f;
        body->CreateFixture(&fd);
        bodies.push_back(body);
    }
    rr.setupMs = msSince(t0, Clock::now());

    const float dt = (float)sc.dt;
    const bool track = sc.name == "massratio";
    rr.stepMs.reserve(sc.steps);
    for (int s = 0; s < sc.steps; ++s) {
        auto a = Clock::now();
        world->Step(dt, o.velIters, o.posIters);
        auto b = Clock::now();
        rr.stepMs.push_back(msSince(a, b));
        if (track) observeMassRatio(sc, rr.track, s, stateOf(bodies[sc.bottomIndex]), stateOf(bodies[sc.topIndex]));
        if (s == 0 && sc.name == "bullet") rr.track.vxAfterFirstStep = stateOf(bodies[sc.topIndex]).vx;
        if (sc.name == "stack") observeStack(sc, rr.track, s, stateOf(bodies[sc.topIndex]));
    }

    rr.final.resize(bodies.size());
    for (size_t i = 0; i < bodies.size(); ++i) rr.final[i] = stateOf(bodies[i]);
    int touching = 0;
    for (b2Contact* c = world->GetContactList(); c; c = c->GetNext()) touching += c->IsTouching() ? 1 : 0;
    rr.contacts = touching;
    return rr;
}

// ------------------------------------------------------ Box2D v3's suite --
// The ten scenes of Box2D v3's benchmark suite, built as rigidlab's engine/app/bench_suite.cpp
// builds them (the same bodies, shapes, materials, filters, joints and step counts) in Box2D
// 2.4.1's vocabulary; each place where 2.4.1 has no exact equivalent says what stands in for it.

namespace {

struct SuiteEntry {
    b2Body* body = nullptr;  // nullptr once destroyed (the ragdoll rain removes its oldest column)
    bool tracked = false;    // existed after the first step
    double x0 = 0, y0 = 0;   // where it was then
};

struct SuiteWorld {
    std::unique_ptr<b2World> world;
    std::vector<SuiteEntry> dynamic;                      // every dynamic body created, in order
    std::function<void(SuiteWorld&, int)> beforeStep;     // the ragdoll rain's spawning and removal

    b2Body* addBody(b2BodyType type, b2Vec2 position, float linearDamping = 0.0f, bool awake = true) {
        b2BodyDef d;
        d.type = type;
        d.position = position;
        d.linearDamping = linearDamping;
        d.awake = awake;  // smash's wall is created asleep
        b2Body* body = world->CreateBody(&d);
        if (type == b2_dynamicBody) dynamic.push_back({body});
        return body;
    }
};

// Box2D 2.4.1 mixes frictions as sqrt(a b) and restitutions as max(a, b), as rigidlab does, so
// each fixture gets the scene's value.
void addFixture(b2Body* body, const b2Shape& shape, float density = 1.0f, float friction = 0.6f,
                float restitution = 0.0f, b2Filter filter = b2Filter()) {
    b2FixtureDef fd;
    fd.shape = &shape;
    fd.density = density;
    fd.friction = friction;
    fd.restitution = restitution;
    fd.filter = filter;
    body->CreateFixture(&fd);
}

// rigidlab's makeBox(w, h, centre) takes the full width and height.
b2PolygonShape boxShape(float w, float h, b2Vec2 center = b2Vec2(0.0f, 0.0f)) {
    b2PolygonShape p;
    p.SetAsBox(0.5f * w, 0.5f * h, center, 0.0f);
    return p;
}

// rigidlab's (and Box2D v3's) capsule mass: a rectangle of length l and width 2r plus two half
// discs; the rotational inertia about the body origin, as b2MassData keeps it.
b2MassData capsuleMass(b2Vec2 p1, b2Vec2 p2, float radius, float density) {
    const double pi = 3.14159265358979323846;
    const double r = radius, l = (p2 - p1).Length(), h = 0.5 * l;
    const double mRect = density * 2.0 * r * l, mDisc = density * pi * r * r, lc = 4.0 * r / (3.0 * pi);
    b2MassData md;
    md.mass = (float)(mRect + mDisc);
    md.center = 0.5f * (p1 + p2);
    md.I = (float)(mRect * (l * l + 4.0 * r * r) / 12.0 + mDisc * (0.5 * r * r + h * h + 2.0 * h * lc)) +
           md.mass * b2Dot(md.center, md.center);
    return md;
}

b2MassData addMass(const b2MassData& a, const b2MassData& b) {
    b2MassData md;
    md.mass = a.mass + b.mass;
    md.center = (1.0f / md.mass) * (a.mass * a.center + b.mass * b.center);
    md.I = a.I + b.I;  // both about the body origin
    return md;
}

// Box2D 2.4.1 has no capsule shape: a box between the two end centres (half-width = radius) and a
// disc at each end, with the capsule's density, friction, restitution and filter. The three
// overlap, so the compound alone would weigh 1.4x (spinner) to 1.8x (ragdoll hip) the capsule: the
// caller sets the capsule's mass data (capsuleMass) once the body's fixtures are made. The box's
// polygon skin (b2_polygonRadius, 1 cm) makes the capsule's sides 1 cm fatter than its ends.
void addCapsule(b2Body* body, b2Vec2 p1, b2Vec2 p2, float radius, float density, float friction,
                float restitution = 0.0f, b2Filter filter = b2Filter()) {
    const b2Vec2 d = p2 - p1;
    b2PolygonShape box;
    box.SetAsBox(0.5f * d.Length(), radius, 0.5f * (p1 + p2), std::atan2(d.y, d.x));
    addFixture(body, box, density, friction, restitution, filter);
    for (const b2Vec2& p : {p1, p2}) {
        b2CircleShape disc;
        disc.m_p = p;
        disc.m_radius = radius;
        addFixture(body, disc, density, friction, restitution, filter);
    }
}

// A revolute joint at one world anchor (rigidlab's anchor_a); Initialize sets the reference angle
// to the bodies' current relative angle (0 here), as rigidlab's default.
void addRevolute(b2World& w, b2Body* a, b2Body* b, b2Vec2 anchor, b2RevoluteJointDef jd = b2RevoluteJointDef()) {
    jd.Initialize(a, b, anchor);
    w.CreateJoint(&jd);
}

SuiteWorld emptySuiteWorld(bool sleeping, const Options& o) {
    SuiteWorld s;
    s.world = std::make_unique<b2World>(b2Vec2(0.0f, -10.0f));
    s.world->SetAllowSleeping(sleeping);
    s.world->SetContinuousPhysics(o.continuous);
    return s;
}

// 100 x 100 discs (radius 0.4, 1 m apart) pinned to their neighbours by revolute joints, hanging
// from 7 static discs in the middle of the top row; discs do not collide with each other.
SuiteWorld jointGrid(const Options& o) {
    SuiteWorld s = emptySuiteWorld(false, o);
    const int n = 100;
    b2Filter filter;
    filter.categoryBits = 2;
    filter.maskBits = 0xFFFF & ~2;  // rigidlab's ~2 (64 bits); 2.4.1's masks have 16 bits
    b2CircleShape disc;
    disc.m_radius = 0.4f;
    std::vector<b2Body*> bodies;
    bodies.reserve(n * n);
    for (int k = 0; k < n; ++k) {
        for (int i = 0; i < n; ++i) {
            const bool pinned = k >= n / 2 - 3 && k <= n / 2 + 3 && i == 0;
            b2Body* body = s.addBody(pinned ? b2_staticBody : b2_dynamicBody, b2Vec2((float)k, (float)-i));
            addFixture(body, disc, 1.0f, 0.6f, 0.0f, filter);
            // Box2D v3's benchmark also joins the 7 static discs to each other (6 joints that do
            // nothing); rigidlab refuses a joint without a dynamic body, so they are left out here too.
            const bool leftPinned = k - 1 >= n / 2 - 3 && k - 1 <= n / 2 + 3 && i == 0;
            if (i > 0) addRevolute(*s.world, bodies.back(), body, b2Vec2((float)k, -i + 0.5f));
            if (k > 0 && !(pinned && leftPinned))
                addRevolute(*s.world, bodies[bodies.size() - n], body, b2Vec2(k - 0.5f, (float)-i));
            bodies.push_back(body);
        }
    }
    return s;
}

// Box2D v3's large_pyramid: base 100 of 1 m boxes on a 200 m ground box.
SuiteWorld largePyramid(const Options& o) {
    SuiteWorld s = emptySuiteWorld(false, o);
    addFixture(s.addBody(b2_staticBody, b2Vec2(0.0f, -1.0f)), boxShape(200.0f, 2.0f));
    const int base = 100;
    const double a = 0.5;
    const b2PolygonShape box = boxShape(1.0f, 1.0f);
    for (int i = 0; i < base; ++i)
        for (int j = i; j < base; ++j)
            addFixture(s.addBody(b2_dynamicBody, b2Vec2((float)((i + 1.0) * a + 2.0 * (j - i) * a - a * base),
                                                         (float)((2.0 * i + 1.0) * a))),
                       box);
    return s;
}

// 20 rows x 20 columns of pyramids of base 10 (55 boxes each, 22 000 boxes), each row on its own
// ground segment.
SuiteWorld manyPyramids(const Options& o) {
    SuiteWorld s = emptySuiteWorld(false, o);
    const int base = 10, rows = 20, columns = 20;
    const double extent = 0.5;
    b2Body* ground = s.addBody(b2_staticBody, b2Vec2(0.0f, 0.0f));
    const double groundDy = 2.0 * extent * (base + 1.0), groundWidth = 2.0 * extent * columns * (base + 1.0);
    for (int i = 0; i < rows; ++i) {
        b2EdgeShape segment;  // rigidlab's segment is two-sided
        segment.SetTwoSided(b2Vec2((float)(-0.5 * groundWidth), (float)(i * groundDy)),
                            b2Vec2((float)(0.5 * groundWidth), (float)(i * groundDy)));
        addFixture(ground, segment, 0.0f);
    }
    const double baseWidth = 2.0 * extent * base;
    const b2PolygonShape box = boxShape((float)(2 * extent), (float)(2 * extent));
    for (int r = 0; r < rows; ++r) {
        const double baseY = r * groundDy;
        for (int c = 0; c < columns; ++c) {
            const double centerX = -0.5 * groundWidth + c * (baseWidth + 2.0 * extent) + 2.0 * extent;
            for (int i = 0; i < base; ++i)
                for (int j = i; j < base; ++j)
                    addFixture(s.addBody(b2_dynamicBody,
                                         b2Vec2((float)((i + 1.0) * extent + 2.0 * (j - i) * extent + centerX - 0.5),
                                                (float)((2.0 * i + 1.0) * extent + baseY))),
                               box);
        }
    }
    return s;
}

// Box2D v3's ragdoll ("human"): 11 capsule bones, 10 revolute joints with limits and a friction
// motor. Same-index humans of different groups share a negative group (they never collide); feet
// touch only the ground.
struct Human {
    std::vector<size_t> bones;  // indices into SuiteWorld::dynamic
};

Human addHuman(SuiteWorld& s, b2Vec2 position, int group) {
    const float pi = 3.14159265358979323846f;
    const float sc = 1.0f, frictionTorque = 0.05f;
    b2Filter bodyFilter;
    bodyFilter.groupIndex = (int16)-group;
    bodyFilter.categoryBits = 2;
    bodyFilter.maskBits = 1 | 2;
    b2Filter footFilter = bodyFilter;
    footFilter.maskBits = 1;
    // bone: centre height, capsule ends and radius, parent, pivot height, limits (x pi), friction
    // scale, linear damping, reference angle (x pi), foot: rigidlab's kBones.
    struct Bone {
        float y, y0, y1, r;
        int parent;
        float pivot, lower, upper, frictionScale, damping, reference;
        bool foot;
    };
    static const Bone kBones[] = {
        {0.95f, -0.02f, 0.02f, 0.095f, -1, 0, 0, 0, 1.0f, 0.0f, 0, false},                // hip
        {1.2f, -0.135f, 0.135f, 0.09f, 0, 1.0f, -0.25f, 0.0f, 0.5f, 0.0f, 0, false},       // torso
        {1.475f, -0.038f, 0.039f, 0.075f, 1, 1.4f, -0.3f, 0.1f, 0.25f, 0.1f, 0, false},    // head
        {0.775f, -0.125f, 0.125f, 0.06f, 0, 0.9f, -0.05f, 0.4f, 1.0f, 0.0f, 0, false},     // upper left leg
        {0.475f, -0.155f, 0.125f, 0.045f, 3, 0.625f, -0.5f, -0.02f, 0.5f, 0.0f, 0, true},  // lower left leg
        {0.775f, -0.125f, 0.125f, 0.06f, 0, 0.9f, -0.05f, 0.4f, 1.0f, 0.0f, 0, false},     // upper right leg
        {0.475f, -0.155f, 0.125f, 0.045f, 5, 0.625f, -0.5f, -0.02f, 0.5f, 0.0f, 0, true},  // lower right leg
        {1.225f, -0.125f, 0.125f, 0.035f, 1, 1.35f, -0.1f, 0.8f, 0.5f, 0.0f, 0, false},    // upper left arm
        {0.975f, -0.125f, 0.125f, 0.03f, 7, 1.1f, -0.2f, 0.3f, 0.1f, 0.1f, 0.25f, false},  // lower left arm
        {1.225f, -0.125f, 0.125f, 0.035f, 1, 1.35f, -0.1f, 0.8f, 0.5f, 0.0f, 0, false},    // upper right arm
        {0.975f, -0.125f, 0.125f, 0.03f, 9, 1.1f, -0.2f, 0.3f, 0.1f, 0.1f, 0.25f, false},  // lower right arm
    };
    const b2Vec2 foot[4] = {{-0.03f * sc, -0.185f * sc}, {0.11f * sc, -0.185f * sc}, {0.11f * sc, -0.16f * sc},
                            {-0.03f * sc, -0.14f * sc}};
    b2PolygonShape footShape;
    footShape.Set(foot, 4);
    Human h;
    for (const Bone& bone : kBones) {
        b2Body* body = s.addBody(b2_dynamicBody, position + b2Vec2(0.0f, bone.y * sc), bone.damping);
        const b2Vec2 p1(0.0f, bone.y0 * sc), p2(0.0f, bone.y1 * sc);
        addCapsule(body, p1, p2, bone.r * sc, 1.0f, 0.2f, 0.0f, bodyFilter);
        b2MassData md = capsuleMass(p1, p2, bone.r * sc, 1.0f);
        if (bone.foot) {
            addFixture(body, footShape, 1.0f, 0.05f, 0.0f, footFilter);
            b2MassData footMass;
            footShape.ComputeMass(&footMass, 1.0f);
            md = addMass(md, footMass);
        }
        body->SetMassData(&md);  // the capsule's (and foot's) mass, not the overlapping compound's
        if (bone.parent >= 0) {
            b2RevoluteJointDef jd;
            jd.Initialize(s.dynamic[h.bones[bone.parent]].body, body, position + b2Vec2(0.0f, bone.pivot * sc));
            // Box2D v3 turns the lower arms' frame on the upper arm by pi/4: joint angle 0 (the
            // limits' origin) is the elbow bent by pi/4. After Initialize, which sets it to 0.
            jd.referenceAngle = bone.reference * pi;
            jd.enableLimit = true;
            jd.lowerAngle = bone.lower * pi;
            jd.upperAngle = bone.upper * pi;
            jd.enableMotor = true;  // the joint's friction: a motor held at speed 0, torque-limited
            jd.motorSpeed = 0.0f;
            jd.maxMotorTorque = bone.frictionScale * frictionTorque * sc;
            // rigidlab (and Box2D v3) also pull each joint towards the rest pose with a spring
            // (5 Hz, damping ratio 0.5); 2.4.1's b2RevoluteJoint has no spring: left out.
            s.world->CreateJoint(&jd);
        }
        h.bones.push_back(s.dynamic.size() - 1);
    }
    return h;
}

// Box2D v3's rain: ragdolls in groups of 5 rain onto 5 floors of 501 small static boxes, a column
// of groups (one per floor) every 8 steps; after `columns` columns (the suite's 40: 11 000 bodies
// at most) the oldest column is removed as a new one falls.
SuiteWorld ragdollRain(const Options& o, int columns) {
    SuiteWorld s = emptySuiteWorld(true, o);
    constexpr int kRows = 5, kGroup = 5, kGridCount = 500;
    constexpr double kGrid = 0.5;
    b2Body* ground = s.addBody(b2_staticBody, b2Vec2(0.0f, 0.0f));
    for (int i = 0; i < kRows; ++i) {
        double x = -0.5 * kGridCount * kGrid;
        for (int j = 0; j <= kGridCount; ++j, x += kGrid)
            addFixture(ground, boxShape((float)kGrid, (float)kGrid, b2Vec2((float)x, 45.0f * i)));
    }
    struct Rain {
        int columns;
        std::vector<std::vector<Human>> groups;
        int columnCount = 0, columnIndex = 0;
    };
    auto rain = std::make_shared<Rain>(Rain{columns, std::vector<std::vector<Human>>(kRows * columns)});
    const auto create = [rain](SuiteWorld& w, int row, int column) {
        const double span = kGridCount * kGrid, distance = span / rain->columns;
        double x = -0.5 * span + distance * (column + 0.5);
        const double y = 40.0 + 45.0 * row;
        std::vector<Human>& g = rain->groups[row * rain->columns + column];
        for (int i = 0; i < kGroup; ++i, x += 0.5) g.push_back(addHuman(w, b2Vec2((float)x, (float)y), i + 1));
    };
    s.beforeStep = [rain, create](SuiteWorld& w, int step) {
        if ((step & 7) != 0) return;
        if (rain->columnCount < rain->columns) {
            for (int i = 0; i < kRows; ++i) create(w, i, rain->columnCount);
            ++rain->columnCount;
            return;
        }
        for (int i = 0; i < kRows; ++i) {
            std::vector<Human>& g = rain->groups[i * rain->columns + rain->columnIndex];
            for (const Human& h : g)
                for (size_t bone : h.bones) {
                    w.world->DestroyBody(w.dynamic[bone].body);  // its joints go with it
                    w.dynamic[bone].body = nullptr;
                }
            g.clear();
            create(w, i, rain->columnIndex);
        }
        rain->columnIndex = (rain->columnIndex + 1) % rain->columns;
    };
    return s;
}

// Box2D v3's smash: a heavy 8 m box at 40 m/s into a wall of 120 x 80 small boxes created asleep,
// without gravity.
SuiteWorld smash(const Options& o) {
    SuiteWorld s = emptySuiteWorld(true, o);
    s.world->SetGravity(b2Vec2(0.0f, 0.0f));
    b2Body* heavy = s.addBody(b2_dynamicBody, b2Vec2(-20.0f, 0.0f));
    heavy->SetLinearVelocity(b2Vec2(40.0f, 0.0f));
    addFixture(heavy, boxShape(8.0f, 8.0f), 8.0f);
    const double size = 0.4;
    const int columns = 120, rows = 80;
    const b2PolygonShape box = boxShape((float)size, (float)size);
    for (int i = 0; i < columns; ++i)
        for (int j = 0; j < rows; ++j)
            addFixture(s.addBody(b2_dynamicBody, b2Vec2((float)(i * size + 30.0), (float)((j - rows / 2.0) * size)),
                                 0.0f, false),
                       box);
    return s;
}

// Box2D v3's spinner: 6076 capsules, discs and squares in a 40 m ring (a closed chain of 360
// points) stirred by a 40 m paddle on a motor (5 rad/s, unlimited torque).
SuiteWorld spinner(const Options& o) {
    SuiteWorld s = emptySuiteWorld(true, o);
    b2Body* ground = s.addBody(b2_staticBody, b2Vec2(0.0f, 0.0f));
    {
        constexpr int kPoints = 360;
        const double pi = 3.14159265358979323846;
        std::vector<b2Vec2> points;
        for (int i = 0; i < kPoints; ++i) {
            // clockwise, as rigidlab's and v3's: 2.4.1's chain edges are one-sided and collide on
            // their right, the ring's inside (rigidlab uses portableCos/Sin for the same bits on
            // every machine; the C library's here, floats anyway).
            const double t = -2.0 * pi * i / kPoints;
            points.push_back(b2Vec2((float)(40.0 * std::cos(t)), (float)(40.0 * std::sin(t) + 32.0)));
        }
        b2ChainShape chain;
        chain.CreateLoop(points.data(), kPoints);
        addFixture(ground, chain, 0.0f, 0.1f);
    }
    // Box2D v3's paddle is a 0.8 x 40 m box rounded by 0.2 m; rigidlab uses the box that encloses
    // it, and so does this (2.4.1's polygon radius is fixed at b2_polygonRadius).
    b2Body* paddle = s.addBody(b2_dynamicBody, b2Vec2(0.0f, 12.0f));
    addFixture(paddle, boxShape(2.0f * (0.4f + 0.2f), 2.0f * (20.0f + 0.2f)), 1.0f, 0.0f);
    b2RevoluteJointDef jd;
    jd.enableMotor = true;
    jd.motorSpeed = 5.0f;
    jd.maxMotorTorque = FLT_MAX;  // rigidlab's infinity; 2.4.1 clamps the impulse to dt * this, finite
    addRevolute(*s.world, ground, paddle, b2Vec2(0.0f, 12.0f), jd);
    const int count = 2 * 3038;
    double x = -23.0, y = 2.0;
    b2CircleShape disc;
    disc.m_radius = 0.35f;
    const b2PolygonShape box = boxShape(0.7f, 0.7f);
    for (int i = 0; i < count; ++i) {
        b2Body* body = s.addBody(b2_dynamicBody, b2Vec2((float)x, (float)y));
        if (i % 3 == 0) {
            const b2Vec2 p1(-0.25f, 0.0f), p2(0.25f, 0.0f);
            addCapsule(body, p1, p2, 0.25f, 0.25f, 0.1f, 0.1f);
            const b2MassData md = capsuleMass(p1, p2, 0.25f, 0.25f);
            body->SetMassData(&md);  // the capsule's mass, not the overlapping compound's
        } else if (i % 3 == 1) {
            addFixture(body, disc, 0.25f, 0.1f, 0.1f);
        } else {
            addFixture(body, box, 0.25f, 0.1f, 0.1f);
        }
        x += 0.5;
        if (x >= 23.0) {
            x = -23.0;
            y += 0.5;
        }
    }
    return s;
}

// Box2D v3's tumbler: a 20 m box drum of four walls (density 50) turned at 25 deg/s by a motor,
// tumbling 45 x 45 small boxes.
SuiteWorld tumbler(const Options& o) {
    SuiteWorld s = emptySuiteWorld(true, o);
    b2Body* ground = s.addBody(b2_staticBody, b2Vec2(0.0f, 0.0f));
    b2Body* drum = s.addBody(b2_dynamicBody, b2Vec2(0.0f, 10.0f));
    addFixture(drum, boxShape(1.0f, 20.0f, b2Vec2(10.0f, 0.0f)), 50.0f);
    addFixture(drum, boxShape(1.0f, 20.0f, b2Vec2(-10.0f, 0.0f)), 50.0f);
    addFixture(drum, boxShape(20.0f, 1.0f, b2Vec2(0.0f, 10.0f)), 50.0f);
    addFixture(drum, boxShape(20.0f, 1.0f, b2Vec2(0.0f, -10.0f)), 50.0f);
    b2RevoluteJointDef jd;
    jd.enableMotor = true;
    jd.motorSpeed = (float)(3.14159265358979323846 / 180.0 * 25.0);
    jd.maxMotorTorque = 1e8f;
    addRevolute(*s.world, ground, drum, b2Vec2(0.0f, 10.0f), jd);
    const int grid = 45;
    const b2PolygonShape box = boxShape(0.25f, 0.25f);
    double y = -0.2 * grid + 10.0;
    for (int i = 0; i < grid; ++i, y += 0.4) {
        double x = -0.2 * grid;
        for (int k = 0; k < grid; ++k, x += 0.4) addFixture(s.addBody(b2_dynamicBody, b2Vec2((float)x, (float)y)), box);
    }
    return s;
}

// The static container of compounds and junkyard: a floor of 1.1 x 1 m boxes 1 m apart along y = 0
// from x = -half to half, and at x = +-half a wall of `wall` 1 x 1.1 m boxes stacked from y = 1.
void addBoxContainer(b2Body* ground, int half, int wall) {
    for (int i = 0; i <= 2 * half; ++i) addFixture(ground, boxShape(1.1f, 1.0f, b2Vec2((float)(i - half), 0.0f)));
    for (int side : {-1, 1})
        for (int i = 0; i < wall; ++i) addFixture(ground, boxShape(1.0f, 1.1f, b2Vec2((float)(side * half), i + 1.0f)));
}

// Box2D v3's compounds: 20 x 150 bodies of two overlapping triangles (density 1, friction 0.5)
// fall into an 80 m container with 100 m walls; a 1600 m segment 80 m below catches what falls out.
SuiteWorld compounds(const Options& o) {
    SuiteWorld s = emptySuiteWorld(true, o);
    b2Body* ground = s.addBody(b2_staticBody, b2Vec2(0.0f, 0.0f));
    addBoxContainer(ground, 40, 100);
    b2EdgeShape segment;
    segment.SetTwoSided(b2Vec2(-800.0f, -80.0f), b2Vec2(800.0f, -80.0f));
    addFixture(ground, segment, 0.0f);
    const b2Vec2 leftPoints[3] = {{-1.0f, 0.0f}, {0.5f, 1.0f}, {0.0f, 2.0f}};
    const b2Vec2 rightPoints[3] = {{1.0f, 0.0f}, {-0.5f, 1.0f}, {0.0f, 2.0f}};
    b2PolygonShape left, right;
    left.Set(leftPoints, 3);
    right.Set(rightPoints, 3);
    const int columns = 20, rows = 150;
    const double shift = 2.0, extraY = 0.25, centerX = shift * columns / 2.0 - 1.0, centerY = 1.15 / 2.0, yStart = 5.0;
    double side = 0.25;
    for (int i = 0; i < columns; ++i)
        for (int j = 0; j < rows; ++j, side = -side) {
            b2Body* body = s.addBody(b2_dynamicBody, b2Vec2((float)(i * shift - centerX + side),
                                                            (float)(j * (shift + extraY) + centerY + yStart)));
            addFixture(body, left, 1.0f, 0.5f);
            addFixture(body, right, 1.0f, 0.5f);
        }
    return s;
}

// Box2D v3's junkyard: 200 x 40 pentagons (radius 0.25 m) fall into a 160 m container with 50 m
// walls, swept by a kinematic 4 x 8 m pusher. 2.4.1 has no b2Body_SetTargetTransform: before step
// k the pusher gets the velocity that takes it to x = 60 sin(0.2 k dt) in one step, which is what
// that function (and rigidlab's World::setTarget) sets.
SuiteWorld junkyard(const Options& o) {
    SuiteWorld s = emptySuiteWorld(true, o);
    addBoxContainer(s.addBody(b2_staticBody, b2Vec2(0.0f, 0.0f)), 80, 50);
    const double pi = 3.14159265358979323846, radius = 0.25, phi = pi * (std::sqrt(5.0) - 1.0);
    b2Vec2 points[5];
    for (int k = 0; k < 5; ++k) points[k] = b2Vec2((float)(radius * std::cos(phi * k)), (float)(radius * std::sin(phi * k)));
    b2PolygonShape pentagon;
    pentagon.Set(points, 5);  // the convex hull, in 2.4.1's order
    const int columns = 200, rows = 40;
    double side = -0.1;
    for (int i = 0; i < columns; ++i)
        for (int j = 0; j < rows; ++j, side = -side)
            addFixture(s.addBody(b2_dynamicBody, b2Vec2((float)(1.5 * (2.0 * i - columns) * radius + side),
                                                        (float)(4.0 * j * radius + 15.0))),
                       pentagon);
    b2Body* pusher = s.addBody(b2_kinematicBody, b2Vec2(0.0f, 0.0f));
    addFixture(pusher, boxShape(4.0f, 8.0f, b2Vec2(0.0f, 4.0f)));
    s.beforeStep = [pusher](SuiteWorld&, int step) {
        const double dt = 1.0 / 60.0;
        const double x = 60.0 * std::sin(0.2 * dt * step);
        pusher->SetLinearVelocity(b2Vec2((float)((x - pusher->GetPosition().x) / dt), (float)(-pusher->GetPosition().y / dt)));
    };
    return s;
}

// Box2D v3's washer: a kinematic drum turning at 25 deg/s about (0, 10), drifting at (0.001, -0.002)
// m/s, of 36 ring pieces (16 to 18 m, 10 deg plus 1 deg over each neighbour) and 4 fins (14 to 16 m)
// holds 90 x 90 boxes of 0.2 m. v3 (and rigidlab) report hit events of the boxes; 2.4.1 has none
// (a contact listener would be the nearest, and would cost what v3's events do not): left out.
SuiteWorld washer(const Options& o) {
    SuiteWorld s = emptySuiteWorld(true, o);
    s.addBody(b2_staticBody, b2Vec2(0.0f, 0.0f));  // v3's ground body without shapes
    b2Body* drum = s.addBody(b2_kinematicBody, b2Vec2(0.0f, 10.0f));
    const double pi = 3.14159265358979323846, r0 = 14.0, r1 = 16.0, r2 = 18.0, step = pi / 18.0;
    const auto at = [](double r, double angle) { return b2Vec2((float)(r * std::cos(angle)), (float)(r * std::sin(angle))); };
    for (int i = 0; i < 36; ++i) {
        const double t1 = i * step, t2 = (i + 1) * step;
        const b2Vec2 quad[4] = {at(r1, t1 - 0.1 * step), at(r2, t1 - 0.1 * step), at(r2, t2 + 0.1 * step), at(r1, t2 + 0.1 * step)};
        b2PolygonShape piece;
        piece.Set(quad, 4);
        addFixture(drum, piece);
        if (i % 9 == 0) {
            const b2Vec2 fin[4] = {at(r0, t1), at(r1, t1), at(r1, t2), at(r0, t2)};
            piece.Set(fin, 4);
            addFixture(drum, piece);
        }
    }
    drum->SetAngularVelocity((float)(pi / 180.0 * 25.0));
    drum->SetLinearVelocity(b2Vec2(0.001f, -0.002f));
    const int grid = 90;
    const double a = 0.1;
    const b2PolygonShape box = boxShape((float)(2.0 * a), (float)(2.0 * a));
    double y = -1.1 * a * grid + 10.0;
    for (int i = 0; i < grid; ++i, y += 2.1 * a) {
        double x = -1.1 * a * grid;
        for (int j = 0; j < grid; ++j, x += 2.1 * a) addFixture(s.addBody(b2_dynamicBody, b2Vec2((float)x, (float)y)), box);
    }
    return s;
}

SuiteWorld buildSuite(const std::string& name, const Options& o) {
    if (name == "compounds") return compounds(o);
    if (name == "junkyard") return junkyard(o);
    if (name == "washer") return washer(o);
    if (name == "large_pyramid") return largePyramid(o);
    if (name == "many_pyramids") return manyPyramids(o);
    if (name == "joint_grid") return jointGrid(o);
    if (name == "ragdolls") return ragdollRain(o, 40);
    if (name == "smash") return smash(o);
    if (name == "spinner") return spinner(o);
    return tumbler(o);
}

// One repetition: a fresh world, `steps` timed steps, then the figures (suite.h).
SuiteRun runSuiteOnce(const SuiteInfo& info, int steps, const Options& o) {
    SuiteRun run;
    auto t0 = Clock::now();
    SuiteWorld s = buildSuite(info.name, o);
    run.setupMs = msSince(t0, Clock::now());

    const float dt = 1.0f / 60.0f;
    run.stepMs.reserve(steps);
    for (int i = 0; i < steps; ++i) {
        // rigidlab times the scene's own edits before the step (bench_run.cpp), so this does too
        auto a = Clock::now();
        if (s.beforeStep) s.beforeStep(s, i);
        s.world->Step(dt, o.velIters, o.posIters);
        run.stepMs.push_back(msSince(a, Clock::now()));
        if (i == 0) {
            for (SuiteEntry& e : s.dynamic) {
                if (!e.body) continue;
                e.tracked = true;
                e.x0 = e.body->GetPosition().x;
                e.y0 = e.body->GetPosition().y;
            }
        }
    }

    SuiteFigures f;
    std::vector<SuiteBody> figures;
    for (const SuiteEntry& e : s.dynamic) {
        if (!e.body) continue;
        ++f.bodies;
        f.awake += e.body->IsAwake() ? 1 : 0;
        SuiteBody b;
        b.tracked = e.tracked;
        b.x0 = e.x0;
        b.y0 = e.y0;
        b.x = e.body->GetPosition().x;
        b.y = e.body->GetPosition().y;
        figures.push_back(b);
    }
    f.joints = s.world->GetJointCount();
    for (b2Joint* j = s.world->GetJointList(); j; j = j->GetNext())
        if (j->GetType() == e_revoluteJoint) f.maxJointGap = std::max(f.maxJointGap, (double)(j->GetAnchorA() - j->GetAnchorB()).Length());
    // touching contacts of the last step, as rigidlab counts them (before its contact-finding step)
    int touching = 0;
    for (b2Contact* c = s.world->GetContactList(); c; c = c->GetNext()) touching += c->IsTouching() ? 1 : 0;
    run.contacts = touching;
    run.dynamicBodies = f.bodies;

    // The deepest contact where the bodies are now: a step's contacts are found at its start, before
    // the solve moves the bodies. b2World::Step(0) runs Collide and skips Solve and SolveTOI when
    // dt = 0 (moves nothing; a contact that starts or stops touching wakes its bodies, hence after
    // the awake count). The separation includes 2.4.1's polygon skin (b2_polygonRadius), as given.
    s.world->Step(0.0f, o.velIters, o.posIters);
    for (b2Contact* c = s.world->GetContactList(); c; c = c->GetNext()) {
        if (!c->IsTouching()) continue;
        b2WorldManifold wm;
        c->GetWorldManifold(&wm);
        for (int k = 0; k < c->GetManifold()->pointCount; ++k)
            f.maxPenetration = std::max(f.maxPenetration, (double)-wm.separations[k]);
    }
    f.escaped = suiteEscaped(info.name, figures);
    run.metrics = suiteMetricsJson(f, figures);
    return run;
}

}  // namespace

// Box2D 2.4.1's b2_version still says 2.4.0; report both.
static std::string versionString() {
    char ver[64];
    std::snprintf(ver, sizeof ver, "2.4.1 (b2_version %d.%d.%d)", b2_version.major, b2_version.minor,
                  b2_version.revision);
    return ver;
}

static std::string settingsString(const Options& o, double dt) {
    return settingsJson({{"dt", dt},
                         {"velocityIterations", (double)o.velIters},
                         {"positionIterations", (double)o.posIters},
                         {"continuous", o.continuous ? 1.0 : 0.0},
                         {"bullet", o.bullet ? 1.0 : 0.0},
                         {"linearSlop", b2_linearSlop},
                         {"polygonRadius", b2_polygonRadius}});
}

int main(int argc, char** argv) {
    Options o;
    if (!parseArgs(argc, argv, o)) {
        usage(argv[0]);
        return 2;
    }
    if (const SuiteInfo* info = suiteInfo(o.scene)) {
        const int steps = o.steps > 0 ? o.steps : info->steps;
        std::vector<SuiteRun> runs;
        for (int r = 0; r < o.reps; ++r) runs.push_back(runSuiteOnce(*info, steps, o));
        printSuiteResult("box2d", versionString(), *info, steps, settingsString(o, 1.0 / 60.0), runs);
        return 0;
    }
    Scene sc = buildScene(o);
    std::vector<RunResult> runs;
    for (int r = 0; r < o.reps; ++r) runs.push_back(runOnce(sc, o));
    printResult("box2d", versionString(), o, sc, settingsString(o, sc.dt), runs);
    return 0;
}
