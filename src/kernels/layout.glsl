// The contract between the host and the effect update shader
// (src/gpu/shaders/effects_update.comp), written once for both languages:
// limits, workgroup size, passes, specialization constant ids, binding
// numbers, buffer headers and the push constant block; the same for the
// back-to-front sort and the fluid's passes (the renderer's contracts are
// in render_layout.glsl). The shader declares its
// buffer blocks with these headers as members; src/gpu sizes, fills and reads
// the buffers with the same structs. Headers are 4-byte fields in groups of
// four (std430 offsets equal C++ offsets); the static_asserts at the end fail
// the C++ build if either side's layout drifts. The parameter structs
// themselves are in types.glsl.
#ifndef SPINDRIFT_KERNELS_LAYOUT
#define SPINDRIFT_KERNELS_LAYOUT
#include "types.glsl"
SD_BEGIN

// Limits. An emitter selects forces and colliders with 32-bit masks
// (EmitterParams::forceMask, colliderMask), and the step counts hits per
// collider (StepCounters::hits): at most 32 of each per world.
SD_CONST uint SD_MAX_FORCES = 32u;
SD_CONST uint SD_MAX_COLLIDERS = 32u;
// Sampled fields of one Vulkan world, the sizes of the sampler arrays of set 2.
// effects_update.comp switches over literal indices 0..7 (lavapipe cannot index
// sampler arrays dynamically): raising these needs more cases there.
SD_CONST uint SD_MAX_FLOW_FIELDS = 8u;
SD_CONST uint SD_MAX_HEIGHT_MAPS = 8u;
SD_CONST uint SD_MAX_CUBE_MAPS = 8u;

// Threads per workgroup of effects_update.comp (local_size_x).
SD_CONST uint SD_UPDATE_WORKGROUP = 64u;

// Most positions a particle's trail keeps (EmitterDef::trail.points): the
// ribbon's vertices are drawn per instance, 6 (points - 1) of them.
SD_CONST uint SD_MAX_TRAIL_POINTS = 64u;

// The passes of one emitter's step, each a module of effects_update.comp.
SD_CONST uint SD_PASS_RECYCLE_UPDATE = 0u;
SD_CONST uint SD_PASS_SPAWN_UPDATE = 1u;
SD_CONST uint SD_PASS_SPAWN_EMIT = 2u;
SD_CONST uint SD_PASS_SPAWN_FINISH = 3u;
SD_CONST uint SD_PASS_SUB_EMIT = 4u;  // a sub-emitter's births from its parent's requests (sub_emit.glsl)

// Specialization constant ids, in the order the host passes them.
SD_CONST uint SD_SPEC_FLOW_FIELDS = 0u;  // flow fields of the world, 0..SD_MAX_FLOW_FIELDS
SD_CONST uint SD_SPEC_HEIGHT_MAPS = 1u;
SD_CONST uint SD_SPEC_CUBE_MAPS = 2u;
SD_CONST uint SD_SPEC_INTEGRATOR = 3u;   // SD_INTEGRATE_*, or SD_ANY_INTEGRATOR
SD_CONST uint SD_SPEC_CURL_NOISE = 4u;   // 1: the emitter selects a curl-noise force (else its code is dropped)
SD_CONST uint SD_SPEC_COUNT = 5u;
// INTEGRATOR value that reads the emitter's own (EmitterParams::integrator).
SD_CONST uint SD_ANY_INTEGRATOR = 0xFFFFFFFFu;

// Descriptor sets of effects_update.comp.
SD_CONST uint SD_SET_EMITTER = 0u;  // per emitter and frame in flight
SD_CONST uint SD_SET_LISTS = 1u;    // spawn mode's slot lists (recycle emitters bind a placeholder)
SD_CONST uint SD_SET_FIELDS = 2u;   // the world's sampled fields

// Set 0 bindings, in order.
SD_CONST uint SD_BINDING_EMITTER = 0u;    // EmitterParams
SD_CONST uint SD_BINDING_FORCES = 1u;     // TableHeader, ForceParams[SD_MAX_FORCES]
SD_CONST uint SD_BINDING_COLLIDERS = 2u;  // TableHeader, ColliderParams[SD_MAX_COLLIDERS]
SD_CONST uint SD_BINDING_POSITIONS = 3u;  // float[3 capacity] (m)
SD_CONST uint SD_BINDING_VELOCITIES = 4u; // float[3 capacity] (m/s)
SD_CONST uint SD_BINDING_AGES = 5u;       // float[capacity] (s)
SD_CONST uint SD_BINDING_BIRTHS = 6u;     // uint[capacity], birth serials
SD_CONST uint SD_BINDING_ROTATIONS = 7u;  // float[capacity] (rad)
SD_CONST uint SD_BINDING_COUNTERS = 8u;   // StepCounters, host-visible, per frame
SD_CONST uint SD_BINDING_EVENTS = 9u;     // EventsHeader, EventRecord[capacity], per frame
SD_CONST uint SD_BINDING_TRAILS = 10u;    // float[3 points capacity] (m), trail.glsl; 1 entry without a trail
// This step's spawn requests for sub-emitters (sub_emit.glsl), one buffer per
// event kind: EventsHeader (count, capacity), SpawnRequest[capacity]; a
// placeholder for a kind no sub-emitter follows.
SD_CONST uint SD_BINDING_BIRTH_REQUESTS = 11u;
SD_CONST uint SD_BINDING_DEATH_REQUESTS = 12u;
SD_CONST uint SD_BINDING_COLLISION_REQUESTS = 13u;
SD_CONST uint SD_EMITTER_BINDINGS = 14u;

