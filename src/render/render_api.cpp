// The public render API (include/spindrift/render.h): definitions checked,
// renderers kept in a table of ids. The drawing itself is in renderer.cpp.
#include "render/render_rules.h"
#include "render/renderer.h"

#include <spindrift/render.h>

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

namespace spindrift {

FluidRenderDef FluidRenderDef::upTo(int n) {
    FieldCheck("render").number("fluid.steps", n, render_rules::kFluidSteps);
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

std::string vec3Text(glm::vec3 v) { return fmt::format("[{}, {}, {}]", v.x, v.y, v.z); }

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

void validateCameraDef(const CameraDef& c) {
    const FieldCheck check("camera");
    check.finite("eye", c.eye);
    check.finite("target", c.target);
    check.finite("up", c.up);
    const glm::vec3 view = c.target - c.eye;
    check.expect(glm::length(view) > 1e-6f, "target", "a target that differs from the eye", vec3Text(c.target));
    // lookAt needs an up that is not along the view.
    check.expect(glm::length(c.up) > 0.0f &&
                     glm::length(glm::cross(glm::normalize(view), glm::normalize(c.up))) >= 1e-3f,
                 "up", "a direction not parallel to the view direction (target - eye)", vec3Text(c.up));
    check.number("fov", c.fovDegrees, render_rules::kFov);
    check.number("ortho_height", c.orthoHeight, render_rules::kOrthoHeight);
}

void validateLightDef(const LightDef& light) {
    const FieldCheck check(objectLabel("light", light.name));
    check.finite("position", light.position);
    check.colour("color", light.colour);
    check.number("radius", light.radius, render_rules::kLightRadius);
    check.number("flicker", light.flicker, render_rules::kLightFlicker);
}

void validateRenderDef(const RenderDef& def) {
    // Each field against its rule (render_rules.h), named as a scene file's
    // [render] spells its key.
    namespace rules = render_rules;
    const FieldCheck check("render");
    check.number("width", def.width, rules::kFrameSide);
    check.number("height", def.height, rules::kFrameSide);
    check.number("fps", def.fps, rules::kFps);
    check.number("seconds", def.seconds, rules::kSeconds);
    check.finite("sun", def.sunDirection);
    check.expect(glm::length(def.sunDirection) > 0.0f, "sun", "a non-zero direction", vec3Text(def.sunDirection));
    check.colour("sun_color", def.sunColour);
    check.colour("ambient", def.ambient);
    check.expect(def.lights.size() <= kRenderMaxLights, "lights", fmt::format("at most {}", kRenderMaxLights),
                 std::to_string(def.lights.size()));
    for (const LightDef& light : def.lights) {
        validateLightDef(light);
    }
    check.number("exposure", def.exposure, rules::kExposure);
    check.expect(def.toneMap == ToneMap::Aces || def.toneMap == ToneMap::None, "tone_map",
                 fmt::format("none ({}) or aces ({})", static_cast<std::uint32_t>(ToneMap::None),
                             static_cast<std::uint32_t>(ToneMap::Aces)),
                 std::to_string(static_cast<std::uint32_t>(def.toneMap)));
    check.number("bloom", def.bloom, rules::kBloom);
    check.colour("background.color", def.background.colour);
    check.colour("background.top", def.background.top);
    check.colour("background.bottom", def.background.bottom);
    check.expect(def.background.kind != BackgroundKind::Image || !def.background.image.empty(), "background.image",
                 "a PNG file path", "none");
    check.colour("fluid.color", def.fluid.colour);
    check.number("fluid.opacity", def.fluid.opacity, rules::kFluidOpacity);
    check.number("fluid.radius_scale", def.fluid.radiusScale, rules::kFluidRadiusScale);
    check.expect(def.fluid.style == FluidStyle::Surface || def.fluid.style == FluidStyle::Splats, "fluid.style",
                 fmt::format("surface ({}) or splats ({})", static_cast<std::uint32_t>(FluidStyle::Surface),
                             static_cast<std::uint32_t>(FluidStyle::Splats)),
                 std::to_string(static_cast<std::uint32_t>(def.fluid.style)));
    check.number("fluid.surface_scale", def.fluid.surfaceScale, rules::kFluidSurfaceScale);
    try {
        validateCameraDef(def.camera);
    } catch (const FieldError& e) {
        throw FieldError("render", "camera." + e.field(), e.message());
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
