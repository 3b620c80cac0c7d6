// bvh_embree_test.cpp: Embree 3 as the peer. Its scene is built with RTC_SCENE_FLAG_ROBUST (watertight) and
// RTC_BUILD_QUALITY_HIGH; our CPU traversal must agree on hit or miss and on the triangle id for >= 200k rays per
// scene (when ids differ, both hits must lie at the same t within 1e-5 relative: a tie on a shared edge) on the
// bunny, BrainStem, MetalRoughSpheresNoTextures (about 1M triangles) and the rotated atrium.
// Also prints the SAH of Embree's own high-quality builder (rtcBuildBVH with spatial splits) by our formula.
#include "bvh_test_util.hpp"

#include "bvh/geometry.hpp"
#include "bvh/procedural.hpp"
#include "scene/gltf_loader.hpp"

#include <embree3/rtcore.h>

#include <chrono>
#include <iostream>
#include <new>
#include <set>

namespace idk::bvh {
namespace {

using test::bunny;

class EmbreeScene {
public:
    explicit EmbreeScene(const std::vector<Triangle>& tris) {
        device_ = rtcNewDevice(nullptr);
        scene_ = rtcNewScene(device_);
        rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
        RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                     RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * tris.size()));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                       RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris.size()));
        for (size_t t = 0; t < tris.size(); ++t) {
            const glm::vec3* v[3] = {&tris[t].v0, &tris[t].v1, &tris[t].v2};
            for (int k = 0; k < 3; ++k) {
                for (int c = 0; c < 3; ++c) vertices[9 * t + 3 * k + c] = (*v[k])[c];
                indices[3 * t + k] = unsigned(3 * t + k);
            }
        }
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene_, geometry);
        rtcReleaseGeometry(geometry);
        rtcCommitScene(scene_);
    }
    ~EmbreeScene() {
        rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
    }
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    Hit intersect(const Ray& ray) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh{};
        rh.ray.org_x = ray.origin.x, rh.ray.org_y = ray.origin.y, rh.ray.org_z = ray.origin.z;
        rh.ray.dir_x = ray.direction.x, rh.ray.dir_y = ray.direction.y, rh.ray.dir_z = ray.direction.z;
        rh.ray.tnear = ray.tMin;
        rh.ray.tfar = ray.tMax;
        rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &context, &rh);
        Hit hit;
        if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
            hit.triangleId = rh.hit.primID;
            hit.t = rh.ray.tfar;
            hit.u = rh.hit.u;
            hit.v = rh.hit.v;
        }
        return hit;
    }

private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
};

struct PeerResult {
    uint32_t hits = 0;
    uint32_t hitMissDisagreements = 0;
    uint32_t ties = 0;          // different ids at the same t (within 1e-5)
    uint32_t idDisagreements = 0;  // different ids at different t
};

PeerResult compareWithEmbree(const Blas& blas, const EmbreeScene& embree, const std::vector<Ray>& rays) {
    PeerResult r;
    for (const Ray& ray : rays) {
        const Hit ours = closestHit(blas, ray);
        const Hit theirs = embree.intersect(ray);
        r.hits += ours.hit() ? 1 : 0;
        if (ours.hit() != theirs.hit()) {
            if (r.hitMissDisagreements++ < 5) {
                std::cout << "  hit/miss differs: ours " << ours.triangleId << " embree " << theirs.triangleId << "\n";
            }
            continue;
        }
        if (!ours.hit() || ours.triangleId == theirs.triangleId) continue;
        if (test::relativeClose(ours.t, theirs.t, 1e-5f)) {
            ++r.ties;
        } else if (r.idDisagreements++ < 5) {
            std::cout << "  id differs: ours " << ours.triangleId << " t " << ours.t << ", embree " << theirs.triangleId
                      << " t " << theirs.t << "\n";
        }
    }
    return r;
}

// minHitFraction: a sanity floor so a scene the rays mostly miss cannot pass by agreeing on misses.
void expectAgreement(const char* scene, const PeerResult& r, uint32_t rayCount, double minHitFraction = 0.25) {
    std::cout << "[ embree ] " << scene << ": " << rayCount << " rays, " << r.hits << " hits, " << r.ties
              << " edge ties\n";
    EXPECT_EQ(r.hitMissDisagreements, 0u) << scene;
    EXPECT_EQ(r.idDisagreements, 0u) << scene;
    EXPECT_GT(r.hits, uint32_t(rayCount * minHitFraction)) << scene;
}