// Set 1 bindings (spawn mode), in order.
SD_CONST uint SD_BINDING_DEAD = 0u;       // DeadHeader, uint deadSlots[capacity]
SD_CONST uint SD_BINDING_ALIVE_IN = 1u;   // TableHeader, uint slots[capacity]
SD_CONST uint SD_BINDING_ALIVE_OUT = 2u;  // TableHeader, uint slots[capacity]
SD_CONST uint SD_BINDING_SCHEDULE = 3u;   // ScheduleHeader, uvec2 runs[], host-visible, per frame
SD_CONST uint SD_BINDING_PARENT_REQUESTS = 4u;  // a sub-emitter's parent's requests of its kind (else a placeholder)
SD_CONST uint SD_LIST_BINDINGS = 5u;

// Set 2 bindings: combined image samplers, arrays of SD_MAX_* elements.
SD_CONST uint SD_BINDING_FLOW_FIELDS = 0u;  // sampler3D, xyz velocity (m/s)
SD_CONST uint SD_BINDING_HEIGHT_MAPS = 1u;  // sampler2D, height (m)
SD_CONST uint SD_BINDING_CUBE_MAPS = 2u;    // samplerCube, outward normal xyz, depth w (m)
SD_CONST uint SD_FIELD_BINDINGS = 3u;

// Head of a counted array (forces, colliders, alive lists): the count and
// three pads, so the array starts 16-byte aligned as std430 needs for the
// vec4 members of its elements. 16 bytes.
struct TableHeader {
    uint count;
    uint pad0, pad1, pad2;
};

// Head of a spawn emitter's dead-slot stack (its top at deadSlots[deadCount -
// 1]). dispatch*: the indirect dispatch (VkDispatchIndirectCommand) of the
// next update pass; popped: slots the emit pass took; nextSerial: serial of
// the emitter's next birth, kept on the device so the host need not wait for a
// step's birth count to schedule the next; subPopped: slots the sub-emit pass
// took, after the emit pass's. 32 bytes.
struct DeadHeader {
    uint dispatchX, dispatchY, dispatchZ, deadCount;
    uint popped, nextSerial, subPopped, pad1;
};

// Head of a step's birth schedule (BirthSchedule of
// src/particles/birth_schedule.h, written by the host): burst runs (end index,
// age) first, then the rate's births. 32 bytes.
struct ScheduleHeader {
    uint burstRuns;
    uint rateFirst;   // index of the rate's first birth
    uint pad0, pad1;
    float rateSpan;   // t1 - t0 (s)
    float rateCarry;  // the rate's carry before the step (particles)
    float rate;       // 1/s
    float maxAge;     // dt (s)
};

// Counts of one emitter's step, read by the host through a mapping once the
// step's fence has signalled. 160 bytes.
struct StepCounters {
    uint born;
    uint died;
    uint clamped;  // births without a free slot
    uint nonFinite;  // removed: a number became NaN or infinite (SD_EVENT_NON_FINITE)
    uint hits[SD_MAX_COLLIDERS];  // per collider
    uint subBorn;  // of born: sub-emitted (they take no serial from nextSerial)
    uint pad0, pad1, pad2;
};

// Head of a frame's events buffer, shared by every emitter of the world: at
// most capacity records are written; count keeps counting beyond it, so the
// host knows how many were dropped. 16 bytes.
struct EventsHeader {
    uint count;
    uint capacity;
    uint pad0, pad1;
};

// The push constants of every pass. count: slots (recycle update) or births
// owed (spawn emit and finish), particles per request (sub-emit).
// trailPoints, trailHead: the emitter's trail (trail.glsl; 0 points: none),
// the ring index this step writes. step: the world's step (low 32 bits);
// requestKinds: bit k, record spawn requests of kind k (sub_emit.glsl);
// inherit: a sub-emitter's share of the parent's velocity. 48 bytes.
struct StepPush {
    float dt;  // s
    uint count;
    uint emitterIndex;
    float time;  // s, the world time at the start of the step (animated forces)
    uint trailPoints;
    uint trailHead;
    uint step;
    uint requestKinds;
    float inherit;
    uint pad0, pad1, pad2;
};

