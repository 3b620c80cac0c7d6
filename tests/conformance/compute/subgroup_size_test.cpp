// subgroup_size_test.cpp: the primitives must not depend on a subgroup size. Probes what the device runs (and
// prints it: lavapipe runs 8), checks the facts the kernels rely on, and shows that sizing the shared
// per-subgroup slots for any subgroup size from 1 up to the device minimum gives identical results.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <map>
#include <numeric>
#include <set>

#include "conformance/device_array.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/shader_library.hpp"

namespace idk::test {
namespace {

using conformance::DeviceArray;
using conformance::randomUints;

class SubgroupSizeTest : public GpuTest {};

TEST_F(SubgroupSizeTest, ProbeMatchesWhatTheKernelsAssume) {
    const vk::DeviceCapabilities& caps = ctx().capabilities();
    const uint32_t group = gpu::kComputeGroupSize;
    DeviceArray records(ctx(), group * 5, "subgroup probe");
    gpu::ProbePush push{records.array().buffer.value, 0};
    const vk::Pipeline& probe =
        shaders().compute({vk::ShaderId::conformance_subgroup_probe_comp, {}, sizeof(push), {{group, 1, 1}}});
    ctx().runImmediate([&](VkCommandBuffer cmd) {
        vk::bindPipeline(cmd, probe);
        ctx().bindless().bind(cmd);
        vk::pushConstants(cmd, ctx(), push);
        vkCmdDispatch(cmd, 1, 1, 1);
    });
    std::vector<uint32_t> raw = records.download<uint32_t>(group * 5);
    std::vector<gpu::SubgroupProbeRecord> r(group);
    std::memcpy(r.data(), raw.data(), raw.size() * 4);

    uint32_t size = r[0].subgroupSize;
    std::cout << "[ subgroups ] device '" << ctx().info().name << "': reported size " << caps.subgroupSize
              << " (min " << caps.minSubgroupSize << ", max " << caps.maxSubgroupSize << "), a 256-wide workgroup ran "
              << r[0].numSubgroups << " subgroups of " << size << "; kernels size shared slots for subgroups of "
              << render::resolvedSlotSubgroupSize({ctx(), shaders()}) << "\n";
    uint32_t slots = (group + render::resolvedSlotSubgroupSize({ctx(), shaders()}) - 1) /
                     render::resolvedSlotSubgroupSize({ctx(), shaders()});

    std::map<uint32_t, std::set<uint32_t>> lanesOf;  // subgroup id -> lanes seen
    for (uint32_t i = 0; i < group; ++i) {
        SCOPED_TRACE(i);
        ASSERT_EQ(r[i].numSubgroups, r[0].numSubgroups);
        ASSERT_GE(r[i].subgroupSize, std::max(caps.minSubgroupSize, 1u));
        ASSERT_LE(r[i].subgroupSize, std::max(caps.maxSubgroupSize, caps.subgroupSize));
        ASSERT_LT(r[i].subgroupId, r[i].numSubgroups);
        ASSERT_LT(r[i].subgroupInvocationId, r[i].subgroupSize);
        // What the shared-slot sizing relies on: every subgroup id has a slot.
        ASSERT_LE(r[i].numSubgroups, slots);
        ASSERT_TRUE(lanesOf[r[i].subgroupId].insert(r[i].subgroupInvocationId).second) << "lane seen twice";
    }
    ASSERT_EQ(lanesOf.size(), r[0].numSubgroups);
    uint32_t active = 0;
    for (const auto& [id, lanes] : lanesOf) {
        // subgroupAdd(1) agrees with the lanes that reported this subgroup id.
        for (uint32_t i = 0; i < group; ++i) {
            if (r[i].subgroupId == id) {
                ASSERT_EQ(r[i].subgroupSum, lanes.size()) << "subgroup " << id;
            }
        }
        active += uint32_t(lanes.size());
    }
    EXPECT_EQ(active, group);
}

TEST_F(SubgroupSizeTest, ResultsDoNotDependOnSlotSizing) {
    const uint32_t deviceMin = render::resolvedSlotSubgroupSize({ctx(), shaders()});
    const uint32_t n = 300001;
    std::vector<uint32_t> uints = randomUints(n, 0, 21);
    std::vector<float> floats(n);
    for (uint32_t i = 0; i < n; ++i) floats[i] = float(uints[i] >> 8) * 0x1p-20f;
    std::vector<uint32_t> index(n);
    std::iota(index.begin(), index.end(), 0u);

    DeviceArray u(ctx(), n, "uints"), f(ctx(), n, "floats"), scanned(ctx(), n, "scanned");
    DeviceArray keys(ctx(), n, "keys"), values(ctx(), n, "values");
    DeviceArray sums(ctx(), 2, "sums");
    DeviceArray scratch(ctx(),
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
        render::ComputeKernels k{ctx(), shaders(), slotSubgroupSize};
        keys.upload(uints);
        values.upload(index);
        // One submission per primitive: they share the scratch buffer.
        ctx().runImmediate([&](VkCommandBuffer cmd) {
            render::recordReduce(cmd, k, render::SumElement::Uint, u.array(), n, sums.array(0), scratch.array());
        });
        ctx().runImmediate([&](VkCommandBuffer cmd) {
            render::recordReduce(cmd, k, render::SumElement::Float, f.array(), n, sums.array(1), scratch.array());
        });
        ctx().runImmediate([&](VkCommandBuffer cmd) {
            render::recordExclusiveScan(cmd, k, u.array(), scanned.array(), n, scratch.array());
        });
        ctx().runImmediate([&](VkCommandBuffer cmd) {
            render::recordRadixSort(cmd, k, keys.array(), values.array(), n, scratch.array());
        });
        std::vector<uint32_t> s = sums.download<uint32_t>(2);
        return Result{s[0], s[1], scanned.download<uint32_t>(n), keys.download<uint32_t>(n),
                      values.download<uint32_t>(n)};
    };

    Result reference = run(0);  // the device minimum
    EXPECT_EQ(reference.uintSum, std::accumulate(uints.begin(), uints.end(), 0u));
    // Every sizing from "one slot per invocation" (no assumption) up to the device minimum gives the same bits:
    // the slot array only grows, the kernels only ever touch gl_NumSubgroups slots.
    for (uint32_t size = 1; size < deviceMin; size *= 2) {
        SCOPED_TRACE(size);
        Result r = run(size);
        EXPECT_EQ(r.uintSum, reference.uintSum);
        EXPECT_EQ(r.floatSumBits, reference.floatSumBits);
        EXPECT_EQ(r.scan, reference.scan);
        EXPECT_EQ(r.keys, reference.keys);
        EXPECT_EQ(r.values, reference.values);
    }
    // A sizing for larger subgroups than the device may run would overflow shared memory: rejected up front.
    EXPECT_THROW(render::resolvedSlotSubgroupSize({ctx(), shaders(), deviceMin * 2}), std::invalid_argument);
}

}  // namespace
}  // namespace idk::test
