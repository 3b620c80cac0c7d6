// bvh_bench.cpp: the BVH (engine/bvh, issues 4 and 19) against Embree 3 on six scenes (bunny, BrainStem, ToyCar,
// MetalRoughSpheresNoTextures ~1M triangles after instancing, the procedural atrium and the atrium rotated 45 degrees
// on all axes): build time, SAH (our formula, bvh::computeSah) and EPO of our SweepSAH builder at split factors 0,
// 0.3 and 1.0, of our spatial-split builder (SBVH, reference budget 2x) and of Embree's rtcBuildBVH at low / medium /
// high quality (spatial splits for high, with the same 2x room for references and the same exact triangle clipping
// as ours through the split-primitive callback; its nodes are converted into our tree shape through the
// create-node / set-bounds callbacks); CPU closest-hit throughput of our
// traversal vs rtcIntersect1 (RTC_SCENE_FLAG_ROBUST), single ray, single thread, on primary camera rays and diffuse
// bounce rays; and the GLSL traversal's throughput on the Vulkan device (lavapipe here). Builds use every hardware
// thread on both sides. The 1M-triangle scene runs fewer repetitions (see kRepetitions).
#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <random>
#include <set>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>

#include "bench_support.hpp"
#include "bvh_bench_scenes.hpp"
#include "bvh/blas.hpp"
#include "bvh/flatten.hpp"
#include "bvh/metrics.hpp"
#include "bvh/procedural.hpp"
#include "bvh/raw_mesh.hpp"
#include "bvh/traverse.hpp"
#include "render/bvh_gpu.hpp"
#include "scene/gltf_loader.hpp"
#include "vk/transfer.hpp"