// The back-to-front sort (src/gpu/shaders/back_to_front_sort.comp, src/gpu/
// gpu_sort.cpp); its digit and tile sizes are in sort_key.glsl.
SD_CONST uint SD_SORT_PASS_KEYS = 0u;  // the PASS specialization constant (id 0)
SD_CONST uint SD_SORT_PASS_COUNT = 1u;
SD_CONST uint SD_SORT_PASS_SCAN = 2u;
SD_CONST uint SD_SORT_PASS_SCATTER = 3u;
// Set 0 bindings, in order.
SD_CONST uint SD_SORT_BINDING_POSITIONS = 0u;    // float[3 n], tightly packed xyz (m)
SD_CONST uint SD_SORT_BINDING_AGES = 1u;         // float[n] (s), read with SD_SORT_FLAG_AGES
SD_CONST uint SD_SORT_BINDING_KEYS = 2u;         // uint[n], the current pairs
SD_CONST uint SD_SORT_BINDING_VALUES = 3u;
SD_CONST uint SD_SORT_BINDING_NEXT_KEYS = 4u;    // uint[n], the next pairs
SD_CONST uint SD_SORT_BINDING_NEXT_VALUES = 5u;
SD_CONST uint SD_SORT_BINDING_TILE_COUNTS = 6u;  // per (digit, tile), digit-major
SD_CONST uint SD_SORT_BINDING_HEADER = 7u;       // TableHeader: count of live pairs
SD_CONST uint SD_SORT_BINDINGS = 8u;
// SortPush::flags: ages are bound, a negative age is a dead slot (sorted last).
SD_CONST uint SD_SORT_FLAG_AGES = 1u;

// The sort's push constants (std430: two vec4 then four uints). 48 bytes.
struct SortPush {
    vec4 eye;      // xyz camera position (m)
    vec4 forward;  // xyz unit view direction
    uint count;    // pairs
    uint tiles;    // workgroups of the keys pass
    uint shift;    // of the pass's digit (bits)
    uint flags;    // SD_SORT_FLAG_*
};

// The constraint fluid's grid on the device (src/gpu/shaders/fluid_grid.comp,
// src/gpu/gpu_fluid_grid.cpp): keys by fluid.glsl's fluidGridKey, sorted by
// the back-to-front sort's radix passes, then where each key's particles start.
SD_CONST uint SD_FLUID_GRID_PASS_KEYS = 0u;    // the PASS specialization constant (id 0)
SD_CONST uint SD_FLUID_GRID_PASS_STARTS = 1u;
SD_CONST uint SD_FLUID_GRID_WORKGROUP = 64u;
// Set 0 bindings, in order.
SD_CONST uint SD_FLUID_GRID_BINDING_POSITIONS = 0u;    // float[dimension n], tightly packed (m), as the CPU's arrays
SD_CONST uint SD_FLUID_GRID_BINDING_KEYS = 1u;         // uint[n]: the keys pass's keys (the radix sort's first pair)
SD_CONST uint SD_FLUID_GRID_BINDING_VALUES = 2u;       // uint[n]: particle indices
SD_CONST uint SD_FLUID_GRID_BINDING_SORTED_KEYS = 3u;  // uint[n]: the keys in grid order (the pair the sort ended in)
SD_CONST uint SD_FLUID_GRID_BINDING_KEY_START = 4u;    // uint[keyTotal + 1]
SD_CONST uint SD_FLUID_GRID_BINDINGS = 5u;

// The grid passes' push constants (std430: a vec4, an ivec4, four uints). 48 bytes.
struct FluidGridPush {
    vec4 origin;     // xyz corner of sub-cell 0 (m; z 0 in 2D), w = 1 / h (1/m)
    ivec4 cells;     // xyz cells 2h wide per axis (z 1 in 2D), w unused
    uint count;      // particles
    uint dimension;  // 2 or 3
    uint keyTotal;   // cells x 2^dimension
    uint pad0;
};

