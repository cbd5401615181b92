// The constraint fluid's contacts with static colliders on the device (issue
// 16, fourth slice): the CPU's findContacts and solveContacts
// (src/fluid/collide.cpp) on the particles of the device setup
// (gpu_fluid_setup.h), src/gpu/shaders/fluid_contacts.comp. The find pass
// writes the colliders' share of the density, which the setup reads (its
// `wall` input); the solve pass runs between the solve's sweeps
// (recordFluidSolve). On a device that rounds to nearest both are the CPU's
// bit for bit.
//
// Rigid bodies (2D) are found in the same passes, from shapes the host
// places each substep (setFluidBodies). A contact with a body the fluid does
// not move (static, kinematic) changes only its particle and is solved with
// the particle's colliders; one with a body it moves (dynamic) changes the
// body too, so they are listed in the CPU's order after the find (a prefix
// sum of each particle's count) and solved in it by one invocation, then the
// joints' rows, after every per-particle solve (the CPU's solveBodyContacts).
#pragma once

#include "gpu/gpu_fluid_setup.h"
#include "gpu/vulkan_buffer.h"
#include "gpu/vulkan_pipeline.h"
#include "kernels/fluid.glsl"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace spindrift::gpu {

/// What a fluid's contacts see, uploaded by setFluidSurfaces.
struct FluidSurfaces {
    /// The world's fluid colliders (planes, spheres, boxes) in creation order.
    std::span<const kernels::ColliderParams> colliders;
    std::span<const kernels::FluidPolygon> polygons;
    /// The colliders' share by distance (fluid::WallTable): density, push.
    std::span<const glm::vec2> wallTable;
    float tableStart = 0.0f;  // m, distance of entry 0
    float tableStep = 1.0f;   // m between entries
};

/// The rigid bodies near a 2D fluid this substep, as the CPU's
/// fluid::FluidBodyStep holds them.
struct FluidBodies {
    std::span<const kernels::FluidBodyShape> shapes;       // at the substep's start poses
    /// At its end poses; pad0 1: the body does not move. Empty when a body
    /// the fluid moves is among them (then the solve decides the end poses:
    /// setFluidBodyShapesAtEnd after it).
    std::span<const kernels::FluidBodyShape> shapesAtEnd;
    std::span<const kernels::FluidJointRow> jointRows;     // at the start poses
    bool moves = false;  // a body the fluid moves (dynamic) is among them
    std::span<const glm::ivec4> shapeCells;                // each shape's grid cells: first x, y, last x, y
    std::span<const kernels::FluidBodyMotion> bodies;
    glm::vec2 gridOrigin{0.0f};  // m, the substep's grid (FluidGridParams)
    float gridInvH = 1.0f;       // 1/m
    glm::ivec2 cells{1, 1};
    float particleInvMass = 0.0f;  // 1/kg
    float binnedReach = 0.0f;      // m: every shape this near a particle is in its cell's list
    float impactSpeed = 0.0f;      // m/s: a faster approach is an impact (kFluidImpactSpeed)
};

/// What the body contacts' find reported, and its impacts (unordered).
struct FluidBodyReadback {
    kernels::FluidBodyReport report{};
    std::vector<kernels::FluidBodyImpact> impacts;
};

/// A contact pass's constants, as fluid::FluidState holds them.
struct FluidContactParams {
    float radius = 0.0f;   // m, FluidState::radius
    float spacing = 0.0f;  // m
    float dt = 0.0f;       // s, of the substep
    float friction = 0.0f; // FluidDef::friction
    bool split = true;     // FluidDef::splitImpulse
};

/// Pipelines, surfaces and masks of the contacts, for one Device.
struct GpuFluidContacts {
    Device* device = nullptr;
    /// fluid_contacts.comp's passes (find, solve); sets[0] the find pass's,
    /// sets[1] the solve pass's (written when the solve is recorded, once its
    /// working velocities exist).
    ComputePasses passes;
    Buffer colliders, polygons, wallTable;
    Buffer masks;  // uint per particle: the surfaces within reach
    std::uint32_t colliderCount = 0, polygonCount = 0, tableSize = 0;
    // The bodies (FluidBodies), and each particle's contacts with them.
    Buffer shapes, shapesAtEnd, shapeCells, bodies;
    Buffer bodyContacts;  // FluidBodyContact[bodySlots capacity]
    Buffer bodyCounts;    // uint[capacity]
    Buffer bodyReport;    // FluidBodyReport, FluidBodyImpact[impactRoom]
    Buffer dynamicList;   // uint[bodySlots capacity]: the dynamic contacts in order
    Buffer dynamicStarts; // uint[capacity], groupStarts uint[workgroups]: the
    Buffer groupStarts;   //   listing's prefix sum (fluid_contacts.comp)
    Buffer jointRows;     // FluidJointRow[]
    std::uint32_t shapeCount = 0;
    std::uint32_t jointRowCount = 0;
    std::uint32_t bodyCount = 0;
    bool moves = false;
    std::uint32_t bodySlots = 4;    // contacts a particle holds
    std::uint32_t impactRoom = 256;
    std::uint32_t bodyCapacity = 0;  // particles bodyContacts and bodyCounts hold
    glm::vec4 grid{0.0f};            // origin xy, invH, the particle's inverse mass
    glm::ivec2 cells{1, 1};
    float binnedReach = 0.0f;
    float impactSpeed = 0.0f;
    float tableStart = 0.0f, tableStep = 1.0f;
    std::uint32_t capacity = 0;  // particles `masks` holds
    // Of the last recorded find.
    std::uint32_t count = 0;
    std::uint32_t dimension = 2;
    FluidContactParams params;
    const Buffer* boundX = nullptr;     // the find's positions (the setup's, grid order)
    const Buffer* boundV = nullptr;
    const Buffer* boundWall = nullptr;
    const Buffer* boundOrder = nullptr;  // grid order -> particle index
    const Buffer* boundIds = nullptr;    // particle order: serials
    const Buffer* boundStills = nullptr;  // particle order: times still