namespace idk::bench {
namespace {

constexpr uint32_t kImageSize = 256;         // primary rays: 256 x 256 pinhole camera
constexpr uint32_t kBounceRays = 1u << 16;   // diffuse bounce rays from the primary hits
constexpr float kTraceSplitFactor = 0.3f;    // the BLAS the traversal benchmarks use (IDKEngine's default)

struct SceneSpec {
    const char* name;
    const char* source;     // for the row's input column
    glm::vec3 viewFrom;     // outside camera direction (ignored for the atrium's inside camera)
    bool big;               // ~1M triangles: fewer repetitions
};

const SceneSpec kScenes[] = {
    {"bunny", "bunny.bin", {0.3f, 0.4f, 1.0f}, false},
    {"BrainStem", "BrainStem.glb, world space", {0.2f, 0.1f, 1.0f}, false},
    {"ToyCar", "ToyCar.gltf, world space", {0.6f, 0.5f, 1.0f}, false},
    {"MetalRoughSpheres", "MetalRoughSpheresNoTextures.glb, instanced, world space", {0.1f, 0.2f, 1.0f}, true},
    {"atrium", "procedural atrium", {0.0f, 0.0f, 0.0f}, false},
    {"atrium_rotated", "procedural atrium rotated 45 degrees on x, y, z", {0.0f, 0.0f, 0.0f}, false},
};

std::filesystem::path sharedPath(const std::string& relative) {
    return std::filesystem::path(IDK_BENCH_SOURCE_DIR) / ".." / "shared" / relative;
}

glm::mat4 atriumRotation(const bvh::IndexedMesh& mesh) {  // as bvh::rotateAboutCenter(mesh, 45)
    bvh::Box box;
    for (const glm::vec3& p : mesh.positions) box.grow(p);
    const glm::vec3 center = 0.5f * (box.min + box.max);
    const float r = glm::radians(45.0f);
    glm::mat4 m = glm::translate(glm::mat4(1.0f), center);
    m = glm::rotate(m, r, glm::vec3(0, 0, 1));
    m = glm::rotate(m, r, glm::vec3(0, 1, 0));
    m = glm::rotate(m, r, glm::vec3(1, 0, 0));
    return glm::translate(m, -center);
}

// Everything a scene's benchmarks share, built on first use and kept for the whole run.
struct SceneData {
    render::TriangleMesh mesh;
    std::vector<bvh::Triangle> triangles;
    glm::vec3 eye{0.0f}, target{0.0f};
    std::unique_ptr<bvh::Blas> traceBlas;  // split kTraceSplitFactor
    std::vector<bvh::Ray> primary, diffuse;
    std::vector<bvh::Hit> primaryHits, diffuseHits;  // our CPU traversal: the GPU's reference
};

std::vector<bvh::Triangle> trianglesOf(const render::TriangleMesh& mesh) {
    std::vector<bvh::Triangle> out(mesh.indices.size());
    for (size_t t = 0; t < out.size(); ++t) {
        const glm::uvec3 i = mesh.indices[t];
        out[t] = {mesh.positions[i.x], mesh.positions[i.y], mesh.positions[i.z]};
    }
    return out;
}

render::TriangleMesh loadMesh(const std::string& name, glm::vec3& eye, glm::vec3& target) {
    if (name == "bunny") {
        const std::vector<bvh::Triangle> tris = bvh::loadRawTriangles(sharedPath("scenes/bunny/bunny.bin").string());
        render::TriangleMesh mesh;
        for (uint32_t t = 0; t < tris.size(); ++t) {
            mesh.positions.insert(mesh.positions.end(), {tris[t].v0, tris[t].v1, tris[t].v2});
            mesh.indices.push_back({3 * t, 3 * t + 1, 3 * t + 2});
        }
        return mesh;
    }
    if (name == "atrium" || name == "atrium_rotated") {
        bvh::IndexedMesh atrium = bvh::makeAtrium();
        glm::mat4 m(1.0f);
        if (name == "atrium_rotated") {
            m = atriumRotation(atrium);
            bvh::rotateAboutCenter(atrium, 45.0f);
        }
        eye = glm::vec3(m * glm::vec4(-25.0f, 5.0f, -8.0f, 1.0f));  // inside the hall, looking along it
        target = glm::vec3(m * glm::vec4(20.0f, 10.0f, 5.0f, 1.0f));
        return {atrium.positions, atrium.indices};
    }
    std::filesystem::path path = name == "ToyCar" ? sharedPath("scenes/ToyCar/glTF/ToyCar.gltf")
                                                  : sharedScene(name == "MetalRoughSpheres" ? "MetalRoughSpheresNoTextures" : name);
    return render::worldTriangles(scene::loadGltf(path));
}

std::vector<bvh::Ray> cameraRays(glm::vec3 eye, glm::vec3 target) {
    const glm::vec3 forward = glm::normalize(target - eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, forward);
    const float tanHalf = std::tan(0.5f * 0.9f);
    std::vector<bvh::Ray> rays;
    for (uint32_t y = 0; y < kImageSize; ++y) {
        for (uint32_t x = 0; x < kImageSize; ++x) {
            const float sx = (2.0f * (float(x) + 0.5f) / float(kImageSize) - 1.0f) * tanHalf;
            const float sy = (2.0f * (float(y) + 0.5f) / float(kImageSize) - 1.0f) * tanHalf;
            rays.push_back({eye, glm::normalize(forward + sx * right + sy * up)});
        }
    }
    return rays;
}

// Cosine-weighted directions around the geometric normal at the primary hits (facing the camera), from origins moved
// off the surface with bvh::offsetRayOrigin: the rays a path tracer's first bounce traces.
std::vector<bvh::Ray> bounceRays(const SceneData& s) {
    std::vector<uint32_t> hitIndices;
    for (uint32_t i = 0; i < s.primaryHits.size(); ++i) {
        if (s.primaryHits[i].hit()) hitIndices.push_back(i);
    }
    std::vector<bvh::Ray> rays;
    if (hitIndices.empty()) return rays;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (uint32_t k = 0; k < kBounceRays; ++k) {
        const uint32_t i = hitIndices[k % hitIndices.size()];
        const bvh::Ray& ray = s.primary[i];
        const bvh::Hit& hit = s.primaryHits[i];
        const bvh::Triangle& tri = s.triangles[hit.triangleId];
        glm::vec3 n = glm::normalize(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
        if (glm::dot(n, ray.direction) > 0.0f) n = -n;
        const glm::vec3 p = ray.origin + hit.t * ray.direction;
        const glm::vec3 a = std::abs(n.x) > 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::vec3 t = glm::normalize(glm::cross(n, a));
        const glm::vec3 b = glm::cross(n, t);
        const float r = std::sqrt(u(rng)), phi = 6.2831853f * u(rng);
        const glm::vec3 d = r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0f, 1.0f - r * r)) * n;
        rays.push_back({bvh::offsetRayOrigin(p, n), glm::normalize(d)});
    }
    return rays;
}

SceneData& sceneData(const std::string& name) {
    static std::map<std::string, std::unique_ptr<SceneData>> cache;
    std::unique_ptr<SceneData>& slot = cache[name];
    if (slot) return *slot;
    auto s = std::make_unique<SceneData>();
    s->mesh = loadMesh(name, s->eye, s->target);
    s->triangles = trianglesOf(s->mesh);
    bvh::BuildOptions options;
    options.splitFactor = kTraceSplitFactor;
    s->traceBlas = std::make_unique<bvh::Blas>(bvh::buildBlas(s->triangles, options));
    if (s->eye == s->target) {  // outside camera
        const bvh::Box box = s->traceBlas->bounds();
        const glm::vec3 center = 0.5f * (box.min + box.max);
        const float radius = 0.5f * glm::length(box.extent());
        for (const SceneSpec& spec : kScenes) {
            if (name == spec.name) s->eye = center + 2.0f * radius * glm::normalize(spec.viewFrom);
        }
        s->target = center;
    }
    s->primary = cameraRays(s->eye, s->target);
    for (const bvh::Ray& r : s->primary) s->primaryHits.push_back(bvh::closestHit(*s->traceBlas, r));
    s->diffuse = bounceRays(*s);
    for (const bvh::Ray& r : s->diffuse) s->diffuseHits.push_back(bvh::closestHit(*s->traceBlas, r));
    slot = std::move(s);
    return *slot;
}

std::string inputText(const SceneSpec& spec) {
    const SceneData& s = sceneData(spec.name);
    return std::string(spec.name) + " (" + spec.source + ", " + std::to_string(s.triangles.size()) + " triangles)";
}

// The report's label (bench_support.hpp setRow) plus the BVH table's own keys: bvh=build|cpu|gpu, rays=...
void setBvhRow(benchmark::State& state, const RowInfo& row, const std::string& kind, const std::string& rays = "") {
    std::string label = "group=" + row.group + ";input=" + row.input + ";settings=" + row.settings +
                        ";rung=" + row.rung + ";role=" + row.role + ";time=" + row.time + ";bvh=" + kind;
    if (!rays.empty()) label += ";rays=" + rays;
    if (!row.peer.empty()) label += ";peer=" + row.peer;
    state.SetLabel(label);
}

template <class Fn>
double secondsOf(Fn&& fn) {
    const auto start = std::chrono::steady_clock::now();
    fn();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Metrics of a finished build are deterministic: computed once per (scene, builder) and kept across repetitions.
struct TreeMetrics {
    double sah = 0, epo = 0;
    uint32_t nodes = 0, references = 0, fragments = 0, depth = 0, stack = 0, spatialSplits = 0;
};
std::map<std::string, TreeMetrics>& metricsCache() {
    static std::map<std::string, TreeMetrics> cache;
    return cache;
}

void setMetricCounters(benchmark::State& state, const TreeMetrics& m) {
    state.counters["sah"] = m.sah;
    state.counters["epo"] = m.epo;
    state.counters["nodes"] = m.nodes;
    state.counters["references"] = m.references;
    state.counters["depth"] = m.depth;
    state.counters["stack"] = m.stack;
    if (m.fragments) state.counters["fragments"] = m.fragments;
    if (m.spatialSplits) state.counters["spatial_splits"] = m.spatialSplits;
}

std::string splitName(float split) {
    char text[16];
    std::snprintf(text, sizeof text, "%g", double(split));
    return text;
}

// ---- our builder --------------------------------------------------------------------------------------------

// spatial: the spatial-split builder (sbvh.hpp, budget 2: the room Embree-high gets below) instead of pre-splitting.
void BM_BvhBuild(benchmark::State& state, const SceneSpec* spec, float split, bool spatial) {
    SceneData& s = sceneData(spec->name);
    bvh::BuildOptions options;
    options.splitFactor = split;
    options.spatialSplits = spatial;
    options.splitBudget = 2.0f;
    std::unique_ptr<bvh::Blas> blas;
    for (auto _ : state) {
        blas.reset();
        state.SetIterationTime(secondsOf([&] { blas = std::make_unique<bvh::Blas>(bvh::buildBlas(s.triangles, options)); }));
    }
    const std::string key = std::string(spec->name) + "/ours/" + (spatial ? "spatial" : splitName(split));
    if (!metricsCache().count(key)) {
        TreeMetrics m;
        m.sah = blas->stats.sah;
        m.epo = bvh::computeEpo(*blas, s.triangles);
        m.nodes = blas->stats.nodeCount;
        m.references = blas->stats.referenceCount;
        m.fragments = blas->stats.fragmentCount;
        m.depth = blas->stats.maxDepth;
        m.stack = blas->stats.requiredStackSize;
        m.spatialSplits = blas->stats.spatialSplits;
        metricsCache()[key] = m;
    }
    setMetricCounters(state, metricsCache()[key]);
    const std::string builder =
        spatial ? std::string("ours: spatial splits (SBVH), reference budget 2x") : "ours: SweepSAH, split factor " + splitName(split);
    const std::string embree = std::string("BM_EmbreeBuild/") + spec->name;
    setBvhRow(state,
              {"bvh", inputText(*spec), builder + ", leaves <= 8, " +
                                            std::to_string(std::max(1u, std::thread::hardware_concurrency())) + " threads",
               "-", embree + "/medium," + embree + "/high"},
              "build");
}

// ---- Embree's builder, converted into our tree shape --------------------------------------------------------

struct EmbreeNode {
    bool leaf = false;
    bvh::Box bounds[2];
    EmbreeNode* children[2] = {nullptr, nullptr};
    std::vector<uint32_t>* ids = nullptr;  // leaf: distinct triangle ids (fragments of one triangle merged)
};

struct EmbreeBuild {
    const std::vector<bvh::Triangle>* triangles = nullptr;
    bool exactClip = false;  // splitPrimitive: exact clipped boxes instead of splitTriangle's padded ones
    std::mutex mutex;
    std::vector<std::unique_ptr<std::vector<uint32_t>>> leafIds;  // owned here: Embree's allocator does not run destructors
};

void* embreeCreateNode(RTCThreadLocalAllocator alloc, unsigned int, void*) {
    return new (rtcThreadLocalAlloc(alloc, sizeof(EmbreeNode), 16)) EmbreeNode();
}
void embreeSetChildren(void* node, void** children, unsigned int count, void*) {
    for (unsigned i = 0; i < count && i < 2; ++i) static_cast<EmbreeNode*>(node)->children[i] = static_cast<EmbreeNode*>(children[i]);
}
void embreeSetBounds(void* node, const RTCBounds** bounds, unsigned int count, void*) {
    for (unsigned i = 0; i < count && i < 2; ++i) {
        static_cast<EmbreeNode*>(node)->bounds[i] = {{bounds[i]->lower_x, bounds[i]->lower_y, bounds[i]->lower_z},
                                                     {bounds[i]->upper_x, bounds[i]->upper_y, bounds[i]->upper_z}};
    }
}
void* embreeCreateLeaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void* user) {
    auto* node = new (rtcThreadLocalAlloc(alloc, sizeof(EmbreeNode), 16)) EmbreeNode();
    node->leaf = true;
    auto ids = std::make_unique<std::vector<uint32_t>>();
    for (size_t i = 0; i < count; ++i) {
        ids->push_back(prims[i].primID);
        node->bounds[0].grow(bvh::Box{{prims[i].lower_x, prims[i].lower_y, prims[i].lower_z},
                                      {prims[i].upper_x, prims[i].upper_y, prims[i].upper_z}});
    }
    std::sort(ids->begin(), ids->end());
    ids->erase(std::unique(ids->begin(), ids->end()), ids->end());
    node->ids = ids.get();
    auto* build = static_cast<EmbreeBuild*>(user);
    std::lock_guard<std::mutex> lock(build->mutex);
    build->leafIds.push_back(std::move(ids));
    return node;
}
void embreeSplit(const RTCBuildPrimitive* prim, unsigned int dim, float pos, RTCBounds* left, RTCBounds* right, void* user) {
    const auto* build = static_cast<EmbreeBuild*>(user);
    const bvh::Triangle& tri = (*build->triangles)[prim->primID];
    const bvh::Box current{{prim->lower_x, prim->lower_y, prim->lower_z}, {prim->upper_x, prim->upper_y, prim->upper_z}};
    bvh::Box l, r;
    if (build->exactClip) {
        // The exact box of the triangle's part on each side, as our spatial splits chop. Embree calls this for every
        // bin its spatial binning tries, so it costs Embree about 10x its build time (our builder bins with cheap
        // estimates and clips exactly only at the chosen plane); hence the fast variant below is the timed peer.
        bvh::Box lh = current, rh = current;
        lh.max[dim] = std::min(lh.max[dim], pos);
        rh.min[dim] = std::max(rh.min[dim], pos);
        l = bvh::clippedTriangleBox(tri, lh);
        r = bvh::clippedTriangleBox(tri, rh);
    } else {
        bvh::splitTriangle(tri, int(dim), pos, current, l, r);
    }
    auto store = [&](bvh::Box b, RTCBounds* out, bool isLeft) {  // Embree wants both sides inside the current box
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

// Our Blas shape (root 0, pairs appended depth first when the parent is visited, leaf ranges in depth-first order).
bvh::Blas toOurTree(const EmbreeNode* root, const std::vector<bvh::Triangle>& tris) {
    bvh::Blas blas;
    blas.triangleCount = uint32_t(tris.size());
    struct Item {
        const EmbreeNode* node;
        uint32_t index;
    };
    bvh::Box rootBox = root->bounds[0];
    if (!root->leaf) rootBox.grow(root->bounds[1]);
    blas.nodes.emplace_back();
    blas.nodes[0].setBox(rootBox);
    std::vector<Item> stack{{root, 0}};
    while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        if (item.node->leaf) {
            blas.nodes[item.index].first = uint32_t(blas.triIds.size());
            blas.nodes[item.index].count = uint32_t(item.node->ids->size());
            for (uint32_t id : *item.node->ids) {
                blas.triIds.push_back(id);
                blas.leafTriangles.push_back(tris[id]);
            }
            continue;
        }
        const uint32_t first = uint32_t(blas.nodes.size());
        blas.nodes[item.index].first = first;
        blas.nodes[item.index].count = 0;
        for (int c = 0; c < 2; ++c) {
            blas.nodes.emplace_back();
            blas.nodes[first + c].setBox(item.node->bounds[c]);
        }
        stack.push_back({item.node->children[1], first + 1});
        stack.push_back({item.node->children[0], first});
    }
    return blas;
}

const char* qualityName(RTCBuildQuality q) {
    return q == RTC_BUILD_QUALITY_LOW ? "low" : q == RTC_BUILD_QUALITY_MEDIUM ? "medium" : "high";
}

void BM_EmbreeBuild(benchmark::State& state, const SceneSpec* spec, RTCBuildQuality quality, bool exactClip) {
    SceneData& s = sceneData(spec->name);
    RTCDevice device = rtcNewDevice(nullptr);
    std::vector<RTCBuildPrimitive> prims(2 * s.triangles.size());
    const std::string key = std::string(spec->name) + "/embree/" + qualityName(quality) + (exactClip ? "_exact" : "");
    for (auto _ : state) {
        EmbreeBuild build;
        build.triangles = &s.triangles;
        build.exactClip = exactClip;
        RTCBVH bvh = rtcNewBVH(device);
        const EmbreeNode* root = nullptr;
        state.SetIterationTime(secondsOf([&] {
            for (size_t i = 0; i < s.triangles.size(); ++i) {
                const bvh::Box b = s.triangles[i].box();
                prims[i] = {b.min.x, b.min.y, b.min.z, 0, b.max.x, b.max.y, b.max.z, unsigned(i)};
            }
            RTCBuildArguments args = rtcDefaultBuildArguments();
            args.buildQuality = quality;
            args.maxBranchingFactor = 2;
            args.maxDepth = 1024;
            args.maxLeafSize = 8;
            args.traversalCost = bvh::kTraversalCost;
            args.intersectionCost = bvh::kTriangleCost;
            args.bvh = bvh;
            args.primitives = prims.data();
            args.primitiveCount = s.triangles.size();
            args.primitiveArrayCapacity = prims.size();  // room for spatial-split fragments (high quality)
            args.createNode = embreeCreateNode;
            args.setNodeChildren = embreeSetChildren;
            args.setNodeBounds = embreeSetBounds;
            args.createLeaf = embreeCreateLeaf;
            args.splitPrimitive = embreeSplit;
            args.userPtr = &build;
            root = static_cast<const EmbreeNode*>(rtcBuildBVH(&args));
        }));
        if (root && !metricsCache().count(key)) {
            const bvh::Blas ours = toOurTree(root, s.triangles);
            TreeMetrics m;
            m.sah = bvh::computeSah(ours.nodes);
            m.epo = bvh::computeEpo(ours, s.triangles);
            m.nodes = uint32_t(ours.nodes.size());
            m.references = uint32_t(ours.triIds.size());
            m.depth = bvh::maxDepth(ours.nodes);
            m.stack = bvh::requiredStackSize(ours.nodes);
            metricsCache()[key] = m;
        }
        rtcReleaseBVH(bvh);
    }
    rtcReleaseDevice(device);
    if (metricsCache().count(key)) setMetricCounters(state, metricsCache()[key]);
    setBvhRow(state,
              {"bvh", inputText(*spec),
               std::string("Embree 3 rtcBuildBVH, ") + qualityName(quality) + " quality" +
                   (quality == RTC_BUILD_QUALITY_HIGH ? " (spatial splits)" : "") +
                   (exactClip ? ", exact triangle clipping" : "") + ", leaves <= 8, all threads",
               "-", "", "peer"},
              "build");
}

// ---- CPU traversal --------------------------------------------------------------------------------------------

class EmbreeScene {
public:
    explicit EmbreeScene(const render::TriangleMesh& mesh) {
        device_ = rtcNewDevice(nullptr);
        scene_ = rtcNewScene(device_);
        rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
        RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                     3 * sizeof(float), mesh.positions.size()));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                       3 * sizeof(unsigned), mesh.indices.size()));
        std::memcpy(vertices, mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
        std::memcpy(indices, mesh.indices.data(), mesh.indices.size() * sizeof(glm::uvec3));
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

    uint32_t intersect(const bvh::Ray& ray) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh{};
        rh.ray.org_x = ray.origin.x, rh.ray.org_y = ray.origin.y, rh.ray.org_z = ray.origin.z;
        rh.ray.dir_x = ray.direction.x, rh.ray.dir_y = ray.direction.y, rh.ray.dir_z = ray.direction.z;
        rh.ray.tnear = ray.tMin;
        rh.ray.tfar = ray.tMax;
        rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &context, &rh);
        return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? bvh::kInvalidIndex : rh.hit.primID;
    }

