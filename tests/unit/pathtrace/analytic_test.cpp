// analytic_test.cpp: the CPU reference path tracer against closed-form answers: the white furnace (an albedo-1
// Lambert sphere in a uniform environment returns the environment's radiance), lossless glass is invisible in a
// furnace, a glass slab with Beer-Lambert absorption and Fresnel inter-reflections, punctual lights' irradiance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "pathtrace/cpu_path_tracer.hpp"
#include "pt_test_scenes.hpp"
#include "scene/gltf_loader.hpp"
#include "scene/primitive_ops.hpp"

namespace idk::test {
namespace {

using pathtrace::PtSettings;

scene::Scene furnaceScene() {
    scene::Scene s;
    scene::Material white = diffuse(glm::vec3(1.0f));
    white.ior = 1.0f;  // no Fresnel coat: the whole albedo is the Lambert lobe
    // Flat normals: shading normal = geometric normal, so no direction is lost at the silhouette (a smooth-shaded
    // tessellated sphere rejects samples that go below the facet, a real but unwanted loss here).
    scene::Primitive sphere = uvSphere(glm::vec3(0.0f), 1.0f, 24, 48);
    scene::makeFlatNormals(sphere);
    addObject(s, sphere, white);
    return s;
}

TEST(PtReference, WhiteFurnace) {
    const pathtrace::PathTraceScene pts =
        pathtrace::buildPathTraceScene(furnaceScene(), nullptr, 1.0f, glm::vec3(0.75f));
    const scene::CameraView cam = lookAt(glm::vec3(0.0f, 0.5f, 4.0f), glm::vec3(0.0f), 0.5f);
    for (bool nee : {true, false}) {
        PtSettings settings;
        settings.spp = 16;
        settings.maxDepth = 16;
        settings.nee = nee;
        const core::ImageRgba32f img = pathtrace::renderReference(pts, cam, 16, 16, settings);
        const glm::dvec3 mean = imageMean(img);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], 0.75, 0.0075) << (nee ? "nee" : "bsdf");
        // BSDF sampling alone is exact here (weight 1, every bounce escapes the convex sphere); NEE + MIS only
        // on average, each pixel is a 16-sample estimate.
        const float tolerance = nee ? 0.2f : 1e-4f;
        for (size_t i = 0; i < img.pixels.size(); i += 4)
            ASSERT_NEAR(img.pixels[i], 0.75f, tolerance) << "pixel " << i / 4 << (nee ? " nee" : " bsdf");
    }
}

// Direct light from punctual lights on a Lambert floor (IOR 1: no Fresnel coat), one NEE sample per path and a
// single light, so every estimate is exact: albedo / pi * E, E = I cos / d^2 (point), with the spot cone's
// smooth falloff and the range window as include/pbr.glsl computes them, or the directional illuminance * cos.
TEST(PtReference, PunctualLightsGiveTheAnalyticIrradiance) {
    const float pi = 3.14159265f;
    const glm::vec3 p(0.3f, 0.0f, -0.2f);  // the floor point the camera ray hits
    for (scene::LightType type : {scene::LightType::Point, scene::LightType::Spot, scene::LightType::Directional}) {
        scene::Scene s;
        scene::Material floor = diffuse(glm::vec3(0.5f));
        floor.ior = 1.0f;
        addObject(s, quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}), floor);
        scene::Light light;
        light.type = type;
        light.position = glm::vec3(-0.2f, 1.5f, 0.4f);
        light.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.1f));
        light.color = glm::vec3(1.0f, 0.5f, 0.25f);
        light.intensity = 8.0f;
        light.range = type == scene::LightType::Point ? 3.0f : 0.0f;
        light.innerConeAngle = 0.2f;
        light.outerConeAngle = 0.6f;
        s.lights.push_back(light);
        const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, nullptr, 1.0f);
        PtSettings settings;
        settings.maxDepth = 2;
        const glm::vec3 origin = p + glm::vec3(0.0f, 2.0f, 1.0f);
        gpu::PtRng rng = gpu::ptRngInit(1, 2, 3);
        const glm::vec3 l = pathtrace::traceRadiance(pts, origin, glm::normalize(p - origin), rng, settings);

        glm::vec3 e;
        if (type == scene::LightType::Directional) {
            e = light.color * light.intensity * -light.direction.y;
        } else {
            const glm::vec3 toLight = light.position - p;
            const float d2 = glm::dot(toLight, toLight);
            float attenuation = 1.0f / d2;
            if (light.range > 0.0f) {
                const float r = d2 / (light.range * light.range);
                attenuation *= std::pow(std::clamp(1.0f - r * r, 0.0f, 1.0f), 2.0f);
            }
            if (type == scene::LightType::Spot) {
                const float cd = glm::dot(light.direction, -glm::normalize(toLight));
                const float scale = 1.0f / std::max(0.001f, std::cos(0.2f) - std::cos(0.6f));
                attenuation *= std::pow(std::clamp((cd - std::cos(0.6f)) * scale, 0.0f, 1.0f), 2.0f);
            }
            e = light.color * light.intensity * attenuation * (toLight.y / std::sqrt(d2));
        }
        const glm::vec3 expected = 0.5f / pi * e;
        ASSERT_GT(expected.x, 0.01f) << "the point is lit";
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(l[c], expected[c], 1e-4f * expected.x) << int(type) << " " << c;
    }
}