// The constraint fluid's setup on the device (src/gpu/shaders/fluid_setup.comp,
// src/gpu/gpu_fluid_setup.cpp): the particles gathered into the grid's order,
// then every particle's neighbours within h counted, the counts' prefix sum,
// and the lists, density, bias and effective mass, as the CPU's
// setupConstraints (src/fluid/neighbours.cpp) computes them.
SD_CONST uint SD_FLUID_SETUP_PASS_GATHER = 0u;  // the PASS specialization constant (id 0)
SD_CONST uint SD_FLUID_SETUP_PASS_COUNT = 1u;   // neighbours per particle, and per workgroup (tile)
SD_CONST uint SD_FLUID_SETUP_PASS_TILES = 2u;   // the tiles' exclusive prefix sum (one invocation)
SD_CONST uint SD_FLUID_SETUP_PASS_SETUP = 3u;   // lists and constraints
SD_CONST uint SD_FLUID_SETUP_WORKGROUP = 64u;   // particles per tile of the prefix sum
// Set 0 bindings, in order. "Grid order": place i of the grid's sort.
SD_CONST uint SD_FLUID_SETUP_BINDING_ORDER = 0u;        // uint[n]: grid order -> particle index
SD_CONST uint SD_FLUID_SETUP_BINDING_SORTED_KEYS = 1u;  // uint[n]: keys in grid order
SD_CONST uint SD_FLUID_SETUP_BINDING_KEY_START = 2u;    // uint[keyTotal + 1]
SD_CONST uint SD_FLUID_SETUP_BINDING_POSITIONS = 3u;    // float[dimension n] (m), particle order
SD_CONST uint SD_FLUID_SETUP_BINDING_VELOCITIES = 4u;   // float[dimension n] (m/s), particle order
SD_CONST uint SD_FLUID_SETUP_BINDING_PRESSURES = 5u;    // float[n] (m/s), particle order: last accumulated impulse
SD_CONST uint SD_FLUID_SETUP_BINDING_X = 6u;            // float[dimension n]: positions in grid order
SD_CONST uint SD_FLUID_SETUP_BINDING_V = 7u;            // float[dimension n]: velocities in grid order
SD_CONST uint SD_FLUID_SETUP_BINDING_P = 8u;            // float[n]: pressures in grid order
SD_CONST uint SD_FLUID_SETUP_BINDING_WALL = 9u;         // vec4[n], grid order: colliders' density, xyz their g sum
SD_CONST uint SD_FLUID_SETUP_BINDING_COUNTS = 10u;      // uint[n]: neighbours stored per particle
SD_CONST uint SD_FLUID_SETUP_BINDING_TILES = 11u;       // uint[tiles]: neighbours per tile, then the tile's first
SD_CONST uint SD_FLUID_SETUP_BINDING_HEADER = 12u;      // FluidSetupHeader
SD_CONST uint SD_FLUID_SETUP_BINDING_FIRST = 13u;       // uint[n]: first list entry of each particle
SD_CONST uint SD_FLUID_SETUP_BINDING_LIST_INDEX = 14u;  // uint[entries]: the neighbour (grid order); g is recomputed (fluidPairG)
SD_CONST uint SD_FLUID_SETUP_BINDING_CONSTRAINTS = 15u; // vec4[n]: bias (m/s), 1 / A, rho / rho0, fastest closing (m/s)
SD_CONST uint SD_FLUID_SETUP_BINDING_WARM = 16u;        // vec4[n]: xyz the gathered warm start (m/s)
SD_CONST uint SD_FLUID_SETUP_BINDINGS = 17u;

// What the setup reports (std430, 16 bytes).
struct FluidSetupHeader {
    uint entries;    // list entries of all particles (those past the lists' capacity not written)
    uint overflows;  // neighbours left out: crushed sub-cells' and lists' caps (FluidStepStats)
    uint pad0;
    uint pad1;
};

// The setup passes' push constants (std430: an ivec4, a vec4, four uints,
// eight floats, a uint, a float, two uints, a float, three pads). 112
// bytes. The floats are the CPU setup's, computed the same way on the host
// (h2 = h h, invH2 = 1 / h2, ...).
struct FluidSetupPush {
    ivec4 cells;          // xyz cells 2h wide per axis (z 1 in 2D), w = dimension
    vec4 velocityChange;  // xyz m/s the gather adds to every velocity: gravity x dt (the step's external force)
    uint count;           // particles
    uint readLimit;       // most particles read from one sub-cell (FluidState::subCellReadLimit)
    uint cap;             // most neighbours stored per particle (FluidState::maxNeighbours)
    uint listCapacity;    // entries the lists hold
    float h;              // m
    float h2;             // m^2
    float invH;           // 1/m
    float invH2;          // 1/m^2
    float restDensity;    // kernel-sum units
    float baumgarte;
    float invDt;          // 1/s, of the substep
    float warmFraction;   // of the last pressure the warm start applies
    float invRest;        // 1 / restDensity
    uint tiles;           // workgroups of the count pass
    float relaxation;     // FluidDef::relaxation (fluidInverseMass)
    uint countClosing;    // 1: the closing speeds too (the step's first substep; setupConstraints)
    float warmCap;        // m/s: the gather caps the last pressures at it (fluidWarmCap)
    uint pad0;
    uint pad1;
    uint pad2;
};

