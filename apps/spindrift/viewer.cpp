// `spindrift view`: the scene in a GLFW window. Each frame steps the world
// (unless paused), records the renderer's offscreen frame, blits its colour
// target into the acquired swapchain image, draws a Dear ImGui panel over it in
// a small render pass of its own, and presents. One frame in flight: the
// renderer's host-visible buffers (uniforms, splats, sprite copies) are single,
// so the host waits for the previous frame before it writes them again.
//
// Restart (R) rebuilds everything Vulkan from the scene: a CPU world's renderer
// owns its device, so the surface, swapchain and ImGui's Vulkan objects die
// with it. The window and ImGui's context live for the whole session.
#include "viewer.h"

#include "presenter.h"
#include "validation_report.h"

#include "fluid/fluid_rules.h"
#include "gpu/device_settings.h"
#include "gpu/vulkan_device.h"
#include "render/render_target.h"
#include "render/renderer.h"

#include <spindrift/fires.h>
#include <spindrift/render.h>
#include <spindrift/scene.h>
#include <spindrift/world.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <fmt/format.h>
#include <imgui.h>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace spindrift::app {
namespace {

using gpu::check;
using gpu::vkStruct;

// Window and input ------------------------------------------------------------------

/// What the callbacks saw since the last frame; consumed by the loop.
struct Input {
    bool togglePause = false, quit = false, restart = false;
    int steps = 0;         // single steps asked for while paused
    double scroll = 0.0;   // wheel notches, up positive
    bool resized = false;
};

Input& inputOf(GLFWwindow* window) { return *static_cast<Input*>(glfwGetWindowUserPointer(window)); }

// Installed before ImGui's, which chains to them: they see every event, and
// skip those ImGui wants (typing in a field, scrolling the panel).
void onKey(GLFWwindow* window, int key, int, int action, int) {
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    if (ImGui::GetCurrentContext() != nullptr && ImGui::GetIO().WantCaptureKeyboard) return;
    Input& in = inputOf(window);
    switch (key) {
        case GLFW_KEY_ESCAPE: in.quit = true; break;
        case GLFW_KEY_SPACE: if (action == GLFW_PRESS) in.togglePause = true; break;
        case GLFW_KEY_N:
        case GLFW_KEY_RIGHT: ++in.steps; break;
        case GLFW_KEY_R: if (action == GLFW_PRESS) in.restart = true; break;
        default: break;
    }
}

void onScroll(GLFWwindow* window, double, double y) {
    if (ImGui::GetCurrentContext() != nullptr && ImGui::GetIO().WantCaptureMouse) return;
    inputOf(window).scroll += y;
}

void onResize(GLFWwindow* window, int, int) { inputOf(window).resized = true; }

void onGlfwError(int code, const char* text) { std::fprintf(stderr, "glfw error %d: %s\n", code, text); }

/// Owns glfwInit and the window.
struct Window {
    GLFWwindow* handle = nullptr;
    Input input;
    Window(std::uint32_t width, std::uint32_t height, const std::string& title) {
        glfwSetErrorCallback(onGlfwError);
        if (glfwInit() == GLFW_FALSE) {
            throw Error("view: cannot open a window (no display? set DISPLAY or run under xvfb-run)");
        }
        if (glfwVulkanSupported() == GLFW_FALSE) {
            glfwTerminate();
            throw Error("view: GLFW finds no Vulkan loader able to present");
        }
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
        handle = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
        if (handle == nullptr) {
            glfwTerminate();
            throw Error("view: glfwCreateWindow failed");
        }
        glfwSetWindowUserPointer(handle, &input);
        glfwSetKeyCallback(handle, onKey);
        glfwSetScrollCallback(handle, onScroll);
        glfwSetFramebufferSizeCallback(handle, onResize);
    }
    ~Window() {
        glfwDestroyWindow(handle);
        glfwTerminate();
    }
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;
};

// Session: world, renderer, presenter ----------------------------------------------------

struct Session {
    WorldId world{};
    RendererId renderer{};
    bool hasWorld = false, hasRenderer = false;
    Presenter presenter;
    std::vector<EmitterDef> emitters;     // as last applied (the panel edits copies)
    std::vector<std::uint64_t> alive;     // per emitter, refreshed now and then
    StepStats last;                       // of the last step
    double simMs = 0.0, frameMs = 0.0;
};

void stopSession(Session& s) {
    destroyPresenter(s.presenter);
    if (s.hasRenderer) destroyRenderer(s.renderer);
    if (s.hasWorld) destroyWorld(s.world);
    s = Session{};
}

void startSession(Session& s, const SceneDef& scene, GLFWwindow* window) {
    try {
        s.world = buildWorld(scene);
        s.hasWorld = true;
        s.renderer = createRenderer(s.world, scene.render);
        s.hasRenderer = true;
        s.presenter = createPresenter(*render::rendererOf(s.renderer).device, window);
    } catch (...) {
        stopSession(s);
        throw;
    }
    for (std::uint32_t i = 0; i < emitterCount(s.world); ++i) s.emitters.push_back(emitterDef(s.world, EmitterId{i + 1}));
    s.alive.assign(s.emitters.size(), 0);
}

void refreshAlive(Session& s) {
    for (std::uint32_t i = 0; i < s.emitters.size(); ++i) {
        s.alive[i] = readParticles(s.world, EmitterId{i + 1}).count();
    }
}

// Camera ---------------------------------------------------------------------------------

/// Mouse drag: orbit the target (perspective) or pan (orthographic); wheel:
/// dolly or zoom. `dx`, `dy` in pixels of a window `height` pixels tall.
CameraDef moveCamera(CameraDef c, double dx, double dy, double scroll, double height) {
    const glm::vec3 forward = glm::normalize(c.target - c.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, c.up));
    const glm::vec3 up = glm::cross(right, forward);
    const float zoom = std::pow(0.9f, float(scroll));
    if (c.orthographic) {
        const float perPixel = c.orthoHeight / float(std::max(height, 1.0));
        const glm::vec3 shift = (-float(dx) * right + float(dy) * up) * perPixel;
        c.eye += shift;
        c.target += shift;
        c.orthoHeight = std::clamp(c.orthoHeight * zoom, 1e-3f, 1e5f);
        return c;
    }
    glm::vec3 offset = c.eye - c.target;
    const float radians = glm::pi<float>() / float(std::max(height, 1.0));  // a window's height: half a turn
    offset = glm::angleAxis(-float(dx) * radians, glm::normalize(c.up)) * offset;
    // Pitch, stopping short of the poles where the view would flip over up.
    const glm::vec3 side = glm::normalize(glm::cross(glm::normalize(c.up), offset));
    const glm::vec3 pitched = glm::angleAxis(float(dy) * radians, side) * offset;
    if (std::abs(glm::dot(glm::normalize(pitched), glm::normalize(c.up))) < 0.99f) offset = pitched;
    const float distance = std::clamp(glm::length(offset) * zoom, 1e-3f, 1e5f);
    c.eye = c.target + glm::normalize(offset) * distance;
    return c;
}

