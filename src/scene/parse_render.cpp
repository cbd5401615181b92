// [render]: frame size, video timing, sun, exposure, tone map, bloom, and the [render.background] and
// [render.fluid] sub-tables. Values are read with type checks only; their
// ranges are validateRenderDef's rules (src/render/render_rules.h), checked
// once through validateAt, so an error points at the line that is wrong.
#include <fmt/format.h>

#include "render/render_rules.h"
#include "scene/parse_internal.h"

namespace spindrift::scene {

namespace {

std::vector<std::string_view> backgroundKeys(BackgroundKind kind) {
    switch (kind) {
        case BackgroundKind::Colour:
            return {"kind", "color"};
        case BackgroundKind::Gradient:
            return {"kind", "top", "bottom"};
        case BackgroundKind::Image:
            return {"kind", "image"};
    }
    return {"kind"};
}

BackgroundDef parseBackground(const Table& t) {
    BackgroundDef def;
    const Value kind = t.require("kind", "\"color\", \"gradient\" or \"image\"");
    def.kind = kind.choice<BackgroundKind>(
        {{"color", BackgroundKind::Colour}, {"gradient", BackgroundKind::Gradient}, {"image", BackgroundKind::Image}});
    t.allowOnly(backgroundKeys(def.kind), fmt::format("a background of kind \"{}\"", kind.string()));
    def.colour = t.vec3("color", def.colour);
    def.top = t.vec3("top", def.top);
    def.bottom = t.vec3("bottom", def.bottom);
    if (def.kind == BackgroundKind::Image) {
        def.image = readPngPath(t.require("image", "a PNG file path, relative to the scene file"));
    }
    return def;
}

// `render` is the [render] table, where FluidRenderDef::upTo's error is located.
FluidRenderDef parseFluidRender(const Table& render, const Table& t) {
    t.allowOnly({"style", "color", "opacity", "radius_scale", "surface_scale", "steps", "size_from_density", "stretch",
                 "refraction", "edges", "splashes", "bubbles"},
                "[render.fluid]");
    FluidRenderDef def;
    // `style` picks the look; `steps` are the splat style's, so they select
    // it unless a style is written, and steps beside style = "surface" are a
    // contradiction the user should hear about.
    if (auto v = t.find("style")) {
        def.style = v->choice<FluidStyle>({{"surface", FluidStyle::Surface}, {"splats", FluidStyle::Splats}});
        if (def.style == FluidStyle::Surface && t.find("steps")) {
            t.find("steps")->fail("\"steps\" are the splat style's; with style = \"surface\" remove them");
        }
    } else if (t.find("steps")) {
        def.style = FluidStyle::Splats;
    }
    // `steps` is the baseline (the Sprinkle slides' steps 1..n on, the rest
    // off); a flag written beside it overrides it, so "steps = 5" plus
    // "bubbles = true" reads as what it says.
    if (auto v = t.find("steps")) {
        const int steps = v->whole<int>(render_rules::kFluidSteps);
        FluidRenderDef preset;
        validateAt(render, [&] { preset = FluidRenderDef::upTo(steps); });
        def.sizeFromDensity = preset.sizeFromDensity;
        def.stretch = preset.stretch;
        def.refraction = preset.refraction;
        def.edges = preset.edges;
        def.splashes = preset.splashes;
        def.bubbles = preset.bubbles;
    }
    def.colour = t.vec3("color", def.colour);
    def.opacity = t.real("opacity", def.opacity, render_rules::kFluidOpacity);
    def.radiusScale = t.real("radius_scale", def.radiusScale, render_rules::kFluidRadiusScale);
    def.surfaceScale = t.real("surface_scale", def.surfaceScale, render_rules::kFluidSurfaceScale);
    def.sizeFromDensity = t.boolean("size_from_density", def.sizeFromDensity);
    def.stretch = t.boolean("stretch", def.stretch);
    def.refraction = t.boolean("refraction", def.refraction);
    def.edges = t.boolean("edges", def.edges);
    def.splashes = t.boolean("splashes", def.splashes);
    def.bubbles = t.boolean("bubbles", def.bubbles);
    return def;
}

}  // namespace

RenderDef parseRender(const Table& t) {
    t.allowOnly({"width", "height", "fps", "seconds", "draw_colliders", "sun", "sun_color", "ambient", "exposure",
                 "tone_map", "bloom", "background", "fluid"},
                "[render]");
    RenderDef def;
    def.width = t.whole<std::uint32_t>("width", def.width, render_rules::kFrameSide);
    def.height = t.whole<std::uint32_t>("height", def.height, render_rules::kFrameSide);
    def.fps = t.real("fps", def.fps, render_rules::kFps);
    def.seconds = t.real("seconds", def.seconds, render_rules::kSeconds);
    def.drawColliders = t.boolean("draw_colliders", def.drawColliders);
    def.sunDirection = t.direction("sun", def.sunDirection);
    def.sunColour = t.vec3("sun_color", def.sunColour);
    def.ambient = t.vec3("ambient", def.ambient);
    def.exposure = t.real("exposure", def.exposure, render_rules::kExposure);
    if (auto v = t.find("tone_map")) {
        def.toneMap = v->choice<ToneMap>({{"aces", ToneMap::Aces}, {"none", ToneMap::None}});
    }
    def.bloom = t.real("bloom", def.bloom, render_rules::kBloom);
    if (auto background = t.subTable("background")) {
        def.background = parseBackground(*background);
    }
    if (auto fluid = t.subTable("fluid")) {
        def.fluid = parseFluidRender(t, *fluid);
    }
    // The camera is the [camera] table's (parseCamera); the default one here is valid.
    validateAt(t, [&] { validateRenderDef(def); });
    return def;
}

}  // namespace spindrift::scene
