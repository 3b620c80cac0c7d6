// barrier_planner_model_test.cpp: random access sequences checked against an independent model of the
// Vulkan execution/memory dependency rules (a small "sync validation"): every RAW, WAR, WAW and layout
// transition hazard must be covered by the planned barriers, and every access must see the layout it needs.
#include "graph/barrier_planner.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <string>
#include <vector>

namespace idk::graph {
namespace {

constexpr VkPipelineStageFlags2 kAll = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;

bool stagesCovered(VkPipelineStageFlags2 have, VkPipelineStageFlags2 need) {
    return (have & kAll) != 0 || (have & need) == need;
}
bool inScope(VkPipelineStageFlags2 stages, VkPipelineStageFlags2 scope) {
    return (scope & kAll) != 0 || (stages & scope) != 0;
}

// One earlier access (or layout transition) as the model tracks it.
struct Earlier {
    VkPipelineStageFlags2 stages = 0;        // 0 for a layout transition (it happens inside a barrier)
    VkAccessFlags2 writes = 0;               // write bits it performed
    VkPipelineStageFlags2 orderedBefore = 0; // stages of later work it is ordered before (via barriers)
    bool available = false;
    std::map<VkAccessFlags2, VkPipelineStageFlags2> visible;   // access bit -> stages it is visible to
};

class Model {
public:
    explicit Model(VkImageLayout layout) : layout_(layout) {}
    std::string error;

    void barrier(const PlannedBarrier& b, bool isImage) {
        // Availability: writes inside the first access scope.
        for (Earlier& e : earlier_) {
            if (e.writes && e.stages && inScope(e.stages, b.srcStages) && (e.writes & b.srcAccess) == e.writes) {
                e.available = true;
            }
        }
        const bool transition = isImage && b.oldLayout != b.newLayout;
        if (isImage && b.oldLayout != VK_IMAGE_LAYOUT_UNDEFINED && b.oldLayout != layout_) {
            fail("barrier old layout does not match the current layout");
        }
        // Chains: anything in the first scope (directly or through earlier barriers) is ordered before dst.
        for (Earlier& e : earlier_) {
            const bool ordered = (e.stages && inScope(e.stages, b.srcStages)) || inScope(e.orderedBefore, b.srcStages);
            if (transition && e.stages != 0 && !ordered) fail("layout transition not ordered after an earlier access");
            if (transition && e.writes && !e.available) fail("layout transition before an earlier write was available");
            if (!ordered) continue;
            e.orderedBefore |= b.dstStages;
            if (e.available) {
                for (VkAccessFlags2 bits = b.dstAccess; bits; bits &= bits - 1) e.visible[bits & (~bits + 1)] |= b.dstStages;
            }
        }
        if (transition) {
            Earlier t;
            t.writes = VK_ACCESS_2_MEMORY_WRITE_BIT;
            t.available = true;   // layout transitions are automatically made available
            t.orderedBefore = b.dstStages;
            for (VkAccessFlags2 bits = b.dstAccess; bits; bits &= bits - 1) t.visible[bits & (~bits + 1)] |= b.dstStages;
            earlier_.push_back(t);
            layout_ = b.newLayout;
        }
    }

    void access(const Use& use) {
        const AccessInfo info = accessInfo(use.access, use.kind);
        const VkPipelineStageFlags2 stages = effectiveStages(use);
        if (use.kind == ResourceKind::Image && layout_ != info.layout) fail("access in the wrong layout");
        const bool isWrite = info.isWrite;
        for (const Earlier& e : earlier_) {
            if (!e.writes && !isWrite) continue;   // read after read
            if (!e.writes && e.stages == 0) continue;   // Present: the presentation engine, not a GPU stage
            if (stages == 0) continue;              // Present: no GPU access
            if (!stagesCovered(e.orderedBefore, stages)) {
                fail(isWrite ? (e.writes ? "WAW execution hazard" : "WAR hazard") : "RAW execution hazard");
            }
            if (!e.writes) continue;
            if (!e.available) fail("earlier write never made available");
            for (VkAccessFlags2 bits = info.access; bits; bits &= bits - 1) {
                const VkAccessFlags2 bit = bits & (~bits + 1);
                const auto it = e.visible.find(bit);
                if (it == e.visible.end() || !stagesCovered(it->second, stages)) fail("earlier write not visible");
            }
        }
        Earlier self;
        self.stages = stages;
        self.writes = info.access & kWriteAccessMask;
        earlier_.push_back(self);
    }