// The constraint fluid's solve on the device (src/gpu/shaders/fluid_solve.comp,
// src/gpu/gpu_fluid_solve.cpp): the CPU's solveConstraints (src/fluid/
// solver.cpp) in its Parallel order, on the setup's lists.
SD_CONST uint SD_FLUID_SOLVE_PASS_START = 0u;   // the PASS specialization constant (id 0)
SD_CONST uint SD_FLUID_SOLVE_PASS_WARM = 1u;    // one colour's scattered warm start (lists that overflowed)
SD_CONST uint SD_FLUID_SOLVE_PASS_SWEEP = 2u;   // one colour's visits
SD_CONST uint SD_FLUID_SOLVE_PASS_FINISH = 3u;  // the velocities back from the working copy
SD_CONST uint SD_FLUID_SOLVE_WORKGROUP = 64u;
// Set 0 bindings, in order; per particle in grid order.
SD_CONST uint SD_FLUID_SOLVE_BINDING_KEY_START = 0u;       // uint[keyTotal + 1], the grid's
SD_CONST uint SD_FLUID_SOLVE_BINDING_FIRST = 1u;           // uint[n], the setup's
SD_CONST uint SD_FLUID_SOLVE_BINDING_COUNTS = 2u;          // uint[n]
SD_CONST uint SD_FLUID_SOLVE_BINDING_X = 3u;               // float[dimension n] (m): the setup's positions, grid order
SD_CONST uint SD_FLUID_SOLVE_BINDING_LIST_INDEX = 4u;      // uint[entries]
SD_CONST uint SD_FLUID_SOLVE_BINDING_CONSTRAINTS = 5u;     // vec4[n]: bias (m/s), 1 / A, ...
SD_CONST uint SD_FLUID_SOLVE_BINDING_WARM = 6u;            // vec4[n]: xyz the gathered warm start (m/s)
SD_CONST uint SD_FLUID_SOLVE_BINDING_WALL = 7u;            // vec4[n]: yzw the colliders' g sum
SD_CONST uint SD_FLUID_SOLVE_BINDING_V = 8u;               // float[dimension n] (m/s): in, and out after FINISH
SD_CONST uint SD_FLUID_SOLVE_BINDING_P = 9u;               // float[n] (m/s): last pressure in, accumulated out
SD_CONST uint SD_FLUID_SOLVE_BINDING_PSEUDO_IMPULSE = 10u; // float[n] (m/s): accumulated pseudo impulse
SD_CONST uint SD_FLUID_SOLVE_BINDING_MOTION = 11u;         // float[2 dimension n]: velocity, pseudo velocity (m/s)
SD_CONST uint SD_FLUID_SOLVE_BINDING_HEADER = 12u;         // FluidSetupHeader: overflows pick the warm start
SD_CONST uint SD_FLUID_SOLVE_BINDINGS = 13u;

// The solve passes' push constants (std430: an ivec4, four uints, four
// floats). 48 bytes.
struct FluidSolvePush {
    ivec4 cells;          // xyz cells 2h wide per axis (z 1 in 2D), w = dimension
    uint count;           // particles
    uint colour;          // of a WARM or SWEEP pass: cell parities x | y << 1 | z << 2
    uint split;           // 1: split impulses (FluidDef::splitImpulse)
    uint pad0;
    float warmFraction;   // of the last pressure the warm start applies
    float allowanceSlop;  // m/s (fluidAllowanceSlop)
    float invH2;          // 1/m^2: 1 / (h h), as the setup's push (the pairs' g, fluidPairG)
    float pad2;
};

