// The public render API (include/spindrift/render.h): definitions checked,
// renderers kept in a table of ids. The drawing itself is in renderer.cpp.
#include "render/renderer.h"

#include <spindrift/render.h>

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

namespace spindrift {

FluidRenderDef FluidRenderDef::upTo(int n) {
    if (n < 1 || n > 7) {
        throw Error(fmt::format("fluid splat steps: {} is not in [1, 7]", n));
    }
    FluidRenderDef def;
    def.style = FluidStyle::Splats;
    def.sizeFromDensity = n >= 2;
    def.stretch = n >= 3;
    def.refraction = n >= 4;
    def.edges = n >= 5;
    def.splashes = n >= 6;
    def.bubbles = n >= 7;
    return def;
}

namespace {

// The surface field's smallest resolution, as a fraction of the frame's side.
constexpr float kMinSurfaceScale = 0.125f;

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Renderers by id (index + 1); destroyed ones leave a null.
std::mutex registryMutex;
std::vector<std::unique_ptr<render::Renderer>> renderers;

render::Renderer& rendererFromId(RendererId id) {
    std::lock_guard lock(registryMutex);
    if (id.index == 0 || id.index > renderers.size() || !renderers[id.index - 1]) {
        throw Error(fmt::format("renderer {} does not exist", id.index));
    }
    return *renderers[id.index - 1];
}

}  // namespace

render::Renderer& render::rendererOf(RendererId id) { return rendererFromId(id); }

void validateRenderDef(const RenderDef& def) {
    // 16384: the smallest maxImageDimension2D a desktop driver reports is far
    // above what a frame needs; lavapipe allows 16384.
    if (def.width < 1 || def.height < 1 || def.width > 16384 || def.height > 16384) {
        throw Error(fmt::format("render: width and height must be in [1, 16384], got {} x {}", def.width, def.height));
    }
    const CameraDef& c = def.camera;
    if (!finite(c.eye) || !finite(c.target) || !finite(c.up) || !(glm::length(c.target - c.eye) > 1e-6f)) {
        throw Error("render: camera eye and target must be finite and differ");
    }
    if (!(c.fovDegrees > 0.0f && c.fovDegrees < 180.0f) || !(c.orthoHeight > 0.0f)) {
        throw Error("render: camera fov must be in (0, 180) degrees and ortho_height > 0");
    }
    if (def.background.kind == BackgroundKind::Image && def.background.image.empty()) {
        throw Error("render: an image background needs an image path");
    }
    if (!(def.fluid.opacity > 0.0f && def.fluid.opacity <= 1.0f) || !(def.fluid.radiusScale > 0.0f)) {
        throw Error("render: fluid opacity must be in (0, 1] and radius_scale > 0");
    }
    if (def.fluid.style != FluidStyle::Surface && def.fluid.style != FluidStyle::Splats) {
        throw Error(fmt::format("render: fluid style {} is neither surface ({}) nor splats ({})",
                                static_cast<std::uint32_t>(def.fluid.style),
                                static_cast<std::uint32_t>(FluidStyle::Surface),
                                static_cast<std::uint32_t>(FluidStyle::Splats)));
    }
    if (!(def.fluid.surfaceScale >= kMinSurfaceScale && def.fluid.surfaceScale <= 1.0f)) {
        throw Error(fmt::format("render: fluid surface_scale must be in [0.125, 1], got {}", def.fluid.surfaceScale));
    }
    if (!(def.fps > 0.0f) || !(def.seconds > 0.0f) || !finite(def.sunDirection) ||
        !(glm::length(def.sunDirection) > 0.0f)) {
        throw Error("render: fps and seconds must be > 0 and the sun direction non-zero");
    }
}

RendererId createRenderer(WorldId world, const RenderDef& def) {
    validateRenderDef(def);
    auto r = render::createRenderer(world, def);
    std::lock_guard lock(registryMutex);
    renderers.push_back(std::move(r));
    return RendererId{static_cast<std::uint32_t>(renderers.size())};
}

void destroyRenderer(RendererId id) {
    std::unique_ptr<render::Renderer> r;
    {
        std::lock_guard lock(registryMutex);
        if (id.index == 0 || id.index > renderers.size() || !renderers[id.index - 1]) {
            throw Error(fmt::format("renderer {} does not exist", id.index));
        }
        r = std::move(renderers[id.index - 1]);
    }
    render::destroyRenderer(*r);
}

void setRenderCamera(RendererId id, const CameraDef& camera) {
    render::Renderer& r = rendererFromId(id);
    RenderDef def = r.def;
    def.camera = camera;
    validateRenderDef(def);
    r.def.camera = camera;
}

void setFluidRender(RendererId id, const FluidRenderDef& fluid) {
    render::Renderer& r = rendererFromId(id);
    RenderDef def = r.def;
    def.fluid = fluid;
    validateRenderDef(def);
    r.def.fluid = fluid;
}

Frame renderFrame(RendererId id) { return render::renderFrame(rendererFromId(id)); }

RenderStats renderStats(RendererId id) { return rendererFromId(id).stats; }

}  // namespace spindrift
