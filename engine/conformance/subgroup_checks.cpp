// subgroup_checks.cpp: the compute primitives must not depend on a subgroup size. Probes what the device runs
// (lavapipe: 8), checks the facts the kernels rely on (ids, lanes, one shared slot per subgroup, subgroupAdd), and
// shows that sizing the shared per-subgroup slots for any subgroup size from 1 up to the device minimum gives
// bit-identical results. Moved here from tests/conformance/compute/subgroup_size_test.cpp.
#include <algorithm>
#include <cstring>
#include <map>
#include <numeric>
#include <set>

#include "conformance/conformance.hpp"
#include "conformance/device_array.hpp"
#include "vk/shader_library.hpp"

namespace idk::conformance {
namespace {

void probeMatchesAssumptions(CheckEnv& env, Verdict& v) {
    const vk::DeviceCapabilities& caps = env.ctx.capabilities();
    const uint32_t group = gpu::kComputeGroupSize;
    DeviceArray records(env.ctx, group * 5, "subgroup probe");
    gpu::ProbePush push{records.array().buffer.value, 0};
    const vk::Pipeline& probe =
        env.shaders.compute({vk::ShaderId::conformance_subgroup_probe_comp, {}, sizeof(push), {{group, 1, 1}}});
    env.ctx.runImmediate([&](VkCommandBuffer cmd) {
        vk::bindPipeline(cmd, probe);
        env.ctx.bindless().bind(cmd);
        vk::pushConstants(cmd, env.ctx, push);
        vkCmdDispatch(cmd, 1, 1, 1);
    });
    std::vector<uint32_t> raw = records.download<uint32_t>(group * 5);
    std::vector<gpu::SubgroupProbeRecord> r(group);
    std::memcpy(r.data(), raw.data(), raw.size() * 4);

    const uint32_t slotSize = render::resolvedSlotSubgroupSize({env.ctx, env.shaders});
    const uint32_t slots = (group + slotSize - 1) / slotSize;
    std::map<uint32_t, std::set<uint32_t>> lanesOf;  // subgroup id -> lanes seen
    for (uint32_t i = 0; i < group; ++i) {
        const std::string at = "invocation " + std::to_string(i) + ": ";
        const bool ok = v.expectEq(r[i].numSubgroups, r[0].numSubgroups, at + "numSubgroups") &&
                        v.expect(r[i].subgroupSize >= std::max(caps.minSubgroupSize, 1u), at + "size below the minimum") &&
                        v.expect(r[i].subgroupSize <= std::max(caps.maxSubgroupSize, caps.subgroupSize),
                                 at + "size above the maximum") &&
                        v.expect(r[i].subgroupId < r[i].numSubgroups, at + "subgroup id out of range") &&
                        v.expect(r[i].subgroupInvocationId < r[i].subgroupSize, at + "lane out of range") &&
                        // What the shared-slot sizing relies on: every subgroup id has a slot.
                        v.expect(r[i].numSubgroups <= slots, at + "more subgroups than shared slots") &&
                        v.expect(lanesOf[r[i].subgroupId].insert(r[i].subgroupInvocationId).second, at + "lane seen twice");
        if (!ok) return;
    }
    if (!v.expectEq(lanesOf.size(), size_t(r[0].numSubgroups), "subgroups seen")) return;
    uint32_t active = 0;
    for (const auto& [id, lanes] : lanesOf) {
        // subgroupAdd(1) agrees with the lanes that reported this subgroup id.
        for (uint32_t i = 0; i < group; ++i)
            if (r[i].subgroupId == id) v.expectEq(r[i].subgroupSum, uint32_t(lanes.size()), "subgroupAdd of subgroup " + std::to_string(id));
        active += uint32_t(lanes.size());
    }
    v.expectEq(active, group, "active invocations");
}

void resultsIndependentOfSlotSizing(CheckEnv& env, Verdict& v) {
    const uint32_t deviceMin = render::resolvedSlotSubgroupSize({env.ctx, env.shaders});
    const uint32_t n = 300001;
    std::vector<uint32_t> uints = randomUints(n, 0, 21);
    std::vector<float> floats(n);
    for (uint32_t i = 0; i < n; ++i) floats[i] = float(uints[i] >> 8) * 0x1p-20f;
    std::vector<uint32_t> index(n);
    std::iota(index.begin(), index.end(), 0u);

    DeviceArray u(env.ctx, n, "uints"), f(env.ctx, n, "floats"), scanned(env.ctx, n, "scanned");
    DeviceArray keys(env.ctx, n, "keys"), values(env.ctx, n, "values");
    DeviceArray sums(env.ctx, 2, "sums");
    DeviceArray scratch(env.ctx,
                        std::max({render::reduceScratchElements(n), render::exclusiveScanScratchElements(n),
                                  render::radixSortScratchElements(n, true)}),
                        "scratch");
    u.upload(uints);
    f.upload(floats);

    struct Result {
        uint32_t uintSum, floatSumBits;
        std::vector<uint32_t> scan, keys, values;
    };
    auto run = [&](uint32_t slotSubgroupSize) {
        render::ComputeKernels k{env.ctx, env.shaders, slotSubgroupSize};
        keys.upload(uints);
        values.upload(index);
        // One submission per primitive: they share the scratch buffer.
        env.ctx.runImmediate([&](VkCommandBuffer cmd) {
            render::recordReduce(cmd, k, render::SumElement::Uint, u.array(), n, sums.array(0), scratch.array());
        });
        env.ctx.runImmediate([&](VkCommandBuffer cmd) {
            render::recordReduce(cmd, k, render::SumElement::Float, f.array(), n, sums.array(1), scratch.array());
        });
        env.ctx.runImmediate([&](VkCommandBuffer cmd) {
            render::recordExclusiveScan(cmd, k, u.array(), scanned.array(), n, scratch.array());
        });
        env.ctx.runImmediate([&](VkCommandBuffer cmd) {
            render::recordRadixSort(cmd, k, keys.array(), values.array(), n, scratch.array());
        });
        std::vector<uint32_t> s = sums.download<uint32_t>(2);
        return Result{s[0], s[1], scanned.download<uint32_t>(n), keys.download<uint32_t>(n), values.download<uint32_t>(n)};
    };

    const Result reference = run(0);  // the device minimum
    v.expectEq(reference.uintSum, std::accumulate(uints.begin(), uints.end(), 0u), "uint sum");
    // Every sizing from "one slot per invocation" (no assumption) up to the device minimum gives the same bits:
    // the slot array only grows, the kernels only ever touch gl_NumSubgroups slots.
    for (uint32_t size = 1; size < deviceMin; size *= 2) {
        const std::string at = "slots sized for subgroups of " + std::to_string(size) + ": ";
        const Result r = run(size);
        v.expectEq(r.uintSum, reference.uintSum, at + "uint sum");
        v.expectEq(r.floatSumBits, reference.floatSumBits, at + "float sum bits");
        v.expect(r.scan == reference.scan, at + "scan differs");
        v.expect(r.keys == reference.keys, at + "sorted keys differ");
        v.expect(r.values == reference.values, at + "sorted values differ");
    }
    // A sizing for larger subgroups than the device may run would overflow shared memory: rejected up front.
    bool threw = false;
    try {
        render::resolvedSlotSubgroupSize({env.ctx, env.shaders, deviceMin * 2});
    } catch (const std::invalid_argument&) {
        threw = true;
    }
    v.expect(threw, "slots sized above the device minimum must be rejected");
}

}  // namespace

std::vector<Check> subgroupChecks() {
    return {
        {"subgroups/probe matches the kernels' assumptions", "", "exact", probeMatchesAssumptions},
        {"subgroups/results independent of slot sizing", "", "bit-identical", resultsIndependentOfSlotSizing},
    };
}

}  // namespace idk::conformance