// The constraint fluid's contacts with static colliders on the device
// (src/gpu/shaders/fluid_contacts.comp, src/gpu/gpu_fluid_contacts.cpp): the
// CPU's findContacts and solveContacts (src/fluid/collide.cpp).
SD_CONST uint SD_FLUID_CONTACTS_PASS_FIND = 0u;   // the PASS specialization constant (id 0)
SD_CONST uint SD_FLUID_CONTACTS_PASS_SOLVE = 1u;
SD_CONST uint SD_FLUID_CONTACTS_PASS_ORDER = 2u;    // the dynamic contacts listed in the CPU's order (per particle)
SD_CONST uint SD_FLUID_CONTACTS_PASS_DYNAMIC = 3u;  // they and the joints' rows solved in it (one invocation)
// Before ORDER, an exclusive prefix sum of each particle's dynamic contacts:
SD_CONST uint SD_FLUID_CONTACTS_PASS_COUNT = 4u;   // within each workgroup, and each workgroup's total
SD_CONST uint SD_FLUID_CONTACTS_PASS_GROUPS = 5u;  // over the workgroups' totals (one invocation)
SD_CONST uint SD_FLUID_CONTACTS_PASSES = 6u;
SD_CONST uint SD_FLUID_CONTACTS_WORKGROUP = 64u;
// Surfaces a fluid's contacts tell apart: one bit each in a particle's mask.
SD_CONST uint SD_FLUID_MAX_SURFACES = 32u;
// Set 0 bindings, in order; per particle in grid order.
SD_CONST uint SD_FLUID_CONTACTS_BINDING_X = 0u;          // float[dimension n] (m)
SD_CONST uint SD_FLUID_CONTACTS_BINDING_V = 1u;          // float[dimension n] (m/s), at the search
SD_CONST uint SD_FLUID_CONTACTS_BINDING_COLLIDERS = 2u;  // ColliderParams[]: the fluid's planes, spheres and boxes
SD_CONST uint SD_FLUID_CONTACTS_BINDING_POLYGONS = 3u;   // FluidPolygon[]
SD_CONST uint SD_FLUID_CONTACTS_BINDING_WALL_TABLE = 4u; // vec2[size]: density, push (wall_density.cpp)
SD_CONST uint SD_FLUID_CONTACTS_BINDING_WALL = 5u;       // vec4[n] out: colliders' density, xyz their g sum
SD_CONST uint SD_FLUID_CONTACTS_BINDING_MASK = 6u;       // uint[n]: the surfaces within reach
SD_CONST uint SD_FLUID_CONTACTS_BINDING_MOTION = 7u;     // float[2 dimension n]: the solve's velocity, pseudo velocity
// Rigid bodies the fluid does not move (static, kinematic; 2D): their shapes
// at the substep's start poses, each shape's grid cells (the CPU's bins),
// the bodies, each particle's contacts (`bodySlots` a particle) and their
// count, the report with the impacts, and what names a particle in an
// impact (grid order -> particle index, particle order -> serial).
SD_CONST uint SD_FLUID_CONTACTS_BINDING_SHAPES = 8u;        // FluidBodyShape[shapes]
SD_CONST uint SD_FLUID_CONTACTS_BINDING_SHAPE_CELLS = 9u;   // ivec4[shapes]: first cell x, y, last cell x, y
SD_CONST uint SD_FLUID_CONTACTS_BINDING_BODIES = 10u;       // FluidBodyMotion[]
SD_CONST uint SD_FLUID_CONTACTS_BINDING_BODY_CONTACTS = 11u;  // FluidBodyContact[bodySlots n]
SD_CONST uint SD_FLUID_CONTACTS_BINDING_BODY_COUNTS = 12u;  // uint[n]: contacts found (may exceed bodySlots)
SD_CONST uint SD_FLUID_CONTACTS_BINDING_BODY_REPORT = 13u;  // FluidBodyReport, then FluidBodyImpact[impactRoom]
SD_CONST uint SD_FLUID_CONTACTS_BINDING_ORDER = 14u;        // uint[n]: grid order -> particle index
SD_CONST uint SD_FLUID_CONTACTS_BINDING_IDS = 15u;          // uint[n], particle order: creation serials
// Bodies the fluid moves (dynamic): their contacts' places in
// BODY_CONTACTS in the CPU's order, the joints' rows, and the particles'
// times still (particle order), which a touch of such a body resets.
SD_CONST uint SD_FLUID_CONTACTS_BINDING_DYNAMIC = 16u;     // uint[bodySlots n]
SD_CONST uint SD_FLUID_CONTACTS_BINDING_JOINT_ROWS = 17u;  // FluidJointRow[]
SD_CONST uint SD_FLUID_CONTACTS_BINDING_STILLS = 18u;      // float[n] (s), particle order
// The listing's prefix sum: each particle's first place in DYNAMIC within
// its workgroup, and each workgroup's first place (its total until GROUPS).
SD_CONST uint SD_FLUID_CONTACTS_BINDING_DYNAMIC_STARTS = 19u;  // uint[n]
SD_CONST uint SD_FLUID_CONTACTS_BINDING_GROUP_STARTS = 20u;    // uint[workgroups]
SD_CONST uint SD_FLUID_CONTACTS_BINDINGS = 21u;

// What the body contacts' find reports (std430, 16 bytes), followed in its
// buffer by the impacts it found.
struct FluidBodyReport {
    uint contacts;      // contacts found, all particles
    uint mostContacts;  // the most one particle found (> bodySlots: the find runs again with more room)
    uint impacts;       // impacts found (> impactRoom: the same)
    uint dynamic;       // contacts with bodies the fluid moves (the GROUPS pass)
};
// A particle's strike on a body shape (the CPU's BodyImpact, and where it
// came from: sorted by place, then shape, it is the CPU's order). 32 bytes.
struct FluidBodyImpact {
    uint place;      // grid-order index of the particle this substep
    uint shape;      // index in the shapes
    uint id;         // the particle's creation serial
    uint body;       // index in the step's body list
    vec2 position;   // m
    float approach;  // m/s along the normal
    uint pad0;
};