TEST(BvhEmbree, BunnyAgreesWithEmbreeRobustOn200kRays) {
    const std::vector<Triangle>& tris = bunny();
    const EmbreeScene embree(tris);
    const std::vector<Ray> rays = test::randomRays(test::boundsOf(tris), 200000, 101);
    expectAgreement("bunny", compareWithEmbree(buildBlas(tris), embree, rays), 200000);
}

// Every instanced triangle of a glTF asset in world space (the peer sees exactly the same triangles).
std::vector<Triangle> gltfWorldTriangles(const char* relativePath) {
    scene::Scene s = scene::loadGltf(std::string(IDK_SHARED_DIR) + "/scenes/" + relativePath);
    std::vector<Triangle> tris;
    for (const scene::Instance& instance : s.instances) {
        for (const scene::Primitive& p : s.meshes[instance.mesh].primitives) {
            auto world = [&](uint32_t i) { return glm::vec3(instance.world * glm::vec4(p.positions[i], 1.0f)); };
            for (size_t k = 0; k + 2 < p.indices.size(); k += 3)
                tris.push_back({world(p.indices[k]), world(p.indices[k + 1]), world(p.indices[k + 2])});
        }
    }
    return tris;
}

TEST(BvhEmbree, BrainStemAgreesWithEmbreeRobustOn200kRays) {
    const std::vector<Triangle> tris = gltfWorldTriangles("BrainStem/glTF-Binary/BrainStem.glb");
    ASSERT_GT(tris.size(), 60000u);
    const EmbreeScene embree(tris);
    const std::vector<Ray> rays = test::randomRays(test::boundsOf(tris), 200000, 103);
    // A thin figure inside its bounding box: about 22% of the random rays hit it.
    expectAgreement("BrainStem", compareWithEmbree(buildBlas(tris), embree, rays), 200000, 0.15);
}

TEST(BvhEmbree, MetalRoughSpheresAgreeWithEmbreeRobustOn200kRays) {
    const std::vector<Triangle> tris =
        gltfWorldTriangles("MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb");
    ASSERT_GT(tris.size(), 1000000u);  // about 1.04 M triangles after instancing
    const EmbreeScene embree(tris);
    const std::vector<Ray> rays = test::randomRays(test::boundsOf(tris), 200000, 104);
    expectAgreement("MetalRoughSpheresNoTextures", compareWithEmbree(buildBlas(tris), embree, rays), 200000);
}

TEST(BvhEmbree, RotatedAtriumAgreesWithEmbreeRobustOn200kRays) {
    IndexedMesh mesh = makeAtrium();
    rotateAboutCenter(mesh, 45.0f);
    const std::vector<Triangle> tris = mesh.triangles();
    const EmbreeScene embree(tris);
    const std::vector<Ray> rays = test::randomRays(test::boundsOf(tris), 200000, 102);
    expectAgreement("rotated atrium", compareWithEmbree(buildBlas(tris), embree, rays), 200000);
    expectAgreement("rotated atrium, split 1.0",
                    compareWithEmbree(buildBlas(tris, BuildOptions{.splitFactor = 1.0f}), embree, rays), 200000);
    expectAgreement("rotated atrium, spatial splits",
                    compareWithEmbree(buildBlas(tris, BuildOptions{.spatialSplits = true}), embree, rays), 200000);
}

// --- Embree's own builder (rtcBuildBVH), only to put its SAH next to ours. ---

struct EmbreeNode {
    bool leaf = false;
    Box bounds[2];
    EmbreeNode* children[2] = {nullptr, nullptr};
    uint32_t references = 0;  // leaf: distinct triangles (fragments of one triangle merged, as in our leaves)
};

struct EmbreeBuildContext {
    const std::vector<Triangle>* triangles = nullptr;
};

