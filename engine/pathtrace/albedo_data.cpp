// albedo_data.cpp: the committed directional-albedo tables (shared/pt_albedo_tables.h) packed into one float
// array, the layout the GLSL lookups of shared/pt_energy.h read from a storage buffer.
#include <algorithm>
#include <iterator>

#include "pathtrace/albedo_integrator.hpp"
#include "shared/pt_albedo_tables.h"

namespace idk::pathtrace {

std::vector<float> albedoTableData() {
    using namespace idk::gpu;
    std::vector<float> out(kPtAlbedoTableFloats);
    auto put = [&](const auto& table, uint32_t offset) {
        std::copy(std::begin(table), std::end(table), out.begin() + offset);
    };
    put(kPtAlbedoMetal, kPtAlbedoMetalOffset);
    put(kPtAlbedoMetalAvg, kPtAlbedoMetalAvgOffset);
    put(kPtAlbedoDielectric, kPtAlbedoDielectricOffset);
    put(kPtAlbedoSheen, kPtAlbedoSheenOffset);
    put(kPtAlbedoMsBinTable, kPtAlbedoMsBinTableOffset);
    put(kPtAlbedoAnisoMetal, kPtAlbedoAnisoMetalOffset);
    put(kPtAlbedoAnisoAvg, kPtAlbedoAnisoAvgOffset);
    put(kPtAlbedoSpecular, kPtAlbedoSpecularOffset);
    put(kPtAlbedoSpecularAvg, kPtAlbedoSpecularAvgOffset);
    return out;
}

}  // namespace idk::pathtrace
