// Binning into the uniform grid (slide 46): a counting sort of the particles by
// cell and quadrant, then every particle array gathered into that order, so
// that neighbours sit close together in memory for the passes that follow.
#include "core/room.h"
#include "fluid/fluid_state.h"

#include <algorithm>
#include <type_traits>
#include <cmath>
#include <limits>

namespace spindrift::fluid {
namespace {

/// At most this many cells in the grid: a particle flung far away must not
/// make the grid (one counter per sub-cell) huge. Particles beyond the capped
/// grid are clamped into its edge cells, which keeps every neighbour pair in
/// adjacent sub-cells (clamping never increases a distance in cells).
std::size_t cellBudget(std::size_t particles) { return std::max<std::size_t>(1u << 16, 2 * particles); }

template <int D>
struct Bounds {
    Vec<D> lo{std::numeric_limits<float>::max()};
    Vec<D> hi{-std::numeric_limits<float>::max()};
};

template <int D>
Bounds<D> particleBounds(WorkerPool& pool, const std::vector<Vec<D>>& x) {
    std::vector<Bounds<D>> chunks(WorkerPool::chunkCount(x.size(), kParticleChunk));
    pool.forChunks(x.size(), kParticleChunk, [&](std::size_t c, std::size_t begin, std::size_t end) {
        Bounds<D> b;
        for (std::size_t i = begin; i < end; ++i) {
            b.lo = glm::min(b.lo, x[i]);
            b.hi = glm::max(b.hi, x[i]);
        }
        chunks[c] = b;
    });
    Bounds<D> all;  // min and max are exact: any combination order gives the same box
    for (const Bounds<D>& b : chunks) {
        all.lo = glm::min(all.lo, b.lo);
        all.hi = glm::max(all.hi, b.hi);
    }
    return all;
}

/// A particle array and the scratch it is gathered into.
template <class T>
struct GatherArray {
    std::vector<T>* live;
    std::vector<T>* sorted;
};

/// sorted[i] = live[order[i]] for i in [begin, end), for every array.
template <class T>
void gatherRange(const std::vector<GatherArray<T>>& arrays, const std::vector<std::uint32_t>& order, std::size_t begin,
                 std::size_t end) {
    for (const GatherArray<T>& a : arrays) {
        const T* from = a.live->data();
        T* to = a.sorted->data();
        for (std::size_t i = begin; i < end; ++i) to[i] = from[order[i]];
    }
}

/// x in 3D, for the kernels (z 0 in 2D).
template <int D>
glm::vec3 toVec3(Vec<D> x) {
    if constexpr (D == 2) {
        return glm::vec3(x, 0.0f);
    } else {
        return x;
    }
}

}  // namespace

/// The key of grid.cpp's sort (cell * 2^D + quadrant): kernels::fluidGridKey,
/// which the device's grid (src/gpu/gpu_fluid_grid.cpp) computes too.
template <int D>
std::uint32_t keyOf(const Grid<D>& g, Vec<D> x, float invH) {
    return kernels::fluidGridKey(toVec3<D>(x), D, toVec3<D>(g.origin), invH,
                                 glm::ivec3(g.cells[0], g.cells[1], g.cells[2]));
}

/// Where a capped grid starts along an axis: its window (`width` m, the cell
/// budget's cells) centred on the particles' median coordinate, kept inside
/// their box. Anchored at the box's low end instead, a few particles fallen
/// off a level (a stream leaving the showcase's right edge, 90 m down after
/// 9 s) moved the window below everything else, which was clamped into the
/// top row of cells: every particle of the level then searched one row of
/// sub-cells holding all of them, the crushed-cell bound cut their lists
/// (1.4e8 neighbour overflows in 9 s) and the automatic substeps went to 16.
/// The median is the bulk's as long as it holds most particles; the few
/// outside the window are clamped into its edge cells, which keeps every
/// neighbour pair in adjacent sub-cells.
float cappedWindowOrigin(float median, float lo, float hi, float width) {
    return std::max(lo, std::min(median - 0.5f * width, hi - width));  // hi - width may be below lo
}

template <int D>
float medianAlong(const std::vector<Vec<D>>& x, int a, std::vector<float>& scratch) {
    scratch.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) scratch[i] = x[i][a];
    const auto middle = scratch.begin() + static_cast<std::ptrdiff_t>(scratch.size() / 2);
    std::nth_element(scratch.begin(), middle, scratch.end());
    return *middle;
}

template <int D>
std::uint32_t placeGridInBox(Vec<D> lo, Vec<D> hi, std::size_t n, float h, Grid<D>& g) {
    if (n == 0) {
        lo = hi = Vec<D>(0.0f);
    }
    g.h = h;
    g.origin = lo;
    const double budget = static_cast<double>(cellBudget(n));
    const int axisCap = std::max(2, static_cast<int>(std::pow(budget, 1.0 / D)));
    g.cells = {1, 1, 1};
    std::uint32_t capped = 0;
    for (int a = 0; a < D; ++a) {
        const double span = static_cast<double>(hi[a]) - static_cast<double>(lo[a]);
        const double needed = span / (2.0 * h) + 1.0;
        g.cells[a] = static_cast<int>(std::clamp(needed, 1.0, static_cast<double>(axisCap)));
        if (needed > axisCap) capped |= 1u << a;
    }
    return capped;
}

