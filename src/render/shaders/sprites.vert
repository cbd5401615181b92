#version 450
// Effect particles as camera-facing quads (GPU particle talk, "Rendering"),
// read straight from the particle buffers: one instance per slot (stored
// emitters) or per candidate serial (stateless emitters, evaluated here from
// their closed form). Colour and size are recomputed with the update's own
// kernels::restoreDerived, so the device stores nothing for drawing.
#include "frame.glsl"
#include "derived.glsl"
#include "stateless.glsl"
#include "sprite_look.glsl"
#include "curves.glsl"
#include "trail.glsl"

layout(std430, set = SD_SPRITE_SET, binding = SD_SPRITE_BINDING_EMITTER) readonly buffer Emitter {
    EmitterParams emitter;
};
// The GPU world's layout (effects_update.comp): float triples, one per slot.
layout(std430, set = SD_SPRITE_SET, binding = SD_SPRITE_BINDING_POSITIONS) readonly buffer Positions {
    float positions[];
};
layout(std430, set = SD_SPRITE_SET, binding = SD_SPRITE_BINDING_VELOCITIES) readonly buffer Velocities {
    float velocities[];
};
layout(std430, set = SD_SPRITE_SET, binding = SD_SPRITE_BINDING_AGES) readonly buffer Ages { float ages[]; };
layout(std430, set = SD_SPRITE_SET, binding = SD_SPRITE_BINDING_BIRTHS) readonly buffer Births { uint births[]; };
layout(std430, set = SD_SPRITE_SET, binding = SD_SPRITE_BINDING_ROTATIONS) readonly buffer Rotations {
    float rotations[];
};
// Draw order: slot of instance i (back to front for alpha blending).
layout(std430, set = SD_SPRITE_SET, binding = SD_SPRITE_BINDING_ORDER) readonly buffer Order { uint order[]; };
// Stateless candidates in runs: x first serial, y instances before this run,
// z age of the first serial (float bits), w birth interval (float bits).
layout(std430, set = SD_SPRITE_SET, binding = SD_SPRITE_BINDING_RUNS) readonly buffer Runs { uvec4 runs[]; };
// Trails (draw.trailPoints > 0): the positions, trail.glsl's ring per slot,
// and their width and colour over the ribbon.
layout(std430, set = SD_SPRITE_SET, binding = SD_SPRITE_BINDING_TRAILS) readonly buffer Trails { float trails[]; };
layout(std430, set = SD_SPRITE_SET, binding = SD_SPRITE_BINDING_TRAIL_LOOK) readonly buffer Look {
    TrailLook trailLook;
};

layout(push_constant) uniform Draw { SpriteDraw draw; };  // SpriteDraw in layout.glsl

layout(location = 0) out vec4 colour;  // linear, premultiplied by alpha
layout(location = 1) out vec2 local;   // quad coordinates, -1..1
layout(location = 2) flat out vec4 cells;     // flipbook: xy this frame's column and row, zw the next frame's
layout(location = 3) flat out float frameMix; // flipbook: share of the next frame

Particle storedParticle(uint slot) {
    Particle p;
    p.position = vec3(positions[3u * slot], positions[3u * slot + 1u], positions[3u * slot + 2u]);
    p.velocity = vec3(velocities[3u * slot], velocities[3u * slot + 1u], velocities[3u * slot + 2u]);
    p.age = ages[slot];
    p.rotation = rotations[slot];
    p.birth = births[slot];
    p.mass = emitter.mass;
    p.alive = p.age >= 0.0 ? 1u : 0u;
    return restoreDerived(emitter, p);
}

Particle statelessParticle(uint instance) {
    uint r = 0u;
    while (r + 1u < draw.runCount && runs[r + 1u].y <= instance) {
        ++r;
    }
    uint j = instance - runs[r].y;
    float age = uintBitsToFloat(runs[r].z) - float(j) * uintBitsToFloat(runs[r].w);
    Particle p = evaluateStatelessParticle(emitter, runs[r].x + j, age);
    if (age < 0.0) {
        p.alive = 0u;
    }
    return p;
}

vec3 trailPoint(uint slot, uint k) {
    uint i = trailPointIndex(slot, k, draw.trailHead, draw.trailPoints);
    return vec3(trails[3u * i], trails[3u * i + 1u], trails[3u * i + 2u]);
}

// Half the ribbon's width across at point k, perpendicular to its direction
// there (from the neighbouring points) and to the view; zero where it has no
// direction (a newborn's points all at its birth) or no width.
vec3 trailEdge(uint slot, uint k, vec3 here) {
    uint last = draw.trailPoints - 1u;
    vec3 along = trailPoint(slot, k == 0u ? 0u : k - 1u) - trailPoint(slot, min(k + 1u, last));
    vec3 view = frame.eye.w > 0.5 ? frame.forward.xyz : here - frame.eye.xyz;
    vec3 across = cross(along, view);
    float acrossLength = length(across);
    float halfWidth = 0.5 * trailLook.width * evaluateCurve(trailLook.widthOverLength, float(k) / float(last)).x;
    return acrossLength > 1e-12 && halfWidth > 0.0 ? across * (halfWidth / acrossLength) : vec3(0.0);
}

