// pt_wavefront_checks.hpp: the wavefront path tracer's queue oracle (pt_wavefront_checks.cpp), shared with the
// sorting test (tests/conformance/pathtrace/), which checks compaction after a sorted trace too.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "conformance/conformance.hpp"
#include "render/path_tracer.hpp"

namespace idk::conformance {

// The items of a ray queue (header word 0 = count).
std::vector<uint32_t> queueItems(const std::vector<uint32_t>& queue);

// Compaction is exact: the next queue holds exactly the pixels whose path the shade stage extended (a CPU filter
// over the path states), each once; the indirect dispatch size is ceil(count / kPtGroupSize) x 1 x 1; some paths
// die and some survive (or the check could not fail).
void expectExactCompaction(Verdict& v, const render::PtCapture& c, const std::string& what);

}  // namespace idk::conformance
