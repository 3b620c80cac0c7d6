// albedo_integrator.cpp: stratified quadrature of the lobes' directional albedos and the table header writer.
// Deterministic (cell midpoints, no random numbers), so the committed tables are reproducible bit for bit.
#include "pathtrace/albedo_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "shared/pt_albedo_layout.h"
#include "shared/pt_anisotropy.h"
#include "shared/pt_microfacet.h"
#include "shared/pt_sheen.h"

namespace idk::pathtrace {

namespace {

using namespace idk::gpu;

glm::vec3 outgoing(float mu) {
    const float c = std::max(mu, kPtAlbedoMinMu);
    return glm::vec3(std::sqrt(std::max(0.0f, 1.0f - c * c)), 0.0f, c);
}

float alphaOf(float roughness) { return std::max(roughness * roughness, kPtDeltaAlpha); }

// The visible-normal sampler's radial uniform u1 for row a of `strata`, as u1 = 1 - t^2 with t at the row's
// midpoint, and its Jacobian du1/dt = 2 t (the rows' mean of it is 1). GGX's long tail lives at u1 -> 1 (the
// facet slope grows like 1 / sqrt(1 - u1)): plain midpoints in u1 miss it (0.6% off at roughness 0.3), midpoints
// in t are smooth there.
float tailWarp(int a, int strata, double& weight) {
    const double t = (double(a) + 0.5) / double(strata);
    weight = 2.0 * t;
    return float(1.0 - t * t);
}

// 2 * integral of the piecewise-linear interpolant of values (nodes mu_i = i / (n - 1)) times mu over [0, 1].
float cosineWeightedMean(const float* values, uint32_t n) {
    double sum = 0.0;
    for (uint32_t i = 0; i + 1 < n; ++i) {
        const double a = double(i) / (n - 1), b = double(i + 1) / (n - 1);
        const double e0 = values[i], e1 = values[i + 1];
        const double slope = (e1 - e0) / (b - a);
        sum += e0 * (b * b - a * a) / 2.0 + slope * ((b * b * b - a * a * a) / 3.0 - a * (b * b - a * a) / 2.0);
    }
    return float(2.0 * sum);
}

// Eavg of the anisotropic table at one (r, s): (1 / pi) integral of E cos over the hemisphere, E the lookup's
// interpolant, linear in mu and in q = |cos phi| between nodes. By symmetry it is (2 / pi) integral over q in
// [0, 1] of M(q) / sqrt(1 - q^2) (dphi = dq / sqrt(1 - q^2) on [0, pi/2]), M(q) = 2 integral E mu dmu, itself
// linear in q between the nodes' M_j: integrated exactly per segment with asin and sqrt(1 - q^2).
float anisoCosineWeightedMean(const float* rows) {
    double sum = 0.0;
    std::vector<double> m(kPtAlbedoAnisoAz);
    for (uint32_t j = 0; j < kPtAlbedoAnisoAz; ++j) m[j] = cosineWeightedMean(rows + j * kPtAlbedoAnisoMu, kPtAlbedoAnisoMu);
    for (uint32_t j = 0; j + 1 < kPtAlbedoAnisoAz; ++j) {
        const double a = double(j) / (kPtAlbedoAnisoAz - 1), b = double(j + 1) / (kPtAlbedoAnisoAz - 1);
        const double i0 = std::asin(b) - std::asin(a);                        // integral of 1 / sqrt(1 - q^2)
        const double i1 = std::sqrt(1.0 - a * a) - std::sqrt(1.0 - b * b);    // integral of q / sqrt(1 - q^2)
        sum += m[j] * i0 + (m[j + 1] - m[j]) / (b - a) * (i1 - a * i0);
    }
    return float(sum * 2.0 / 3.14159265358979323846);
}

// C++ sees the array; GLSL sees only its offset in the packed table buffer (pt_energy.h), because glslang copies a
// dynamically indexed constant array into a function-local variable at every use (tens of KB per lookup).
void writeArray(std::ostringstream& out, const char* name, const std::vector<float>& values, uint32_t& offset) {
    out << "IDK_CONST(uint, " << name << "Offset, " << offset << "u);\n";
    offset += uint32_t(values.size());
    out << "#ifdef __cplusplus\ninline constexpr float " << name << "[" << values.size() << "] = {\n";
    char buffer[32];
    for (size_t i = 0; i < values.size(); ++i) {
        std::snprintf(buffer, sizeof(buffer), "%.9g", double(values[i]));
        std::string text = buffer;
        if (text.find_first_of(".e") == std::string::npos) text += ".0";
        out << text << (i + 1 < values.size() ? "," : "") << ((i + 1) % 8 == 0 ? "\n" : " ");
    }
    out << "\n};\n#endif\n\n";
}

}  // namespace

double ggxReflectionAlbedo(float mu, float roughness, int strata) {
    const glm::vec3 o = outgoing(mu);
    const float alpha = alphaOf(roughness);
    const double g1 = ptGgxG1(o.z, alpha);
    double sum = 0.0;
    for (int a = 0; a < strata; ++a) {
        double weight;
        const float u1 = tailWarp(a, strata, weight);
        for (int b = 0; b < strata; ++b) {
            const glm::vec3 h = ptSampleGgxVndf(o, alpha, u1, (float(b) + 0.5f) / float(strata));
            const glm::vec3 l = h * (2.0f * glm::dot(o, h)) - o;
            if (l.z > 0.0f) sum += weight * ptGgxG2(o.z, l.z, alpha) / g1;
        }
    }
    return sum / (double(strata) * double(strata));
}

double ggxAnisoReflectionAlbedo(float mu, float q, float roughness, float strength, int strata) {
    const float c = std::max(mu, kPtAlbedoMinMu);
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - c * c));
    const float qc = std::clamp(q, 0.0f, 1.0f);
    const glm::vec3 o(sinTheta * qc, sinTheta * std::sqrt(std::max(0.0f, 1.0f - qc * qc)), c);
    const float alpha = roughness * roughness;
    const float ax = std::max(alpha + (1.0f - alpha) * strength * strength, kPtDeltaAlpha);  // mix(alpha, 1, s^2)
    const float ay = std::max(alpha, kPtDeltaAlpha);
    const double g1 = ptGgxAnisoG1(o, ax, ay);
    double sum = 0.0;
    for (int a = 0; a < strata; ++a) {
        double weight;
        const float u1 = tailWarp(a, strata, weight);
        for (int b = 0; b < strata; ++b) {
            const glm::vec3 h = ptSampleGgxAnisoVndf(o, ax, ay, u1, (float(b) + 0.5f) / float(strata));
            const glm::vec3 l = h * (2.0f * glm::dot(o, h)) - o;
            if (l.z > 0.0f) sum += weight * ptGgxAnisoG2(o, l, ax, ay) / g1;
        }
    }
    return sum / (double(strata) * double(strata));
}