// A ribbon thinner than this (half its width, in pixels) is widened to it
// and made fainter by as much: thinner, it fell between pixel centres and
// broke into dashes.
const float kTrailMinHalfPixels = 0.75;

// Half the ribbon's width on screen (pixels) at `at` with edge `edge`; 0
// where the point is behind the camera.
float edgePixels(vec3 at, vec3 edge) {
    vec4 c0 = frame.viewProj * vec4(at, 1.0);
    vec4 c1 = frame.viewProj * vec4(at + edge, 1.0);
    if (c0.w <= 0.0 || c1.w <= 0.0) {
        return 0.0;
    }
    return length((c1.xy / c1.w - c0.xy / c0.w) * 0.5 * vec2(frame.right.w, frame.up.w));
}

// A trail instance: segment v / 6 of the ribbon joins points k and k + 1
// (k = 0 the newest) with two triangles, (k-, k+, (k+1)-) and ((k+1)-, k+,
// (k+1)+), so neighbouring segments share their edges. A triangle that
// would have no area (a segment of zero length, an edge of zero width) is
// culled whole: rasterising one gave NaN fragments on llvmpipe.
void trailVertex(Particle p, uint slot) {
    uint v = uint(gl_VertexIndex);
    uint corner = v % 6u;
    uint k0 = v / 6u;
    vec3 a = trailPoint(slot, k0);
    vec3 b = trailPoint(slot, k0 + 1u);
    vec3 edgeA = trailEdge(slot, k0, a);
    vec3 edgeB = trailEdge(slot, k0 + 1u, b);
    bool firstTriangle = corner < 3u;
    if (a == b || (firstTriangle ? edgeA == vec3(0.0) : edgeB == vec3(0.0))) {
        gl_Position = kCulled;
        return;
    }
    bool atB = corner == 2u || corner == 3u || corner == 5u;
    float side = (corner == 1u || corner == 4u || corner == 5u) ? 1.0 : -1.0;
    vec3 at = atB ? b : a;
    vec3 edge = atB ? edgeB : edgeA;
    float pixels = edgePixels(at, edge);
    float grow = pixels > 0.0 && pixels < kTrailMinHalfPixels ? kTrailMinHalfPixels / pixels : 1.0;
    gl_Position = frame.viewProj * vec4(at + edge * (grow * side), 1.0);
    local = vec2(0.0, side);
    cells = vec4(0.0);
    frameMix = 0.0;
    float t = float(atB ? k0 + 1u : k0) / float(draw.trailPoints - 1u);
    vec4 c = p.color * evaluateCurve(trailLook.colorOverLength, t);
    float alpha = clamp(c.a, 0.0, 1.0);
    colour = vec4(max(c.rgb, vec3(0.0)) * alpha, alpha) / grow;
}

void main() {
    uint instance = uint(gl_InstanceIndex);
    Particle p;
    uint slot = draw.mode == SD_SPRITE_MODE_ORDERED ? order[instance] : instance;
    if (draw.mode == SD_SPRITE_MODE_STATELESS) {
        p = statelessParticle(instance);
    } else {
        p = storedParticle(slot);
    }
    if (p.alive == 0u || (p.size <= 0.0 && draw.trailPoints == 0u)) {
        gl_Position = kCulled;
        return;
    }
    if (draw.trailPoints > 0u) {
        trailVertex(p, slot);
        return;
    }
    vec2 corner = quadCorner(gl_VertexIndex);
    local = corner;
    vec3 frames = flipbookFrames(p.age, p.lifetime, draw.frames, draw.fps, draw.blendFrames);
    uint a = uint(frames.x);
    uint b = uint(frames.y);
    cells = vec4(float(a % draw.columns), float(a / draw.columns), float(b % draw.columns), float(b / draw.columns));
    frameMix = frames.z;
    float half_ = 0.5 * p.size;
    // Axes of the quad in the camera plane: rotated by the particle's rotation,
    // or along its screen-space velocity when stretched.
    vec3 axisA = frame.right.xyz;
    vec3 axisB = frame.up.xyz;
    float lengthA = half_;
    vec2 screenVelocity = vec2(dot(p.velocity, frame.right.xyz), dot(p.velocity, frame.up.xyz));
    float speed = length(screenVelocity);
    if (draw.stretch > 0.0 && speed > 1e-6) {
        vec2 d = screenVelocity / speed;
        axisA = d.x * frame.right.xyz + d.y * frame.up.xyz;
        axisB = -d.y * frame.right.xyz + d.x * frame.up.xyz;
        lengthA = half_ + 0.5 * speed * draw.stretch;
    } else {
        float c = cos(p.rotation);
        float s = sin(p.rotation);
        axisA = c * frame.right.xyz + s * frame.up.xyz;
        axisB = -s * frame.right.xyz + c * frame.up.xyz;
    }
    vec3 world = p.position + axisA * (corner.x * lengthA) + axisB * (corner.y * half_);
    gl_Position = frame.viewProj * vec4(world, 1.0);
    float alpha = clamp(p.color.a, 0.0, 1.0);
    colour = vec4(max(p.color.rgb, vec3(0.0)) * alpha, alpha);
}
