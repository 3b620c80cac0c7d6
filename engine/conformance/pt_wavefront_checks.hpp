// pt_wavefront_checks.hpp: the wavefront path tracer's queue and sort oracles (pt_wavefront_checks.cpp), shared with
// the asset-based sorting test (tests/conformance/pathtrace/).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "conformance/conformance.hpp"
#include "pathtrace/pt_scene.hpp"
#include "render/path_tracer.hpp"

namespace idk::conformance {

// The items of a ray queue (header word 0 = count).
std::vector<uint32_t> queueItems(const std::vector<uint32_t>& queue);

// Compaction is exact: the next queue holds exactly the pixels whose path the shade stage extended (a CPU filter
// over the path states), each once; the indirect dispatch size is ceil(count / kPtGroupSize) x 1 x 1; some paths
// die and some survive (or the check could not fail).
void expectExactCompaction(Verdict& v, const render::PtCapture& c, const std::string& what);

// Ray sorting: `sorted` (a capture with PathTracerOptions::sortRays) holds the same rays as `plain` (the same trace
// unsorted), in non-decreasing key order, each key the CPU's (material << 3 | direction octant; misses after all
// hits), dead slots last with kPtSortKeyDead, at least three distinct keys; and compaction after it stays exact.
void expectSortedByKey(Verdict& v, const pathtrace::PathTraceScene& pts, const render::PtCapture& sorted,
                       const render::PtCapture& plain, const std::string& what);

}  // namespace idk::conformance