void* embreeCreateNode(RTCThreadLocalAllocator alloc, unsigned int, void*) {
    return new (rtcThreadLocalAlloc(alloc, sizeof(EmbreeNode), 16)) EmbreeNode();
}
void embreeSetChildren(void* node, void** children, unsigned int count, void*) {
    for (unsigned i = 0; i < count; ++i) static_cast<EmbreeNode*>(node)->children[i] = static_cast<EmbreeNode*>(children[i]);
}
void embreeSetBounds(void* node, const RTCBounds** bounds, unsigned int count, void*) {
    for (unsigned i = 0; i < count; ++i) {
        static_cast<EmbreeNode*>(node)->bounds[i] = {{bounds[i]->lower_x, bounds[i]->lower_y, bounds[i]->lower_z},
                                                     {bounds[i]->upper_x, bounds[i]->upper_y, bounds[i]->upper_z}};
    }
}
void* embreeCreateLeaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
    auto* node = new (rtcThreadLocalAlloc(alloc, sizeof(EmbreeNode), 16)) EmbreeNode();
    node->leaf = true;
    std::set<unsigned> ids;
    for (size_t i = 0; i < count; ++i) {
        ids.insert(prims[i].primID);
        node->bounds[0].grow(Box{{prims[i].lower_x, prims[i].lower_y, prims[i].lower_z},
                                 {prims[i].upper_x, prims[i].upper_y, prims[i].upper_z}});
    }
    node->references = uint32_t(ids.size());
    return node;
}
void embreeSplit(const RTCBuildPrimitive* prim, unsigned int dim, float pos, RTCBounds* left, RTCBounds* right, void* user) {
    const auto& tris = *static_cast<EmbreeBuildContext*>(user)->triangles;
    const Box current{{prim->lower_x, prim->lower_y, prim->lower_z}, {prim->upper_x, prim->upper_y, prim->upper_z}};
    Box l, r;
    splitTriangle(tris[prim->primID], int(dim), pos, current, l, r);
    // Embree expects both sides inside the current box; an empty side becomes a degenerate box on the plane.
    auto store = [&](Box b, RTCBounds* out, bool isLeft) {
        if (b.isEmpty()) {
            b = current;
            (isLeft ? b.min : b.max)[dim] = pos;
            (isLeft ? b.max : b.min)[dim] = pos;
        }
        *out = {b.min.x, b.min.y, b.min.z, 0.0f, b.max.x, b.max.y, b.max.z, 0.0f};
    };
    store(l, left, true);
    store(r, right, false);
}

double embreeSah(const EmbreeNode* node, const Box& box, double rootArea) {
    const double p = double(box.halfArea()) / rootArea;
    if (node->leaf) return kTriangleCost * node->references * p;
    return kTraversalCost * p + embreeSah(node->children[0], node->bounds[0], rootArea) +
           embreeSah(node->children[1], node->bounds[1], rootArea);
}

TEST(BvhEmbree, SahOfEmbreeBuildersNextToOurs) {
    const std::vector<Triangle>& tris = bunny();
    RTCDevice device = rtcNewDevice(nullptr);
    EmbreeBuildContext context{&tris};
    for (RTCBuildQuality quality : {RTC_BUILD_QUALITY_LOW, RTC_BUILD_QUALITY_MEDIUM, RTC_BUILD_QUALITY_HIGH}) {
        std::vector<RTCBuildPrimitive> prims(2 * tris.size());
        for (size_t i = 0; i < tris.size(); ++i) {
            const Box b = tris[i].box();
            prims[i] = {b.min.x, b.min.y, b.min.z, 0, b.max.x, b.max.y, b.max.z, unsigned(i)};
        }
        RTCBVH bvh = rtcNewBVH(device);
        RTCBuildArguments args = rtcDefaultBuildArguments();
        args.buildQuality = quality;
        args.maxDepth = 1024;
        args.maxLeafSize = 8;
        args.traversalCost = kTraversalCost;
        args.intersectionCost = kTriangleCost;
        args.bvh = bvh;
        args.primitives = prims.data();
        args.primitiveCount = tris.size();
        args.primitiveArrayCapacity = prims.size();  // room for spatial-split fragments (high quality)
        args.createNode = embreeCreateNode;
        args.setNodeChildren = embreeSetChildren;
        args.setNodeBounds = embreeSetBounds;
        args.createLeaf = embreeCreateLeaf;
        args.splitPrimitive = embreeSplit;
        args.userPtr = &context;
        const auto start = std::chrono::steady_clock::now();
        const auto* root = static_cast<const EmbreeNode*>(rtcBuildBVH(&args));
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        ASSERT_NE(root, nullptr);
        Box rootBox = root->bounds[0];
        if (!root->leaf) rootBox.grow(root->bounds[1]);
        const double sah = embreeSah(root, rootBox, rootBox.halfArea());
        std::cout << "[ embree rtcBuildBVH ] bunny quality " << int(quality) << ": SAH " << sah << ", build " << ms
                  << " ms\n";
        EXPECT_GT(sah, 1.0);
        rtcReleaseBVH(bvh);
    }
    rtcReleaseDevice(device);
    std::cout << "[ ours ] bunny split 0: SAH " << buildBlas(tris).stats.sah << "\n";
}

}  // namespace
}  // namespace idk::bvh
