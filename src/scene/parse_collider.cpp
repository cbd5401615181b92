// [[collider]]: planes, spheres, boxes, height-map terrain and depth cube maps.
//
// Values of the Def are read with type checks only; their ranges are
// validateColliderDef's rules (src/particles/collider_rules.h), checked once
// through validateAt. What is checked here is what never reaches the Def: the
// parameters of the hills generator and of a cube map's shapes, an image's
// height scale and size, and that a cube map's centre lies inside its shapes.
#include "particles/collider_rules.h"
#include "particles/params.h"
#include "scene/cube_map.h"
#include "scene/field_sources.h"
#include "scene/heightmap_png.h"
#include "scene/parse_internal.h"

#include <fmt/format.h>

#include <algorithm>

namespace spindrift::scene {

namespace {

enum class HeightSource { None, Hills, Image, Inline };

const std::vector<std::string_view> kCommonKeys = {"name", "kind", "friction", "resilience",
                                                   "rest_speed", "color", "texture", "texture_scale"};

std::vector<std::string_view> withCommon(std::initializer_list<std::string_view> keys) {
    std::vector<std::string_view> all = kCommonKeys;
    all.insert(all.end(), keys);
    return all;
}

// --- Terrain -----------------------------------------------------------------

std::vector<std::string_view> terrainKeys(HeightSource source) {
    switch (source) {
        case HeightSource::Hills:
            return withCommon({"origin", "size", "generate", "resolution", "amplitude", "frequency",
                               "octaves", "seed"});
        case HeightSource::Image:
            return withCommon({"origin", "size", "image", "height_scale"});
        case HeightSource::Inline:
            return withCommon({"origin", "size", "heights", "resolution"});
        case HeightSource::None:
            break;
    }
    return withCommon({"origin", "size", "generate", "resolution", "amplitude", "frequency",
                       "octaves", "seed", "image", "height_scale", "heights"});
}

HeightSource heightSource(const Table& t) {
    HeightSource source = HeightSource::None;
    for (const auto& [key, kind] :
         {std::pair{"generate", HeightSource::Hills}, std::pair{"image", HeightSource::Image},
          std::pair{"heights", HeightSource::Inline}}) {
        if (!t.has(key)) {
            continue;
        }
        if (source != HeightSource::None) {
            t.failAtKey(key, "give only one height source: `generate`, `image` or `heights`");
        }
        source = kind;
    }
    if (source == HeightSource::None) {
        t.allowOnly(terrainKeys(HeightSource::None), "a terrain collider");
        t.fail(
            "a terrain needs heights: `generate = \"hills\"`, `image = \"file.png\"` or "
            "`heights = [...]`");
    }
    return source;
}

glm::uvec2 readTerrainResolution(const Value& v) {
    const FieldRule& axis = collider_rules::kTerrainAxis;
    if (v.array().size() != 2) {
        v.failExpected(fmt::format("[nx, nz], each {}", axis.describe()));
    }
    return {v.element(0).whole<std::uint32_t>(axis), v.element(1).whole<std::uint32_t>(axis)};
}

void setGrid(ColliderDef& def, glm::uvec2 n) {
    def.terrainNx = n.x;
    def.terrainNz = n.y;
}

void readHills(const Table& t, ColliderDef& def) {
    t.find("generate")->choice<int>({{"hills", 0}});
    auto resolution = t.find("resolution");
    setGrid(def, resolution ? readTerrainResolution(*resolution) : glm::uvec2(64, 64));
    validateAt(t, [&] { validateColliderGrid(def); });  // before the heights are generated
    HillParams params;
    params.amplitude = t.real("amplitude", params.amplitude, Bounds::nonNegative());
    params.frequency = t.real("frequency", params.frequency, Bounds::positive());
    params.octaves =
        static_cast<std::uint32_t>(t.integer("octaves", params.octaves, Bounds::between(1, 8)));
    params.seed = static_cast<std::uint32_t>(
        t.integer("seed", params.seed, Bounds::between(0, 4294967295.0)));
    checkNoiseCost(t, hillsEvaluations(def, params.octaves),
                   fmt::format("hills of {} x {} samples x {} octaves", def.terrainNx, def.terrainNz,
                               params.octaves));
    fillHills(def, params);
}

void readImageHeights(const Table& t, ColliderDef& def) {
    const Value file = *t.find("image");
    const float scale = t.real("height_scale", 1.0f, Bounds::positive());
    DataFileRef ref;
    const std::string bytes = readDataFile(file, ref);
    GreyImage image;
    std::string error;
    if (!decodeGreyPng(bytes, kTerrainMaxAxis, image, error)) {
        file.fail(fmt::format("cannot use \"{}\" as a height map: {}", ref.display, error));
    }
    // The image is the grid: its size is checked as the resolution would be,
    // at the image (the file has no resolution key).
    const auto tooSmallOrBig = [](std::uint32_t n) { return !collider_rules::kTerrainAxis.bounds.contains(n); };
    if (tooSmallOrBig(image.width) || tooSmallOrBig(image.height)) {
        file.fail(fmt::format("expected an image of 2 to {} pixels a side, got {} x {}",
                              kTerrainMaxAxis, image.width, image.height));
    }
    setGrid(def, {image.width, image.height});
    def.heights.resize(image.values.size());
    std::transform(image.values.begin(), image.values.end(), def.heights.begin(),
                   [scale](float grey) { return grey * scale; });
}

void readInlineHeights(const Table& t, ColliderDef& def) {
    const glm::uvec2 n =
        readTerrainResolution(t.require("resolution", "[nx, nz] for the heights array"));
    setGrid(def, n);
    // As many as the file has: that they are nx * nz is validateColliderDef's rule.
    const Value heights = *t.find("heights");
    def.heights.clear();
    for (std::size_t i = 0; i < heights.array().size(); ++i) {
        def.heights.push_back(heights.element(i).real());
    }
}

void readTerrain(const Table& t, ColliderDef& def) {
    const HeightSource source = heightSource(t);
    def.position = t.vec3("origin", def.position);
    const std::vector<float> size = t.require("size", "[size_x, size_z] (m)").numbers(2);
    def.terrainSizeX = size[0];
    def.terrainSizeZ = size[1];
    switch (source) {
        case HeightSource::Hills:
            readHills(t, def);
            break;
        case HeightSource::Image:
            readImageHeights(t, def);
            break;
        case HeightSource::Inline:
        case HeightSource::None:
            readInlineHeights(t, def);
            break;
    }
}

// --- Cube map ----------------------------------------------------------------

CubeShape readCubeShape(const Value& v) {
    if (!v.node().is_table()) {
        v.failExpected("a shape table {kind = \"sphere\" | \"box\", center = [x, y, z], ...}");
    }
    const Table t(v.context(), *v.node().as_table(), v.path());
    CubeShape shape;
    shape.kind = t.require("kind", "\"sphere\" or \"box\"")
                     .choice<CubeShape::Kind>(
                         {{"sphere", CubeShape::Kind::Sphere}, {"box", CubeShape::Kind::Box}});
    const bool sphere = shape.kind == CubeShape::Kind::Sphere;
    t.allowOnly(sphere ? std::vector<std::string_view>{"kind", "center", "radius"}
                       : std::vector<std::string_view>{"kind", "center", "half_extents"},
                sphere ? "a sphere shape" : "a box shape");
    shape.center = t.require("center", "[x, y, z] (m)").vec3();
    if (sphere) {
        shape.radius = t.require("radius", "a number > 0 (m)").real(Bounds::positive());
    } else {
        shape.halfExtents =
            t.require("half_extents", "[hx, hy, hz] (m), each > 0").vec3(Bounds::positive());
    }
    return shape;
}

void readCubeShapes(const Table& t, ColliderDef& def) {
    def.cubeResolution = t.whole<std::uint32_t>("resolution", 64, collider_rules::kCubeResolution);
    validateAt(t, [&] { validateColliderGrid(def); });  // before the depths are computed
    const Value list = *t.find("shapes");
    if (list.array().empty()) {
        list.failExpected("at least one shape");
    }
    std::vector<CubeShape> shapes;
    for (std::size_t i = 0; i < list.array().size(); ++i) {
        shapes.push_back(readCubeShape(list.element(i)));
    }
    def.cubeDepths = cubeDepthsFromShapes(shapes, def.position, def.cubeResolution);
    // A ray that leaves no shape means the centre is outside the union, which a
    // depth-from-centre map cannot describe.
    if (*std::min_element(def.cubeDepths.begin(), def.cubeDepths.end()) <= 0.0f) {
        const std::string message = fmt::format(
            "the centre [{}, {}, {}] must lie inside the shapes: the cube map stores the "
            "distance from it to their surface in every direction",
            def.position.x, def.position.y, def.position.z);
        t.has("center") ? t.failAtKey("center", message) : t.fail(message);
    }
}

// Depths come from `file` or from `shapes`: exactly one of them.
bool cubeMapFromFile(const Table& t) {
    const bool fromFile = t.has("file");
    if (fromFile == t.has("shapes")) {
        t.allowOnly(withCommon({"center", "resolution", "shapes", "file"}), "a cube map collider");
        if (fromFile) {
            t.failAtKey("shapes", "give either `shapes` or `file`, not both");
        }
        t.fail("a cube map needs `shapes = [...]` or `file = \"...\"`");
    }
    return fromFile;
}

void readCubeMap(const Table& t, ColliderDef& def) {
    def.position = t.vec3("center", def.position);
    if (cubeMapFromFile(t)) {
        DataFileRef ref;
        const std::string text = readDataFile(*t.find("file"), ref);
        def.cubeDepths = readCubeMapFile(ref, text, def.cubeResolution);
    } else {
        readCubeShapes(t, def);
    }
}

// --- Simple shapes -----------------------------------------------------------

std::vector<std::string_view> simpleKeys(ColliderKind kind) {
    switch (kind) {
        case ColliderKind::Plane:
            return withCommon({"point", "normal"});
        case ColliderKind::Sphere:
            return withCommon({"center", "radius"});
        default:
            return withCommon({"center", "half_extents", "rotation"});
    }
}

void readSimple(const Table& t, ColliderDef& def) {
    switch (def.kind) {
        case ColliderKind::Plane:
            def.position = t.vec3("point", def.position);
            def.normal = t.direction("normal", def.normal);
            break;
        case ColliderKind::Sphere:
            def.position = t.vec3("center", def.position);
            def.radius = t.require("radius", "a number > 0 (m)").real(collider_rules::kRadius);
            break;
        default:
            def.position = t.vec3("center", def.position);
            def.halfExtents = t.require("half_extents", "[hx, hy, hz] (m), each > 0").vec3();
            def.rotationDegrees = t.vec3("rotation", def.rotationDegrees);
            break;
    }
}

// Keys of another kind, or of another data source, are errors.
void checkKeys(const Table& t, ColliderKind kind) {
    if (kind == ColliderKind::Terrain) {
        t.allowOnly(terrainKeys(heightSource(t)), "a terrain collider");
    } else if (kind == ColliderKind::CubeMap) {
        const bool fromFile = cubeMapFromFile(t);
        t.allowOnly(fromFile ? withCommon({"center", "file"})
                             : withCommon({"center", "resolution", "shapes"}),
                    fromFile ? "a cube map collider read from a file (its header gives the "
                               "resolution)"
                             : "a cube map collider made from shapes");
    } else {
        t.allowOnly(simpleKeys(kind),
                    fmt::format("a collider of kind \"{}\"", t.find("kind")->string()));
    }
}

void readSurface(const Table& t, ColliderDef& def) {
    def.friction = t.real("friction", def.friction, collider_rules::kFriction);
    def.resilience = t.real("resilience", def.resilience, collider_rules::kResilience);
    def.restSpeed = t.real("rest_speed", def.restSpeed, collider_rules::kRestSpeed);
    // Type only: that each channel is >= 0 is validateColliderDef's rule.
    if (auto v = t.find("color")) def.colour = v->vec3();
    def.texture = readSurfaceTexture(t);
}

}  // namespace

ColliderDef parseCollider(const Table& t, NameTable& names) {
    ColliderDef def;
    def.kind = t.require("kind",
                         "a collider kind: \"plane\", \"sphere\", \"box\", \"terrain\" or "
                         "\"cube_map\"")
                   .choice<ColliderKind>({{"plane", ColliderKind::Plane},
                                          {"sphere", ColliderKind::Sphere},
                                          {"box", ColliderKind::Box},
                                          {"terrain", ColliderKind::Terrain},
                                          {"cube_map", ColliderKind::CubeMap}});
    checkKeys(t, def.kind);
    def.name = names.add(t);
    readSurface(t, def);
    if (def.kind == ColliderKind::Terrain) {
        readTerrain(t, def);
    } else if (def.kind == ColliderKind::CubeMap) {
        readCubeMap(t, def);
    } else {
        readSimple(t, def);
    }
    validateAt(t, [&] { validateColliderDef(def); });
    return def;
}

}  // namespace spindrift::scene