// Panel ------------------------------------------------------------------------------------

void panel(Session& s, bool paused, std::uint64_t frames) {
    const RendererId rid = s.renderer;
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.8f);
    ImGui::Begin("spindrift", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::Text("%s  t = %.3f s  frame %llu", paused ? "paused" : "running", worldTime(s.world),
                static_cast<unsigned long long>(frames));
    ImGui::TextDisabled("Space pause, N step, R restart, drag/scroll camera, right button aims the jet, Esc quit");
    if (ImGui::CollapsingHeader("Statistics", ImGuiTreeNodeFlags_DefaultOpen)) {
        const RenderStats rs = renderStats(rid);
        ImGui::Text("sim %.2f ms/step   frame %.2f ms", s.simMs, s.frameMs);
        ImGui::Text("render: device %.2f ms (fluid %.2f, sprites %.2f), host %.2f ms", rs.totalDeviceMs, rs.fluidMs,
                    rs.spritesMs, rs.cpuMs);
        ImGui::Text("sprites %llu  splats %llu", static_cast<unsigned long long>(rs.sprites),
                    static_cast<unsigned long long>(rs.splats));
        for (const FluidStepStats& f : s.last.fluids) {
            ImGui::Text("fluid %u: %llu particles, density error mean %.2f%% max %.2f%%", f.fluid.index,
                        static_cast<unsigned long long>(f.particles), 100.0 * f.meanDensityError,
                        100.0 * f.maxDensityError);
        }
    }
    if (fireCount(s.world) > 0 && ImGui::CollapsingHeader("Fires", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (std::uint32_t i = 1; i <= fireCount(s.world); ++i) {
            const float strength = fireStrength(s.world, FireId{i});
            const std::string label = fmt::format("fire {}: {} strikes", i, fireStrikes(s.world, FireId{i}));
            ImGui::ProgressBar(strength, ImVec2(160.0f, 0.0f), strength > 0.0f ? nullptr : "out");
            ImGui::SameLine();
            ImGui::TextUnformatted(label.c_str());
        }
    }
    if (!s.last.fluids.empty() && ImGui::CollapsingHeader("Fluid splats")) {
        FluidRenderDef fluid = render::rendererOf(rid).def.fluid;
        bool changed = false;
        changed |= ImGui::Checkbox("size from density", &fluid.sizeFromDensity);
        changed |= ImGui::Checkbox("stretch", &fluid.stretch);
        changed |= ImGui::Checkbox("refraction", &fluid.refraction);
        changed |= ImGui::Checkbox("edges", &fluid.edges);
        changed |= ImGui::Checkbox("splashes", &fluid.splashes);
        changed |= ImGui::Checkbox("bubbles", &fluid.bubbles);
        changed |= ImGui::SliderFloat("opacity", &fluid.opacity, 0.05f, 1.0f);
        changed |= ImGui::SliderFloat("radius scale", &fluid.radiusScale, 0.25f, 4.0f);
        changed |= ImGui::ColorEdit3("colour", &fluid.colour.x);
        if (changed) setFluidRender(rid, fluid);
    }
    for (std::uint32_t f = 1; f <= fluidCount(s.world); ++f) {
        ImGui::PushID(int(1000 + f));
        const FluidDef& def = fluidDef(s.world, FluidId{f});
        if (ImGui::CollapsingHeader(fmt::format("fluid {} '{}' solver", f, def.name).c_str())) {
            int iterations = int(def.iterations);
            float baumgarte = def.baumgarte;
            // The ranges of the rules setFluidSolver checks (fluid_rules.h),
            // so a slider never offers a value the API refuses.
            namespace rules = fluid::rules;
            bool changed = ImGui::SliderInt("iterations", &iterations, int(rules::kIterations.bounds.min),
                                            int(rules::kIterations.bounds.max));
            changed |= ImGui::SliderFloat("baumgarte", &baumgarte, float(rules::kBaumgarte.bounds.min),
                                          float(rules::kBaumgarte.bounds.max));
            if (changed) setFluidSolver(s.world, FluidId{f}, std::uint32_t(iterations), baumgarte);
        }
        ImGui::PopID();
    }
    for (std::uint32_t i = 0; i < s.emitters.size(); ++i) {
        EmitterDef& e = s.emitters[i];
        ImGui::PushID(int(i));
        const std::string title = fmt::format("emitter {} '{}': {} alive###emitter", i + 1, e.name, s.alive[i]);
        if (ImGui::CollapsingHeader(title.c_str())) {
            if (e.stateless) {
                ImGui::TextDisabled("stateless: its closed form is fixed at creation");
            } else {
                // Only what acts at birth is live (setEmitterRate/Speed): both
                // backends then agree on every particle already alive.
                if (e.lifecycle == Lifecycle::Spawn && ImGui::DragFloat("rate /s", &e.rate, 1.0f, 0.0f, 1e6f)) {
                    e.rate = std::max(e.rate, 0.0f);
                    setEmitterRate(s.world, EmitterId{i + 1}, e.rate);
                }
                FloatRange speed = e.speed;
                if (ImGui::DragFloatRange2("speed m/s", &speed.min, &speed.max, 0.05f, 0.0f, 1e3f) &&
                    speed.min <= speed.max) {
                    setEmitterSpeed(s.world, EmitterId{i + 1}, speed);
                    e.speed = speed;
                }
            }
        }
        ImGui::PopID();
    }
    ImGui::End();
}

// Loop --------------------------------------------------------------------------------------

/// Mouse drag since the last frame, unless ImGui has the mouse.
struct Drag {
    bool active = false;
    double x = 0.0, y = 0.0;
};

void applyCamera(Session& s, GLFWwindow* window, Drag& drag, Input& in) {
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window, &x, &y);
    const bool down = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    if (down && !drag.active && ImGui::GetIO().WantCaptureMouse) return;  // a drag that starts on the panel
    double dx = 0.0, dy = 0.0;
    if (down && drag.active) {
        dx = x - drag.x;
        dy = y - drag.y;
    }
    drag = {down, x, y};
    if (dx == 0.0 && dy == 0.0 && in.scroll == 0.0) return;
    int w = 0, h = 0;
    glfwGetWindowSize(window, &w, &h);
    const CameraDef now = render::rendererOf(s.renderer).def.camera;
    setRenderCamera(s.renderer, moveCamera(now, dx, dy, in.scroll, double(h)));
    in.scroll = 0.0;
}

