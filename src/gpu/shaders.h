// SPIR-V of src/gpu/shaders/*.comp and src/render/shaders/*, compiled by glslc at build time and
// embedded by src/gpu/embed_spirv.cmake (see CMakeLists.txt).
#pragma once

#include <cstddef>
#include <cstdint>

namespace spindrift::gpu::shaders {
// effects_update.comp, one module per pass (CMakeLists.txt).
extern const std::uint32_t kEffectsUpdatePassRecycleUpdate[];
extern const std::size_t kEffectsUpdatePassRecycleUpdateWords;
extern const std::uint32_t kEffectsUpdatePassSpawnUpdate[];
extern const std::size_t kEffectsUpdatePassSpawnUpdateWords;
extern const std::uint32_t kEffectsUpdatePassSpawnEmit[];
extern const std::size_t kEffectsUpdatePassSpawnEmitWords;
extern const std::uint32_t kEffectsUpdatePassSpawnFinish[];
extern const std::size_t kEffectsUpdatePassSpawnFinishWords;
extern const std::uint32_t kEffectsUpdatePassSubEmit[];
extern const std::size_t kEffectsUpdatePassSubEmitWords;
extern const std::uint32_t kBackToFrontSort[];
extern const std::size_t kBackToFrontSortWords;
extern const std::uint32_t kFluidGrid[];
extern const std::size_t kFluidGridWords;
extern const std::uint32_t kFluidSetup[];
extern const std::size_t kFluidSetupWords;
extern const std::uint32_t kFluidSolve[];
extern const std::size_t kFluidSolveWords;
extern const std::uint32_t kFluidContacts[];
extern const std::size_t kFluidContactsWords;
extern const std::uint32_t kFluidIntegrate[];
extern const std::size_t kFluidIntegrateWords;
extern const std::uint32_t kFluidCarry[];
extern const std::size_t kFluidCarryWords;
// The renderer (src/render/shaders/).
extern const std::uint32_t kFluidWaterComp[];
extern const std::size_t kFluidWaterCompWords;
extern const std::uint32_t kBackgroundVert[];
extern const std::size_t kBackgroundVertWords;
extern const std::uint32_t kBackgroundFrag[];
extern const std::size_t kBackgroundFragWords;
extern const std::uint32_t kMeshVert[];
extern const std::size_t kMeshVertWords;
extern const std::uint32_t kMeshFrag[];
extern const std::size_t kMeshFragWords;
extern const std::uint32_t kSpritesVert[];
extern const std::size_t kSpritesVertWords;
extern const std::uint32_t kSpritesFrag[];
extern const std::size_t kSpritesFragWords;
extern const std::uint32_t kSpritesSoftFrag[];
extern const std::size_t kSpritesSoftFragWords;
extern const std::uint32_t kSpritesOitFrag[];
extern const std::size_t kSpritesOitFragWords;
extern const std::uint32_t kOitCompositeVert[];
extern const std::size_t kOitCompositeVertWords;
extern const std::uint32_t kOitCompositeFrag[];
extern const std::size_t kOitCompositeFragWords;
extern const std::uint32_t kSplatsVert[];
extern const std::size_t kSplatsVertWords;
extern const std::uint32_t kSplatsFrag[];
extern const std::size_t kSplatsFragWords;
extern const std::uint32_t kSurfaceFieldVert[];
extern const std::size_t kSurfaceFieldVertWords;
extern const std::uint32_t kSurfaceFieldFrag[];
extern const std::size_t kSurfaceFieldFragWords;
extern const std::uint32_t kSurfaceBlurFrag[];
extern const std::size_t kSurfaceBlurFragWords;
extern const std::uint32_t kSurfaceDepthFrag[];
extern const std::size_t kSurfaceDepthFragWords;
extern const std::uint32_t kSurfaceVert[];
extern const std::size_t kSurfaceVertWords;
extern const std::uint32_t kBloomThresholdFrag[];
extern const std::size_t kBloomThresholdFragWords;
extern const std::uint32_t kBloomBlurFrag[];
extern const std::size_t kBloomBlurFragWords;
extern const std::uint32_t kToneMapFrag[];
extern const std::size_t kToneMapFragWords;
extern const std::uint32_t kSurfaceFrag[];
extern const std::size_t kSurfaceFragWords;
extern const std::uint32_t kScreenFluidSphereVert[];
extern const std::size_t kScreenFluidSphereVertWords;
extern const std::uint32_t kScreenFluidDepthFrag[];
extern const std::size_t kScreenFluidDepthFragWords;
extern const std::uint32_t kScreenFluidThicknessFrag[];
extern const std::size_t kScreenFluidThicknessFragWords;
extern const std::uint32_t kScreenFluidSmoothFrag[];
extern const std::size_t kScreenFluidSmoothFragWords;
extern const std::uint32_t kScreenFluidFrag[];
extern const std::size_t kScreenFluidFragWords;
}  // namespace spindrift::gpu::shaders