    // An imported state: the last access as stateAfterAccess describes it.
    void seed(Access a, ResourceKind kind, VkPipelineStageFlags2 stages) {
        const AccessInfo info = accessInfo(a, kind);
        Earlier e;
        e.stages = stages ? stages : info.defaultStages;
        e.writes = info.access & kWriteAccessMask;
        if (!e.writes) e.orderedBefore = 0;
        earlier_.push_back(e);
        layout_ = info.layout;
    }

private:
    void fail(const char* what) {
        if (error.empty()) error = what;
    }
    VkImageLayout layout_;
    std::vector<Earlier> earlier_;
};

std::vector<Access> accessesFor(ResourceKind kind) {
    std::vector<Access> out;
    for (uint32_t i = 0; i < kAccessCount; ++i) {
        const auto a = static_cast<Access>(i);
        if (accessInfo(a, kind).valid) out.push_back(a);
    }
    return out;
}

VkPipelineStageFlags2 randomStages(Access a, ResourceKind kind, std::mt19937& rng) {
    const AccessInfo info = accessInfo(a, kind);
    if (info.defaultStages != (VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                               VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT)) {
        return 0;   // fixed-function accesses use their table stages
    }
    static constexpr VkPipelineStageFlags2 kChoices[] = {
        0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
        VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT};
    return kChoices[rng() % std::size(kChoices)];
}

void runRandomSequences(ResourceKind kind, uint32_t seed) {
    std::mt19937 rng(seed);
    const std::vector<Access> accesses = accessesFor(kind);
    for (int sequence = 0; sequence < 4000; ++sequence) {
        ResourceState state;
        Model model(VK_IMAGE_LAYOUT_UNDEFINED);
        std::string trace;
        if (rng() % 3 == 0) {   // start from an imported state
            const Access a = accesses[rng() % accesses.size()];
            const VkPipelineStageFlags2 stages = randomStages(a, kind, rng);
            state = stateAfterAccess(a, kind, stages);
            model.seed(a, kind, stages);
            trace += "import " + std::string(toString(a)) + "; ";
        }
        const int length = 1 + static_cast<int>(rng() % 8);
        for (int step = 0; step < length; ++step) {
            Use use{kind, accesses[rng() % accesses.size()], 0, false};
            use.stages = randomStages(use.access, kind, rng);
            // A read of never-written contents is a graph error, never planned: start with a write instead.
            if (step == 0 && state == ResourceState{} && !accessInfo(use.access, kind).isWrite) {
                use.access = Access::TransferDst;
                use.stages = 0;
            }
            // Contents may be discarded only by a write (the graph does it for the first write of a version 0).
            use.discard = kind == ResourceKind::Image && accessInfo(use.access, kind).isWrite && rng() % 4 == 0;
            trace += std::string(toString(use.access)) + "@" + std::to_string(use.stages) + (use.discard ? "!" : "") + "; ";
            const Transition t = applyUse(state, use);
            if (t.barrier) model.barrier(*t.barrier, kind == ResourceKind::Image);
            model.access(use);
            state = t.after;
            ASSERT_TRUE(model.error.empty()) << model.error << " after: " << trace;
        }
    }
}

TEST(BarrierPlannerModel, RandomImageSequencesHaveNoHazards) { runRandomSequences(ResourceKind::Image, 1234); }
TEST(BarrierPlannerModel, RandomBufferSequencesHaveNoHazards) { runRandomSequences(ResourceKind::Buffer, 5678); }

// The model itself must be able to fail: a missing RAW barrier and a missing WAR wait are reported.
TEST(BarrierPlannerModel, ModelDetectsMissingBarriers) {
    Model raw(VK_IMAGE_LAYOUT_UNDEFINED);
    raw.access(Use{ResourceKind::Buffer, Access::StorageWrite, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, false});
    raw.access(Use{ResourceKind::Buffer, Access::StorageRead, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, false});
    EXPECT_EQ(raw.error, "RAW execution hazard");

    Model war(VK_IMAGE_LAYOUT_UNDEFINED);
    war.seed(Access::StorageRead, ResourceKind::Buffer, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
    PlannedBarrier tooNarrow;
    tooNarrow.kind = ResourceKind::Buffer;
    tooNarrow.srcStages = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;   // misses the FRAGMENT reader
    tooNarrow.dstStages = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    war.barrier(tooNarrow, false);
    war.access(Use{ResourceKind::Buffer, Access::StorageWrite, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, false});
    EXPECT_EQ(war.error, "WAR hazard");

    Model invisible(VK_IMAGE_LAYOUT_UNDEFINED);
    invisible.access(Use{ResourceKind::Buffer, Access::StorageWrite, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, false});
    PlannedBarrier executionOnly;
    executionOnly.kind = ResourceKind::Buffer;
    executionOnly.srcStages = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    executionOnly.dstStages = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    invisible.barrier(executionOnly, false);
    invisible.access(Use{ResourceKind::Buffer, Access::StorageRead, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, false});
    EXPECT_EQ(invisible.error, "earlier write never made available");
}

}  // namespace
}  // namespace idk::graph
