// Collisions (GPU particle talk after Sims 1990): the velocity is split against
// the collider normal n into vn = (v.n) n and vt = v - vn, and becomes
// (1 - mu) vt - e vn; friction is skipped below a rest speed so slow particles
// are not dragged to a creep. A particle whose path crossed the collider during
// the step is put back at the contact point found from its start and end
// signed distances, so nothing tunnels however fast it moves.
// Requires the hooks of context_hooks.glsl.
#ifndef SPINDRIFT_KERNELS_COLLIDE
#define SPINDRIFT_KERNELS_COLLIDE
#include "types.glsl"
SD_BEGIN

// Contact points are lifted this far (m) off the surface so the next step
// starts strictly outside despite rounding.
SD_CONST float SD_COLLISION_SKIN = 1e-4f;
// At most this many samples when marching a path through a sampled collider.
SD_CONST float SD_MAX_MARCH_SAMPLES = 64.0f;
// Bisections of a bracketed contact: 2^-10 of a march step.
SD_CONST uint SD_CONTACT_BISECTIONS = 10u;

struct Hit {
    vec3 point;   // contact point (m)
    vec3 normal;  // unit, pointing out of the collider
    float t;      // fraction of the step's path at the contact
    uint hit;     // 0 or 1
};

SD_FN Hit noHit() {
    Hit h;
    h.point = vec3(0.0f);
    h.normal = vec3(0.0f, 1.0f, 0.0f);
    h.t = 1.0f;
    h.hit = 0u;
    return h;
}

SD_FN Hit makeHit(vec3 point, vec3 normal, float t) {
    Hit h;
    h.point = point;
    h.normal = normal;
    h.t = t;
    h.hit = 1u;
    return h;
}

// The contact on the segment p0 -> p1 from signed distances d0 >= 0 > d1
// (the talk's frontbackRatio = |d0| / (|d0| + |d1|)).
SD_FN float contactFraction(float d0, float d1) {
    return clamp(d0 / (d0 - d1), 0.0f, 1.0f);
}

// --- Plane: signed distance dot(p - point, n) --------------------------------
SD_FN float planeDistance(SD_IN(ColliderParams) c, vec3 p) {
    return dot(p - vec3(c.position), vec3(c.normal));
}

// Whether a path whose end point lies at signed distance d1 from a plane
// stays clear of it: the end on or above the plane. Not `d1 < 0`: a NaN
// distance hits, as it always has. Scalar callers test it first and skip
// intersectPlane's work.
SD_FN bool planeKeepsClear(float d1) {
    return d1 >= 0.0f;
}

// No hit when planeKeepsClear (the end point on or above the plane). Selects, not
// branches, so the CPU's lane loops vectorise: every case is computed and the
// discarded ones may divide by 0, which is harmless.
SD_FN Hit intersectPlane(SD_IN(ColliderParams) c, vec3 p0, vec3 p1) {
    vec3 n = vec3(c.normal);
    float d0 = planeDistance(c, p0);
    float d1 = planeDistance(c, p1);
    float t = contactFraction(d0, d1);
    // Crossing from above: where the path meets the plane. Started behind
    // (spawned inside): the end point projected out.
    bool crossing = d0 >= 0.0f;
    Hit h = makeHit(select3(p1 - n * d1, mix(p0, p1, t), crossing), n, crossing ? t : 1.0f);
    Hit none = noHit();
    bool hit = !planeKeepsClear(d1);
    h.point = select3(none.point, h.point, hit);
    h.normal = select3(none.normal, h.normal, hit);
    h.t = hit ? h.t : none.t;
    h.hit = hit ? h.hit : none.hit;
    return h;
}

// --- Sphere: first root of |p0 + t (p1 - p0) - c| = r ------------------------
SD_FN Hit intersectSphere(SD_IN(ColliderParams) c, vec3 p0, vec3 p1) {
    vec3 centre = vec3(c.position);
    float r = c.position.w;
    vec3 m = p0 - centre;
    vec3 d = p1 - p0;
    float cc = dot(m, m) - r * r;
    if (cc < 0.0f) {
        // Started inside: push the end point out radially.
        vec3 out1 = p1 - centre;
        float len = length(out1);
        vec3 n = len > 0.0f ? out1 / len : vec3(0.0f, 1.0f, 0.0f);
        return makeHit(centre + n * r, n, 1.0f);
    }
    float a = dot(d, d);
    float b = dot(m, d);
    float disc = b * b - a * cc;
    if (a <= 0.0f || b >= 0.0f || disc < 0.0f) {
        return noHit();
    }
    float t = (-b - sqrt(disc)) / a;
    if (t > 1.0f) {
        return noHit();
    }
    t = max(t, 0.0f);
    vec3 point = p0 + d * t;
    return makeHit(point, normalize(point - centre), t);
}

// --- Oriented box: slab test in the box frame -------------------------------
SD_FN vec3 toBoxFrame(SD_IN(ColliderParams) c, vec3 p) {
    vec3 q = p - vec3(c.position);
    return vec3(dot(q, vec3(c.axisX)), dot(q, vec3(c.axisY)), dot(q, vec3(c.axisZ)));
}

