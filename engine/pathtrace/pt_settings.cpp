// pt_settings.cpp: names of the path tracer's samplers (the --sampler option) and their shader ids.
#include "pathtrace/pt_settings.hpp"

#include "shared/pt_sampler.h"

namespace idk::pathtrace {

const char* samplerName(PtSampler sampler) { return sampler == PtSampler::Sobol ? "sobol" : "independent"; }

std::optional<PtSampler> parseSampler(std::string_view name) {
    if (name == "sobol") return PtSampler::Sobol;
    if (name == "independent") return PtSampler::Independent;
    return std::nullopt;
}

uint32_t samplerId(PtSampler sampler) {
    return sampler == PtSampler::Sobol ? gpu::kPtSamplerSobol : gpu::kPtSamplerIndependent;
}

}  // namespace idk::pathtrace
