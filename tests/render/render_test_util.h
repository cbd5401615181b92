// Shared helpers of the renderer tests: a renderer owned by the test,
// sRGB arithmetic (IEC 61966-2-1) to predict pixel values independently of
// the shaders, and PNG dumps for looking at a failure.
#pragma once

#include "gpu/gpu_test_util.h"

#include <spindrift/render.h>
#include <spindrift/scene.h>

#include <stb/stb_image_write.h>

#include <cmath>
#include <cstdlib>
#include <string>

namespace spindrift::test {

struct ScopedRenderer {
    ScopedRenderer(WorldId world, const RenderDef& def) : id(createRenderer(world, def)) {}
    ~ScopedRenderer() { destroyRenderer(id); }
    ScopedRenderer(const ScopedRenderer&) = delete;
    ScopedRenderer& operator=(const ScopedRenderer&) = delete;
    RendererId id;
};

/// The sRGB transfer function, as a PNG viewer decodes: linear -> encoded.
inline double srgbEncode(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}
inline double srgbDecode(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}
/// 8-bit value of a linear intensity.
inline int srgbByte(double linear) { return static_cast<int>(std::lround(srgbEncode(linear) * 255.0)); }

inline const std::uint8_t* pixel(const Frame& f, std::uint32_t x, std::uint32_t y) {
    return &f.rgba[(std::size_t{y} * f.width + x) * 4];
}

/// A view down -z at the xy plane, `orthoHeight` m from bottom to top, over
/// one background colour, for closed forms of linear light: the tone map a
/// plain clamp, no bloom (tests/render/light_test.cpp tests both).
inline RenderDef orthoView(std::uint32_t width, std::uint32_t height, float orthoHeight,
                           glm::vec3 background = glm::vec3(0.0f)) {
    RenderDef def;
    def.width = width;
    def.height = height;
    def.camera.eye = {0.0f, 0.0f, 5.0f};
    def.camera.target = {0.0f, 0.0f, 0.0f};
    def.camera.orthographic = true;
    def.camera.orthoHeight = orthoHeight;
    def.background.kind = BackgroundKind::Colour;
    def.background.colour = background;
    def.toneMap = ToneMap::None;
    def.bloom = 0.0f;
    return def;
}

/// A world whose bodies do not fall (nothing moves between frames).
inline WorldId worldWithoutBodyGravity() {
    WorldDef wd;
    wd.bodyGravity = glm::vec2(0.0f);
    return createWorld(wd);
}

/// A static box 0.6 x 0.4 m centred at (0, 0.4): in orthoView(64, 64, 2) it
/// covers pixels 22 to 41 across and 13 to 25 down; 2D bodies are drawn as
/// slabs whose front face is at z = 0.5 m, normal +z.
inline BodyDef staticBox() {
    BodyDef box;
    box.type = BodyType::Static;
    box.position = {0.0f, 0.4f};
    box.shapes = {boxShape({0.3f, 0.2f})};
    return box;
}

/// Writes `f` to $SPINDRIFT_RENDER_DUMP/<name>.png when that variable is set
/// (to look at what a test saw).
inline void dumpFrame(const Frame& f, const std::string& name) {
    if (const char* dir = std::getenv("SPINDRIFT_RENDER_DUMP")) {
        std::string path = std::string(dir) + "/" + name + ".png";
        stbi_write_png(path.c_str(), static_cast<int>(f.width), static_cast<int>(f.height), 4, f.rgba.data(),
                       static_cast<int>(f.width * 4));
    }
}

}  // namespace spindrift::test