namespace {

// The rough dielectric interface's albedo, by VNDF samples on the tail-warped grid: the reflected energy, plus the
// refracted energy when `withTransmission`.
double ggxDielectricInterface(float mu, float roughness, float eta, int strata, bool withTransmission) {
    const glm::vec3 o = outgoing(mu);
    const float alpha = alphaOf(roughness);
    const double g1 = ptGgxG1(o.z, alpha);
    double sum = 0.0;
    for (int a = 0; a < strata; ++a) {
        double weight;
        const float u1 = tailWarp(a, strata, weight);
        for (int b = 0; b < strata; ++b) {
            const glm::vec3 h = ptSampleGgxVndf(o, alpha, u1, (float(b) + 0.5f) / float(strata));
            const float cosOH = glm::dot(o, h);
            const float f = ptFresnelDielectric(cosOH, eta);
            const glm::vec3 r = h * (2.0f * cosOH) - o;
            if (r.z > 0.0f) sum += weight * f * ptGgxG2(o.z, r.z, alpha) / g1;
            if (!withTransmission) continue;
            const float sin2T = (1.0f - cosOH * cosOH) / (eta * eta);
            if (sin2T >= 1.0f) continue;
            const glm::vec3 t = glm::normalize(-o / eta + h * (cosOH / eta - std::sqrt(1.0f - sin2T)));
            if (t.z < 0.0f) sum += weight * (1.0f - f) * ptGgxG2(o.z, -t.z, alpha) / g1;
        }
    }
    return sum / (double(strata) * double(strata));
}

}  // namespace

