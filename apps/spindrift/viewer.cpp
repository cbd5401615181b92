// `spindrift view`: the scene in a GLFW window. Each frame steps the world by
// the wall time since the last one, in whole steps of dt (playback.h), unless
// paused; records the renderer's offscreen frame, blits its colour
// target into the acquired swapchain image, draws a Dear ImGui panel over it in
// a small render pass of its own, and presents. One frame in flight: the
// renderer's host-visible buffers (uniforms, splats, sprite copies) are single,
// so the host waits for the previous frame before it writes them again.
//
// Restart (R) and a reload of the changed scene file rebuild everything Vulkan
// from the scene: a CPU world's renderer owns its device, so the surface,
// swapchain and ImGui's Vulkan objects die with it. The window and ImGui's
// context live for the whole session. The panel is viewer_panel.cpp.
//
// Over 500 lines: the window, its input, the camera and the hand on bodies
// and fluid, and the frame loop share one session and one script of test
// input; each part is a few short functions.
#include "viewer.h"
#include "viewer_panel.h"
#include "viewer_session.h"

#include "playback.h"
#include "presenter.h"
#include "validation_report.h"
#include "view_script.h"

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
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace spindrift::app {
namespace {

using gpu::check;
using gpu::vkStruct;

// Window and input ------------------------------------------------------------------

/// What the callbacks saw since the last frame; consumed by the loop.
struct Input {
    bool togglePause = false, quit = false, restart = false, togglePanel = false;
    int steps = 0;         // single steps asked for while paused
    double scroll = 0.0;   // wheel notches, up positive
    bool resized = false;
};

Input& inputOf(GLFWwindow* window) { return *static_cast<Input*>(glfwGetWindowUserPointer(window)); }

/// A key pressed (`repeat`: held down), from GLFW or a test script.
void pressKey(Input& in, int key, bool repeat) {
    switch (key) {
        case GLFW_KEY_ESCAPE: in.quit = true; break;
        case GLFW_KEY_SPACE: if (!repeat) in.togglePause = true; break;
        case GLFW_KEY_N:
        case GLFW_KEY_RIGHT: ++in.steps; break;
        case GLFW_KEY_R: if (!repeat) in.restart = true; break;
        case GLFW_KEY_H: if (!repeat) in.togglePanel = true; break;
        default: break;
    }
}

// Installed before ImGui's, which chains to them: they see every event, and
// skip those ImGui wants (typing in a field, scrolling the panel).
void onKey(GLFWwindow* window, int key, int, int action, int) {
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    if (ImGui::GetCurrentContext() != nullptr && ImGui::GetIO().WantCaptureKeyboard) return;
    pressKey(inputOf(window), key, action == GLFW_REPEAT);
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
    for (const FireDef& fire : scene.fires) s.fireNames.push_back(fire.name);
}

void refreshAlive(Session& s) {
    for (std::uint32_t i = 0; i < s.emitters.size(); ++i) {
        s.alive[i] = readParticles(s.world, EmitterId{i + 1}).count();
    }
}

/// The scene file with the command line's overrides; throws SceneError.
SceneDef loadViewScene(const ViewOptions& o) {
    SceneDef scene = loadScene(o.scene);
    if (!o.backend.empty()) {
        scene.world.backend = o.backend == "vulkan" ? Backend::Vulkan : o.backend == "auto" ? Backend::Auto : Backend::Cpu;
    }
    if (o.width > 0) scene.render.width = o.width;
    if (o.height > 0) scene.render.height = o.height;
    validateRenderDef(scene.render);
    return scene;
}

/// What identifies a version of the scene file on disk; a change of either
/// (or the file vanishing, as while an editor renames its copy into place)
/// makes the viewer load it again.
struct FileStamp {
    bool exists = false;
    std::filesystem::file_time_type time{};
    std::uintmax_t size = 0;
    bool operator==(const FileStamp&) const = default;
};

FileStamp stampOf(const std::string& path) {
    std::error_code error;
    FileStamp stamp;
    stamp.time = std::filesystem::last_write_time(path, error);
    if (error) return FileStamp{};
    stamp.size = std::filesystem::file_size(path, error);
    if (error) return FileStamp{};
    stamp.exists = true;
    return stamp;
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

// Loop --------------------------------------------------------------------------------------

/// The mouse as the loop reads it: from GLFW, or from a test script once
/// the script has moved it (Xvfb has no mouse to press).
struct Pointer {
    double x = 0.0, y = 0.0;  // window units
    bool left = false, right = false, middle = false, shift = false;
};

Pointer readPointer(GLFWwindow* window) {
    Pointer p;
    glfwGetCursorPos(window, &p.x, &p.y);
    p.left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    p.right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    p.middle = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    p.shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    return p;
}

/// Mouse drag since the last frame, unless ImGui has the mouse.
struct Drag {
    bool active = false;
    double x = 0.0, y = 0.0;
};

/// `leftTaken`: the left button holds a body or the brush, not the camera.
void applyCamera(Session& s, GLFWwindow* window, const Pointer& pointer, bool leftTaken, Drag& drag, Input& in) {
    const double x = pointer.x, y = pointer.y;
    const bool down = pointer.left && !leftTaken;
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

/// The world point (xy) under the pointer in an orthographic view (beyond
/// the frame's edges too); none in a perspective one.
std::optional<glm::vec2> pointerInWorld(const Session& s, GLFWwindow* window, const Pointer& pointer) {
    const render::Renderer& r = render::rendererOf(s.renderer);
    const CameraDef& c = r.def.camera;
    if (!c.orthographic) return std::nullopt;
    // Cursor (window units) to swapchain pixels, then into the letterboxed frame.
    double x = pointer.x, y = pointer.y;
    int ww = 0, wh = 0;
    glfwGetWindowSize(window, &ww, &wh);
    const VkExtent2D extent = s.presenter.chain.extent;
    if (ww <= 0 || wh <= 0) return std::nullopt;
    x *= double(extent.width) / ww;
    y *= double(extent.height) / wh;
    const VkOffset3D lo = fitted(r.target.width, r.target.height, extent, false);
    const VkOffset3D hi = fitted(r.target.width, r.target.height, extent, true);
    if (hi.x <= lo.x || hi.y <= lo.y) return std::nullopt;
    const float u = float((x - lo.x) / (hi.x - lo.x) * 2.0 - 1.0);
    const float v = float(1.0 - (y - lo.y) / (hi.y - lo.y) * 2.0);
    const glm::vec3 forward = glm::normalize(c.target - c.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, c.up));
    const glm::vec3 up = glm::cross(right, forward);
    const float halfHeight = 0.5f * c.orthoHeight;
    const float aspect = float(r.target.width) / float(r.target.height);
    return glm::vec2(c.target + right * (u * halfHeight * aspect) + up * (v * halfHeight));
}

/// Right mouse button in an orthographic view: the first 2D fluid jet aims at
/// the cursor (its aim keys are replaced from then on; aimFluidJet).
void aimWithMouse(Session& s, GLFWwindow* window, const Pointer& pointer) {
    if (!pointer.right || pointer.shift || ImGui::GetIO().WantCaptureMouse) return;
    FluidId jetFluid{};
    for (std::uint32_t f = 1; f <= fluidCount(s.world) && jetFluid.index == 0; ++f) {
        const FluidDef& def = fluidDef(s.world, FluidId{f});
        if (def.dimension == 2 && !def.jets.empty()) jetFluid = FluidId{f};
    }
    if (jetFluid.index == 0) return;
    const std::optional<glm::vec2> point = pointerInWorld(s, window, pointer);
    if (!point) return;
    const FluidJetPose pose = fluidJetPose(s.world, jetFluid, 0);
    const glm::vec2 d = *point - pose.nozzle;
    if (glm::length(d) < 1e-4f) return;
    aimFluidJet(s.world, jetFluid, 0, std::atan2(d.y, d.x) - pose.frameAngle);
}

/// The body the left button holds, if any.
struct Hand {
    bool holding = false;
    GrabId grab{};
};

/// Brush radius in the fluid's spacings: a few particles across, so a
/// stroke makes a stream, not a flood.
constexpr float kBrushSpacings = 3.0f;

/// Mouse on the world in orthographic views of 2D scenes: a left press on a
/// dynamic body grabs it (createGrab) and drags it to the pointer until
/// released; with Shift held the left button pours fluid into the first 2D
/// fluid (pourFluid) and the right one removes it (removeFluid). Returns
/// whether the left button was used here (then the camera leaves it).
bool handOnWorld(Session& s, GLFWwindow* window, const Pointer& pointer, bool leftWasDown, Hand& hand) {
    const std::optional<glm::vec2> at = pointerInWorld(s, window, pointer);
    if (hand.holding) {
        if (pointer.left && at) {
            moveGrab(s.world, hand.grab, *at);
        } else if (!pointer.left) {
            destroyGrab(s.world, hand.grab);
            hand = Hand{};
        }
        return true;
    }
    if (!at || ImGui::GetIO().WantCaptureMouse) return false;
    if (pointer.shift) {
        FluidId fluid{};
        for (std::uint32_t f = 1; f <= fluidCount(s.world) && fluid.index == 0; ++f) {
            if (fluidDef(s.world, FluidId{f}).dimension == 2) fluid = FluidId{f};
        }
        if (fluid.index == 0) return false;
        const float radius = kBrushSpacings * fluidDef(s.world, fluid).spacing;
        if (pointer.left) pourFluid(s.world, fluid, glm::vec3(*at, 0.0f), radius);
        if (pointer.right) removeFluid(s.world, fluid, glm::vec3(*at, 0.0f), radius);
        return pointer.left;
    }
    if (pointer.left && !leftWasDown) {  // a press, not a drag that began elsewhere
        const BodyId body = bodyAt(s.world, *at);
        if (body.index == 0) return false;
        GrabDef def;
        def.body = body;
        def.point = *at;
        hand.grab = createGrab(s.world, def);
        hand.holding = true;
        return true;
    }
    return false;
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

/// The test script's input and checks at the start of `frame`.
struct ScriptPlayer {
    std::vector<ScriptLine> lines;
    std::size_t next = 0;
    std::optional<Pointer> pointer;  // set by the first pointer command

    /// Runs the lines of `frame`; `report` is called for each `report`.
    template <class Report>
    void play(std::uint64_t frame, Input& in, Report&& report) {
        for (; next < lines.size() && lines[next].frame <= frame; ++next) {
            const ScriptLine& line = lines[next];
            const auto need = [&](std::size_t n) {
                if (line.args.size() != n) {
                    throw Error(fmt::format("view script, frame {}: {} takes {} arguments", line.frame, line.command, n));
                }
            };
            const auto button = [&](bool down) {
                need(1);
                Pointer& p = pointer ? *pointer : pointer.emplace();
                const std::string& b = line.args[0];
                if (b == "left") {
                    p.left = down;
                } else if (b == "right") {
                    p.right = down;
                } else if (b == "middle") {
                    p.middle = down;
                } else {
                    throw Error(fmt::format("view script, frame {}: no button '{}' (left, right, middle)", line.frame, b));
                }
            };
            if (line.command == "key") {
                need(1);
                const std::string& k = line.args[0];
                const int key = k == "space" ? GLFW_KEY_SPACE : k == "n" ? GLFW_KEY_N : k == "r" ? GLFW_KEY_R
                              : k == "h" ? GLFW_KEY_H : k == "escape" ? GLFW_KEY_ESCAPE : GLFW_KEY_UNKNOWN;
                if (key == GLFW_KEY_UNKNOWN) throw Error(fmt::format("view script, frame {}: no key '{}'", line.frame, k));
                pressKey(in, key, false);
            } else if (line.command == "pointer") {
                need(2);
                Pointer& p = pointer ? *pointer : pointer.emplace();
                p.x = std::stod(line.args[0]);
                p.y = std::stod(line.args[1]);
            } else if (line.command == "press") {
                button(true);
            } else if (line.command == "release") {
                button(false);
            } else if (line.command == "shift") {
                need(1);
                Pointer& p = pointer ? *pointer : pointer.emplace();
                p.shift = line.args[0] == "on";
            } else if (line.command == "copy") {
                need(2);
                std::filesystem::copy_file(line.args[0], line.args[1],
                                           std::filesystem::copy_options::overwrite_existing);
            } else if (line.command == "report") {
                report();
            } else {
                throw Error(fmt::format("view script, frame {}: unknown command '{}'", line.frame, line.command));
            }
        }
    }
};

std::string joined(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
    return text;
}

}  // namespace

int viewCommand(const ViewOptions& o) {
    SceneDef scene = loadViewScene(o);  // before any window: a bad file is just an error
    FileStamp stamp = stampOf(o.scene);
    ScriptPlayer script;
    if (!o.script.empty()) script.lines = loadViewScript(o.script);

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
        bool paused = false, recreate = false, submitted = false, panelShown = true;
        Drag drag;
        Input& in = window.input;
        Playback playback;
        playback.dt = scene.run.dt;
        std::string loadError;  // of the last reload that failed; empty once one loads
        PanelShown lastPanel;
        Hand hand;
        bool leftWasDown = false;
        const auto started = std::chrono::steady_clock::now();
        auto lastFrame = started;

        // Rebuilds world, renderer and presenter from `next`, keeping the
        // camera as the user left it; on a failure to build, the scene that
        // ran before comes back.
        const auto rebuild = [&](const SceneDef& next) {
            const CameraDef camera = render::rendererOf(s.renderer).def.camera;
            stopSession(s);
            try {
                startSession(s, next, window.handle);
                scene = next;
                loadError.clear();
            } catch (const Error& e) {
                loadError = e.what();
                startSession(s, scene, window.handle);
            }
            setRenderCamera(s.renderer, camera);
            hand = Hand{};  // its grab went with the old world
            playback.dt = scene.run.dt;
            resetPlayback(playback);
            lastFrame = std::chrono::steady_clock::now();
            submitted = false;
        };
        const auto report = [&] {
            int ww = 0, wh = 0;
            glfwGetWindowSize(window.handle, &ww, &wh);
            const CameraDef& c = render::rendererOf(s.renderer).def.camera;
            std::uint64_t particles = 0;
            for (std::uint32_t f = 1; f <= fluidCount(s.world); ++f) particles += readFluid(s.world, FluidId{f}).count();
            fmt::print("report {} time: {:.6f}\n", frames, worldTime(s.world));
            fmt::print("report {} wall: {:.6f}\n", frames,
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
            fmt::print("report {} speed: {:.4f}\n", frames, playback.speed);
            fmt::print("report {} paused: {}\n", frames, paused ? 1 : 0);
            fmt::print("report {} window: {} {}\n", frames, ww, wh);
            fmt::print("report {} panel: {} {:.0f} {:.0f} {:.0f} {:.0f}\n", frames, lastPanel.shown ? 1 : 0,
                       lastPanel.pos.x, lastPanel.pos.y, lastPanel.size.x, lastPanel.size.y);
            fmt::print("report {} fires: {}\n", frames, joined(lastPanel.fires));
            fmt::print("report {} bodies: {}\n", frames, joined(lastPanel.bodies));
            fmt::print("report {} camera: {:.4f} {:.4f} {:.4f} {:.4f}\n", frames, c.eye.x, c.eye.y, c.eye.z,
                       c.orthoHeight);
            fmt::print("report {} fluid particles: {}\n", frames, particles);
            for (const BodySnapshot& b : readBodies(s.world)) {
                if (b.dynamic) fmt::print("report {} body {}: {:.4f} {:.4f}\n", frames, b.name, b.position.x, b.position.y);
            }
            fmt::print("report {} error: {}\n", frames, loadError);
            std::fflush(stdout);
        };

        while (glfwWindowShouldClose(window.handle) == GLFW_FALSE && !in.quit && (o.frames == 0 || frames < o.frames)) {
            glfwPollEvents();
            script.play(frames, in, report);
            const Pointer pointer = script.pointer ? *script.pointer : readPointer(window.handle);

            // The scene file changed on disk (checked every frame: one stat).
            if (const FileStamp now = stampOf(o.scene); !(now == stamp)) {
                stamp = now;
                std::optional<SceneDef> next;
                try {
                    next = loadViewScene(o);
                } catch (const Error& e) {
                    loadError = e.what();  // the scene that runs keeps running
                }
                if (next) {
                    rebuild(*next);
                    in = Input{};
                    continue;
                }
            }
            if (in.restart) {
                rebuild(scene);
                in = Input{};
                continue;
            }
            if (in.togglePause) {
                paused = !paused;
                resetPlayback(playback);  // time spent paused is not owed
            }
            in.togglePause = false;
            if (in.togglePanel) panelShown = !panelShown;
            in.togglePanel = false;

            // The previous frame: done before its buffers are written again.
            Presenter& p = s.presenter;
            check(vkWaitForFences(p.d->device, 1, &p.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
            if (submitted) render::readFrameTimes(render::rendererOf(s.renderer));
            if (recreate || in.resized) {
                recreateSwapchain(p, window.handle);
                recreate = in.resized = false;
            }

            const auto frameStart = std::chrono::steady_clock::now();
            const double wall = std::chrono::duration<double>(frameStart - lastFrame).count();
            lastFrame = frameStart;
            const int steps = paused ? in.steps : advancePlayback(playback, wall);
            in.steps = 0;
            for (int i = 0; i < steps; ++i) {
                s.last = stepWorld(s.world, scene.run.dt);
                s.simMs = s.last.milliseconds;
            }
            // readParticles copies back from the device: a few times a second.
            if (frames % 15 == 0 || (paused && steps > 0)) refreshAlive(s);

            const bool leftTaken = handOnWorld(s, window.handle, pointer, leftWasDown, hand);
            leftWasDown = pointer.left;
            applyCamera(s, window.handle, pointer, leftTaken, drag, in);
            aimWithMouse(s, window.handle, pointer);
            ImGui_ImplVulkan_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            if (script.pointer) {
                // ImGui sees the scripted pointer too, so the panel takes
                // what lands on it as a user's click would be.
                ImGuiIO& io = ImGui::GetIO();
                io.MousePos = ImVec2(float(pointer.x), float(pointer.y));
                io.MouseDown[0] = pointer.left;
                io.MouseDown[1] = pointer.right;
                io.MouseDown[2] = pointer.middle;
            }
            ImGui::NewFrame();
            lastPanel = panelShown ? panel(s, paused, playback) : PanelShown{};
            if (!loadError.empty()) loadErrorBox(loadError);
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