/// Right mouse button in an orthographic view: the first 2D fluid jet aims at
/// the cursor (its aim keys are replaced from then on; aimFluidJet).
void aimWithMouse(Session& s, GLFWwindow* window) {
    if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) != GLFW_PRESS || ImGui::GetIO().WantCaptureMouse) return;
    const render::Renderer& r = render::rendererOf(s.renderer);
    const CameraDef& c = r.def.camera;
    if (!c.orthographic) return;
    FluidId jetFluid{};
    for (std::uint32_t f = 1; f <= fluidCount(s.world) && jetFluid.index == 0; ++f) {
        const FluidDef& def = fluidDef(s.world, FluidId{f});
        if (def.dimension == 2 && !def.jets.empty()) jetFluid = FluidId{f};
    }
    if (jetFluid.index == 0) return;
    // Cursor (window units) to swapchain pixels, then into the letterboxed frame.
    double x = 0.0, y = 0.0;
    int ww = 0, wh = 0;
    glfwGetCursorPos(window, &x, &y);
    glfwGetWindowSize(window, &ww, &wh);
    const VkExtent2D extent = s.presenter.chain.extent;
    if (ww <= 0 || wh <= 0) return;
    x *= double(extent.width) / ww;
    y *= double(extent.height) / wh;
    const VkOffset3D lo = fitted(r.target.width, r.target.height, extent, false);
    const VkOffset3D hi = fitted(r.target.width, r.target.height, extent, true);
    if (hi.x <= lo.x || hi.y <= lo.y) return;
    const float u = float((x - lo.x) / (hi.x - lo.x) * 2.0 - 1.0);
    const float v = float(1.0 - (y - lo.y) / (hi.y - lo.y) * 2.0);
    const glm::vec3 forward = glm::normalize(c.target - c.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, c.up));
    const glm::vec3 up = glm::cross(right, forward);
    const float halfHeight = 0.5f * c.orthoHeight;
    const float aspect = float(r.target.width) / float(r.target.height);
    const glm::vec3 point = c.target + right * (u * halfHeight * aspect) + up * (v * halfHeight);
    const FluidJetPose pose = fluidJetPose(s.world, jetFluid, 0);
    const glm::vec2 d = glm::vec2(point) - pose.nozzle;
    if (glm::length(d) < 1e-4f) return;
    aimFluidJet(s.world, jetFluid, 0, std::atan2(d.y, d.x) - pose.frameAngle);
}