// The contact passes' push constants (std430: eight uints or floats, four,
// then the bodies' vec4, ivec4 and four). 96 bytes.
struct FluidContactsPush {
    uint count;           // particles
    uint dimension;
    uint colliders;       // entries of COLLIDERS
    uint polygons;        // entries of POLYGONS
    float radius;         // m, a particle's against the colliders
    float spacing;        // m
    float dt;             // s, of the substep
    float friction;       // mu (FluidDef::friction)
    float tableStart;     // m, distance of the wall table's entry 0
    float tableStep;      // m between entries
    uint tableSize;
    uint split;           // 1: split impulses
    vec4 grid;            // the grid's origin xy (m), 1 / its sub-cell size (1/m), the particle's inverse mass (1/kg)
    ivec4 cells;          // the grid's cells x, y; body shapes; contact slots a particle (bodySlots)
    float impactSpeed;    // m/s (kFluidImpactSpeed)
    uint impactRoom;      // impacts the report's buffer holds
    uint jointRows;       // entries of JOINT_ROWS
    uint pad1;
};

// The constraint fluid's integration on the device (src/gpu/shaders/
// fluid_integrate.comp, src/gpu/gpu_fluid_integrate.cpp): the CPU's
// integratePositions (src/fluid/collide.cpp) without bodies.
SD_CONST uint SD_FLUID_INTEGRATE_PASS_MOVE = 0u;    // the PASS specialization constant (id 0)
SD_CONST uint SD_FLUID_INTEGRATE_PASS_TOTALS = 1u;  // the workgroups' sums added in order (one invocation)
SD_CONST uint SD_FLUID_INTEGRATE_WORKGROUP = 64u;
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_ORDER = 0u;      // uint[n]: grid order -> particle index
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_X = 1u;          // float[dimension n] (m), grid order: in, then out
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_V = 2u;          // float[dimension n] (m/s), grid order: the solve's, then out
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_P = 3u;          // float[n] (m/s): the solve's pressures
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_MOTION = 4u;     // float[2 dimension n]: the solve's pseudo velocities
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_ANCHOR_IN = 5u;  // float[dimension n] (m), particle order
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_STILL_IN = 6u;   // float[n] (s), particle order
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_ANCHOR = 7u;     // float[dimension n], grid order, out
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_STILL = 8u;      // float[n], grid order, out
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_COLLIDERS = 9u;  // ColliderParams[], the contacts'
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_POLYGONS = 10u;  // FluidPolygon[]
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_STATS = 11u;     // FluidIntegrateStats
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_CONSTRAINTS = 12u;  // vec4[n], the setup's: z rho / rho0, w fastest closing (m/s)
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_COUNTS = 13u;    // uint[n], the setup's: neighbours stored
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_PARTIALS = 14u;  // float[workgroups]: each workgroup's compression sum
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_ID_IN = 15u;     // uint[n], particle order: creation serials (carriesIds)
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_ID = 16u;        // uint[n], grid order, out
// Rigid bodies (2D): their shapes at the substep's end poses (pad0 1: its
// body does not move), and each shape's grid cells (the contacts').
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_SHAPES = 17u;      // FluidBodyShape[shapes]
SD_CONST uint SD_FLUID_INTEGRATE_BINDING_SHAPE_CELLS = 18u; // ivec4[shapes]
SD_CONST uint SD_FLUID_INTEGRATE_BINDINGS = 19u;

// The closing-speed histogram's bins (fluid.glsl, fluidApproachBin): m/s wide,
// and how many (the last one open-ended).
SD_CONST float SD_FLUID_APPROACH_BIN = 0.5f;
SD_CONST uint SD_FLUID_APPROACH_BINS = 64u;

// What the integration reports (std430, 320 bytes): the substep's statistics
// and the particles' box, reduced with integer atomics, so in any order the
// same (floats as order-preserving keys, fluidOrderKey); the compression sum
// is added in a fixed order (per workgroup in a tree, then the workgroups in
// order by the TOTALS pass).
struct FluidIntegrateStats {
    uint fastest;      // floatBitsToUint of the largest speed (m/s, >= 0)
    uint pressedLow;   // key (fluidOrderKey) of the least depth along gravity of a particle under pressure
    uint pressedHigh;  // key of the greatest
    uint nonFinite;    // particles whose numbers became NaN or infinite (position set to NaN)
    uint lowX;         // keys of the finite particles' box after the move (m; z 0 in 2D)
    uint lowY;
    uint lowZ;
    uint maxError;     // key of the largest rho / rho0 - 1 at the setup
    uint highX;
    uint highY;
    uint highZ;
    uint neighbours;   // neighbours stored, all particles
    float errorSum;    // sum of max(rho / rho0 - 1, 0) at the setup (TOTALS)
    uint pad0;
    uint pad1;
    uint pad2;
    uint approach[SD_FLUID_APPROACH_BINS];  // particles by fastest closing speed (fluidApproachBin)
};

