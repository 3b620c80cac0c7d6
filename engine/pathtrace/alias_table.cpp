// alias_table.cpp: Vose's construction of the alias table (numerically stable: small and large worklists, the
// leftovers of both lists get threshold 1).
#include "pathtrace/alias_table.hpp"

#include <algorithm>
#include <cmath>

namespace idk::pathtrace {

std::vector<gpu::GpuPtAliasEntry> buildAliasTable(std::span<const double> weights) {
    const size_t n = weights.size();
    std::vector<double> w(n);
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        w[i] = std::isfinite(weights[i]) && weights[i] > 0.0 ? weights[i] : 0.0;
        sum += w[i];
    }
    if (n == 0 || !(sum > 0.0) || !std::isfinite(sum)) return {};

    std::vector<gpu::GpuPtAliasEntry> table(n);
    std::vector<double> scaled(n);
    std::vector<uint32_t> small, large;
    for (size_t i = 0; i < n; ++i) {
        table[i].probability = float(w[i] / sum);
        table[i].alias = uint32_t(i);
        scaled[i] = w[i] / sum * double(n);
        (scaled[i] < 1.0 ? small : large).push_back(uint32_t(i));
    }
    while (!small.empty() && !large.empty()) {
        const uint32_t s = small.back();
        small.pop_back();
        const uint32_t l = large.back();
        table[s].threshold = float(scaled[s]);
        table[s].alias = l;
        scaled[l] = (scaled[l] + scaled[s]) - 1.0;
        if (scaled[l] < 1.0) {
            large.pop_back();
            small.push_back(l);
        }
    }
    for (uint32_t i : large) table[i].threshold = 1.0f;
    for (uint32_t i : small) table[i].threshold = 1.0f;  // rounding leftovers: probability ~1 each
    return table;
}

std::vector<double> aliasSelectionProbabilities(std::span<const gpu::GpuPtAliasEntry> table) {
    const size_t n = table.size();
    std::vector<double> p(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
        const double keep = std::min(1.0, std::max(0.0, double(table[i].threshold)));
        p[i] += keep / double(n);
        if (table[i].alias < n) p[table[i].alias] += (1.0 - keep) / double(n);
    }
    return p;
}

}  // namespace idk::pathtrace