/// Records and submits one frame; false when the swapchain must be
/// recreated before anything can be shown.
bool drawFrame(Session& s, GLFWwindow* window, bool& recreate) {
    Presenter& p = s.presenter;
    gpu::Device& d = *p.d;
    render::Renderer& r = render::rendererOf(s.renderer);
    std::uint32_t index = 0;
    const VkResult acquired = vkAcquireNextImageKHR(d.device, p.chain.swapchain, UINT64_MAX, p.acquired,
                                                    VK_NULL_HANDLE, &index);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) return false;
    if (acquired != VK_SUBOPTIMAL_KHR) check(acquired, "vkAcquireNextImageKHR");
    recreate |= acquired == VK_SUBOPTIMAL_KHR;

    const auto start = std::chrono::steady_clock::now();
    render::prepareFrame(r);
    r.stats.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    (void)window;
    check(vkResetCommandBuffer(p.cmd, 0), "vkResetCommandBuffer");
    auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(p.cmd, &begin), "vkBeginCommandBuffer");
    render::recordFrame(r, p.cmd);
    recordPresent(p, r.target, index);
    check(vkEndCommandBuffer(p.cmd), "vkEndCommandBuffer");

    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;  // the first write to the image
    auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &p.acquired;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &p.cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &p.chain.rendered[index];
    check(vkResetFences(d.device, 1, &p.done), "vkResetFences");
    check(vkQueueSubmit(d.queue, 1, &submit, p.done), "vkQueueSubmit");

    auto present = vkStruct<VkPresentInfoKHR>(VK_STRUCTURE_TYPE_PRESENT_INFO_KHR);
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &p.chain.rendered[index];
    present.swapchainCount = 1;
    present.pSwapchains = &p.chain.swapchain;
    present.pImageIndices = &index;
    const VkResult presented = vkQueuePresentKHR(d.queue, &present);
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) {
        recreate = true;
    } else {
        check(presented, "vkQueuePresentKHR");
    }
    return true;
}

}  // namespace