private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
};

const std::vector<bvh::Ray>& raysOf(const SceneData& s, bool diffuse) { return diffuse ? s.diffuse : s.primary; }
const char* rayKind(bool diffuse) { return diffuse ? "diffuse" : "primary"; }

void BM_BvhTraceCpu(benchmark::State& state, const SceneSpec* spec, bool diffuse) {
    const SceneData& s = sceneData(spec->name);
    const std::vector<bvh::Ray>& rays = raysOf(s, diffuse);
    uint64_t hits = 0;
    for (auto _ : state) {
        hits = 0;
        for (const bvh::Ray& r : rays) hits += bvh::closestHit(*s.traceBlas, r).hit() ? 1 : 0;
    }
    state.SetItemsProcessed(state.iterations() * int64_t(rays.size()));
    state.counters["rays"] = double(rays.size());
    state.counters["hit_rate"] = rays.empty() ? 0.0 : double(hits) / double(rays.size());
    setBvhRow(state,
              {"bvh", inputText(*spec),
               std::string("ours: closest hit, ") + rayKind(diffuse) + " rays, 1 thread, single ray, BLAS split " +
                   splitName(kTraceSplitFactor),
               "-", std::string("BM_EmbreeTraceCpu/") + spec->name + "/" + rayKind(diffuse), "ours", "cpu"},
              "cpu", rayKind(diffuse));
}