SD_FN vec3 fromBoxFrameDirection(SD_IN(ColliderParams) c, vec3 d) {
    return vec3(c.axisX) * d.x + vec3(c.axisY) * d.y + vec3(c.axisZ) * d.z;
}

// Local outward normal of the face nearest to local point q.
SD_FN vec3 nearestBoxFace(vec3 q, vec3 h) {
    vec3 gap = h - abs(q);
    if (gap.x <= gap.y && gap.x <= gap.z) {
        return vec3(q.x >= 0.0f ? 1.0f : -1.0f, 0.0f, 0.0f);
    }
    if (gap.y <= gap.z) {
        return vec3(0.0f, q.y >= 0.0f ? 1.0f : -1.0f, 0.0f);
    }
    return vec3(0.0f, 0.0f, q.z >= 0.0f ? 1.0f : -1.0f);
}

SD_FN bool insideBox(vec3 q, vec3 h) {
    return abs(q.x) < h.x && abs(q.y) < h.y && abs(q.z) < h.z;
}

SD_FN Hit intersectBox(SD_IN(ColliderParams) c, vec3 p0, vec3 p1) {
    vec3 h = vec3(c.halfExtents);
    vec3 q0 = toBoxFrame(c, p0);
    vec3 q1 = toBoxFrame(c, p1);
    if (insideBox(q0, h)) {
        // Started inside: push the end point out through its nearest face.
        vec3 q = clamp(q1, -h, h);
        vec3 n = nearestBoxFace(q, h);
        q = q * (vec3(1.0f) - abs(n)) + n * h;
        return makeHit(vec3(c.position) + fromBoxFrameDirection(c, q), fromBoxFrameDirection(c, n), 1.0f);
    }
    // Liang-Barsky clipping of the segment against the three slabs.
    vec3 d = q1 - q0;
    float tEnter = 0.0f;
    float tExit = 1.0f;
    vec3 enterNormal = vec3(0.0f);
    for (int axis = 0; axis < 3; ++axis) {
        float origin = axis == 0 ? q0.x : (axis == 1 ? q0.y : q0.z);
        float dir = axis == 0 ? d.x : (axis == 1 ? d.y : d.z);
        float halfWidth = axis == 0 ? h.x : (axis == 1 ? h.y : h.z);
        vec3 unit = axis == 0 ? vec3(1.0f, 0.0f, 0.0f) : (axis == 1 ? vec3(0.0f, 1.0f, 0.0f) : vec3(0.0f, 0.0f, 1.0f));
        if (abs(dir) < 1e-30f) {
            if (abs(origin) >= halfWidth) {
                return noHit();
            }
            continue;
        }
        float ta = (-halfWidth - origin) / dir;
        float tb = (halfWidth - origin) / dir;
        vec3 na = -unit;
        if (ta > tb) {
            float tmp = ta;
            ta = tb;
            tb = tmp;
            na = unit;
        }
        if (ta > tEnter) {
            tEnter = ta;
            enterNormal = na;
        }
        tExit = min(tExit, tb);
        if (tEnter > tExit) {
            return noHit();
        }
    }
    if (dot(enterNormal, enterNormal) == 0.0f) {
        return noHit();
    }
    vec3 n = fromBoxFrameDirection(c, enterNormal);
    return makeHit(mix(p0, p1, tEnter), n, tEnter);
}

// --- Sampled colliders: terrain height map and depth cube map ---------------
// Both are marched along the path in steps of at most c.marchStep (about one
// texel) and at most SD_MAX_MARCH_SAMPLES samples, so a fast particle cannot
// skip over a hill or a thin part of the shape finer than that.

// Heights are samples at grid vertices spanning the terrain (vertex i of n at
// i / (n - 1) of the size); a sampler's texel i has its centre at (i + 0.5) / n.
SD_FN vec2 terrainUv(SD_IN(ColliderParams) c, vec3 p) {
    vec2 u = vec2((p.x - c.position.x) / c.grid.x, (p.z - c.position.z) / c.grid.y);
    vec2 n = vec2(c.grid.z, c.grid.w);
    return (u * (n - 1.0f) + 0.5f) / n;
}

// Height above the terrain (m); vertical distance, exact on flat ground.
SD_FN float terrainDistance(SD_IN(KernelContext) ctx, SD_IN(ColliderParams) c, vec3 p) {
    return p.y - (c.position.y + sampleTerrainHeight(ctx, c.dataIndex, terrainUv(c, p)));
}

// Normal from central differences of the heights one grid cell apart.
SD_FN vec3 terrainNormal(SD_IN(KernelContext) ctx, SD_IN(ColliderParams) c, vec3 p) {
    vec2 uv = terrainUv(c, p);
    vec2 texel = vec2(1.0f / c.grid.z, 1.0f / c.grid.w);
    float hl = sampleTerrainHeight(ctx, c.dataIndex, uv - vec2(texel.x, 0.0f));
    float hr = sampleTerrainHeight(ctx, c.dataIndex, uv + vec2(texel.x, 0.0f));
    float hd = sampleTerrainHeight(ctx, c.dataIndex, uv - vec2(0.0f, texel.y));
    float hu = sampleTerrainHeight(ctx, c.dataIndex, uv + vec2(0.0f, texel.y));
    float dx = 2.0f * c.grid.x / (c.grid.z - 1.0f);
    float dz = 2.0f * c.grid.y / (c.grid.w - 1.0f);
    return normalize(vec3(-(hr - hl) / dx, 1.0f, -(hu - hd) / dz));
}

