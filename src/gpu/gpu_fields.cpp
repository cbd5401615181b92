// The sampled fields of a Vulkan world (set 2 of effects_update.comp): flow
// fields, terrain height maps and depth cube maps as images with one linear
// clamp-to-edge sampler, uploaded once.
#include "gpu/gpu_world_parts.h"

#include "gpu/vulkan_pipeline.h"

#include <fmt/format.h>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <array>
#include <cstring>

namespace spindrift::gpu {
namespace {

// --- Sampled fields (set 2) ---------------------------------------------------
// Bindings of set 2 of effects_update.comp, one array of combined image
// samplers each, indexed by binding number: flowFields (sampler3D),
// heightMaps (sampler2D), cubeMaps (samplerCube).
static_assert(kernels::SD_BINDING_FLOW_FIELDS == 0 && kernels::SD_BINDING_HEIGHT_MAPS == 1 &&
              kernels::SD_BINDING_CUBE_MAPS == 2 && kernels::SD_FIELD_BINDINGS == 3);
constexpr std::array<std::uint32_t, 3> kFieldArraySizes{kMaxGpuFlowFields, kMaxGpuHeightMaps, kMaxGpuCubeMaps};
constexpr std::uint32_t kFieldDescriptors = kMaxGpuFlowFields + kMaxGpuHeightMaps + kMaxGpuCubeMaps;

// 32-bit float where the device filters it linearly (lavapipe and desktop GPUs
// do), else 16-bit float; UNDEFINED when neither.
VkFormat pickFloatFormat(const Device& d, VkFormat full, VkFormat half) {
    if (linearFilterable(d, full)) {
        return full;
    }
    return linearFilterable(d, half) ? half : VK_FORMAT_UNDEFINED;
}

bool isHalf(VkFormat f) { return f == VK_FORMAT_R16_SFLOAT || f == VK_FORMAT_R16G16B16A16_SFLOAT; }

// Texels as the image stores them: the floats as they are, or as halves.
std::vector<char> texelBytes(const float* values, std::size_t count, VkFormat format) {
    std::vector<char> bytes;
    if (isHalf(format)) {
        bytes.resize(count * 2);
        for (std::size_t i = 0; i < count; ++i) {
            std::uint16_t h = glm::packHalf1x16(values[i]);
            std::memcpy(bytes.data() + 2 * i, &h, 2);
        }
    } else {
        bytes.resize(count * 4);
        std::memcpy(bytes.data(), values, count * 4);
    }
    return bytes;
}


VkDescriptorSetLayout createFieldLayout(Device& d) {
    std::array<VkDescriptorSetLayoutBinding, 3> bindings{};
    for (std::uint32_t i = 0; i < 3; ++i) {
        bindings[i].binding = i;
        bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        bindings[i].descriptorCount = kFieldArraySizes[i];
        bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    auto info = vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    info.bindingCount = 3;
    info.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(d.device, &info, nullptr, &layout), "vkCreateDescriptorSetLayout(fields)");
    return layout;
}

// Points every element of set 2 at its field's image, or at the placeholder.
// Only between submissions: every submission has completed (submitOnce waits
// on its fence), so no pending command buffer uses the set.
void writeFieldSet(GpuWorld& w) {
    GpuFields& f = w.fields;
    std::array<VkDescriptorImageInfo, kFieldDescriptors> infos{};
    std::array<VkWriteDescriptorSet, 3> writes{};
    const std::array<const std::vector<Image>*, 3> images{&f.flows, &f.heights, &f.cubes};
    const std::array<const Image*, 3> placeholders{&f.placeholder3d, &f.placeholder2d, &f.placeholderCube};
    std::uint32_t at = 0;
    for (std::uint32_t b = 0; b < 3; ++b) {
        writes[b] = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        writes[b].dstSet = f.set;
        writes[b].dstBinding = b;
        writes[b].descriptorCount = kFieldArraySizes[b];
        writes[b].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        writes[b].pImageInfo = &infos[at];
        for (std::uint32_t i = 0; i < kFieldArraySizes[b]; ++i, ++at) {
            const Image& img = i < images[b]->size() ? (*images[b])[i] : *placeholders[b];
            infos[at] = {f.sampler, img.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        }
    }
    vkUpdateDescriptorSets(w.device->device, 3, writes.data(), 0, nullptr);
}

}  // namespace

void createFields(GpuWorld& w) {
    Device& d = *w.device;
    GpuFields& f = w.fields;
    f.flowFormat = pickFloatFormat(d, VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT);
    f.heightFormat = pickFloatFormat(d, VK_FORMAT_R32_SFLOAT, VK_FORMAT_R16_SFLOAT);
    f.cubeFormat = pickFloatFormat(d, VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT);
    f.sampler = createLinearSampler(d);
    f.layout = createFieldLayout(d);
    // Placeholders: R8G8B8A8_UNORM, which every device samples and filters
    // (Vulkan spec, "Required Format Support"); zeros, never read.
    const ImageShape shapes[3] = {{VK_IMAGE_VIEW_TYPE_3D, VK_FORMAT_R8G8B8A8_UNORM, 1, 1, 1},
                                  {VK_IMAGE_VIEW_TYPE_2D, VK_FORMAT_R8G8B8A8_UNORM, 1, 1, 1},
                                  {VK_IMAGE_VIEW_TYPE_CUBE, VK_FORMAT_R8G8B8A8_UNORM, 1, 1, 1}};
    Image* placeholders[3] = {&f.placeholder3d, &f.placeholder2d, &f.placeholderCube};
    for (int i = 0; i < 3; ++i) {
        *placeholders[i] = createSampledImage(d, shapes[i]);
        clearImage(d, *placeholders[i], shapes[i]);
    }
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kFieldDescriptors};
    auto poolInfo = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    check(vkCreateDescriptorPool(d.device, &poolInfo, nullptr, &f.pool), "vkCreateDescriptorPool(fields)");
    auto alloc = vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    alloc.descriptorPool = f.pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &f.layout;
    check(vkAllocateDescriptorSets(d.device, &alloc, &f.set), "vkAllocateDescriptorSets(fields)");
    writeFieldSet(w);
}

void destroyFields(Device& d, GpuFields& f) {
    if (f.pool != VK_NULL_HANDLE) {
        vkDestroyDescriptorPool(d.device, f.pool, nullptr);  // frees its set
    }
    for (std::vector<Image>* images : {&f.cubes, &f.heights, &f.flows}) {
        for (Image& img : *images) {
            destroyImage(d, img);
        }
        images->clear();
    }
    for (Image* img : {&f.placeholderCube, &f.placeholder2d, &f.placeholder3d}) {
        destroyImage(d, *img);
    }
    if (f.layout != VK_NULL_HANDLE) {
        vkDestroyDescriptorSetLayout(d.device, f.layout, nullptr);
    }
    if (f.sampler != VK_NULL_HANDLE) {
        vkDestroySampler(d.device, f.sampler, nullptr);
    }
    f = GpuFields{};
}

namespace {

// The checks every field shares, before anything is created.
void requireFieldRoom(const GpuWorld& w, const std::vector<Image>& images, std::uint32_t max, VkFormat format,
                      const char* what, const std::string& name) {
    const Device& d = *w.device;
    if (images.size() >= max) {
        throw Error(fmt::format("{} '{}': a vulkan world holds at most {} {}s", what, name, max, what));
    }
    if (format == VK_FORMAT_UNDEFINED) {
        throw Error(fmt::format("{} '{}': this Vulkan device ({}) cannot filter 32-bit or 16-bit float images "
                                "linearly; use backend 'cpu'",
                                what, name, d.properties.deviceName));
    }
}

void requireExtent(const Device& d, std::uint32_t size, std::uint32_t limit, const char* what,
                   const std::string& name) {
    if (size > limit) {
        throw Error(fmt::format("{} '{}': {} texels along an axis exceed this Vulkan device's limit of {} ({})", what,
                                name, size, limit, d.properties.deviceName));
    }
}

// Creates and uploads one field image; on failure nothing is left behind.
void appendField(GpuWorld& w, std::vector<Image>& images, const ImageShape& shape, const std::vector<char>& bytes) {
    waitForSteps(w);  // no step in flight may use the descriptor set rewritten below
    Device& d = *w.device;
    Image img = createSampledImage(d, shape);
    try {
        uploadImage(d, img, shape, bytes.data(), bytes.size());
        images.push_back(img);
    } catch (...) {
        destroyImage(d, img);
        throw;
    }
    writeFieldSet(w);
}

}  // namespace

void addFlowField(GpuWorld& w, const FlowGrid& grid, const std::string& name) {
    GpuFields& f = w.fields;
    requireFieldRoom(w, f.flows, kMaxGpuFlowFields, f.flowFormat, "flow field", name);
    const std::uint32_t limit = w.device->properties.limits.maxImageDimension3D;
    requireExtent(*w.device, std::max({grid.nx, grid.ny, grid.nz}), limit, "flow field", name);
    // x fastest, then y, then z: the layout of FlowGrid and of a 3D image copy.
    std::vector<glm::vec4> texels(grid.velocity.size());
    for (std::size_t i = 0; i < texels.size(); ++i) {
        texels[i] = glm::vec4(grid.velocity[i], 0.0f);
    }
    appendField(w, f.flows, {VK_IMAGE_VIEW_TYPE_3D, f.flowFormat, grid.nx, grid.ny, grid.nz},
                texelBytes(&texels.data()->x, texels.size() * 4, f.flowFormat));
}

void addHeightMap(GpuWorld& w, const HeightMap& map, const std::string& name) {
    GpuFields& f = w.fields;
    requireFieldRoom(w, f.heights, kMaxGpuHeightMaps, f.heightFormat, "height map", name);
    const std::uint32_t limit = w.device->properties.limits.maxImageDimension2D;
    requireExtent(*w.device, std::max(map.nx, map.nz), limit, "height map", name);
    // x fastest, then z: image x is the terrain's x, image y its z.
    appendField(w, f.heights, {VK_IMAGE_VIEW_TYPE_2D, f.heightFormat, map.nx, map.nz, 1},
                texelBytes(map.height.data(), map.height.size(), f.heightFormat));
}

void addCubeMap(GpuWorld& w, const DepthCubeMap& cube, const std::string& name) {
    GpuFields& f = w.fields;
    requireFieldRoom(w, f.cubes, kMaxGpuCubeMaps, f.cubeFormat, "cube map", name);
    const std::uint32_t limit = w.device->properties.limits.maxImageDimensionCube;
    requireExtent(*w.device, cube.resolution, limit, "cube map", name);
    // Texel (face, u, v) at (face * res + v) * res + u: layer = face in Vulkan's
    // order (+x, -x, +y, -y, +z, -z; src/core/cube_map.h), row v, column u.
    appendField(w, f.cubes, {VK_IMAGE_VIEW_TYPE_CUBE, f.cubeFormat, cube.resolution, cube.resolution, 1},
                texelBytes(&cube.texels.data()->x, cube.texels.size() * 4, f.cubeFormat));
}

}  // namespace spindrift::gpu
