// The device carry's layout (src/gpu/shaders/fluid_carry.comp,
// src/gpu/gpu_fluid_carry.cpp), apart from layout.glsl: only the carry reads
// it. (In layout.glsl these lines made Debian 12's glslc run for
// minutes on fluid_integrate.comp, which includes layout.glsl, and be
// killed; apart they compile in a fraction of a second.)
#ifndef SPINDRIFT_KERNELS_CARRY_LAYOUT
#define SPINDRIFT_KERNELS_CARRY_LAYOUT

#include "prelude.glsl"

SD_BEGIN
// The carry after Box2D's step on the device (src/gpu/shaders/
// fluid_carry.comp, src/gpu/gpu_fluid_carry.cpp): the CPU's
// carryOutOfMovedBodies (src/fluid/body_contacts.cpp). A particle inside a
// shape of a body the fluid moves goes with the body from where the fluid's
// copy ended to where Box2D put it, then out through the nearest surface,
// never through a still edge or a collider.
SD_CONST uint SD_FLUID_CARRY_WORKGROUP = 64u;
SD_CONST uint SD_FLUID_CARRY_BINDING_X = 0u;          // float[2 n] (m), particle order: in and out
SD_CONST uint SD_FLUID_CARRY_BINDING_SHAPES = 1u;     // FluidBodyShape[shapes] at Box2D's poses; pad0 1: its body is still
SD_CONST uint SD_FLUID_CARRY_BINDING_BOXES = 2u;      // vec4[shapes]: each shape's bounds lo.xy, hi.xy (m)
SD_CONST uint SD_FLUID_CARRY_BINDING_BODIES = 3u;     // FluidBodyCarry[]
SD_CONST uint SD_FLUID_CARRY_BINDING_COLLIDERS = 4u;  // ColliderParams[], the fluid's (the contacts')
SD_CONST uint SD_FLUID_CARRY_BINDING_POLYGONS = 5u;   // FluidPolygon[]
SD_CONST uint SD_FLUID_CARRY_BINDING_BOX = 6u;        // uint[6]: keys (fluidOrderKey) of the particles' box after it
SD_CONST uint SD_FLUID_CARRY_BINDINGS = 7u;

// A body's move between the end of the fluid's step and Box2D's (32
// bytes): centres of mass then and now (m), the turn's cosine and sine.
struct FluidBodyCarry {
    vec2 then;
    vec2 now;
    float cosTurn;
    float sinTurn;
    uint moving;  // 1: a body the fluid moves (only its shapes carry)
    uint pad0;
};

// The carry's push constants. 16 bytes.
struct FluidCarryPush {
    uint count;
    uint shapes;
    uint colliders;
    uint polygons;
};

SD_END

#ifdef __cplusplus
namespace spindrift::kernels {
static_assert(sizeof(FluidBodyCarry) == 32);
static_assert(sizeof(FluidCarryPush) == 16);
}  // namespace spindrift::kernels
#endif

#endif
