// [render]: frame size, video timing, sun, and the [render.background] and
// [render.fluid] sub-tables. Ranges are those of validateRenderDef, checked
// here per key so an error points at the line that is wrong.
#include <fmt/format.h>

#include "scene/parse_internal.h"

namespace spindrift::scene {

namespace {

// The renderer's limit (validateRenderDef): lavapipe's maxImageDimension2D.
constexpr double kMaxFrameSide = 16384;

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
    def.colour = t.vec3("color", def.colour, Bounds::nonNegative());
    def.top = t.vec3("top", def.top, Bounds::nonNegative());
    def.bottom = t.vec3("bottom", def.bottom, Bounds::nonNegative());
    if (def.kind == BackgroundKind::Image) {
        def.image = readPngPath(t.require("image", "a PNG file path, relative to the scene file"));
    }
    return def;
}

FluidRenderDef parseFluidRender(const Table& t) {
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
        const FluidRenderDef preset = FluidRenderDef::upTo(static_cast<int>(v->integer(Bounds::between(1, 7))));
        def.sizeFromDensity = preset.sizeFromDensity;
        def.stretch = preset.stretch;
        def.refraction = preset.refraction;
        def.edges = preset.edges;
        def.splashes = preset.splashes;
        def.bubbles = preset.bubbles;
    }
    def.colour = t.vec3("color", def.colour, Bounds::nonNegative());
    def.opacity = t.real("opacity", def.opacity, {0.0, 1.0, true, false});
    def.radiusScale = t.real("radius_scale", def.radiusScale, Bounds::positive());
    def.surfaceScale = t.real("surface_scale", def.surfaceScale, Bounds::between(0.125, 1.0));
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
    t.allowOnly({"width", "height", "fps", "seconds", "draw_colliders", "sun", "background", "fluid"}, "[render]");
    RenderDef def;
    def.width = static_cast<std::uint32_t>(t.integer("width", def.width, Bounds::between(1, kMaxFrameSide)));
    def.height = static_cast<std::uint32_t>(t.integer("height", def.height, Bounds::between(1, kMaxFrameSide)));
    def.fps = t.real("fps", def.fps, Bounds::positive());
    def.seconds = t.real("seconds", def.seconds, Bounds::positive());
    def.drawColliders = t.boolean("draw_colliders", def.drawColliders);
    def.sunDirection = t.direction("sun", def.sunDirection);
    if (auto background = t.subTable("background")) {
        def.background = parseBackground(*background);
    }
    if (auto fluid = t.subTable("fluid")) {
        def.fluid = parseFluidRender(*fluid);
    }
    // The library's own check, so a rule added there and not here still
    // rejects the scene rather than createRenderer mid-command.
    try {
        validateRenderDef(def);
    } catch (const Error& e) {
        t.fail(e.what());
    }
    return def;
}

}  // namespace spindrift::scene