// A lossless smooth dielectric (refracting volume or thin-walled sheet) in a uniform environment is invisible:
// Fresnel reflection, refraction with its 1/eta^2 radiance scaling and total internal reflection conserve energy,
// so every path returns the environment's radiance (flat facets: no shading-normal loss).
TEST(PtReference, GlassFurnace) {
    for (float thickness : {1.0f, 0.0f}) {
        scene::Scene s;
        scene::Material glass = diffuse(glm::vec3(1.0f));
        glass.transmission = 1.0f;
        glass.roughness = 0.0f;
        glass.ior = 1.5f;
        glass.thickness = thickness;
        glass.doubleSided = true;
        scene::Primitive sphere = uvSphere(glm::vec3(0.0f), 1.0f, 12, 24);
        scene::makeFlatNormals(sphere);
        addObject(s, sphere, glass);
        const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, nullptr, 1.0f, glm::vec3(0.5f));
        const scene::CameraView cam = lookAt(glm::vec3(0.0f, 0.5f, 4.0f), glm::vec3(0.0f), 0.5f);
        PtSettings settings;
        settings.spp = 64;
        settings.maxDepth = 64;
        const core::ImageRgba32f img = pathtrace::renderReference(pts, cam, 16, 16, settings);
        const glm::dvec3 mean = imageMean(img);
        // The volume's paths carry weights 1/eta^2 and eta^2 and Russian roulette: 2% at 16k paths (at 1M paths
        // without roulette it measured 0.4994; the sheet is exact).
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], 0.5, 0.01) << "thickness " << thickness;
    }
}

// A smooth glass cube (side 1, attenuation colour c at distance 1: transmittance T = c per crossing) in a white
// environment, seen head-on: every path runs along the axis. IOR 1: exactly T. IOR 1.5, by Monte Carlo: the slab
// series, F + (1 - F)^2 T sum_k (F T)^k = F + (1 - F)^2 T / (1 - F T) (light leaving through the back after 0, 2,
// 4... internal reflections and through the front after 1, 3...), F = ((1.5 - 1) / 2.5)^2 = 0.04.
TEST(PtReference, GlassTransmissionAndBeerLambertAbsorption) {
    for (float ior : {1.0f, 1.5f}) {
        scene::Scene s;
        scene::Material glass = diffuse(glm::vec3(1.0f));
        glass.transmission = 1.0f;
        glass.roughness = 0.0f;
        glass.ior = ior;
        glass.thickness = 1.0f;
        glass.attenuationDistance = 1.0f;
        glass.attenuationColor = glm::vec3(0.5f, 0.8f, 1.0f);
        addObject(s, box(glm::vec3(-0.5f), glm::vec3(0.5f)), glass);
        const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(s, nullptr, 1.0f, glm::vec3(1.0f));
        PtSettings settings;
        settings.maxDepth = 64;
        glm::dvec3 sum(0.0);
        const uint32_t n = ior == 1.0f ? 16 : 40000;
        for (uint32_t i = 0; i < n; ++i) {
            gpu::PtRng rng = gpu::ptRngInit(i, 0, 7);
            sum += glm::dvec3(pathtrace::traceRadiance(pts, glm::vec3(0.1f, 0.05f, 3.0f), glm::vec3(0.0f, 0.0f, -1.0f),
                                                       rng, settings));
        }
        const glm::dvec3 mean = sum / double(n);
        const double f = 0.04;
        for (int c = 0; c < 3; ++c) {
            const double t = glass.attenuationColor[c];
            const double expected = ior == 1.0f ? t : f + (1.0 - f) * (1.0 - f) * t / (1.0 - f * t);
            EXPECT_NEAR(mean[c], expected, ior == 1.0f ? 1e-5 : 0.01) << "ior " << ior << " channel " << c;
        }
    }
}

}  // namespace
}  // namespace idk::test