void BM_EmbreeTraceCpu(benchmark::State& state, const SceneSpec* spec, bool diffuse) {
    const SceneData& s = sceneData(spec->name);
    const std::vector<bvh::Ray>& rays = raysOf(s, diffuse);
    static std::map<std::string, std::unique_ptr<EmbreeScene>> scenes;  // committed once per scene
    std::unique_ptr<EmbreeScene>& slot = scenes[spec->name];
    if (!slot) slot = std::make_unique<EmbreeScene>(s.mesh);
    const EmbreeScene& embree = *slot;
    uint64_t hits = 0, differentHits = 0;
    for (auto _ : state) {
        hits = 0;
        for (const bvh::Ray& r : rays) hits += embree.intersect(r) != bvh::kInvalidIndex ? 1 : 0;
    }
    const std::vector<bvh::Hit>& ours = diffuse ? s.diffuseHits : s.primaryHits;
    for (size_t i = 0; i < rays.size(); ++i) differentHits += (embree.intersect(rays[i]) != bvh::kInvalidIndex) != ours[i].hit();
    state.SetItemsProcessed(state.iterations() * int64_t(rays.size()));
    state.counters["rays"] = double(rays.size());
    state.counters["hit_rate"] = rays.empty() ? 0.0 : double(hits) / double(rays.size());
    state.counters["hit_miss_vs_ours"] = double(differentHits);
    setBvhRow(state,
              {"bvh", inputText(*spec),
               std::string("Embree 3 rtcIntersect1, RTC_SCENE_FLAG_ROBUST, high-quality scene, ") + rayKind(diffuse) +
                   " rays, 1 thread",
               "-", "", "peer", "cpu"},
              "cpu", rayKind(diffuse));
}

