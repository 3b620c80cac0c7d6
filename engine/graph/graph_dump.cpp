// graph_dump.cpp: RenderGraph::toText() and toGraphviz(): the compiled frame in words (order, culled passes,
// every barrier, resources with lifetimes and memory placement) and as a dot graph (passes as boxes, culled
// ones grey; resource versions as ellipses; read/write edges; after() edges dotted).
#include "graph/flags_text.hpp"
#include "graph/render_graph.hpp"
#include "graph/text_format.hpp"

namespace idk::graph {

using detail::Origin;
using detail::PassUse;

namespace {

std::string_view originName(Origin origin) {
    switch (origin) {
        case Origin::Transient: return "transient";
        case Origin::Persistent: return "persistent";
        case Origin::History: return "history";
        case Origin::Imported: return "imported";
    }
    return "?";
}

std::string dotEscape(std::string_view text) {
    std::string out;
    for (char ch : text) {
        if (ch == '"' || ch == '\\') out += '\\';
        out += ch;
    }
    return out;
}

}  // namespace

std::string RenderGraph::toText() const {
    const detail::CompiledGraph& c = compiled();
    std::string out = strformat("render graph: {} passes ({} executed, {} culled), {} resources, output {}x{}\n",
                                  passes_.size(), c.order.size(), passes_.size() - c.order.size(), resources_.size(),
                                  outputExtent_.width, outputExtent_.height);
    const auto listBarriers = [&](std::span<const PlannedBarrier> barriers, const char* indent) {
        for (const PlannedBarrier& b : barriers) out += strformat("{}barrier {}\n", indent, describe(b, resourceName(b.resource)));
    };
    if (!c.prologueBarriers.empty() || !c.prologueClears.empty()) {
        out += "prologue (never-written history, cleared to zero):\n";
        listBarriers(c.prologueBarriers, "  ");
        for (uint32_t r : c.prologueClears) out += strformat("  clear '{}'\n", resources_[r].name);
    }
    out += "passes in execution order:\n";
    for (uint32_t pos = 0; pos < c.order.size(); ++pos) {
        const detail::PassNode& pass = passes_[c.order[pos]];
        out += strformat("  [{}] {}{}\n", pos, pass.name, pass.sideEffect ? " (side effect)" : "");
        listBarriers(c.passes[pos].barriers, "      ");
        for (const PassUse& use : pass.uses) {
            const AccessInfo info = accessInfo(use.access, resources_[use.resource].kind);
            const VkPipelineStageFlags2 stages = use.stages ? use.stages : info.defaultStages;
            if (use.write) {
                out += strformat("      write '{}' v{}->v{} {} @{}\n", resources_[use.resource].name, use.version,
                                   use.version + 1, toString(use.access), stageNames(stages));
            } else {
                out += strformat("      read  '{}' v{} {} @{}\n", resources_[use.resource].name, use.version,
                                   toString(use.access), stageNames(stages));
            }
        }
    }
    for (uint32_t p = 0; p < passes_.size(); ++p) {
        if (c.positionOf[p] == kInvalidId) out += strformat("  culled: {}\n", passes_[p].name);
    }
    if (!c.finalBarriers.empty()) {
        out += "final transitions:\n";
        listBarriers(c.finalBarriers, "  ");
    }
    out += "resources:\n";
    for (uint32_t r = 0; r < resources_.size(); ++r) {
        const detail::ResourceNode& node = resources_[r];
        const detail::ResourcePlan& plan = c.resources[r];
        out += strformat("  '{}' {} {}", node.name, originName(node.origin), toString(node.kind));
        if (node.kind == ResourceKind::Image) {
            const TextureInfo& t = plan.texture;
            out += strformat(" format {} {}x{}x{} mips {} layers {} usage {}", static_cast<int>(t.format),
                               t.extent.width, t.extent.height, t.extent.depth, t.mips, t.layers, hex(t.usage));
        } else {
            out += strformat(" {} bytes usage {}{}", plan.buffer.size, hex(plan.buffer.usage),
                               plan.buffer.hostVisible ? " host-visible" : "");
        }
        if (!plan.used) {
            out += " unused\n";
            continue;
        }
        out += strformat(" passes [{}, {}]", plan.firstPos, plan.lastPos);
        if (node.origin == Origin::History) out += plan.historyValid ? " (last frame)" : " (cleared: never written)";
        if (plan.slot != kInvalidId) {
            const AliasSlot& slot = c.aliasing.slots[plan.slot];
            out += strformat(" heap {} offset {} size {}", slot.heap, slot.offset, slot.size);
        }
        out += '\n';
    }
    out += strformat("transient memory: {} heap(s), {} bytes ({} bytes without aliasing)\n", c.aliasing.heaps.size(),
                       c.aliasing.totalBytes(), c.aliasing.unaliasedBytes());
    return out;
}

std::string RenderGraph::toGraphviz() const {
    const detail::CompiledGraph& c = compiled();
    std::string out = "digraph render_graph {\n  rankdir=LR;\n  node [fontname=\"monospace\", fontsize=10];\n";
    for (uint32_t p = 0; p < passes_.size(); ++p) {
        const uint32_t pos = c.positionOf[p];
        if (pos == kInvalidId) {
            out += strformat("  p{} [shape=box, style=\"filled,dashed\", fillcolor=lightgrey, fontcolor=grey50, "
                               "label=\"{}\\n(culled)\"];\n", p, dotEscape(passes_[p].name));
        } else {
            std::string label = strformat("#{} {}", pos, dotEscape(passes_[p].name));
            for (const PlannedBarrier& b : c.passes[pos].barriers) {
                label += "\\n" + dotEscape(describe(b, resourceName(b.resource)));
            }
            out += strformat("  p{} [shape=box, style=filled, fillcolor=lightblue, label=\"{}\"];\n", p, label);
        }
    }
    for (uint32_t r = 0; r < resources_.size(); ++r) {
        const detail::ResourceNode& node = resources_[r];
        for (uint32_t v = 0; v < node.producers.size(); ++v) {
            out += strformat("  r{}v{} [shape=ellipse, label=\"{} v{}\\n{}\"];\n", r, v, dotEscape(node.name), v,
                               originName(node.origin));
        }
    }
    for (uint32_t p = 0; p < passes_.size(); ++p) {
        const bool culled = c.positionOf[p] == kInvalidId;
        const char* colour = culled ? ", color=grey70" : "";
        for (const PassUse& use : passes_[p].uses) {
            out += strformat("  r{}v{} -> p{} [label=\"{}\"{}];\n", use.resource, use.version, p,
                               toString(use.access), colour);
            if (use.write) out += strformat("  p{} -> r{}v{} [style=bold{}];\n", p, use.resource, use.version + 1, colour);
        }
    }
    for (const detail::Edge& e : c.edges) {
        if (e.kind == detail::EdgeKind::Order) out += strformat("  p{} -> p{} [style=dotted, label=\"after\"];\n", e.from, e.to);
    }
    out += "}\n";
    return out;
}

}  // namespace idk::graph
