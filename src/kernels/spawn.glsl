// Birth: the start state of a particle from its emitter and its key. Every
// random number is drawn from the key by a fixed stream index, so start values
// can be recomputed at any time (the update re-derives the start colour and
// size instead of storing them).
#ifndef SPINDRIFT_KERNELS_SPAWN
#define SPINDRIFT_KERNELS_SPAWN
#include "math.glsl"
#include "random.glsl"
#include "types.glsl"
SD_BEGIN

// Stream indices of the per-particle random numbers.
SD_CONST uint SD_RAND_POS0 = 0u;
SD_CONST uint SD_RAND_POS1 = 1u;
SD_CONST uint SD_RAND_POS2 = 2u;
SD_CONST uint SD_RAND_POS3 = 3u;
SD_CONST uint SD_RAND_DIR0 = 4u;
SD_CONST uint SD_RAND_DIR1 = 5u;
SD_CONST uint SD_RAND_SPEED = 6u;
SD_CONST uint SD_RAND_LIFETIME = 7u;
SD_CONST uint SD_RAND_SIZE = 8u;
SD_CONST uint SD_RAND_ROTATION = 9u;
SD_CONST uint SD_RAND_SPIN = 10u;
SD_CONST uint SD_RAND_COLOR = 11u;

// A particle as the kernels see it: position (m), velocity (m/s), age and
// lifetime (s), diameter (m), rotation (rad), angular velocity (rad/s), mass (kg),
// colour (linear RGBA) and birth serial. alive is 0 or 1.
struct Particle {
    vec3 position;
    vec3 velocity;
    vec4 color;
    float age;
    float lifetime;
    float size;
    float rotation;
    float angularVelocity;
    float mass;
    uint birth;
    uint alive;
};

// Orthonormal basis around unit n, without branches on the sign's magnitude
// (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017).
SD_FN vec3 basisTangent(vec3 n) {
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float b = n.x * n.y * a;
    return vec3(1.0f + s * n.x * n.x * a, s * b, -s * n.x);
}
SD_FN vec3 basisBitangent(vec3 n) {
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float b = n.x * n.y * a;
    return vec3(b, s + n.y * n.y * a, -n.y);
}

// Uniform direction on the spherical cap of half-angle `angle` around unit `axis`.
SD_FN vec3 directionInCone(vec3 axis, float angle, float u0, float u1) {
    float cosTheta = mix(1.0f, sdCos(angle), u0);
    float sinTheta = sqrt(max(0.0f, 1.0f - cosTheta * cosTheta));
    vec2 around = sdSinCos(2.0f * SD_PI * u1);
    return basisTangent(axis) * (around.y * sinTheta) + basisBitangent(axis) * (around.x * sinTheta) +
           axis * cosTheta;
}

// Uniform point in (or on) a sphere of radius r around the origin.
SD_FN vec3 pointInSphere(float r, bool surface, float u0, float u1, float u2) {
    float z = 1.0f - 2.0f * u0;
    float ring = sqrt(max(0.0f, 1.0f - z * z));
    vec2 around = sdSinCos(2.0f * SD_PI * u1);
    float radius = surface ? r : r * sdPow(u2, 1.0f / 3.0f);
    return vec3(ring * around.y, ring * around.x, z) * radius;
}

// Uniform point in a box, or on its surface with faces chosen by area.
SD_FN vec3 pointInBox(vec3 h, bool surface, float u0, float u1, float u2, float u3) {
    vec3 p = (vec3(u0, u1, u2) * 2.0f - 1.0f) * h;
    if (!surface) {
        return p;
    }
    float areaX = h.y * h.z;
    float areaY = h.x * h.z;
    float areaZ = h.x * h.y;
    float pick = u3 * (areaX + areaY + areaZ);
    // Reuse u3's position inside its interval as the sign: still uniform.
    if (pick < areaX) {
        return vec3(pick < 0.5f * areaX ? -h.x : h.x, p.y, p.z);
    }
    if (pick < areaX + areaY) {
        return vec3(p.x, pick - areaX < 0.5f * areaY ? -h.y : h.y, p.z);
    }
    return vec3(p.x, p.y, pick - areaX - areaY < 0.5f * areaZ ? -h.z : h.z);
}

// Start colour and size are pure functions of the key (see file comment).
SD_FN vec4 startColor(SD_IN(EmitterParams) e, uint key) {
    return mix(e.colorMin, e.colorMax, randomUnit(key, SD_RAND_COLOR));
}
SD_FN float startSize(SD_IN(EmitterParams) e, uint key) {
    return randomRange(key, SD_RAND_SIZE, e.sizeMin, e.sizeMax);
}

SD_FN Particle spawnParticle(SD_IN(EmitterParams) e, uint serial) {
    uint key = particleKey(e.keyBase, serial);
    float u0 = randomUnit(key, SD_RAND_POS0);
    float u1 = randomUnit(key, SD_RAND_POS1);
    float u2 = randomUnit(key, SD_RAND_POS2);
    float u3 = randomUnit(key, SD_RAND_POS3);
    vec3 axis = vec3(e.shapeDirection);
    float spread = e.shapeHalfExtents.w;
    bool surface = (e.flags & SD_EMITTER_SHAPE_SURFACE) != 0u;
    vec3 offset = vec3(0.0f);
    vec3 direction = directionInCone(axis, spread, randomUnit(key, SD_RAND_DIR0), randomUnit(key, SD_RAND_DIR1));
    if (e.shapeKind == SD_SHAPE_SPHERE) {
        offset = pointInSphere(e.shapeCenter.w, surface, u0, u1, u2);
    } else if (e.shapeKind == SD_SHAPE_BOX) {
        offset = pointInBox(vec3(e.shapeHalfExtents), surface, u0, u1, u2, u3);
    } else if (e.shapeKind == SD_SHAPE_DISK || e.shapeKind == SD_SHAPE_CONE) {
        float r = e.shapeCenter.w * sqrt(u0);
        vec2 around = sdSinCos(2.0f * SD_PI * u1);
        vec3 radial = basisTangent(axis) * around.y + basisBitangent(axis) * around.x;
        offset = radial * r;
        if (e.shapeKind == SD_SHAPE_CONE) {
            // A diverging cone: the launch angle grows with the distance from
            // the axis, reaching the spread angle at the rim (walls of the cone).
            float angle = e.shapeCenter.w > 0.0f ? spread * (r / e.shapeCenter.w) : 0.0f;
            vec2 launch = sdSinCos(angle);
            direction = axis * launch.y + radial * launch.x;
        }
    }
    Particle p;
    p.position = vec3(e.shapeCenter) + offset;
    p.velocity = direction * randomRange(key, SD_RAND_SPEED, e.speedMin, e.speedMax) +
                 vec3(e.carriedVelocityX, e.carriedVelocityY, 0.0f);
    p.color = startColor(e, key);
    p.age = 0.0f;
    p.lifetime = randomRange(key, SD_RAND_LIFETIME, e.lifetimeMin, e.lifetimeMax);
    p.size = startSize(e, key);
    p.rotation = randomRange(key, SD_RAND_ROTATION, e.rotationMin, e.rotationMax);
    p.angularVelocity = randomRange(key, SD_RAND_SPIN, e.angularVelocityMin, e.angularVelocityMax);
    p.mass = e.mass;
    p.birth = serial;
    p.alive = 1u;
    return p;
}

SD_END
#endif