// ---- GPU traversal ----------------------------------------------------------------------------------------------

void BM_BvhTraceGpu(benchmark::State& state, const SceneSpec* spec, bool diffuse) {
    if (!requireDevice(state)) return;
    vk::Context& ctx = *context();
    const SceneData& s = sceneData(spec->name);
    const std::vector<gpu::GpuBlasNode> nodes = bvh::flatten(*s.traceBlas);
    const std::vector<gpu::GpuBlasTriangle> refs = bvh::flattenTriangles(*s.traceBlas, s.mesh.indices);
    render::GpuBlas blas(ctx, {nodes, refs, s.mesh.positions, bvh::requiredStackSize(s.traceBlas->nodes)}, "bench blas");
    runGpuTrace(state, bvhBenchScene(spec->name), diffuse,
                [&](VkCommandBuffer cmd, VkDeviceAddress rays, VkDeviceAddress hits, uint32_t n) {
                    render::recordTraceRays(cmd, {ctx, *shaders()}, blas, render::TraceMode::Closest, rays, hits, n);
                });
    setBvhRow(state,
              {"bvh", inputText(*spec),
               std::string("ours: GLSL closest hit (include/bvh_traverse.glsl), ") + rayKind(diffuse) +
                   " rays, one dispatch, BLAS split " + splitName(kTraceSplitFactor),
               ctx.info().name, std::string("BM_BvhTraceCpu/") + spec->name + "/" + rayKind(diffuse)},
              "gpu", rayKind(diffuse));
}

