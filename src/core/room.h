// Scratch vectors that are resized every substep: room grown by half again
// when it runs out, never given back. `std::vector::assign` allocates exactly
// what is asked for (libstdc++'s `resize` grows by half or more), so a size
// that creeps up a little each substep (a fluid's grid while a stream falls
// off a level) reallocated on every one, and at a megabyte each allocation
// was fresh memory from the kernel: a page fault per 4 KB, 18 % of the
// showcase's time in the grid's counting sort (perf; docs/performance.md,
// "Seventh session of 2026-12-05").
#pragma once

#include <cstddef>
#include <vector>

namespace spindrift {

/// Makes room for n elements in v, growing by at least half its capacity.
template <class T>
void keepRoomFor(std::vector<T>& v, std::size_t n) {
    if (v.capacity() < n) v.reserve(n > v.capacity() + v.capacity() / 2 ? n : v.capacity() + v.capacity() / 2);
}

/// v = n copies of value, in room kept from substep to substep.
template <class T>
void assignInRoom(std::vector<T>& v, std::size_t n, const T& value) {
    keepRoomFor(v, n);
    v.assign(n, value);
}

/// v = [first, last), in room kept from substep to substep.
template <class T, class It>
void assignInRoom(std::vector<T>& v, It first, It last) {
    keepRoomFor(v, static_cast<std::size_t>(last - first));
    v.assign(first, last);
}

}  // namespace spindrift
