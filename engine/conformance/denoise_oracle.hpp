// denoise_oracle.hpp: the CPU oracle of the denoiser (engine/passes/denoise.cpp, shaders_glsl/denoise/*): the same
// prepare / a-trous / remodulate loops in the same order over the same per-pixel math (shaders_glsl/shared/
// denoise_filter.h compiled as C++), so the GPU result must match it up to float rounding (exp/pow ulps, FMA).
#pragma once
#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include "passes/denoise.hpp"
#include "shared/denoise_filter.h"

namespace idk::conformance {

struct DenoiseImages {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec4> color, albedo, normal;  // normal: xyz
    std::vector<float> depth;
    std::vector<float> variance;  // optional (DenoiseInputs::variance): of the mean luminance, < 0 unknown
};

class DenoiseOracle {
public:
    explicit DenoiseOracle(const DenoiseImages& in) : in_(in), w_(int(in.width)), h_(int(in.height)) {}

    std::vector<glm::vec4> run(const passes::DenoiseSettings& s) const {
        std::vector<glm::vec4> illum(in_.color.size());
        std::vector<float> gradient(in_.color.size());
        prepare(s, illum, gradient);
        for (uint32_t i = 0; i < s.iterations; ++i) illum = atrous(s, illum, gradient, int(1u << i));
        std::vector<glm::vec4> out(in_.color.size());
        std::vector<float> excess(in_.color.size(), 0.0f);
        for (size_t k = 0; k < out.size(); ++k)
            if (valid(k)) excess[k] = gpu::denoiseShrinkExcess(changeVariance(illum, k), gpu::denoiseLuminance(raw(k)),
                                                               gpu::denoiseLuminance(filtered(illum, k)));
        for (size_t k = 0; k < out.size(); ++k) {
            glm::vec4 c = in_.color[k];
            float alpha = gpu::denoiseIsFinite(c.w) ? c.w : 1.0f;
            glm::vec3 radiance = gpu::denoiseSanitize3(glm::vec3(c));
            if (valid(k)) {
                const float v = pixelVariance(k);
                const float w =
                    v >= 0.0f ? gpu::denoiseShrinkWeight(changeVariance(illum, k), meanExcess(k, excess), excess[k]) : 1.0f;
                radiance += w * (filtered(illum, k) - radiance);
            }
            out[k] = glm::vec4(radiance, alpha);
        }
        return out;
    }

private:
    bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < w_ && y < h_; }
    size_t at(int x, int y) const { return size_t(y) * size_t(w_) + size_t(x); }
    glm::vec3 raw(size_t k) const { return gpu::denoiseSanitize3(glm::vec3(in_.color[k])); }
    glm::vec3 filtered(const std::vector<glm::vec4>& illum, size_t k) const {
        return glm::vec3(illum[k]) * gpu::denoiseAlbedoFactor(glm::vec3(in_.albedo[k]));
    }
    float changeVariance(const std::vector<glm::vec4>& illum, size_t k) const {
        return gpu::denoiseChangeVariance(pixelVariance(k), illum[k].w, albedoFactor(k));
    }
    // remodulate.comp.glsl's meanExcess: over the valid neighbours with a known variance.
    float meanExcess(size_t k, const std::vector<float>& excess) const {
        const int x = int(k % size_t(w_)), y = int(k / size_t(w_)), r = gpu::kDenoiseShrinkRadius;
        float sum = 0.0f, count = 0.0f;
        for (int dy = -r; dy <= r; ++dy)
            for (int dx = -r; dx <= r; ++dx) {
                if (!inside(x + dx, y + dy)) continue;
                const size_t q = at(x + dx, y + dy);
                if (!valid(q) || !(pixelVariance(q) >= 0.0f)) continue;
                sum += excess[q];
                count += 1.0f;
            }
        return count > 0.0f ? sum / count : 0.0f;
    }
    float pixelVariance(size_t k) const { return in_.variance.empty() ? -1.0f : in_.variance[k]; }
    glm::vec3 n(size_t k) const { return glm::vec3(in_.normal[k]); }
    bool valid(size_t k) const { return gpu::denoiseValidGuide(n(k), in_.depth[k]); }
    glm::vec3 albedoFactor(size_t k) const { return gpu::denoiseAlbedoFactor(glm::vec3(in_.albedo[k])); }
    glm::vec3 illumination(size_t k) const { return gpu::denoiseSanitize3(glm::vec3(in_.color[k])) / albedoFactor(k); }
    float axisGradient(int x, int y, int ax, int ay, float z) const {
        float g = -1.0f;
        for (int s = -1; s <= 1; s += 2) {
            int qx = x + s * ax, qy = y + s * ay;
            if (!inside(qx, qy) || !valid(at(qx, qy))) continue;
            float d = std::fabs(in_.depth[at(qx, qy)] - z);
            g = g < 0.0f ? d : std::fmin(g, d);
        }
        return std::fmax(g, 0.0f);
    }