// Registration: every scene x builder / ray kind. Fixed iteration counts keep the group to a few minutes on two
// cores; the ~1M-triangle scene runs 3 repetitions instead of the command line's 5.
int registerAll() {
    for (const SceneSpec& spec : kScenes) {
        const std::string scene = spec.name;
        auto tune = [&](benchmark::internal::Benchmark* b, int iterations) {
            b->UseManualTime()->Iterations(iterations)->Unit(benchmark::kMillisecond);
            if (spec.big) b->Repetitions(3);
        };
        for (float split : {0.0f, 0.3f, 1.0f}) {
            tune(benchmark::RegisterBenchmark(("BM_BvhBuild/" + scene + "/split_" + splitName(split)).c_str(),
                                              BM_BvhBuild, &spec, split, false),
                 spec.big ? 1 : 2);
        }
        tune(benchmark::RegisterBenchmark(("BM_BvhBuild/" + scene + "/spatial").c_str(), BM_BvhBuild, &spec, 0.0f, true),
             1);
        for (RTCBuildQuality q : {RTC_BUILD_QUALITY_LOW, RTC_BUILD_QUALITY_MEDIUM, RTC_BUILD_QUALITY_HIGH}) {
            tune(benchmark::RegisterBenchmark(("BM_EmbreeBuild/" + scene + "/" + qualityName(q)).c_str(),
                                              BM_EmbreeBuild, &spec, q, false),
                 spec.big || q == RTC_BUILD_QUALITY_HIGH ? 1 : 2);
        }
        // Embree-high with the exact clipping our spatial splits use: its SAH is the stricter reference. Slow (see
        // embreeSplit), so two repetitions (its SAH is deterministic; its time is only informative).
        auto* exact = benchmark::RegisterBenchmark(("BM_EmbreeBuild/" + scene + "/high_exact").c_str(), BM_EmbreeBuild,
                                                   &spec, RTC_BUILD_QUALITY_HIGH, true);
        exact->UseManualTime()->Iterations(1)->Repetitions(2)->Unit(benchmark::kMillisecond);
        for (bool diffuse : {false, true}) {
            const std::string kind = rayKind(diffuse);
            // Single-threaded CPU traversal is timed in thread CPU time: the median is then robust to other
            // processes on a shared machine (wall time of the same loop is also in the JSON).
            for (auto* b : {benchmark::RegisterBenchmark(("BM_BvhTraceCpu/" + scene + "/" + kind).c_str(), BM_BvhTraceCpu, &spec, diffuse),
                            benchmark::RegisterBenchmark(("BM_EmbreeTraceCpu/" + scene + "/" + kind).c_str(), BM_EmbreeTraceCpu, &spec, diffuse)}) {
                b->Iterations(2)->Unit(benchmark::kMillisecond);
                if (spec.big) b->Repetitions(3);
            }
            tune(benchmark::RegisterBenchmark(("BM_BvhTraceGpu/" + scene + "/" + kind).c_str(), BM_BvhTraceGpu, &spec, diffuse), 1);
        }
    }
    return 0;
}
[[maybe_unused]] const int kRegistered = registerAll();

}  // namespace

