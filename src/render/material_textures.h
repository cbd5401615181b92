// The textures of colliders and bodies (SurfaceTexture): every distinct PNG
// as one layer of a 2D array image, all at the size of the largest (smaller
// ones resampled), with mip levels made on the host in linear light, sampled
// with repeat by mesh.frag. A body created later with a new texture grows
// the array (prepareBodies).
#pragma once

#include "gpu/vulkan_buffer.h"
#include "render/collider_mesh.h"

#include <spindrift/world.h>

namespace spindrift::render {

struct MaterialTextures {
    MaterialLayers paths;  // layer i's PNG
    gpu::Image image;      // the array; one white layer when there are no paths
    VkSampler sampler = VK_NULL_HANDLE;  // trilinear, repeat
};

/// The PNG paths of the world's textured colliders and bodies, each once, in
/// the order first met.
MaterialLayers surfaceTexturePaths(WorldId world);
/// Appends the bodies' paths that `paths` lacks; true when it added any.
bool addBodyTexturePaths(MaterialLayers& paths, const std::vector<BodySnapshot>& bodies);
/// Loads `paths` (throws Error naming a file that cannot be read) into `m`,
/// with its sampler on first use.
void createMaterialTextures(gpu::Device& d, MaterialTextures& m, const MaterialLayers& paths);
void destroyMaterialTextures(gpu::Device& d, MaterialTextures& m);

}  // namespace spindrift::render
