// pt_scene.hpp: a glTF scene prepared for path tracing: one BLAS per mesh (merged primitives in order, the
// triangle numbering of render::meshTriangles) under a TLAS over the placed instances (engine/bvh), per-vertex
// attributes for shading, decoded textures, the path-tracing material fields, the NEE light list (punctual lights
// and emissive triangles) with its alias table by power and per-instance light offsets, and the environment with
// its texel alias table. The CPU reference tracer reads all of it; the GPU tracer uploads the gpu:: arrays as they
// are. Replaces IDKEngine's path-tracer inputs (reference 2.1: no light list, sky cubemap only).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/tlas.hpp"
#include "core/image_file.hpp"
#include "pathtrace/environment_map.hpp"
#include "pathtrace/texture_sampler.hpp"
#include "scene/scene.hpp"
#include "shared/pt_types.h"

namespace idk::pathtrace {

// Shading data of one BLAS: a scene mesh at its default morph weights in object space, or the deformed copy of a
// skinned / individually morphed instance in world space (its instance transform is then the identity).
struct PtGeometry {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec4> tangents;  // xyz + handedness w; w = 0: no tangent (no normal mapping)
    std::vector<glm::vec2> uv0;
    std::vector<glm::vec2> uv1;
    std::vector<glm::vec4> colors;    // COLOR_0, (1, 1, 1, 1) when absent
    std::vector<glm::uvec3> triangles;
    std::vector<uint32_t> triangleMaterial;  // per triangle, index into PathTraceScene::materials
};

// Who poses skinned and morphed instances. Cpu: buildPathTraceScene skins and morphs world-space copies (the CPU
// reference's oracle). Gpu: each such instance gets a geometry of its own in object space at the rest pose (mesh
// default weights, unskinned), its BLAS built over that, placed by its node's transform; the GPU tracer then writes
// the posed vertices with the rasterizer's skinning compute and refits that BLAS (render/pt_pose.hpp). An instance
// whose material emits stays CPU-posed in both modes: its triangles are light-list entries with world positions.
enum class PtPosing : uint8_t { Cpu, Gpu };

struct PathTraceScene {
    std::vector<PtGeometry> geometries;
    std::vector<bvh::Blas> blases;              // blases[i] is built over geometries[i]
    std::vector<bvh::BlasInstance> instances;   // one per scene::Instance (same index), blasIndex = geometry
    std::vector<glm::mat3> normalMatrices;      // per instance: inverse-transpose of the upper 3x3
    std::vector<uint8_t> mirrored;              // per instance: det < 0 (front faces wind clockwise)
    bvh::Tlas tlas;

    std::vector<scene::Material> materials;     // Scene::materials, then glTF's default material (GpuScene order)
    std::vector<gpu::GpuPtMaterial> ptMaterials;  // the same order
    std::vector<CpuTexture> textures;           // per Scene::textures

    std::vector<gpu::GpuPtLight> lights;
    std::vector<gpu::GpuPtAliasEntry> lightAlias;  // over `lights`, probability ~ power; empty: no light emits
    std::vector<gpu::GpuPtInstance> instanceLights;  // per instance: first light of its triangles

    EnvironmentMap environment;
    gpu::GpuPtEnvironment environmentDesc{};     // width/height, NEE environment probability, light count
    std::vector<uint32_t> gpuPosedInstances;     // Gpu posing: instances whose geometry awaits the GPU pose
    bool cpuPosedDeformation = false;            // some skinned/morphed instance was posed here (its own copy)
    bool alphaTesting = false;                   // some material is MASK or BLEND (shadow rays must test alpha)
    glm::vec3 boundsCentre{0.0f};
    float boundsRadius = 0.0f;
    std::vector<std::string> warnings;
};

// `environment`: the equirectangular HDR (core::readImage of render::defaultEnvironmentPath(), as the raster loads
// it), scaled by envIntensity; nullptr: a constant environment of radiance `constantRadiance` (black by default).
PathTraceScene buildPathTraceScene(const scene::Scene& scene, const core::ImageRgba32f* environment,
                                   float envIntensity, glm::vec3 constantRadiance = glm::vec3(0.0f),
                                   PtPosing posing = PtPosing::Cpu);

// Whether the rasterizer's skinning deforms some primitive of `instance` (render::packDeformation's rule: a skin
// with JOINTS_0/WEIGHTS_0 on the primitive, or morph targets with node weights), i.e. it has a GPU pose.
bool hasGpuDeformation(const scene::Scene& scene, const scene::Instance& instance);

// The path-tracing fields of every material (Scene::materials, then the default one).
std::vector<gpu::GpuPtMaterial> packPtMaterials(const scene::Scene& scene);

// Light list, alias table and per-instance offsets (fills those fields and environmentDesc); needs geometries,
// instances, materials, textures and environment already in place.
void buildLights(PathTraceScene& pts, const scene::Scene& scene);

}  // namespace idk::pathtrace
