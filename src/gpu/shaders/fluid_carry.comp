#version 450
// The carry after Box2D's step on the device (the CPU's carryOutOfMovedBodies
// in src/fluid/body_contacts.cpp): Box2D moved the bodies on from where the
// fluid's copies ended its step, so a particle inside a shape of a body the
// fluid moves goes with the body, then out through the nearest surface if
// still inside; neither move may cross a still body's edge or a collider (a
// particle wedged between a crate and a wall stays in the crate, and the
// contacts push it out once there is room). One invocation a particle; the
// particles' box after it is reduced with integer atomics (it places the
// next grid and gathers the next step's bodies).
#include "types.glsl"
// collide.glsl's terrain and cube-map colliders read their maps through the
// backend's context (context_hooks.glsl); they are not fluid colliders, so
// this shader's context has none.
struct KernelContext {
    uint none;
};
float sampleTerrainHeight(KernelContext ctx, uint map, vec2 uv) { return 0.0f; }
vec4 sampleCubeMap(KernelContext ctx, uint map, vec3 direction) { return vec4(0.0f, 1.0f, 0.0f, 3.0e38f); }
#include "collide.glsl"
#include "fluid.glsl"
#include "layout.glsl"
#include "carry_layout.glsl"

layout(local_size_x = SD_FLUID_CARRY_WORKGROUP) in;

layout(std430, set = 0, binding = SD_FLUID_CARRY_BINDING_X) buffer X { float xs[]; };
layout(std430, set = 0, binding = SD_FLUID_CARRY_BINDING_SHAPES) readonly buffer Shapes { FluidBodyShape shapes[]; };
layout(std430, set = 0, binding = SD_FLUID_CARRY_BINDING_BOXES) readonly buffer Boxes { vec4 boxes[]; };
layout(std430, set = 0, binding = SD_FLUID_CARRY_BINDING_BODIES) readonly buffer Bodies { FluidBodyCarry bodies[]; };
layout(std430, set = 0, binding = SD_FLUID_CARRY_BINDING_COLLIDERS) readonly buffer Colliders { ColliderParams colliders[]; };
layout(std430, set = 0, binding = SD_FLUID_CARRY_BINDING_POLYGONS) readonly buffer Polygons { FluidPolygon polygons[]; };
layout(std430, set = 0, binding = SD_FLUID_CARRY_BINDING_BOX) buffer Box { uint box[6]; };

layout(push_constant) uniform Carry { FluidCarryPush args; };  // FluidCarryPush in layout.glsl

shared uint groupBox[6];

// The path from -> to stopped before the edges of every still shape it
// crosses (the CPU's stopBeforeStillEdges with no cell lists).
vec2 stopBeforeStillEdges(vec2 from, vec2 to) {
    FluidPathEnd end;
    end.x1 = to;
    end.v = vec2(0.0f);
    for (int pass = 0; pass < 3; ++pass) {
        bool crossed = false;
        for (uint k = 0u; k < args.shapes; ++k) {
            if (shapes[k].pad0 == 0u) continue;
            FluidPathEnd edge = fluidStopBeforeShapeEdges(shapes[k], from, end.x1, end.v);
            end.x1 = edge.x1;
            end.v = edge.v;
            crossed = crossed || edge.stopped != 0u;
        }
        if (!crossed) break;
    }
    return end.x1;
}

// Whether a path x0 -> x1 crosses a collider or ends inside a polygon (the
// CPU's crossesCollider).
bool crossesCollider(vec2 x0, vec2 x1) {
    for (uint k = 0u; k < args.colliders; ++k) {
        KernelContext none;
        none.none = 0u;
        if (intersectCollider(none, colliders[k], vec3(x0.x, x0.y, 0.0f), vec3(x1.x, x1.y, 0.0f)).hit != 0u) return true;
    }
    for (uint k = 0u; k < args.polygons; ++k) {
        if (fluidPolygonSurface(polygons[k], vec3(x1.x, x1.y, 0.0f)).distance < 0.0f) return true;
    }
    return false;
}

// Whether moving a particle from x0 to x1 would pass through a wall.
bool blocked(vec2 x0, vec2 x1) {
    if (x0 == x1) return false;
    return stopBeforeStillEdges(x0, x1) != x1 || crossesCollider(x0, x1);
}

vec2 carried(vec2 x) {
    for (uint k = 0u; k < args.shapes; ++k) {
        FluidBodyShape shape = shapes[k];
        FluidBodyCarry body = bodies[shape.body];
        if (body.moving == 0u) continue;
        vec4 b = boxes[k];
        if (x.x < b.x || x.y < b.y || x.x > b.z || x.y > b.w ||
            fluidBodyShapeSurface(shape, vec3(x.x, x.y, 0.0f)).distance >= 0.0f) {
            continue;
        }
        precise vec2 d = x - body.then;
        precise float turnedX = body.cosTurn * d.x - body.sinTurn * d.y;
        precise float turnedY = body.sinTurn * d.x + body.cosTurn * d.y;
        precise vec2 to = body.now + vec2(turnedX, turnedY);
        if (blocked(x, to)) return x;
        vec2 pushed = fluidPushOutOfShape(shape, to);  // `to` when outside
        if (pushed != to && !blocked(to, pushed)) to = pushed;
        return to;
    }
    return x;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint local = gl_LocalInvocationID.x;
    if (local == 0u) {
        groupBox[0] = 0xFFFFFFFFu;
        groupBox[1] = 0xFFFFFFFFu;
        groupBox[2] = 0u;
        groupBox[3] = 0u;
    }
    barrier();
    if (i < args.count) {
        vec2 x = carried(vec2(xs[2u * i], xs[2u * i + 1u]));
        xs[2u * i] = x.x;
        xs[2u * i + 1u] = x.y;
        if (fluidFinite(vec3(x.x, x.y, 0.0f))) {
            atomicMin(groupBox[0], fluidOrderKey(x.x));
            atomicMin(groupBox[1], fluidOrderKey(x.y));
            atomicMax(groupBox[2], fluidOrderKey(x.x));
            atomicMax(groupBox[3], fluidOrderKey(x.y));
        }
    }
    barrier();
    if (local == 0u) {
        atomicMin(box[0], groupBox[0]);
        atomicMin(box[1], groupBox[1]);
        atomicMax(box[3], groupBox[2]);
        atomicMax(box[4], groupBox[3]);
    }
}