double ggxDielectricAlbedo(float mu, float roughness, float eta, int strata) {
    if (std::abs(eta - 1.0f) < 1.0e-3f) return 1.0;  // the BSDF's delta pass-through: nothing is lost
    return ggxDielectricInterface(mu, roughness, eta, strata, true);
}

double ggxDielectricReflectionAlbedo(float mu, float roughness, float eta, int strata) {
    return ggxDielectricInterface(mu, roughness, eta, strata, false);
}

double sheenAlbedo(float mu, float roughness, int strata) {
    const glm::vec3 o = outgoing(mu);
    const float alpha = ptSheenAlpha(roughness);
    // The lobe peaks at grazing light for smooth sheens: more cells in cos theta than in phi.
    const int nMu = 4 * strata, nPhi = strata;
    double sum = 0.0;
    for (int a = 0; a < nMu; ++a) {
        const float c = (float(a) + 0.5f) / float(nMu);
        const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
        for (int b = 0; b < nPhi; ++b) {
            const float phi = kPtPi * (float(b) + 0.5f) / float(nPhi);  // symmetric about wo's plane
            sum += ptSheenCos(o, glm::vec3(s * std::cos(phi), s * std::sin(phi), c), alpha);
        }
    }
    return sum * 2.0 * double(kPtPi) / double(nMu * nPhi);
}

AlbedoTables computeAlbedoTables(int strata) {
    AlbedoTables t;
    for (uint32_t j = 0; j < kPtAlbedoRough; ++j) {
        const float r = ptAlbedoNodeRough(j, kPtAlbedoRough);
        for (uint32_t i = 0; i < kPtAlbedoMu; ++i) {
            const float mu = ptAlbedoNodeMu(i, kPtAlbedoMu);
            t.metal.push_back(float(ggxReflectionAlbedo(mu, r, strata)));
            t.sheen.push_back(float(sheenAlbedo(mu, r, strata)));
        }
        t.metalAvg.push_back(cosineWeightedMean(&t.metal[j * kPtAlbedoMu], kPtAlbedoMu));
        // Bin probabilities of (1 - E) mu, E piecewise linear between the nodes: integral over [a, b] of
        // (1 - e0 - (e1 - e0) (mu - a) / (b - a)) mu dmu.
        std::vector<double> w(kPtAlbedoMsBins);
        double total = 0.0;
        for (uint32_t k = 0; k < kPtAlbedoMsBins; ++k) {
            const double a = double(k) / kPtAlbedoMsBins, b = double(k + 1) / kPtAlbedoMsBins;
            const double g0 = 1.0 - t.metal[j * kPtAlbedoMu + k], g1 = 1.0 - t.metal[j * kPtAlbedoMu + k + 1];
            const double slope = (g1 - g0) / (b - a);
            w[k] = std::max(0.0, g0 * (b * b - a * a) / 2.0 +
                                     slope * ((b * b * b - a * a * a) / 3.0 - a * (b * b - a * a) / 2.0));
            total += w[k];
        }
        for (uint32_t k = 0; k < kPtAlbedoMsBins; ++k)  // no loss at all: plain cosine (bins ~ their mu^2 share)
            t.msBins.push_back(float(total > 0.0 ? w[k] / total
                                                 : (double(2 * k + 1) / (kPtAlbedoMsBins * double(kPtAlbedoMsBins)))));
    }
    for (uint32_t l = 0; l < kPtAlbedoAnisoStrength; ++l) {
        const float strength = ptAlbedoNodeRough(l, kPtAlbedoAnisoStrength);
        for (uint32_t k = 0; k < kPtAlbedoAnisoRough; ++k) {
            const float r = ptAlbedoNodeRough(k, kPtAlbedoAnisoRough);
            const size_t first = t.anisoMetal.size();
            for (uint32_t j = 0; j < kPtAlbedoAnisoAz; ++j)
                for (uint32_t i = 0; i < kPtAlbedoAnisoMu; ++i)
                    t.anisoMetal.push_back(float(ggxAnisoReflectionAlbedo(ptAlbedoNodeMu(i, kPtAlbedoAnisoMu),
                                                                          ptAlbedoNodeRough(j, kPtAlbedoAnisoAz), r,
                                                                          strength, strata)));
            t.anisoAvg.push_back(anisoCosineWeightedMean(&t.anisoMetal[first]));
        }
    }
    for (uint32_t side = 0; side < 2; ++side) {
        for (uint32_t k = 0; k < kPtAlbedoDielIor; ++k) {
            const float ior = ptAlbedoNodeIor(k, kPtAlbedoDielIor);
            const float eta = side == 0 ? ior : 1.0f / ior;
            for (uint32_t j = 0; j < kPtAlbedoDielRough; ++j) {
                const float r = ptAlbedoNodeRough(j, kPtAlbedoDielRough);
                for (uint32_t i = 0; i < kPtAlbedoDielMu; ++i)
                    t.dielectric.push_back(float(ggxDielectricAlbedo(ptAlbedoNodeMu(i, kPtAlbedoDielMu), r, eta, strata)));
            }
        }
    }
    for (uint32_t k = 0; k < kPtAlbedoSpecIor; ++k) {
        const float ior = ptAlbedoNodeIor(k, kPtAlbedoSpecIor);
        for (uint32_t j = 0; j < kPtAlbedoSpecRough; ++j) {
            const float r = ptAlbedoNodeRough(j, kPtAlbedoSpecRough);
            const size_t row = t.specular.size();
            for (uint32_t i = 0; i < kPtAlbedoDielMu; ++i)
                t.specular.push_back(
                    float(ggxDielectricReflectionAlbedo(ptAlbedoNodeMu(i, kPtAlbedoDielMu), r, ior, strata)));
            t.specularAvg.push_back(cosineWeightedMean(&t.specular[row], kPtAlbedoDielMu));
        }
    }
    return t;
}

