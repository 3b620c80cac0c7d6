// alias_table.hpp: Walker's alias method (Vose's stable construction) over non-negative weights: O(1) sampling of
// an index with probability weight / sum, one table entry per index (shared/pt_types.h GpuPtAliasEntry), used to
// pick lights by power and environment texels by luminance on the CPU and the GPU. New (IDKEngine samples no lights).
#pragma once
#include <span>
#include <vector>

#include "shared/pt_types.h"

namespace idk::pathtrace {

// Entry i: threshold (keep i when the second uniform is below it), alias, probability = weight[i] / sum. Negative,
// NaN or infinite weights count as 0; an all-zero input (or an empty one) gives an empty table.
std::vector<gpu::GpuPtAliasEntry> buildAliasTable(std::span<const double> weights);

// The exact probability the table selects index i with (sum over slots, for tests): (threshold_i + sum of
// (1 - threshold_j) over slots j aliasing to i) / n.
std::vector<double> aliasSelectionProbabilities(std::span<const gpu::GpuPtAliasEntry> table);

}  // namespace idk::pathtrace
