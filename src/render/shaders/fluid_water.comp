#version 450
// A device fluid's liquid from its own buffers (issue 16; see
// src/render/device_water.h): one invocation a particle writes its kernel
// (2D surface) or sphere (3D screen-space liquid) into the splat instances,
// then its mirror image behind each wall plane (a radius-0 instance where it
// has none), and appends itself to the splash list when it throws one this
// frame. The rules are fluid_look.glsl's, which the host's instances use.
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

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= args.count) return;
    vec3 x = loadVector(i, false);
    vec3 v = loadVector(i, true);
    float density = args.densities != 0u ? constraints[i].z : 1.0f;
    SplatInstance s = args.style == SD_FLUID_WATER_SCREEN ? screenSphere(x, v, density, args.radius)
                                                          : surfaceKernel(x, v, density, args.radius, args.stretch);
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
