// The GPU-visible structs of src/kernels/types.glsl must have their std430 sizes
// and offsets on the C++ side too, or the GPU would read garbage.
#include "kernels/types.glsl"

#include <cstddef>

namespace spindrift::kernels {

static_assert(sizeof(EventRecord) == 32);
static_assert(offsetof(EventRecord, header) == 16);
static_assert(sizeof(CurveParams) == 176);
static_assert(offsetof(CurveParams, times) == 128);
static_assert(offsetof(CurveParams, count) == 160);

static_assert(sizeof(EmitterParams) == 528);
static_assert(offsetof(EmitterParams, speedMin) == 96);
static_assert(offsetof(EmitterParams, shapeKind) == 144);
static_assert(offsetof(EmitterParams, emitterIndex) == 160);
static_assert(offsetof(EmitterParams, colorOverLife) == 176);
static_assert(offsetof(EmitterParams, sizeOverLife) == 352);

static_assert(sizeof(ForceParams) == 112);
static_assert(offsetof(ForceParams, kind) == 80);
static_assert(offsetof(ForceParams, falloff) == 96);

static_assert(sizeof(ColliderParams) == 144);
static_assert(offsetof(ColliderParams, kind) == 112);
static_assert(offsetof(ColliderParams, marchStep) == 132);

}  // namespace spindrift::kernels