    GpuFluidContacts() = default;
    GpuFluidContacts(const GpuFluidContacts&) = delete;
    GpuFluidContacts& operator=(const GpuFluidContacts&) = delete;
    ~GpuFluidContacts();
};

/// Creates the two pipelines.
std::unique_ptr<GpuFluidContacts> createGpuFluidContacts(Device& d);

/// Uploads the surfaces (between submissions). Throws Error for more than
/// SD_FLUID_MAX_SURFACES colliders and polygons together, or a table of
/// fewer than two entries.
void setFluidSurfaces(GpuFluidContacts& c, const FluidSurfaces& surfaces);

/// Uploads the bodies of this substep (between submissions), or none (an
/// empty FluidBodies).
void setFluidBodies(GpuFluidContacts& c, const FluidBodies& bodies);

/// The shapes at the substep's end poses, after a solve that moved bodies
/// (the host advanced its copies from the bodies read back with the report).
void setFluidBodyShapesAtEnd(GpuFluidContacts& c, std::span<const kernels::FluidBodyShape> shapes);

/// Room for `slots` body contacts a particle and `impacts` impacts a
/// substep (after a find that reported more; the substep runs again).
void reserveFluidBodyRoom(GpuFluidContacts& c, std::uint32_t slots, std::uint32_t impacts);

/// Records the find pass for the particles of `setup`'s last gather (its
/// grid-order positions and velocities) into `cmd`: writes `wall` (vec4 per
/// particle: the colliders' density, xyz their g sum), the setup's input,
/// and the body contacts and impacts (naming a particle by its serial in
/// `ids`, particle order, through `order`, grid order to particle index;
/// a touch of a body the fluid moves resets the particle's time still in
/// `stills`, particle order; all three needed only with bodies). Waits for earlier compute writes; its
/// results are visible to later compute passes. Throws Error for a `wall`
/// buffer too small, or bodies without `order` and `ids`.
void recordFluidContactsFind(VkCommandBuffer cmd, GpuFluidContacts& c, const GpuFluidSetup& setup, Buffer& wall,
                             const FluidContactParams& params, const Buffer* order = nullptr,
                             const Buffer* ids = nullptr, Buffer* stills = nullptr);

/// The last find's body report and impacts (two transfers when there are
/// impacts, one otherwise), and `alongside` in the report's transfer (the
/// bodies after a solve that moved them, `c.bodies`, say): waits for the
/// device.
FluidBodyReadback readFluidBodyReport(GpuFluidContacts& c, std::span<const Transfer> alongside = {});

/// The last find's contacts with bodies as the listing read them, and the
/// list it wrote (tests: the list is a prefix sum on the device, the CPU's
/// order by definition): every particle's contact count (may exceed
/// `slots`), its `slots` contacts, the bodies, and the list's entries
/// (indices into `contacts`). Waits for the device.
struct FluidDynamicListing {
    std::uint32_t slots = 0;
    std::vector<std::uint32_t> counts;
    std::vector<kernels::FluidBodyContact> contacts;
    std::vector<kernels::FluidBodyMotion> bodies;
    std::vector<std::uint32_t> list;
};
FluidDynamicListing readFluidDynamicListing(GpuFluidContacts& c);

/// Records the solve pass on `motion` (the solve's working velocities, 2 x
/// dimension floats a particle) of the last recorded find. The first call
/// after a find writes the solve's descriptor set, so `motion` must be the
/// same buffer for every call until the next find.
void recordFluidContactsSolve(VkCommandBuffer cmd, GpuFluidContacts& c, const Buffer& motion, bool firstAfterFind);

}  // namespace spindrift::gpu
