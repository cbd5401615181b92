// A step of the Vulkan backend's world: birth schedules, one submission of
// every emitter's passes, frames in flight and their timestamps, and
// collecting a finished step's counts and events.
#include "gpu/gpu_world_parts.h"

#include "core/saturating.h"
#include "gpu/vulkan_pipeline.h"
#include "particles/birth_schedule.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>

namespace spindrift::gpu {
namespace {

// Writes the spawn emitter's schedule for this step into its mapped buffer
// (read by the emit pass after the submission; host writes before
// vkQueueSubmit need no barrier) and returns how many births it owes.
std::uint32_t writeSchedule(GpuEmitter& e, std::uint32_t frame, EmitterState& s, double time, float dt) {
    BirthSchedule b = scheduleBirths(s, time, dt);
    // At most the capacity (kEmitterMaxCapacity < 2^32); the births beyond it
    // are counted with the step's device counters when they are collected.
    const auto total = static_cast<std::uint32_t>(b.total());
    static_assert(kEmitterMaxCapacity <= std::numeric_limits<std::uint32_t>::max());
    e.scheduleDropped[frame] = b.dropped;
    const ScheduleHeader h = b.header();
    auto* runs = reinterpret_cast<std::uint32_t*>(static_cast<char*>(e.schedules[frame].mapped) + sizeof(h));
    std::uint32_t end = 0;
    for (std::size_t r = 0; r < b.bursts.size(); ++r) {
        end += b.bursts[r].count;
        runs[2 * r] = end;
        std::memcpy(&runs[2 * r + 1], &b.bursts[r].age, 4);
    }
    std::memcpy(e.schedules[frame].mapped, &h, sizeof(h));
    return static_cast<std::uint32_t>(total);
}

void bindEmitter(GpuWorld& w, VkCommandBuffer cmd, std::uint32_t frame, std::size_t index, float time, float dt,
                 std::uint32_t count, float inherit = 0.0f) {
    GpuEmitter& e = *w.emitters[index];
    std::array<VkDescriptorSet, 3> sets{e.descriptorSets[frame],
                                        e.spawn ? e.listSets[e.parity][frame] : w.placeholderSet, w.fields.set};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, w.pipelineLayout, 0, 3, sets.data(), 0, nullptr);
    StepPush push{dt, count, static_cast<std::uint32_t>(index), time, e.trailPoints, e.trailHead,
                  e.step, e.requestKinds, inherit, 0, 0, 0};
    vkCmdPushConstants(cmd, w.pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
}

std::uint32_t groupsFor(std::uint32_t threads) { return (threads + kWorkgroupSize - 1) / kWorkgroupSize; }

// Takes a finished step's counts out of the mapped counters and zeroes them
// for the step that reuses the frame.
void collectCounters(GpuEmitter& e, std::uint32_t frame, EmitterState& s, StepStats& stats) {
    StepCounters c;
    std::memcpy(&c, e.counters[frame].mapped, sizeof(c));
    std::memset(e.counters[frame].mapped, 0, sizeof(c));
    for (std::size_t k = 0; k < stats.colliderHits.size() && k < kernels::SD_MAX_COLLIDERS; ++k) {
        stats.colliderHits[k].hits += c.hits[k];
    }
    s.alive = s.alive + c.born - c.died - c.nonFinite;
    stats.born += c.born;
    stats.died += c.died;
    stats.nonFinite += c.nonFinite;
    stats.clamped = saturatingAdd(stats.clamped, saturatingAdd(c.clamped, e.scheduleDropped[frame]));
    e.scheduleDropped[frame] = 0;
    if (e.spawn) {
        // Every birth of a spawn emitter but the sub-emitted ones came from
        // the emit pass, numbered from the device's nextSerial in schedule
        // order, as the CPU does.
        s.nextSerial += c.born - c.subBorn;
    }
}

// Takes a finished step's events out of the frame's mapped buffer.
void collectEvents(GpuFrame& f, EventQueue& events) {
    EventsHeader h;
    std::memcpy(&h, f.events.mapped, sizeof(h));
    const std::uint32_t kept = std::min(h.count, h.capacity);
    const auto* records =
        reinterpret_cast<const kernels::EventRecord*>(static_cast<const char*>(f.events.mapped) + sizeof(h));
    events.addStep(f.step, std::span(records, kept), h.count - kept);
    h.count = 0;
    std::memcpy(f.events.mapped, &h, sizeof(h));
}

// Waits for frame f's step (if one is pending) and frees its command buffer.
bool waitForFrame(Device& d, GpuFrame& f) {
    if (f.cmd == VK_NULL_HANDLE) {
        return false;
    }
    check(vkWaitForFences(d.device, 1, &f.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    check(vkResetFences(d.device, 1, &f.fence), "vkResetFences");
    vkFreeCommandBuffers(d.device, d.commandPool, 1, &f.cmd);
    f.cmd = VK_NULL_HANDLE;
    return true;
}

// Device time (ms) of frame f's finished step, from its two timestamps.
double deviceMilliseconds(GpuWorld& w, std::uint32_t frame) {
    if (w.timestamps == VK_NULL_HANDLE) {
        return 0.0;
    }
    std::uint64_t ticks[2] = {0, 0};
    VkResult r = vkGetQueryPoolResults(w.device->device, w.timestamps, 2 * frame, 2, sizeof(ticks), ticks,
                                       sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT);
    check(r, "vkGetQueryPoolResults");
    return static_cast<double>(ticks[1] - ticks[0]) * w.timestampPeriodNs * 1e-6;
}

}  // namespace

// The compute queue's timestamps, if it has any: a pool of two per frame.
void createTimestamps(GpuWorld& w) {
    Device& d = *w.device;
    std::uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &families, nullptr);
    std::vector<VkQueueFamilyProperties> properties(families);
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &families, properties.data());
    if (properties.at(d.queueFamily).timestampValidBits == 0) {
        return;
    }
    auto info = vkStruct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2 * kMaxFramesInFlight;
    check(vkCreateQueryPool(d.device, &info, nullptr, &w.timestamps), "vkCreateQueryPool");
    w.timestampPeriodNs = d.properties.limits.timestampPeriod;
}

namespace {

// Waits for frame f's step, if any, and collects its counts and events. The
// fence wait makes the device's writes to host-coherent memory visible (the
// step ends with a barrier to the host stage; Vulkan spec 7.9).
void collectFrame(GpuWorld& w, std::uint32_t frame, std::span<const std::unique_ptr<EmitterState>> emitters,
                  StepStats& stats, EventQueue& events) {
    GpuFrame& f = w.frames[frame];
    const std::uint64_t step = f.step;
    if (!waitForFrame(*w.device, f)) {
        return;
    }
    for (std::size_t i = 0; i < w.emitters.size(); ++i) {
        if (w.emitters[i]) {
            collectCounters(*w.emitters[i], frame, *emitters[i], stats);
        }
    }
    collectEvents(f, events);
    stats.deviceMilliseconds += deviceMilliseconds(w, frame);
    stats.countedSteps += 1;
    stats.lastCountedStep = step;
}

}  // namespace

void waitForSteps(GpuWorld& w) {
    for (std::uint32_t f = 0; f < w.framesInFlight; ++f) {
        GpuFrame& frame = w.frames[f];
        if (frame.cmd != VK_NULL_HANDLE) {
            check(vkWaitForFences(w.device->device, 1, &frame.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        }
    }
}

void collectAll(GpuWorld& w, std::span<const std::unique_ptr<EmitterState>> emitters, StepStats& stats,
                EventQueue& events) {
    // Frames are reused round robin: the next to submit holds the oldest
    // pending step (or none).
    for (std::uint32_t k = 0; k < w.framesInFlight; ++k) {
        collectFrame(w, static_cast<std::uint32_t>((w.submitted + k) % w.framesInFlight), emitters, stats, events);
    }
}

void stepEmitters(GpuWorld& w, std::span<const std::unique_ptr<EmitterState>> emitters, double time, float dt,
                  std::uint64_t step, StepStats& stats, EventQueue& events) {
    Device& d = *w.device;
    // This frame's counters, schedules and events buffer were last used by
    // step `step - framesInFlight`, collected at the end of the previous call.
    const auto frame = static_cast<std::uint32_t>(w.submitted % w.framesInFlight);

    // Births owed this step, per emitter (spawn mode), from the shared schedule.
    std::vector<std::uint32_t> births(w.emitters.size(), 0);
    // The pipelines of each emitter's passes (compiled here on first use, not
    // while recording).
    std::vector<std::array<VkPipeline, 4>> pipelines(w.emitters.size());
    bool anySpawn = false;
    for (std::size_t i = 0; i < w.emitters.size(); ++i) {
        GpuEmitter* e = w.emitters[i].get();
        if (!e || e->capacity == 0) {
            continue;
        }
        e->trailHead = emitters[i]->trailHead;
        e->step = static_cast<std::uint32_t>(step);
        e->requestKinds = emitters[i]->requestKinds;
        if (e->spawn) {
            births[i] = writeSchedule(*e, frame, *emitters[i], time, dt);
            anySpawn = true;
            pipelines[i] = {pipelineFor(w, Pass::SpawnUpdate, *emitters[i]),
                            pipelineFor(w, Pass::SpawnEmit, *emitters[i]),
                            pipelineFor(w, Pass::SpawnFinish, *emitters[i]),
                            e->parent >= 0 ? pipelineFor(w, Pass::SubEmit, *emitters[i]) : VK_NULL_HANDLE};
        } else {
            pipelines[i][0] = pipelineFor(w, Pass::RecycleUpdate, *emitters[i]);
        }
    }
    auto spawning = [&](std::size_t i) {
        GpuEmitter* e = w.emitters[i].get();
        return e && e->spawn && e->capacity > 0;
    };

    VkCommandBuffer cmd = beginOneTime(d);
    if (w.timestamps != VK_NULL_HANDLE) {
        vkCmdResetQueryPool(cmd, w.timestamps, 2 * frame, 2);
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, w.timestamps, 2 * frame);
    }
    // This step's spawn requests start empty: the count zeroed once the
    // previous step's passes are done reading it.
    bool anyRequests = false;
    for (const auto& e : w.emitters) {
        for (std::uint32_t kind = 0; e && kind < kernels::SD_SPAWN_EVENT_KINDS; ++kind) {
            if (e->requests[kind].buffer != VK_NULL_HANDLE) {
                if (!anyRequests) {
                    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, 0);
                    anyRequests = true;
                }
                vkCmdFillBuffer(cmd, e->requests[kind].buffer, 0, 4, 0u);
            }
        }
    }
    // Earlier steps' and uploads' writes (lists, the indirect dispatch)
    // before this step reads them, also as an indirect command.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);

    // Update: recycle emitters over every slot, spawn emitters over their
    // current alive list (its size written by the GPU last step). Emitters
    // touch disjoint buffers and only add to shared counters atomically, so
    // the dispatches of one pass need no barrier between them.
    for (std::size_t i = 0; i < w.emitters.size(); ++i) {
        GpuEmitter* e = w.emitters[i].get();
        if (e && e->capacity > 0) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines[i][0]);
            bindEmitter(w, cmd, frame, i, static_cast<float>(time), dt, e->capacity);
            if (e->spawn) {
                vkCmdDispatchIndirect(cmd, e->dead.buffer, 0);
            } else {
                vkCmdDispatch(cmd, groupsFor(e->capacity), 1, 1);
            }
        }
    }
    if (anySpawn) {
        // Emit: the dead stack is complete once every update is done.
        computeToCompute(cmd);
        for (std::size_t i = 0; i < w.emitters.size(); ++i) {
            if (spawning(i) && births[i] > 0) {
                vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines[i][1]);
                bindEmitter(w, cmd, frame, i, static_cast<float>(time), dt, births[i]);
                // Births beyond the capacity cannot find a slot: thread 0
                // counts them, so the dispatch stays within the device limit.
                vkCmdDispatch(cmd, groupsFor(std::min(births[i], w.emitters[i]->capacity)), 1, 1);
            }
        }
        // Sub-emit: each sub-emitter's births from its parent's requests of
        // this step, in emitter order with a barrier after each, so that a
        // sub-emitter's own requests (a chain) are complete before its
        // children read them. One thread per slot of its capacity.
        computeToCompute(cmd);
        for (std::size_t i = 0; i < w.emitters.size(); ++i) {
            if (spawning(i) && w.emitters[i]->parent >= 0) {
                const SpawnOnDef& on = emitters[i]->def.spawnOn;
                vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines[i][3]);
                bindEmitter(w, cmd, frame, i, static_cast<float>(time), dt, on.count, on.inheritVelocity);
                vkCmdDispatch(cmd, groupsFor(w.emitters[i]->capacity), 1, 1);
                computeToCompute(cmd);
            }
        }
        // Finish: pop the taken slots, number the births, write the next
        // update's dispatch.
        for (std::size_t i = 0; i < w.emitters.size(); ++i) {
            if (spawning(i)) {
                vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines[i][2]);
                bindEmitter(w, cmd, frame, i, static_cast<float>(time), dt, births[i]);
                vkCmdDispatch(cmd, 1, 1, 1);
            }
        }
        // The next step's update reads the dispatch and the lists.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    }
    // Counters and events are read through the mapping after the fence: make
    // the shader's writes available to the host (Vulkan spec 7.9, host access).
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
            VK_ACCESS_HOST_READ_BIT);
    if (w.timestamps != VK_NULL_HANDLE) {
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, w.timestamps, 2 * frame + 1);
    }
    VkResult r = vkEndCommandBuffer(cmd);
    if (r == VK_SUCCESS) {
        auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        r = vkQueueSubmit(d.queue, 1, &submit, w.frames[frame].fence);
    }
    if (r != VK_SUCCESS) {
        vkFreeCommandBuffers(d.device, d.commandPool, 1, &cmd);
        check(r, "vkQueueSubmit(step)");
    }
    w.frames[frame].cmd = cmd;
    w.frames[frame].step = step;
    w.submitted += 1;
    for (auto& e : w.emitters) {
        if (e && e->spawn) {
            e->parity = 1 - e->parity;  // the next list becomes the current one
        }
    }
    // Collect step `step - (framesInFlight - 1)`, whose frame the next call
    // reuses: with one frame that is this step (a wait), with more an earlier
    // one that is usually done, so the host and the device overlap.
    collectFrame(w, static_cast<std::uint32_t>(w.submitted % w.framesInFlight), emitters, stats, events);
}

}  // namespace spindrift::gpu
