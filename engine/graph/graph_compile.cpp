// graph_compile.cpp: RenderGraph::compile(), pure: validation, culling and topological order. The resolved
// descriptions, memory plan and barriers come from graph_plan.cpp.
#include "graph/render_graph.hpp"
#include "graph/text_format.hpp"

#include <algorithm>
#include <map>
#include <queue>
#include <set>

namespace idk::graph {

using detail::Edge;
using detail::EdgeKind;
using detail::Origin;
using detail::PassUse;

namespace {

[[noreturn]] void throwErrors(const std::vector<std::string>& errors) {
    std::string message = errors.size() == 1 ? std::string() : strformat("render graph: {} errors\n", errors.size());
    for (size_t i = 0; i < errors.size(); ++i) {
        if (i) message += '\n';
        message += errors[i];
    }
    throw GraphError(message);
}

bool writeIsOutput(Origin origin) { return origin == Origin::Imported || origin == Origin::Persistent; }

}  // namespace

void RenderGraph::compile() {
    if (executed_) throw GraphError("render graph: compile() after execute(); build a new graph for the next frame");
    compiled_.reset();
    std::vector<std::string> errors = errors_;
    if (!errors.empty()) throwErrors(errors);

    detail::CompiledGraph result;
    result.resources.resize(resources_.size());
    compiled_ = std::move(result);
    try {
        std::vector<std::vector<uint32_t>> afterEdges;
        validatePasses(errors, afterEdges);
        resolveHistory(errors);
        if (!errors.empty()) throwErrors(errors);
        orderPasses(findLivePasses(), afterEdges, errors);
        if (!errors.empty()) throwErrors(errors);
        resolveResources(errors);
        if (!errors.empty()) throwErrors(errors);
        planMemory();
        planBarriers();
    } catch (...) {
        compiled_.reset();
        throw;
    }
}

// Pass names unique and non-empty; after() names resolved to pass indices.
void RenderGraph::validatePasses(std::vector<std::string>& errors, std::vector<std::vector<uint32_t>>& afterEdges) {
    std::map<std::string_view, uint32_t> byName;
    for (uint32_t i = 0; i < passes_.size(); ++i) {
        if (passes_[i].name.empty()) errors.push_back(strformat("render graph: pass #{} has an empty name", i));
        const auto [it, inserted] = byName.emplace(passes_[i].name, i);
        if (!inserted && !passes_[i].name.empty()) {
            errors.push_back(strformat("render graph: duplicate pass name '{}' (passes #{} and #{})", passes_[i].name,
                                         it->second, i));
        }
    }
    afterEdges.assign(passes_.size(), {});
    for (uint32_t i = 0; i < passes_.size(); ++i) {
        for (const std::string& name : passes_[i].after) {
            const auto it = byName.find(name);
            if (it == byName.end()) {
                errors.push_back(strformat("render graph: pass '{}' must run after '{}', but there is no pass named "
                                             "'{}'", passes_[i].name, name, name));
            } else if (it->second == i) {
                errors.push_back(strformat("render graph: pass '{}' must run after itself (cycle)", passes_[i].name));
            } else {
                afterEdges[i].push_back(it->second);
            }
        }
    }
}

// Each history resource names a persistent resource of this graph or of the pool.
void RenderGraph::resolveHistory(std::vector<std::string>& errors) {
    for (uint32_t r = 0; r < resources_.size(); ++r) {
        const detail::ResourceNode& node = resources_[r];
        if (node.origin != Origin::History) continue;
        for (uint32_t p = 0; p < resources_.size(); ++p) {
            if (resources_[p].origin == Origin::Persistent && resources_[p].name == node.persistentName) {
                compiled_->resources[r].pairedWith = p;
                compiled_->resources[p].pairedWith = r;
            }
        }
        const uint32_t paired = compiled_->resources[r].pairedWith;
        const auto* entry = pool_.findPersistent(node.persistentName);
        const ResourceKind kind =
            paired != kInvalidId ? resources_[paired].kind : (entry ? entry->kind : node.kind);
        if (paired == kInvalidId && entry == nullptr) {
            errors.push_back(strformat("render graph: history('{}'): no persistent resource named '{}' is created "
                                         "this frame or kept from an earlier frame (create it with "
                                         "desc.persistent = true)", node.persistentName, node.persistentName));
        } else if (kind != node.kind) {
            errors.push_back(strformat("render graph: history('{}') asks for a {} but '{}' is a {}",
                                         node.persistentName, toString(node.kind), node.persistentName, toString(kind)));
        }
    }
}

// Roots: side effects, writes to imported or persistent resources, marked outputs. Then everything a live
// pass consumes (reads, and the version a write builds on) keeps its producer alive.
std::vector<bool> RenderGraph::findLivePasses() const {
    std::vector<bool> alive(passes_.size(), false);
    std::vector<uint32_t> work;
    const auto keep = [&](uint32_t pass) {
        if (pass != kInvalidId && !alive[pass]) {
            alive[pass] = true;
            work.push_back(pass);
        }
    };
    for (uint32_t p = 0; p < passes_.size(); ++p) {
        if (passes_[p].sideEffect) keep(p);
        for (const PassUse& use : passes_[p].uses) {
            if (use.write && writeIsOutput(resources_[use.resource].origin)) keep(p);
        }
    }
    for (const detail::ResourceNode& node : resources_) {
        for (uint32_t version : node.outputVersions) keep(node.producers[version]);
    }
    while (!work.empty()) {
        const uint32_t pass = work.back();
        work.pop_back();
        for (const PassUse& use : passes_[pass].uses) keep(resources_[use.resource].producers[use.version]);
    }
    return alive;
}

// Edges between live passes, then Kahn's algorithm picking the lowest declaration index among ready passes,
// so the order is declaration order wherever the dependencies leave it free.
void RenderGraph::orderPasses(const std::vector<bool>& alive, const std::vector<std::vector<uint32_t>>& afterEdges,
                              std::vector<std::string>& errors) {
    detail::CompiledGraph& c = *compiled_;
    std::set<std::pair<uint32_t, uint32_t>> seen;
    const auto addEdge = [&](uint32_t from, uint32_t to, EdgeKind kind, uint32_t resource, uint32_t version) {
        if (from == kInvalidId || to == kInvalidId || from == to || !alive[from] || !alive[to]) return;
        if (seen.emplace(from, to).second) c.edges.push_back(Edge{from, to, kind, resource, version});
    };
    for (uint32_t r = 0; r < resources_.size(); ++r) {
        const auto& producers = resources_[r].producers;
        for (uint32_t v = 0; v < producers.size(); ++v) {
            const uint32_t nextWriter = v + 1 < producers.size() ? producers[v + 1] : kInvalidId;
            addEdge(producers[v], nextWriter, EdgeKind::Data, r, v);
            for (uint32_t p = 0; p < passes_.size(); ++p) {
                for (const PassUse& use : passes_[p].uses) {
                    if (use.resource != r || use.version != v || use.write) continue;
                    addEdge(producers[v], p, EdgeKind::Data, r, v);
                    addEdge(p, nextWriter, EdgeKind::WriteAfterRead, r, v);
                }
            }
        }
    }
    for (uint32_t p = 0; p < passes_.size(); ++p) {
        for (uint32_t before : afterEdges[p]) addEdge(before, p, EdgeKind::Order, kInvalidId, 0);
    }

    std::vector<uint32_t> inDegree(passes_.size(), 0);
    std::vector<std::vector<uint32_t>> successors(passes_.size());
    for (const Edge& e : c.edges) {
        ++inDegree[e.to];
        successors[e.from].push_back(e.to);
    }
    std::priority_queue<uint32_t, std::vector<uint32_t>, std::greater<>> ready;
    uint32_t aliveCount = 0;
    for (uint32_t p = 0; p < passes_.size(); ++p) {
        if (!alive[p]) continue;
        ++aliveCount;
        if (inDegree[p] == 0) ready.push(p);
    }
    c.positionOf.assign(passes_.size(), kInvalidId);
    while (!ready.empty()) {
        const uint32_t p = ready.top();
        ready.pop();
        c.positionOf[p] = static_cast<uint32_t>(c.order.size());
        c.order.push_back(p);
        for (uint32_t s : successors[p]) {
            if (--inDegree[s] == 0) ready.push(s);
        }
    }
    if (c.order.size() != aliveCount) {
        std::vector<uint32_t> remaining;
        for (uint32_t p = 0; p < passes_.size(); ++p) {
            if (alive[p] && c.positionOf[p] == kInvalidId) remaining.push_back(p);
        }
        errors.push_back(describeCycle(remaining));
        return;
    }
    c.passes.resize(c.order.size());
    for (uint32_t i = 0; i < c.order.size(); ++i) c.passes[i].pass = c.order[i];
}

// Every remaining pass has a remaining predecessor: walk predecessors until one repeats.
std::string RenderGraph::describeCycle(const std::vector<uint32_t>& remaining) const {
    const detail::CompiledGraph& c = *compiled_;
    const auto isRemaining = [&](uint32_t p) { return std::find(remaining.begin(), remaining.end(), p) != remaining.end(); };
    std::vector<const Edge*> path;   // edges walked backwards
    std::vector<uint32_t> visited{remaining.front()};
    while (true) {
        const uint32_t current = visited.back();
        const Edge* in = nullptr;
        for (const Edge& e : c.edges) {
            if (e.to == current && isRemaining(e.from)) {
                in = &e;
                break;
            }
        }
        if (in == nullptr) break;   // cannot happen; be defensive
        path.push_back(in);
        const auto again = std::find(visited.begin(), visited.end(), in->from);
        if (again != visited.end()) {
            const size_t start = static_cast<size_t>(again - visited.begin());
            std::string text = strformat("'{}'", passes_[in->from].name);
            for (size_t i = path.size(); i-- > start;) {
                const Edge& e = *path[i];
                std::string why;
                switch (e.kind) {
                    case EdgeKind::Order: why = "after()"; break;
                    case EdgeKind::Data: why = strformat("'{}' v{}", resources_[e.resource].name, e.version); break;
                    case EdgeKind::WriteAfterRead:
                        why = strformat("'{}' v{} read before overwritten", resources_[e.resource].name, e.version);
                        break;
                }
                text += strformat(" -> '{}' ({})", passes_[e.to].name, why);
            }
            return "render graph: cycle between passes: " + text;
        }
        visited.push_back(in->from);
    }
    std::string names;
    for (uint32_t p : remaining) names += strformat(" '{}'", passes_[p].name);
    return "render graph: cycle between passes:" + names;
}

}  // namespace idk::graph
