// The number-density ratio (measureFluidNumberDensity in <spindrift/fluid.h>)
// over bare positions, for the API and the tests.
#pragma once

#include <spindrift/fluid.h>

#include <cstdint>
#include <span>
#include <vector>

namespace spindrift::fluid {

/// R / spacing of the count (2 or 3 dimensions); see number_density.cpp.
double numberDensityRadius(std::uint32_t dimension);
/// Points (i, j[, k]) of the integer lattice within numberDensityRadius of the
/// origin, the origin included: 45 in 2D, 251 in 3D.
std::uint32_t numberDensityReference(std::uint32_t dimension);

/// Per point, the count of points (itself included) within R = radius x
/// spacing, over numberDensityReference: the ratios in input order. In 2D z
/// is ignored.
std::vector<double> numberDensityRatios(std::span<const glm::vec3> position, std::uint32_t dimension,
                                        float spacing);

/// Median and 95th percentile of numberDensityRatios (nearest rank: element
/// floor(q (n - 1)) of the sorted ratios); zeros for no points.
FluidNumberDensity measureNumberDensity(std::span<const glm::vec3> position, std::uint32_t dimension,
                                        float spacing);

}  // namespace spindrift::fluid
