// A scene file rendered to a PNG: loads a TOML scene, simulates one second
// and draws the last frame with the Vulkan renderer (Mesa's lavapipe does it
// on the CPU where there is no GPU).
//   render_png [scene.toml] [out.png]
#include <spindrift/render.h>
#include <spindrift/scene.h>

#include <stb/stb_image_write.h>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
    using namespace spindrift;
    const std::string scenePath = argc > 1 ? argv[1] : "scene.toml";
    const std::string pngPath = argc > 2 ? argv[2] : "frame.png";
    try {
        const SceneDef scene = loadScene(scenePath);  // throws SceneError with file:line:col
        const WorldId world = buildWorld(scene);
        const RendererId renderer = createRenderer(world, scene.render);  // [camera] and [render]

        const int steps = static_cast<int>(1.0f / scene.run.dt + 0.5f);
        for (int i = 0; i < steps; ++i) stepWorld(world, scene.run.dt);
        const Frame frame = renderFrame(renderer);  // RGBA8, sRGB, top row first
        const RenderStats stats = renderStats(renderer);

        const int width = static_cast<int>(frame.width), height = static_cast<int>(frame.height);
        if (stbi_write_png(pngPath.c_str(), width, height, 4, frame.rgba.data(), width * 4) == 0) {
            std::fprintf(stderr, "render_png: cannot write %s\n", pngPath.c_str());
            return 1;
        }
        std::printf("wrote %s: %dx%d, %llu sprites, %llu splats after %.2f s\n", pngPath.c_str(), width, height,
                    static_cast<unsigned long long>(stats.sprites), static_cast<unsigned long long>(stats.splats),
                    worldTime(world));
        destroyRenderer(renderer);
        destroyWorld(world);
    } catch (const Error& e) {
        std::fprintf(stderr, "render_png: %s\n", e.what());
        return 1;
    }
    return 0;
}