// For bench/bvh_wide_bench.cpp: the same scenes, rays and CPU hits, and the same row labels.
BvhBenchScene bvhBenchScene(const std::string& name) {
    const SceneSpec* spec = nullptr;
    for (const SceneSpec& s : kScenes) {
        if (name == s.name) spec = &s;
    }
    if (!spec) throw std::invalid_argument("bvhBenchScene: unknown scene " + name);
    const SceneData& s = sceneData(name);
    return {&s.mesh, s.traceBlas.get(), &s.primary, &s.diffuse, &s.primaryHits, &s.diffuseHits, inputText(*spec),
            std::string("BLAS split ") + splitName(kTraceSplitFactor), spec->big};
}

void runGpuTrace(benchmark::State& state, const BvhBenchScene& s, bool diffuse,
                 const std::function<void(VkCommandBuffer, VkDeviceAddress, VkDeviceAddress, uint32_t)>& trace) {
    vk::Context& ctx = *context();
    const std::vector<bvh::Ray>& rays = diffuse ? *s.diffuse : *s.primary;
    const uint32_t n = uint32_t(rays.size());
    std::vector<gpu::GpuBvhRay> gpuRays(n);
    for (uint32_t i = 0; i < n; ++i) gpuRays[i] = {rays[i].origin, rays[i].tMin, rays[i].direction, rays[i].tMax};
    vk::Buffer rayBuffer = vk::createBufferWithData(
        ctx, {n * sizeof(gpu::GpuBvhRay), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "bench rays", "bench"},
        gpuRays.data(), n * sizeof(gpu::GpuBvhRay));
    vk::Buffer hitBuffer = ctx.createBuffer(
        {n * sizeof(gpu::GpuBvhHit), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "bench hits", "bench"});
    vk::TimestampQueries queries(ctx, 1);
    auto record = [&](VkCommandBuffer cmd) { trace(cmd, rayBuffer.address, hitBuffer.address, n); };
    timeGpu(ctx, queries, record);  // warm-up: pipeline creation
    double wall = 0.0;
    for (auto _ : state) state.SetIterationTime(timeGpu(ctx, queries, record, &wall));
    const std::vector<gpu::GpuBvhHit> hits = vk::downloadBuffer<gpu::GpuBvhHit>(ctx, hitBuffer, n);
    const std::vector<bvh::Hit>& expected = diffuse ? *s.diffuseHits : *s.primaryHits;
    double mismatches = 0;
    for (uint32_t i = 0; i < n; ++i) mismatches += (hits[i].triangleId != expected[i].triangleId || hits[i].t != expected[i].t) ? 1 : 0;
    ctx.destroy(rayBuffer);
    ctx.destroy(hitBuffer);
    state.counters["mismatches"] = mismatches;
    state.counters["submit_wall_ms"] = wall * 1e3 / double(state.iterations());
    state.SetItemsProcessed(state.iterations() * int64_t(n));
    state.counters["rays"] = double(n);
}

void setBvhBenchRow(benchmark::State& state, const RowInfo& row, const std::string& kind, const std::string& rays) {
    setBvhRow(state, row, kind, rays);
}
}  // namespace idk::bench
