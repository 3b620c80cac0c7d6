// degenerate_test.cpp: the shared maths never produce NaN or infinity: degenerate and NaN normals, zero and NaN
// directions, roughness 0 and 1, IOR 1 and NaN, zero-area and NaN emitters, grazing angles.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "shared/pt_sampling.h"

namespace idk::test {
namespace {

using namespace idk::gpu;

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

TEST(PtDegenerate, BsdfStaysFinite) {
    const glm::vec3 normals[] = {glm::vec3(0.0f), glm::vec3(kNaN), glm::vec3(0.0f, 0.0f, 1.0f),
                                 glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(kInf, 0.0f, 0.0f), glm::vec3(1e-20f, 0.0f, 0.0f)};
    const glm::vec3 dirs[] = {glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f),
                              glm::vec3(kNaN), glm::normalize(glm::vec3(1.0f, 0.0f, -1e-7f)),
                              glm::vec3(0.0f, 0.0f, -1.0f)};
    const float roughness[] = {0.0f, 1.0f, kNaN, -1.0f, 0.5f};
    const float iors[] = {1.0f, 1.5f, kNaN, 0.0f, 100.0f};
    std::mt19937 gen(1);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    int cases = 0;
    for (const glm::vec3& ns : normals)
        for (const glm::vec3& ng : normals)
            for (const glm::vec3& wo : dirs)
                for (float r : roughness)
                    for (float ior : iors)
                        for (float transmission : {0.0f, 1.0f})
                            for (float thickness : {0.0f, 1.0f}) {
                                PtSurface s{};
                                s.baseColor = glm::vec3(0.8f);
                                s.metallic = 0.2f;
                                s.roughness = r;
                                s.transmission = transmission;
                                s.ior = ior;
                                s.thickness = thickness;
                                s.shadingNormal = ns;
                                s.geometricNormal = ng;
                                s.specular = 1.0f;
                                s.specularColor = glm::vec3(1.0f);
                                s.clearcoat = transmission;  // the extension lobes too
                                s.clearcoatRoughness = r;
                                s.sheenColor = glm::vec3(thickness * 0.5f);
                                s.sheenRoughness = r;
                                glm::vec3 wi, weight;
                                float pdf;
                                uint lobe;
                                ptSampleBsdf(s, wo, glm::vec3(uni(gen), uni(gen), uni(gen)), wi, weight, pdf, lobe);
                                ASSERT_TRUE(finite(weight) && std::isfinite(pdf)) << cases;
                                ASSERT_TRUE(lobe == kPtLobeNone || finite(wi)) << cases;
                                float evalPdf;
                                const glm::vec3 f = ptEvalBsdf(s, wo, dirs[cases % 6], evalPdf);
                                ASSERT_TRUE(finite(f) && std::isfinite(evalPdf)) << cases;
                                ++cases;
                            }
}

TEST(PtDegenerate, LightsStayFinite) {
    GpuPtLight tri{};
    tri.type = kPtLightTriangle;
    tri.position = glm::vec3(0.0f, 1.0f, 0.0f);
    tri.intensity = glm::vec3(1.0f);
    PtLightSample s;
    // Zero-area emitters: a point, a line.
    tri.direction = glm::vec3(0.0f);
    tri.edge2 = glm::vec3(0.0f);
    EXPECT_FALSE(ptSampleLight(tri, glm::vec3(0.0f), glm::vec2(0.3f, 0.6f), s));
    EXPECT_EQ(ptLightPdf(tri, glm::vec3(0.0f), tri.position), 0.0f);
    tri.direction = glm::vec3(1.0f, 0.0f, 0.0f);
    tri.edge2 = glm::vec3(2.0f, 0.0f, 0.0f);
    EXPECT_FALSE(ptSampleLight(tri, glm::vec3(0.0f), glm::vec2(0.3f, 0.6f), s));
    EXPECT_EQ(ptLightPdf(tri, glm::vec3(0.0f), tri.position), 0.0f);
    // NaN vertices.
    tri.edge2 = glm::vec3(kNaN);
    EXPECT_FALSE(ptSampleLight(tri, glm::vec3(0.0f), glm::vec2(0.3f, 0.6f), s));
    EXPECT_TRUE(std::isfinite(ptLightPdf(tri, glm::vec3(0.0f), tri.position)));
    // A point light at the shading point itself.
    GpuPtLight point{};
    point.type = kPtLightPoint;
    point.intensity = glm::vec3(1.0f);
    EXPECT_FALSE(ptSampleLight(point, glm::vec3(0.0f), glm::vec2(0.5f), s));
    // The environment at the poles and for NaN.
    glm::vec3 dir;
    EXPECT_EQ(ptEnvironmentPdf(0.5f, glm::vec3(0.0f, 1.0f, 0.0f), 8, 4), 0.0f);
    EXPECT_TRUE(std::isfinite(ptSampleEnvironment(0, 0.5f, 8, 4, glm::vec2(0.0f), dir)));
    EXPECT_LT(ptEnvironmentTexel(glm::vec3(kNaN), 8, 4), 32u);
    EXPECT_EQ(ptPowerHeuristic(kInf, 1.0f), 1.0f);
    EXPECT_EQ(ptPowerHeuristic(0.0f, 0.0f), 0.0f);
}

}  // namespace
}  // namespace idk::test