int viewCommand(const ViewOptions& o) {
    SceneDef scene = loadScene(o.scene);  // before any window: a bad file is just an error
    if (!o.backend.empty()) {
        scene.world.backend = o.backend == "vulkan" ? Backend::Vulkan : o.backend == "auto" ? Backend::Auto : Backend::Cpu;
    }
    if (o.width > 0) scene.render.width = o.width;
    if (o.height > 0) scene.render.height = o.height;
    validateRenderDef(scene.render);

    Window window(scene.render.width, scene.render.height, "spindrift - " + o.scene);
    requestPresentation();
    gpu::worldDebugLog().clear();

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working directory
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(window.handle, true);
    struct ImGuiGuard {
        ~ImGuiGuard() {
            ImGui_ImplGlfw_Shutdown();
            ImGui::DestroyContext();
        }
    } imguiGuard;

    Session s;
    std::uint64_t frames = 0;
    try {
        startSession(s, scene, window.handle);
        bool paused = false, recreate = false, submitted = false;
        Drag drag;
        Input& in = window.input;
        while (glfwWindowShouldClose(window.handle) == GLFW_FALSE && !in.quit && (o.frames == 0 || frames < o.frames)) {
            glfwPollEvents();
            if (in.restart) {
                stopSession(s);
                startSession(s, scene, window.handle);
                in = Input{};
                submitted = false;
                continue;
            }
            if (in.togglePause) paused = !paused;
            in.togglePause = false;

            // The previous frame: done before its buffers are written again.
            Presenter& p = s.presenter;
            check(vkWaitForFences(p.d->device, 1, &p.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
            if (submitted) render::readFrameTimes(render::rendererOf(s.renderer));
            if (recreate || in.resized) {
                recreateSwapchain(p, window.handle);
                recreate = in.resized = false;
            }

            const auto frameStart = std::chrono::steady_clock::now();
            const int steps = paused ? in.steps : 1;
            in.steps = 0;
            for (int i = 0; i < steps; ++i) {
                s.last = stepWorld(s.world, scene.run.dt);
                s.simMs = s.last.milliseconds;
            }
            // readParticles copies back from the device: a few times a second.
            if (frames % 15 == 0 || (paused && steps > 0)) refreshAlive(s);

            applyCamera(s, window.handle, drag, in);
            aimWithMouse(s, window.handle);
            ImGui_ImplVulkan_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();
            panel(s, paused, frames);
            ImGui::Render();

            if (!drawFrame(s, window.handle, recreate)) {
                recreate = true;
                continue;
            }
            submitted = true;
            ++frames;
            s.frameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frameStart).count();
        }
        stopSession(s);
    } catch (...) {
        stopSession(s);
        throw;
    }

    return finishWithValidationReport(fmt::format("{} frames shown", frames));
}

}  // namespace spindrift::app
