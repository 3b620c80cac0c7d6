// graph_nodes.hpp: the render graph's internal records (declared resources and passes, and what compile()
// derives from them). Included by render_graph.hpp for its members; not meant for pass code.
#pragma once
#include "graph/aliasing.hpp"
#include "graph/barrier_planner.hpp"
#include "graph/graph_types.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace idk::graph {

class PassContext;

namespace detail {

enum class Origin : uint8_t {
    Transient,    // created this frame, contents start undefined, memory aliased
    Persistent,   // created this frame with desc.persistent: this frame's copy of a ping-pong pair
    History,      // last frame's copy of a persistent resource (read-only)
    Imported,     // owned outside the graph
};

struct ResourceNode {
    std::string name;
    ResourceKind kind = ResourceKind::Image;
    Origin origin = Origin::Transient;
    TextureDesc textureDesc;
    BufferDesc bufferDesc;
    PhysicalTexture importedTexture;
    PhysicalBuffer importedBuffer;
    ResourceState importedState;
    std::optional<FinalUse> finalUse;
    std::string persistentName;                 // History: the persistent resource it is last frame's copy of
    std::vector<uint32_t> producers{kInvalidId}; // producers[v]: the pass that wrote version v (v >= 1)
    std::vector<uint32_t> outputVersions;       // versions marked as graph outputs
    VkExtent2D relativeTo{0, 0};                // OutputRelative: the graph's relative extent when declared
};

struct PassUse {
    uint32_t resource = kInvalidId;
    uint32_t version = 0;                       // the version consumed (a write produces version + 1)
    Access access = Access::SampledRead;
    VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
    bool write = false;
};

struct PassNode {
    std::string name;
    std::vector<PassUse> uses;
    std::vector<std::string> after;             // explicit ordering: run after these passes (if they run)
    bool sideEffect = false;
    std::function<void(PassContext&)> exec;
    VkExtent2D extent{0, 0};                    // the graph's relative extent when the pass was added
};

enum class EdgeKind : uint8_t { Data, WriteAfterRead, Order };

struct Edge {
    uint32_t from = 0, to = 0;                  // pass indices
    EdgeKind kind = EdgeKind::Data;
    uint32_t resource = kInvalidId;             // Data / WriteAfterRead
    uint32_t version = 0;
};

struct ResourcePlan {
    bool used = false;                          // some executed pass touches it
    uint32_t firstPos = kInvalidId;             // positions in execution order
    uint32_t lastPos = 0;
    TextureInfo texture;                        // resolved (usage = union of executed accesses)
    BufferInfo buffer;
    ResourceState initial;                      // before the first access this frame
    ResourceState final;                        // after the last access (and final transition)
    bool historyValid = true;                   // History: false when the prologue cleared it this frame
    bool writtenThisFrame = false;
    uint32_t slot = kInvalidId;                 // index into AliasingPlan::slots (transients)
    uint32_t pairedWith = kInvalidId;           // Persistent <-> its History resource in this graph
};

struct PassPlan {
    uint32_t pass = 0;
    std::vector<PlannedBarrier> barriers;       // one vkCmdPipelineBarrier2 before the pass
};

struct CompiledGraph {
    std::vector<uint32_t> order;                // executed passes, in execution order
    std::vector<uint32_t> positionOf;           // per pass: position in order, kInvalidId if culled
    std::vector<PassPlan> passes;               // parallel to order
    std::vector<Edge> edges;                    // between executed passes
    std::vector<PlannedBarrier> prologueBarriers; // history copies never written: to TRANSFER_DST ...
    std::vector<uint32_t> prologueClears;       // ... then cleared to zero (resources)
    std::vector<PlannedBarrier> finalBarriers;  // imported resources to their FinalUse
    std::vector<ResourcePlan> resources;        // per resource
    AliasingPlan aliasing;
};

}  // namespace detail
}  // namespace idk::graph
