// Turning kernel event records into the public ParticleEvent.
#include "particles/event_queue.h"

#include <algorithm>

namespace spindrift {

void EventQueue::addStep(std::uint64_t step, std::span<const kernels::EventRecord> records, std::uint64_t dropped) {
    batch.dropped += dropped;
    for (const kernels::EventRecord& r : records) {
        ParticleEvent e;
        e.kind = r.header.x == kernels::SD_EVENT_KIND_DEATH ? ParticleEventKind::Death : ParticleEventKind::Collision;
        e.step = step;
        e.collider = {r.header.y};
        e.emitter = {r.header.z + 1};
        e.birth = r.header.w;
        e.position = glm::vec3(r.positionSpeed);
        e.speed = r.positionSpeed.w;
        batch.events.push_back(e);
    }
}

void EventQueue::trimUntaken() {
    const std::size_t keep = static_cast<std::size_t>(capacity) * kUntakenEventSteps;
    if (batch.events.size() <= 2 * keep) return;
    const std::size_t drop = batch.events.size() - keep;
    batch.events.erase(batch.events.begin(), batch.events.begin() + static_cast<std::ptrdiff_t>(drop));
    batch.dropped += drop;
}

void EventQueue::beginStep() {
    trimUntaken();
    stepStrikes.clear();
}

void EventQueue::addEvents(std::span<const ParticleEvent> events) {
    stepStrikes.insert(stepStrikes.end(), events.begin(), events.end());
    const std::size_t kept = std::min<std::size_t>(events.size(), capacity);
    batch.events.insert(batch.events.end(), events.begin(), events.begin() + static_cast<std::ptrdiff_t>(kept));
    batch.dropped += events.size() - kept;
}

}  // namespace spindrift