    void prepare(const passes::DenoiseSettings& s, std::vector<glm::vec4>& illum, std::vector<float>& gradient) const {
        const int r = gpu::kDenoiseVarianceRadius;
        for (int y = 0; y < h_; ++y)
            for (int x = 0; x < w_; ++x) {
                size_t k = at(x, y);
                if (!valid(k)) {
                    illum[k] = glm::vec4(0.0f);
                    gradient[k] = 0.0f;
                    continue;
                }
                float z = in_.depth[k];
                float g = std::fmax(axisGradient(x, y, 1, 0, z), axisGradient(x, y, 0, 1, z));
                glm::vec3 centre = illumination(k);
                float lp = gpu::denoiseLuminance(centre);
                float sumW = 0.0f, sumL = 0.0f, sumV = 0.0f;
                for (int pass = 0; pass < 2; ++pass) {
                    float mean = sumW > 0.0f ? sumL / sumW : 0.0f;
                    for (int dy = -r; dy <= r; ++dy)
                        for (int dx = -r; dx <= r; ++dx) {
                            if ((dx == 0 && dy == 0) || !inside(x + dx, y + dy)) continue;
                            size_t q = at(x + dx, y + dy);
                            if (!valid(q)) continue;
                            float distance = std::sqrt(float(dx * dx + dy * dy));
                            float w = gpu::denoiseNormalWeight(n(k), n(q), s.sigmaNormal) *
                                      gpu::denoiseAlbedoWeight(albedoFactor(k), albedoFactor(q)) *
                                      gpu::denoiseDepthWeight(z, in_.depth[q],
                                                              gpu::denoiseDepthScale(g, distance, z, s.sigmaDepth));
                            float l = gpu::denoiseLuminance(illumination(q));
                            if (pass == 0) {
                                sumW += w;
                                sumL += w * l;
                            } else {
                                sumV += w * (l - mean) * (l - mean);
                            }
                        }
                }
                float mean = sumW > 0.0f ? sumL / sumW : 0.0f;
                float limit = gpu::denoiseLuminanceLimit(mean, sumW > 0.0f ? sumV / sumW : 0.0f, sumW, s.fireflyClamp);
                if (pixelVariance(k) < 0.0f && lp > limit) {
                    centre *= limit / lp;
                    lp = limit;
                }
                illum[k] = glm::vec4(centre, gpu::denoiseStartVariance(pixelVariance(k), albedoFactor(k),
                                                                       gpu::denoiseCombinedVariance(sumW, sumV, mean, lp)));
                gradient[k] = g;
            }
    }

    std::vector<glm::vec4> atrous(const passes::DenoiseSettings& s, const std::vector<glm::vec4>& illum,
                                  const std::vector<float>& gradient, int step) const {
        std::vector<glm::vec4> out(illum.size());
        for (int y = 0; y < h_; ++y)
            for (int x = 0; x < w_; ++x) {
                size_t k = at(x, y);
                if (!valid(k)) {
                    out[k] = illum[k];
                    continue;
                }
                float sumK = 0.0f, sumV = 0.0f;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        if (!inside(x + dx, y + dy) || !valid(at(x + dx, y + dy))) continue;
                        float kw = (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
                        sumK += kw;
                        sumV += kw * illum[at(x + dx, y + dy)].w;
                    }
                float lumScale = gpu::denoiseLuminanceScale(sumV / sumK, s.sigmaLuminance);
                float z = in_.depth[k];
                float lp = gpu::denoiseLuminance(glm::vec3(illum[k]));
                glm::vec3 sum(0.0f);
                float sumW = 0.0f, sumVar = 0.0f;
                for (int dy = -2; dy <= 2; ++dy)
                    for (int dx = -2; dx <= 2; ++dx) {
                        int qx = x + dx * step, qy = y + dy * step;
                        if (!inside(qx, qy)) continue;
                        size_t q = at(qx, qy);
                        if (!valid(q)) continue;
                        float distance = float(step) * std::sqrt(float(dx * dx + dy * dy));
                        float w = gpu::denoiseKernel(dx) * gpu::denoiseKernel(dy) *
                                  gpu::denoiseNormalWeight(n(k), n(q), s.sigmaNormal) *
                                  gpu::denoiseAlbedoWeight(albedoFactor(k), albedoFactor(q)) *
                                  gpu::denoiseDepthWeight(z, in_.depth[q],
                                                          gpu::denoiseDepthScale(gradient[k], distance, z, s.sigmaDepth)) *
                                  gpu::denoiseLuminanceWeight(lp, gpu::denoiseLuminance(glm::vec3(illum[q])), lumScale);
                        sum += w * glm::vec3(illum[q]);
                        sumVar += w * w * illum[q].w;
                        sumW += w;
                    }
                out[k] = glm::vec4(sum / sumW, sumVar / (sumW * sumW));
            }
        return out;
    }

    const DenoiseImages& in_;
    int w_, h_;
};

}  // namespace idk::conformance
