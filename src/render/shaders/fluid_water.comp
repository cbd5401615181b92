#version 450
// A device fluid's liquid from its own buffers (issue 16; see
// src/render/device_water.h): one invocation a particle writes its kernel
// (2D surface), sphere (3D screen-space liquid) or splat (Sprinkle's steps,
// its shown orientation kept here by serial) into the splat instances, then
// its mirror image behind each wall plane (a radius-0 instance where it has
// none), and appends itself to the splash list when it throws one this
// frame. The rules are fluid_look.glsl's, which the host's instances use.
#include "fluid.glsl"
#include "fluid_look.glsl"

layout(local_size_x = SD_FLUID_WATER_WORKGROUP) in;

layout(std430, set = 0, binding = SD_FLUID_WATER_BINDING_X) readonly buffer X { float xs[]; };
layout(std430, set = 0, binding = SD_FLUID_WATER_BINDING_V) readonly buffer V { float vs[]; };
layout(std430, set = 0, binding = SD_FLUID_WATER_BINDING_DENSITY) readonly buffer Density { vec4 constraints[]; };
layout(std430, set = 0, binding = SD_FLUID_WATER_BINDING_IDS) readonly buffer Ids { uint ids[]; };
layout(std430, set = 0, binding = SD_FLUID_WATER_BINDING_INSTANCES) writeonly buffer Instances {
    SplatInstance instances[];
};
layout(std430, set = 0, binding = SD_FLUID_WATER_BINDING_PLANES) readonly buffer Planes { vec4 planes[]; };
layout(std430, set = 0, binding = SD_FLUID_WATER_BINDING_SPLASHES) buffer Splashes {
    uint thrown;  // throwers found (may exceed SD_FLUID_SPLASH_ROOM: then only the count is kept)
    uint pad0, pad1, pad2;
    FluidSplashThrower throwers[];
};

layout(std430, set = 0, binding = SD_FLUID_WATER_BINDING_COUNTS) readonly buffer Counts { uint counts[]; };
layout(std430, set = 0, binding = SD_FLUID_WATER_BINDING_FIRST) readonly buffer First { uint firsts[]; };
layout(std430, set = 0, binding = SD_FLUID_WATER_BINDING_LIST) readonly buffer List { uint listIndex[]; };
layout(std430, set = 0, binding = SD_FLUID_WATER_BINDING_SHOWN) buffer Shown { vec4 shown[]; };

layout(push_constant) uniform Push { FluidWaterPush args; };

vec3 loadVector(uint i, bool velocity) {
    uint d = args.dimension;
    vec3 r = vec3(0.0f);
    if (velocity) {
        r.x = vs[i * d];
        r.y = vs[i * d + 1u];
        if (d == 3u) r.z = vs[i * d + 2u];
    } else {
        r.x = xs[i * d];
        r.y = xs[i * d + 1u];
        if (d == 3u) r.z = xs[i * d + 2u];
    }
    return r;
}

// The average neighbour direction over particle i's list, each entry's g
// computed from the positions now as the solve computes it
// (fluid_solve.comp, pairG).
vec3 averageDirection(uint i, vec3 xi) {
    vec3 sumG = vec3(0.0f);
    float weights = 0.0f;
    if (args.lists == 0u) return sumG;
    uint begin = firsts[i];
    for (uint k = 0u; k < counts[i]; ++k) {
        uint j = listIndex[begin + k];
        precise vec3 offset = loadVector(j, false) - xi;
        precise float r2x = offset.x * offset.x;
        precise float r2y = offset.y * offset.y;
        precise float r2 = r2x + r2y;
        if (args.dimension == 3u) {
            precise float r2z = offset.z * offset.z;
            r2 = r2 + r2z;
        }
        vec3 g = fluidPairG(offset, r2, i, j, args.invH2);
        sumG += g;
        weights += length(g);
    }
    return splatAverageDirection(sumG, weights);
}

// Sprinkle's splat of particle i, its shown orientation read and kept by
// serial.
SplatInstance splatOf(uint i, vec3 x, vec3 v, float density) {
    uint id = ids[i];
    vec3 d = args.steps.stretch != 0u || args.steps.edges != 0u ? averageDirection(i, x) : vec3(0.0f);
    vec4 was = args.steps.stretch != 0u ? shown[id] : vec4(0.0f);
    WaterSplat s = splatOfParticle(x, v, density, id, d, was, args.steps);
    if (args.steps.stretch != 0u) shown[id] = s.shown;
    return s.instance;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= args.count) return;
    vec3 x = loadVector(i, false);
    vec3 v = loadVector(i, true);
    float density = args.densities != 0u ? constraints[i].z : 1.0f;
    SplatInstance s;
    if (args.style == SD_FLUID_WATER_SPLATS) {
        s = splatOf(i, x, v, density);
    } else if (args.style == SD_FLUID_WATER_SCREEN) {
        s = screenSphere(x, v, density, args.radius);
    } else {
        s = surfaceKernel(x, v, density, args.radius, args.stretch);
    }
    instances[args.first + i] = s;
    for (uint p = 0u; p < args.planes; ++p) {
        vec3 point = planes[2u * p].xyz;
        vec3 normal = planes[2u * p + 1u].xyz;
        SplatInstance m = mirrorKernel(s, point, normal);
        if (mirroredByPlane(x, point, normal, args.radius) == 0u) {
            m.centre = vec4(x, 0.0f);  // radius 0: no pixels
            m.shade.x = 0.0f;
        }
        instances[args.first + (p + 1u) * args.count + i] = m;
    }
    if (args.splashes != 0u && throwsSplash(density, v, args.up.xyz, ids[i], args.frame, args.up.w) != 0u) {
        uint slot = atomicAdd(thrown, 1u);
        if (slot < SD_FLUID_SPLASH_ROOM) {
            FluidSplashThrower t;
            t.position = vec4(x, 0.0f);
            t.velocity = vec4(v, 0.0f);
            t.index = i;
            t.id = ids[i];
            t.pad0 = 0u;
            t.pad1 = 0u;
            throwers[slot] = t;
        }
    }
}