std::string albedoTablesHeader(const AlbedoTables& tables) {
    std::ostringstream out;
    out << "// pt_albedo_tables.h: GENERATED by `idk_albedo_tables` (engine/app/albedo_tables_main.cpp) from\n"
           "// engine/pathtrace/albedo_integrator.cpp; do not edit. Layout and meaning: pt_albedo_layout.h. The unit test\n"
           "// PtAlbedoTables.CommittedTablesMatchTheIntegrator recomputes them.\n"
           "#ifndef IDK_PT_ALBEDO_TABLES_H\n#define IDK_PT_ALBEDO_TABLES_H\n#include \"pt_albedo_layout.h\"\n\n"
           "IDK_GPU_BEGIN\n\n";
    uint32_t offset = 0;
    writeArray(out, "kPtAlbedoMetal", tables.metal, offset);
    writeArray(out, "kPtAlbedoMetalAvg", tables.metalAvg, offset);
    writeArray(out, "kPtAlbedoDielectric", tables.dielectric, offset);
    writeArray(out, "kPtAlbedoSheen", tables.sheen, offset);
    writeArray(out, "kPtAlbedoMsBinTable", tables.msBins, offset);
    writeArray(out, "kPtAlbedoAnisoMetal", tables.anisoMetal, offset);
    writeArray(out, "kPtAlbedoAnisoAvg", tables.anisoAvg, offset);
    writeArray(out, "kPtAlbedoSpecular", tables.specular, offset);
    writeArray(out, "kPtAlbedoSpecularAvg", tables.specularAvg, offset);
    out << "IDK_CONST(uint, kPtAlbedoTableFloats, " << offset << "u);  // all tables, packed in this order\n\n";
    out << "IDK_GPU_END\n\n#endif\n";
    return out.str();
}

}  // namespace idk::pathtrace