template <int D>
void placeGrid(WorkerPool& pool, const std::vector<Vec<D>>& x, float h, Grid<D>& g) {
    // The grid covers the particles' box, capped at the cell budget.
    const Bounds<D> box = particleBounds<D>(pool, x);
    const std::uint32_t capped = placeGridInBox<D>(box.lo, box.hi, x.size(), h, g);
    for (int a = 0; a < D; ++a) {
        if ((capped & (1u << a)) != 0) {
            const float width = static_cast<float>(g.cells[a]) * 2.0f * h;
            g.origin[a] = cappedWindowOrigin(medianAlong<D>(x, a, g.scratchMedian), box.lo[a], box.hi[a], width);
        }
    }
}

template <int D>
void buildGrid(WorkerPool& pool, FluidState& f) {
    Particles<D>& p = f.particles<D>();
    Grid<D>& g = f.grid<D>();
    const std::size_t n = p.size();
    constexpr std::uint32_t kQuadrants = 1u << D;

    placeGrid<D>(pool, p.position, f.h, g);

    // Keys: cell and quadrant of every particle.
    const float invH = 1.0f / g.h;
    const std::size_t cellTotal = static_cast<std::size_t>(g.cells[0]) * g.cells[1] * g.cells[2];
    const std::size_t keyTotal = cellTotal * kQuadrants;
    {
        g.key.resize(n);
        pool.forChunks(n, kParticleChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) {
                g.key[i] = keyOf<D>(g, p.position[i], invH);
            }
        });
    }

    // Counting sort by key (stable, so equal keys keep their previous order and
    // the result does not depend on anything but the data).
    {
        assignInRoom(g.keyStart, keyTotal + 1, 0u);
        for (std::size_t i = 0; i < n; ++i) {
            g.keyStart[g.key[i] + 1] += 1;
        }
        for (std::size_t k = 0; k < keyTotal; ++k) {
            g.keyStart[k + 1] += g.keyStart[k];
        }
        assignInRoom(g.counts, g.keyStart.begin(), g.keyStart.end() - 1);
        g.order.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            g.order[g.counts[g.key[i]]++] = static_cast<std::uint32_t>(i);
        }
    }

    // Gather every particle array into grid order, all of them in one
    // parallel loop: a loop each (eight) cost more with two threads than
    // the gathers themselves, the grid taking 0.57 to 0.60 ms a step of the
    // 10k dam break against 0.50 with one thread (0.47 to 0.49 now).
    {
        std::vector<GatherArray<Vec<D>>> vecs;
        std::vector<GatherArray<float>> floats;
        std::vector<GatherArray<std::uint32_t>> uints;
        // The scratch arrays' addresses are taken once all exist (a resize
        // of the list of them moves them).
        const auto add = [&](auto& list, auto& scratch, auto& array) {
            if (scratch.size() <= list.size()) scratch.resize(list.size() + 1);
            list.push_back({&array, nullptr});
        };
        p.forEachKept([&](auto& array) {
            using Array = std::decay_t<decltype(array)>;
            if constexpr (std::is_same_v<Array, std::vector<float>>) {
                add(floats, g.scratchFloat, array);
            } else if constexpr (std::is_same_v<Array, std::vector<std::uint32_t>>) {
                add(uints, g.scratchUint, array);
            } else {
                add(vecs, g.scratchVec, array);
            }
        });
        add(uints, g.scratchUint, g.key);
        const auto place = [&](auto& list, auto& scratch) {
            for (std::size_t k = 0; k < list.size(); ++k) {
                scratch[k].resize(n);
                list[k].sorted = &scratch[k];
            }
        };
        place(vecs, g.scratchVec);
        place(floats, g.scratchFloat);
        place(uints, g.scratchUint);
        pool.forChunks(n, kParticleChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
            gatherRange(vecs, g.order, begin, end);
            gatherRange(floats, g.order, begin, end);
            gatherRange(uints, g.order, begin, end);
        });
        for (auto& a : vecs) a.live->swap(*a.sorted);
        for (auto& a : floats) a.live->swap(*a.sorted);
        for (auto& a : uints) a.live->swap(*a.sorted);
    }

    // Colour groups: non-empty cells by the parities of their coordinates.
    {
        for (auto& list : g.colourCells) {
            list.clear();
        }
        for (std::size_t cell = 0; cell < cellTotal; ++cell) {
            if (g.keyStart[cell * kQuadrants] == g.keyStart[(cell + 1) * kQuadrants]) {
                continue;
            }
            g.colourCells[colourOfCell(g, cell)].push_back(static_cast<std::uint32_t>(cell));
        }
    }
}

template float medianAlong<2>(const std::vector<Vec<2>>&, int, std::vector<float>&);
template float medianAlong<3>(const std::vector<Vec<3>>&, int, std::vector<float>&);
template std::uint32_t placeGridInBox<2>(Vec<2>, Vec<2>, std::size_t, float, Grid<2>&);
template std::uint32_t placeGridInBox<3>(Vec<3>, Vec<3>, std::size_t, float, Grid<3>&);
template void placeGrid<2>(WorkerPool&, const std::vector<Vec<2>>&, float, Grid<2>&);
template void placeGrid<3>(WorkerPool&, const std::vector<Vec<3>>&, float, Grid<3>&);
template void buildGrid<2>(WorkerPool&, FluidState&);
template void buildGrid<3>(WorkerPool&, FluidState&);

}  // namespace spindrift::fluid