// Outside-positive distance along the ray from the cube map's centre.
SD_FN float cubeMapDistance(SD_IN(KernelContext) ctx, SD_IN(ColliderParams) c, vec3 p) {
    vec3 offset = p - vec3(c.position);
    float r = length(offset);
    if (r <= 0.0f) {
        return -1.0f;
    }
    return r - sampleCubeMap(ctx, c.dataIndex, offset / r).w;
}

SD_FN float sampledDistance(SD_IN(KernelContext) ctx, SD_IN(ColliderParams) c, vec3 p) {
    return c.kind == SD_COLLIDER_TERRAIN ? terrainDistance(ctx, c, p) : cubeMapDistance(ctx, c, p);
}

SD_FN vec3 sampledNormal(SD_IN(KernelContext) ctx, SD_IN(ColliderParams) c, vec3 p) {
    if (c.kind == SD_COLLIDER_TERRAIN) {
        return terrainNormal(ctx, c, p);
    }
    vec3 offset = p - vec3(c.position);
    float r = length(offset);
    vec3 dir = r > 0.0f ? offset / r : vec3(0.0f, 1.0f, 0.0f);
    return normalize(vec3(sampleCubeMap(ctx, c.dataIndex, dir)));
}

// The point on the surface straight out from p (up for terrain, radially for
// the cube map): where a particle that ended inside is put back.
SD_FN vec3 sampledSurfacePoint(SD_IN(ColliderParams) c, vec3 p, float distance) {
    if (c.kind == SD_COLLIDER_TERRAIN) {
        return vec3(p.x, p.y - distance, p.z);
    }
    vec3 offset = p - vec3(c.position);
    float r = length(offset);
    vec3 dir = r > 0.0f ? offset / r : vec3(0.0f, 1.0f, 0.0f);
    return vec3(c.position) + dir * (r - distance);
}

SD_FN Hit intersectSampled(SD_IN(KernelContext) ctx, SD_IN(ColliderParams) c, vec3 p0, vec3 p1) {
    float d0 = sampledDistance(ctx, c, p0);
    if (d0 < 0.0f) {
        float d1 = sampledDistance(ctx, c, p1);
        if (d1 >= 0.0f) {
            return noHit();
        }
        return makeHit(sampledSurfacePoint(c, p1, d1), sampledNormal(ctx, c, p1), 1.0f);
    }
    float pathLength = length(p1 - p0);
    float samples = clamp(ceil(pathLength / c.marchStep), 1.0f, SD_MAX_MARCH_SAMPLES);
    uint count = uint(samples);
    float previousT = 0.0f;
    for (uint i = 1u; i <= count; ++i) {
        float t = float(i) / samples;
        float d = sampledDistance(ctx, c, mix(p0, p1, t));
        if (d < 0.0f) {
            // Bisect the bracket; keep its outside end, so the contact is never
            // below the surface even where the surface curves between samples.
            float outsideT = previousT;
            float insideT = t;
            for (uint k = 0u; k < SD_CONTACT_BISECTIONS; ++k) {
                float midT = 0.5f * (outsideT + insideT);
                if (sampledDistance(ctx, c, mix(p0, p1, midT)) >= 0.0f) {
                    outsideT = midT;
                } else {
                    insideT = midT;
                }
            }
            vec3 point = mix(p0, p1, outsideT);
            return makeHit(point, sampledNormal(ctx, c, point), outsideT);
        }
        previousT = t;
    }
    return noHit();
}

SD_FN Hit intersectCollider(SD_IN(KernelContext) ctx, SD_IN(ColliderParams) c, vec3 p0, vec3 p1) {
    if (c.kind == SD_COLLIDER_PLANE) {
        return intersectPlane(c, p0, p1);
    }
    if (c.kind == SD_COLLIDER_SPHERE) {
        return intersectSphere(c, p0, p1);
    }
    if (c.kind == SD_COLLIDER_BOX) {
        return intersectBox(c, p0, p1);
    }
    return intersectSampled(ctx, c, p0, p1);
}

// Velocity response at a contact; v is the velocity at the moment of contact.
// Selects, not branches, so the CPU's lane loops vectorise.
SD_FN vec3 collisionVelocity(SD_IN(ColliderParams) c, vec3 n, vec3 v) {
    float vn = dot(v, n);
    vec3 normalPart = n * vn;
    vec3 tangentPart = v - normalPart;
    float keep = selectf(1.0f, 1.0f - c.friction, length(tangentPart) > c.restSpeed);
    vec3 response = tangentPart * keep - normalPart * c.resilience;
    return select3(response, v, vn >= 0.0f);  // already leaving the surface: unchanged
}

SD_END
#endif