// The integration's push constants (std430: a vec4, then twelve 4-byte
// values). 64 bytes.
struct FluidIntegratePush {
    vec4 down;          // xyz unit gravity direction (0 without gravity)
    uint count;
    uint dimension;
    uint colliders;
    uint polygons;
    float dt;           // s, of the substep
    float sleepTime;    // s
    float wakeSpeed;    // m/s
    float drift;        // m, the sleep circle's radius (fluidSleepDrift)
    uint split;         // 1: split impulses (the pseudo velocity moves the particle too)
    uint sleeps;        // 1: FluidDef::sleepSpeed > 0
    uint groups;        // workgroups of the MOVE pass (partials the TOTALS pass adds)
    uint carriesIds;    // 1: the creation serials are carried into grid order too
    vec4 grid;          // the grid's origin xy (m), 1 / its sub-cell size (1/m), the shapes' binned reach (m)
    ivec4 cells;        // the grid's cells x, y; body shapes; unused
};


SD_END

#ifdef __cplusplus
#include <cstddef>
namespace spindrift::kernels {
static_assert(sizeof(TableHeader) == 16);
static_assert(sizeof(DeadHeader) == 32);
static_assert(offsetof(DeadHeader, deadCount) == 12);
static_assert(offsetof(DeadHeader, nextSerial) == 20);
static_assert(sizeof(ScheduleHeader) == 32);
static_assert(offsetof(ScheduleHeader, rateSpan) == 16);
static_assert(offsetof(ScheduleHeader, maxAge) == 28);
static_assert(sizeof(StepCounters) == 32 + 4 * SD_MAX_COLLIDERS);
static_assert(offsetof(StepCounters, subBorn) == 16 + 4 * SD_MAX_COLLIDERS);
static_assert(offsetof(StepCounters, hits) == 16);
static_assert(sizeof(EventsHeader) == 16);
static_assert(sizeof(StepPush) == 48);
static_assert(offsetof(StepPush, inherit) == 32);
static_assert(offsetof(StepPush, trailHead) == 20);
static_assert(offsetof(StepPush, emitterIndex) == 8);
static_assert(offsetof(StepPush, time) == 12);
static_assert(sizeof(SortPush) == 48);
static_assert(sizeof(FluidGridPush) == 48);
static_assert(offsetof(FluidGridPush, cells) == 16);
static_assert(offsetof(FluidGridPush, count) == 32);
static_assert(offsetof(FluidGridPush, keyTotal) == 40);
static_assert(sizeof(FluidSetupPush) == 112);
static_assert(offsetof(FluidSetupPush, warmCap) == 96);
static_assert(offsetof(FluidSetupPush, count) == 32);
static_assert(offsetof(FluidSetupPush, h) == 48);
static_assert(offsetof(FluidSetupPush, restDensity) == 64);
static_assert(offsetof(FluidSetupPush, invRest) == 80);
static_assert(sizeof(FluidSetupHeader) == 16);
static_assert(sizeof(FluidSolvePush) == 48);
static_assert(sizeof(FluidContactsPush) == 96);
static_assert(offsetof(FluidContactsPush, grid) == 48);
static_assert(offsetof(FluidContactsPush, impactSpeed) == 80);
static_assert(sizeof(FluidBodyReport) == 16);
static_assert(sizeof(FluidBodyImpact) == 32);
static_assert(sizeof(FluidIntegratePush) == 96);
static_assert(offsetof(FluidIntegratePush, grid) == 64);
static_assert(offsetof(FluidIntegratePush, dt) == 32);
static_assert(offsetof(FluidContactsPush, radius) == 16);
static_assert(offsetof(FluidContactsPush, tableStart) == 32);
static_assert(offsetof(FluidSolvePush, count) == 16);
static_assert(offsetof(FluidSolvePush, warmFraction) == 32);
static_assert(offsetof(SortPush, count) == 32);
// std140: a mat4 is four vec4 columns, every vec4 16-byte aligned.
// The masks are 32 bits wide.
static_assert(SD_MAX_FORCES <= 32u && SD_MAX_COLLIDERS <= 32u);
static_assert(sizeof(FluidIntegrateStats) == 64 + 4 * SD_FLUID_APPROACH_BINS);
static_assert(offsetof(FluidIntegrateStats, errorSum) == 48);
}  // namespace spindrift::kernels
#endif

#endif
