// The viewer's panel; see viewer_panel.h.
#include "viewer_panel.h"

#include "fluid/fluid_rules.h"
#include "particles/emitter_rules.h"
#include "render/render_rules.h"
#include "render/renderer.h"

#include <spindrift/fires.h>
#include <spindrift/fluid.h>

#include <fmt/format.h>

#include <algorithm>

namespace spindrift::app {
namespace {

/// A name as the scene gives it, or its kind and id when it has none.
std::string nameOr(const std::string& name, const char* kind, std::uint32_t id) {
    return name.empty() ? fmt::format("{} {}", kind, id) : name;
}

void statistics(Session& s) {
    const RenderStats rs = renderStats(s.renderer);
    ImGui::Text("sim %.2f ms/step", s.simMs);
    ImGui::Text("frame %.2f ms", s.frameMs);
    ImGui::TextWrapped("render: device %.2f ms (fluid %.2f, sprites %.2f), host %.2f ms", rs.totalDeviceMs, rs.fluidMs,
                       rs.spritesMs, rs.cpuMs);
    ImGui::Text("sprites %llu, splats %llu", static_cast<unsigned long long>(rs.sprites),
                static_cast<unsigned long long>(rs.splats));
    for (const FluidStepStats& f : s.last.fluids) {
        ImGui::TextWrapped("%s: %llu particles, density error mean %.2f%%, max %.2f%%",
                           nameOr(fluidDef(s.world, f.fluid).name, "fluid", f.fluid.index).c_str(),
                           static_cast<unsigned long long>(f.particles), 100.0 * f.meanDensityError,
                           100.0 * f.maxDensityError);
        // Why a step costs what it does: the substep rules' counts.
        ImGui::Text("  substeps %u (speed %u, depth %u, compression %u)", f.substeps, f.substepsForSpeed,
                    f.substepsForDepth, f.substepsForCompression);
    }
}

void fluidSettings(Session& s) {
    if (ImGui::TreeNode("fluid look")) {
        FluidRenderDef fluid = render::rendererOf(s.renderer).def.fluid;
        bool changed = false;
        bool surface = fluid.style == FluidStyle::Surface;
        if (ImGui::Checkbox("2D surface (off: splats)", &surface)) {
            fluid.style = surface ? FluidStyle::Surface : FluidStyle::Splats;
            changed = true;
        }
        changed |= ImGui::Checkbox("size from density", &fluid.sizeFromDensity);
        changed |= ImGui::Checkbox("stretch", &fluid.stretch);
        changed |= ImGui::Checkbox("refraction", &fluid.refraction);
        changed |= ImGui::Checkbox("edges", &fluid.edges);
        changed |= ImGui::Checkbox("splashes", &fluid.splashes);
        changed |= ImGui::Checkbox("bubbles", &fluid.bubbles);
        // The ranges of the rules setFluidRender checks (render_rules.h); an
        // open or unbounded end is the panel's choice, inside the rule.
        constexpr SliderSpan opacity = sliderSpan(render_rules::kFluidOpacity, 0.05, 1.0);
        constexpr SliderSpan radius = sliderSpan(render_rules::kFluidRadiusScale, 0.25, 4.0);
        changed |= ImGui::SliderFloat("opacity", &fluid.opacity, opacity.min, opacity.max);
        changed |= ImGui::SliderFloat("radius", &fluid.radiusScale, radius.min, radius.max);
        changed |= ImGui::ColorEdit3("colour", &fluid.colour.x, ImGuiColorEditFlags_NoInputs);
        if (changed) setFluidRender(s.renderer, fluid);
        ImGui::TreePop();
    }
    for (std::uint32_t f = 1; f <= fluidCount(s.world); ++f) {
        ImGui::PushID(int(1000 + f));
        const FluidDef& def = fluidDef(s.world, FluidId{f});
        if (ImGui::TreeNode(fmt::format("{} solver", nameOr(def.name, "fluid", f)).c_str())) {
            int iterations = int(def.iterations);
            float baumgarte = def.baumgarte;
            // The ranges of the rules setFluidSolver checks (fluid_rules.h),
            // so a slider never offers a value the API refuses.
            constexpr SliderSpan iterationSpan = sliderSpan(fluid::rules::kIterations, 0, 0);
            constexpr SliderSpan baumgarteSpan = sliderSpan(fluid::rules::kBaumgarte, 0, 0);
            bool changed = ImGui::SliderInt("iterations", &iterations, int(iterationSpan.min), int(iterationSpan.max));
            changed |= ImGui::SliderFloat("baumgarte", &baumgarte, baumgarteSpan.min, baumgarteSpan.max);
            if (changed) setFluidSolver(s.world, FluidId{f}, std::uint32_t(iterations), baumgarte);
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
}

void emitterSettings(Session& s) {
    for (std::uint32_t i = 0; i < s.emitters.size(); ++i) {
        EmitterDef& e = s.emitters[i];
        ImGui::PushID(int(i));
        const std::string title = fmt::format("{}: {}###emitter", nameOr(e.name, "emitter", i + 1), s.alive[i]);
        if (ImGui::TreeNode(title.c_str())) {
            if (e.stateless) {
                ImGui::TextWrapped("stateless: its closed form is fixed at creation");
            } else {
                // Only what acts at birth is live (setEmitterRate/Speed): both
                // backends then agree on every particle already alive.
                // The ranges of the rules setEmitterRate/Speed check
                // (emitter_rules.h); an unbounded top is the panel's choice.
                constexpr SliderSpan rate = sliderSpan(emitter_rules::kRate, 0.0, 1e6);
                constexpr SliderSpan speedSpan = sliderSpan(emitter_rules::kSpeed, 0.0, 1e3);
                if (e.lifecycle == Lifecycle::Spawn && ImGui::DragFloat("rate /s", &e.rate, 1.0f, rate.min, rate.max)) {
                    e.rate = std::max(e.rate, rate.min);
                    setEmitterRate(s.world, EmitterId{i + 1}, e.rate);
                }
                FloatRange speed = e.speed;
                if (ImGui::DragFloatRange2("m/s", &speed.min, &speed.max, 0.05f, speedSpan.min, speedSpan.max) &&
                    speed.min <= speed.max) {
                    setEmitterSpeed(s.world, EmitterId{i + 1}, speed);
                    e.speed = speed;
                }
            }
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
}

}  // namespace

/// A narrow column at the left edge: its width a fifth of the window's
/// (within 170 to 300 pixels, so text still fits and a large window is not
/// crowded), its height what it holds, up to the window's, then it scrolls.
/// The title bar collapses it; H hides it.
PanelShown panel(Session& s, bool paused, const Playback& playback) {
    PanelShown shown;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float width = std::clamp(0.2f * display.x, 170.0f, 300.0f);
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0.0f), ImVec2(width, std::max(display.y - 16.0f, 40.0f)));
    ImGui::SetNextWindowBgAlpha(0.8f);
    ImGui::Begin("spindrift", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::Text("%s  t %.2f s", paused ? "paused" : "running", worldTime(s.world));
    if (paused) {
        ImGui::TextDisabled("Space resumes");
    } else if (playbackBehind(playback)) {
        // Slower than the clock is said, not hidden: the steps a frame may
        // take are capped so a slow machine does not fall ever further behind.
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.7f, 0.2f, 1.0f));
        ImGui::TextWrapped("%.2fx real time: this machine cannot keep up", playback.speed);
        ImGui::PopStyleColor();
    } else {
        ImGui::TextDisabled("real time");
    }
    if (ImGui::CollapsingHeader("Statistics")) statistics(s);
    if (fireCount(s.world) > 0 && ImGui::CollapsingHeader("Fires", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (std::uint32_t i = 1; i <= fireCount(s.world); ++i) {
            const float strength = fireStrength(s.world, FireId{i});
            const std::string name = nameOr(i <= s.fireNames.size() ? s.fireNames[i - 1] : "", "fire", i);
            // One row per fire: the bar is its strength, the text on it its name.
            const std::string label = fmt::format("{}: {}", name,
                                                  strength > 0.0f ? fmt::format("{} strikes", fireStrikes(s.world, FireId{i}))
                                                                  : std::string("out"));
            ImGui::ProgressBar(strength, ImVec2(-1.0f, 0.0f), label.c_str());
            shown.fires.push_back(name);
        }
    }
    if (bodyCount(s.world) > 0 && ImGui::CollapsingHeader("Bodies", ImGuiTreeNodeFlags_DefaultOpen)) {
        // Moving bodies a line each, with where they are; the fixed ones
        // (scenery, kinematic ones too) share a line to keep the panel short.
        std::string fixed;
        for (const BodySnapshot& b : readBodies(s.world)) {
            const std::string name = nameOr(b.name, "body", b.id.index);
            if (b.dynamic) {
                ImGui::Text("%s (%.2f, %.2f)", name.c_str(), b.position.x, b.position.y);
            } else {
                fixed += (fixed.empty() ? "fixed: " : ", ") + name;
            }
            shown.bodies.push_back(name);
        }
        if (!fixed.empty()) ImGui::TextWrapped("%s", fixed.c_str());
    }
    if (fluidCount(s.world) > 0 && ImGui::CollapsingHeader("Fluids")) fluidSettings(s);
    if (!s.emitters.empty() && ImGui::CollapsingHeader("Emitters")) emitterSettings(s);
    if (ImGui::CollapsingHeader("Keys")) {
        ImGui::TextWrapped("H hides this panel, Space pauses, N steps, R restarts, Esc quits. Drag to orbit or pan, "
                           "scroll to zoom; the right button aims a 2D fluid jet. In 2D: drag a body to move it; "
                           "Shift + left pours fluid, Shift + right removes it.");
    }
    shown.shown = true;
    shown.pos = ImGui::GetWindowPos();
    shown.size = ImGui::GetWindowSize();
    ImGui::End();
    return shown;
}

// Over the frame's bottom edge, wrapped to the window.
void loadErrorBox(const std::string& error) {
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(0.5f * display.x, display.y - 8.0f), ImGuiCond_Always, ImVec2(0.5f, 1.0f));
    ImGui::SetNextWindowSizeConstraints(ImVec2(0.0f, 0.0f), ImVec2(display.x - 16.0f, 0.5f * display.y));
    ImGui::SetNextWindowBgAlpha(0.9f);
    ImGui::Begin("scene error", nullptr,
                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoFocusOnAppearing);
    ImGui::PushTextWrapPos(display.x - 32.0f);
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
    ImGui::TextUnformatted(error.c_str());
    ImGui::PopStyleColor();
    ImGui::TextDisabled("The last scene that loaded keeps playing; saving the file again reloads it.");
    ImGui::PopTextWrapPos();
    ImGui::End();
}

}  // namespace spindrift::app
