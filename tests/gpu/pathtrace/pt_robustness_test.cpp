// pt_robustness_test.cpp: no NaN or infinity in any output of the GPU path tracer (radiance and the albedo /
// normal / depth guides) on hard cases: the Cornell box edited to contain a perfect mirror (roughness 0), a fully
// rough metal, a refracting volume with IOR 1 and absorption, zero and NaN vertex normals, and a zero-area emitter;
// and the shared TransmissionTest and AlphaBlendModeTest scenes (refraction, alpha MASK/BLEND pass-through), on both
// traversal rungs.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "app/default_scene.hpp"
#include "gpu/pathtrace/pt_image_util.hpp"
#include "pathtrace/pt_scene.hpp"
#include "scene/gltf_loader.hpp"
#include "support/gpu_fixture.hpp"
#include "vk/acceleration_structure.hpp"

namespace idk::test {
namespace {

constexpr uint32_t kSize = 32;

scene::Scene hardCornell() {
    scene::Scene s = app::loadDefaultScene();
    // Every material gets one of the hard settings in turn (emitters keep their emission).
    for (size_t i = 0; i < s.materials.size(); ++i) {
        scene::Material& m = s.materials[i];
        switch (i % 4) {
            case 0: m.roughness = 0.0f; m.metallic = 1.0f; break;             // perfect mirror
            case 1: m.transmission = 1.0f; m.ior = 1.0f; m.thickness = 1.0f;  // index-matched volume
                    m.roughness = 0.0f; m.attenuationDistance = 0.5f; m.attenuationColor = {0.9f, 0.5f, 0.2f}; break;
            case 2: m.roughness = 1.0f; m.metallic = 1.0f; break;             // fully rough metal
            default: m.transmission = 1.0f; m.ior = 1.5f; m.roughness = 0.3f; m.thickness = 0.0f; break;  // thin
        }
    }
    bool zeroed = false, nanned = false, collapsed = false;
    for (scene::Mesh& mesh : s.meshes) {
        for (scene::Primitive& p : mesh.primitives) {
            const bool emissive = p.material && *p.material < s.materials.size() &&
                                  s.materials[*p.material].emissive != glm::vec3(0.0f);
            if (emissive && !collapsed && p.indices.size() >= 3) {  // a zero-area emitter triangle
                p.positions[p.indices[1]] = p.positions[p.indices[0]];
                p.positions[p.indices[2]] = p.positions[p.indices[0]];
                collapsed = true;
            } else if (!zeroed) {
                for (glm::vec3& n : p.normals) n = glm::vec3(0.0f);
                zeroed = true;
            } else if (!nanned) {
                for (glm::vec3& n : p.normals) n = glm::vec3(std::numeric_limits<float>::quiet_NaN());
                nanned = true;
            }
        }
    }
    EXPECT_TRUE(collapsed && zeroed && nanned) << "the default scene no longer has the parts this test edits";
    return s;
}

scene::Scene shared(const char* relative) { return scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/" + relative); }

class PtRobustnessTest : public GpuTest {
protected:
    void expectFinite(const scene::Scene& scene, const char* name) {
        const pathtrace::PathTraceScene pts = pathtrace::buildPathTraceScene(scene, nullptr, 1.0f, glm::vec3(0.7f));
        // Two configurations cover both rungs, both estimators and both orders: (BVH, NEE+MIS, sorted) and
        // (ray query where available, BSDF sampling only, unsorted).
        for (const bool first : {true, false}) {
            const bool rq = !first && vk::rayQuerySupported(ctx());
            const bool nee = first;
            render::PathTracerOptions options;
            options.traversal = rq ? render::PtTraversal::RayQuery : render::PtTraversal::Bvh;
            options.readGuides = true;
            options.sortRays = first;
            render::PathTracer tracer(ctx(), shaders(), scene, pts, options);
            render::PathTraceSettings s;
            s.spp = 4;
            s.maxDepth = 6;
            s.rouletteDepth = 2;
            s.nee = nee;
            const render::PathTraceResult r = tracer.render(scene::defaultCamera(scene), kSize, kSize, s);
            const std::string what = std::string(name) + (rq ? " rayquery" : " bvh") + (nee ? " nee" : " bsdf");
            EXPECT_EQ(nonFiniteCount(r.image), 0u) << what << " radiance";
            EXPECT_EQ(nonFiniteCount(r.albedo), 0u) << what << " albedo";
            EXPECT_EQ(nonFiniteCount(r.normal), 0u) << what << " normal";
            EXPECT_EQ(nonFiniteCount(r.depth), 0u) << what << " depth";
            EXPECT_GT(meanRadiance(r.image), 0.0) << what << ": an all-black image would hide problems";
        }
    }
};

TEST_F(PtRobustnessTest, HardCornellIsFinite) { expectFinite(hardCornell(), "hard Cornell"); }

TEST_F(PtRobustnessTest, TransmissionTestIsFinite) {
    expectFinite(shared("TransmissionTest/glTF-Binary/TransmissionTest.glb"), "TransmissionTest");
}

TEST_F(PtRobustnessTest, AlphaBlendModeTestIsFinite) {
    expectFinite(shared("AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb"), "AlphaBlendModeTest");
}

}  // namespace
}  // namespace idk::test
