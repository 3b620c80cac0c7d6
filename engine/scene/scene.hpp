// scene.hpp: the CPU scene as flat arrays (meshes with every vertex attribute and morph targets, the glTF
// metallic-roughness material with its extensions, textures, nodes, skins, animations, placed instances, cameras
// and lights, world-space bounds), filled by loadGltf() (the port of IDKEngine's ModelLoader). Plain structs; the
// only behaviour is Scene::features(), a summary that lets the renderer allocate only what the scene needs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace idk::scene {

// Supported joints per skin (Skin::joints.size()); a file with more is rejected with LoadError.
constexpr uint32_t kMaxJoints = 256;

// One morph target of a primitive: per-vertex deltas added with the node's weight. Each array is empty (the
// target does not move that attribute) or has the primitive's vertex count.
struct MorphTarget {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec3> tangents;  // xyz deltas (the handedness w is not morphed)
};

// One triangle list. Every per-vertex array is either empty (the attribute is absent) or has positions.size()
// entries; positions, normals and indices are always present.
struct Primitive {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;    // always present: computed flat (per triangle) when the file has none
    std::vector<glm::vec2> uv0;        // TEXCOORD_0, empty when the primitive has none
    std::vector<uint32_t> indices;     // triangle list, 3 per triangle, each < positions.size()
    std::optional<uint32_t> material;  // index into Scene::materials; empty: the glTF default material
    // KHR_materials_variants: (variant index into Scene::variantNames, material) pairs; applyMaterialVariant.
    std::vector<std::pair<uint32_t, uint32_t>> variantMaterials;
    std::vector<glm::vec2> uv1;        // TEXCOORD_1 (dequantized like uv0; KHR_texture_transform is not baked in)
    std::vector<glm::vec4> colors;     // COLOR_0 as linear RGBA (vec3 files get alpha 1), normalized ints decoded
    // Unit xyz orthogonal to the normal, w = +1 or -1: bitangent = w * cross(normal, tangent.xyz). From the file's
    // TANGENT, else generated from the UVs (generateTangents(); tangentsGenerated tells which). Empty only when
    // the primitive has no UVs (nothing can be normal-mapped then).
    std::vector<glm::vec4> tangents;
    bool tangentsGenerated = false;
    std::vector<glm::uvec4> joints;    // JOINTS_0: indices into the skin's joint list (< Skin::joints.size())
    std::vector<glm::vec4> weights;    // WEIGHTS_0 (normalized ints decoded), used with joints
    std::vector<MorphTarget> targets;  // morph targets; every primitive of a mesh has the same count
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;  // only triangle primitives; points/lines are dropped (with a warning)
    std::vector<float> weights;         // default morph weights, one per target (zeros when the file gives none)
};

enum class AlphaMode { Opaque, Mask, Blend };

// A reference from a material to Scene::textures, with its KHR_texture_transform (identity when absent):
// uv' = offset + rotate(rotation) * (scale * uv), as the extension defines it.
struct TextureRef {
    uint32_t texture = 0;   // index into Scene::textures
    uint32_t texCoord = 0;  // which TEXCOORD_n set: 0 -> Primitive::uv0, 1 -> uv1 (the transform's override applied)
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;  // radians
    glm::vec2 scale{1.0f};
};

// The glTF metallic-roughness material with KHR_materials_emissive_strength, _unlit, _transmission, _ior and
// _volume. Texture channels follow the glTF spec (metallicRoughness: G roughness, B metallic; occlusion: R;
// transmission: R; thickness: G).
struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};  // linear RGBA
    float metallic = 1.0f;
    float roughness = 1.0f;
    glm::vec3 emissive{0.0f};  // emissiveFactor * KHR_materials_emissive_strength
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;
    std::optional<TextureRef> baseColorTexture;  // sRGB
    std::optional<TextureRef> metallicRoughnessTexture;
    std::optional<TextureRef> normalTexture;  // tangent space, needs Primitive::tangents
    float normalScale = 1.0f;                 // scales the normal map's xy
    std::optional<TextureRef> occlusionTexture;
    float occlusionStrength = 1.0f;              // occlusion = 1 + strength * (texel.r - 1)
    std::optional<TextureRef> emissiveTexture;   // sRGB, multiplied by `emissive`
    float emissiveStrength = 1.0f;               // KHR_materials_emissive_strength (already in `emissive`)
    bool unlit = false;                          // KHR_materials_unlit: colour = base colour, no lighting
    float transmission = 0.0f;                   // KHR_materials_transmission factor
    std::optional<TextureRef> transmissionTexture;
    float ior = 1.5f;                            // KHR_materials_ior (the glTF default 1.5 without it)
    float thickness = 0.0f;                      // KHR_materials_volume thicknessFactor (0: thin-walled)
    std::optional<TextureRef> thicknessTexture;
    float attenuationDistance = std::numeric_limits<float>::infinity();  // infinity: no absorption
    glm::vec3 attenuationColor{1.0f};
    // BSDF extensions: gltf_material_ext.cpp. Each texture multiplies its factor (channels as the extensions say).
    float specular = 1.0f;                 // KHR_materials_specular specularFactor, [0, 1]
    glm::vec3 specularColor{1.0f};         // specularColorFactor, linear, >= 0 (may exceed 1)
    float clearcoat = 0.0f;                // KHR_materials_clearcoat clearcoatFactor, [0, 1]
    float clearcoatRoughness = 0.0f;       // clearcoatRoughnessFactor, [0, 1]
    glm::vec3 sheenColor{0.0f};            // KHR_materials_sheen sheenColorFactor, linear, [0, 1]
    float sheenRoughness = 0.0f;           // sheenRoughnessFactor, [0, 1]
    // KHR_materials_specular / _clearcoat / _sheen textures, texCoord and KHR_texture_transform as above.
    std::optional<TextureRef> specularTexture;            // linear, A scales specular
    std::optional<TextureRef> specularColorTexture;       // sRGB, RGB scales specularColor
    std::optional<TextureRef> clearcoatTexture;           // linear, R scales clearcoat
    std::optional<TextureRef> clearcoatRoughnessTexture;  // linear, G scales clearcoatRoughness
    std::optional<TextureRef> sheenColorTexture;          // sRGB, RGB scales sheenColor
    std::optional<TextureRef> sheenRoughnessTexture;      // linear, A scales sheenRoughness
    // KHR_materials_anisotropy
    float anisotropyStrength = 0.0f;       // KHR_materials_anisotropy anisotropyStrength, [0, 1]
    float anisotropyRotation = 0.0f;       // anisotropyRotation, radians counter-clockwise from the tangent
    // KHR_materials_diffuse_transmission, KHR_materials_dispersion
    float diffuseTransmission = 0.0f;            // diffuseTransmissionFactor, [0, 1]
    glm::vec3 diffuseTransmissionColor{1.0f};    // diffuseTransmissionColorFactor, linear, [0, 1]
    std::optional<TextureRef> diffuseTransmissionTexture;       // linear, A scales diffuseTransmission
    std::optional<TextureRef> diffuseTransmissionColorTexture;  // sRGB, RGB scales diffuseTransmissionColor
    float dispersion = 0.0f;                     // KHR_materials_dispersion: 20 / Abbe number V_d, >= 0 (0: none)
    // KHR_materials_iridescence, clearcoat normal and anisotropy textures
    float iridescence = 0.0f;                 // iridescenceFactor, [0, 1]
    float iridescenceIor = 1.3f;              // iridescenceIor of the thin film, [1, 4] here
    float iridescenceThicknessMin = 100.0f;   // iridescenceThicknessMinimum, nanometres, >= 0
    float iridescenceThicknessMax = 400.0f;   // iridescenceThicknessMaximum, nanometres, >= 0
    std::optional<TextureRef> iridescenceTexture;           // linear, R scales iridescence
    std::optional<TextureRef> iridescenceThicknessTexture;  // linear, G: thickness = mix(min, max, G); none: max
    std::optional<TextureRef> clearcoatNormalTexture;       // tangent space, the coat's own shading normal
    float clearcoatNormalScale = 1.0f;                      // scales its xy like normalScale
    std::optional<TextureRef> anisotropyTexture;            // linear, RG direction ([0,1] -> [-1,1]), B strength
};

// Filtering and wrapping as glTF enums (9728 NEAREST, 9729 LINEAR, ...; 10497 REPEAT, 33071 CLAMP, 33648 MIRROR).
struct Sampler {
    int magFilter = -1;  // -1: not specified
    int minFilter = -1;
    int wrapS = 10497;
    int wrapT = 10497;
};

struct Texture {
    std::optional<uint32_t> image;  // index into Scene::images; empty when the texture has no source
    Sampler sampler;
};

// Anything but Ok: the texture decoder substitutes its magenta placeholder (the loader warns once per image).
enum class ImageStatus {
    Ok,
    Missing,        // the external file does not exist
    UnknownFormat,  // the first bytes are no image format we know (PNG, JPEG, KTX2, WebP, GIF, BMP, HDR, EXR...)
};

// An image is recorded, not decoded: either a file next to the asset or the encoded bytes (PNG/JPEG...) that
// were embedded (GLB buffer view or data URI). Decoding happens later on worker threads.
struct Image {
    std::string name;
    std::filesystem::path path;    // absolute/resolved file path for external images, else empty
    std::string mimeType;          // may be empty for external files
    std::vector<uint8_t> encoded;  // embedded bytes, empty for external images
    ImageStatus status = ImageStatus::Ok;
};

struct Node {
    std::string name;
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
    glm::vec3 scale{1.0f};
    std::optional<glm::mat4> matrix;  // set when the file gives a matrix instead of TRS
    std::vector<uint32_t> children;
    std::optional<uint32_t> parent;
    std::optional<uint32_t> mesh;    // index into Scene::meshes
    std::optional<uint32_t> camera;  // index into Scene::cameras (only for nodes in the default scene)
    std::optional<uint32_t> light;   // index into Scene::lights (only for nodes in the default scene)
    glm::mat4 world{1.0f};           // parent world * local, for every node
    std::optional<uint32_t> skin;    // index into Scene::skins (only meaningful with a mesh)
    std::vector<float> weights;      // current morph weights (node's own, else the mesh's; animated)
    // EXT_mesh_gpu_instancing: one local matrix (T * R * S) per instance, applied after `world`; empty: none.
    std::vector<glm::mat4> instanceMatrices;
    // For a node with a mesh and a skin, one matrix per joint of the skin (glTF skinning):
    // inverse(world) * world(joint i) * inverseBindMatrices[i]; all zero when `world` is singular (zero scale).
    std::vector<glm::mat4> jointMatrices;
    // The pose from the file: evaluateAnimations() starts from it, so a frame depends only on its time. A node
    // that is animated and has a `matrix` gets its matrix decomposed into this TRS at load (matrix cleared).
    struct RestPose {
        glm::vec3 translation{0.0f};
        glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
        glm::vec3 scale{1.0f};
        std::vector<float> weights;
    } rest;
};

// One drawn copy of a mesh: a node of the placed scene that references a mesh with primitives (one per
// EXT_mesh_gpu_instancing instance when the node has them).
struct Instance {
    uint32_t mesh = 0;
    uint32_t node = 0;
    glm::mat4 world{1.0f};          // node world (* instanceMatrices[gpuInstance] with GPU instancing)
    uint32_t gpuInstance = 0;       // index into the node's instanceMatrices (0 without GPU instancing)
    std::optional<uint32_t> skin;   // the node's skin: joint matrices are in Scene::nodes[node].jointMatrices
};

// A glTF skin: joints are node indices, at most kMaxJoints.
struct Skin {
    std::string name;
    std::vector<uint32_t> joints;
    std::vector<glm::mat4> inverseBindMatrices;  // one per joint (identity when the file gives none)
    std::optional<uint32_t> skeleton;            // the file's skeleton root hint (not needed for evaluation)
};

enum class Interpolation { Step, Linear, CubicSpline };
enum class AnimationPath { Translation, Rotation, Scale, Weights };

// Keyframes of one animation sampler. `values` holds, per keyframe, `components` floats (LINEAR/STEP) or
// 3 * components for CUBICSPLINE (in-tangent, value, out-tangent), as the glTF file lays them out; rotations
// are x, y, z, w quaternions; weights have one component per morph target.
struct AnimationSampler {
    std::vector<float> times;  // seconds, non-decreasing (validated at load)
    std::vector<float> values;
    uint32_t components = 0;  // 3 translation/scale, 4 rotation, morph target count for weights
    Interpolation interpolation = Interpolation::Linear;
};

struct AnimationChannel {
    uint32_t sampler = 0;  // index into Animation::samplers
    uint32_t node = 0;     // index into Scene::nodes
    AnimationPath path = AnimationPath::Translation;
};

struct Animation {
    std::string name;
    std::vector<AnimationSampler> samplers;
    std::vector<AnimationChannel> channels;
    float start = 0.0f;  // earliest and latest keyframe time over all samplers
    float end = 0.0f;
};

enum class CameraType { Perspective, Orthographic };

// A camera placed by a node of the default scene (one entry per such node).
struct Camera {
    std::string name;
    CameraType type = CameraType::Perspective;
    float yfov = 0.785398f;    // radians (perspective)
    float aspectRatio = 0.0f;  // 0: use the viewport's (the file did not set it)
    float znear = 0.1f;
    float zfar = 0.0f;               // 0: infinite (perspective only)
    float xmag = 1.0f, ymag = 1.0f;  // orthographic half extents
    glm::mat4 world{1.0f};           // camera-to-world; the camera looks down its local -Z, +Y up
    uint32_t node = 0;
};

enum class LightType { Directional, Point, Spot };

// A KHR_lights_punctual light placed by a node of the default scene (one entry per such node).
struct Light {
    std::string name;
    LightType type = LightType::Point;
    glm::vec3 color{1.0f};        // linear RGB
    float intensity = 1.0f;       // candela (point/spot) or lux (directional)
    float range = 0.0f;           // 0: infinite
    float innerConeAngle = 0.0f;  // radians (spot)
    float outerConeAngle = 0.785398f;
    glm::vec3 position{0.0f};                // world space
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // world space, unit: where the light points (node's local -Z)
    uint32_t node = 0;
};

struct Aabb {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{std::numeric_limits<float>::lowest()};
    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    void extend(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    glm::vec3 centre() const { return 0.5f * (min + max); }
};

// What the placed scene needs, so the renderer allocates, compiles and dispatches nothing else. Everything is
// about drawn instances and their materials, not about unreferenced data in the file.
struct SceneFeatures {
    bool hasSkins = false;                // a drawn instance is skinned: joint matrices + skinning pass
    bool hasMorphs = false;               // a drawn mesh has morph targets
    bool hasAnimations = false;           // Scene::animations is not empty
    bool hasBlend = false;                // a drawn primitive's material is AlphaMode::Blend: transparency pass
    bool hasMask = false;                 // ... AlphaMode::Mask: alpha-tested variants
    bool hasTextures = false;             // a drawn material references a texture
    bool hasNormalMaps = false;           // a drawn material has a normal texture
    bool hasTransmission = false;         // transmission > 0 or a transmission texture
    bool hasVolume = false;               // KHR_materials_volume thickness > 0
    bool hasUnlit = false;                // KHR_materials_unlit
    bool hasEmissive = false;             // a drawn material emits (factor or texture)
    bool hasVertexColors = false;         // a drawn primitive has COLOR_0
    bool hasUv1 = false;                  // a drawn primitive has TEXCOORD_1
    bool hasGpuInstancing = false;        // EXT_mesh_gpu_instancing placed more than one copy of a node
    bool hasShadowCastingLights = false;  // a placed light with nonzero intensity (every punctual light casts)
    uint32_t maxJoints = 0;               // largest skin of a drawn instance
    uint32_t maxMorphTargets = 0;         // largest morph target count of a drawn mesh
    // KHR_materials_specular / _clearcoat / _sheen: a drawn material has one of their textures (the
    // G-buffer then carries the per-pixel texels to the lighting pass).
    bool hasLayerTextures = false;
    // A drawn material combines extensions whose per-pixel texels exceed the layers target's bits
    // (include/gbuffer_layer_bits.glsl): diffuse-transmission textures with iridescence, a clearcoat normal texture
    // or anisotropy, or anisotropy with a clearcoat normal texture. The G-buffer then adds its spill target.
    bool hasSpilledLayerTexels = false;
};

struct Scene {
    std::filesystem::path sourcePath;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Image> images;
    std::vector<Node> nodes;
    std::vector<uint32_t> rootNodes;    // the placed scene's root nodes
    std::vector<Instance> instances;    // placed scene only, in depth-first node order
    std::vector<Camera> cameras;        // placed scene only
    std::vector<Light> lights;          // placed scene only
    // World-space AABB of all instanced vertices in the rest pose (default morph weights, skinned by the rest
    // pose's joint matrices); not updated by evaluateAnimations(). Empty if there is nothing to draw.
    Aabb bounds;
    std::vector<std::string> warnings;  // non-fatal problems found while loading
    std::vector<Skin> skins;
    std::vector<Animation> animations;
    uint32_t sceneIndex = 0;              // which glTF scene was placed (LoadOptions::scene, else the default)
    std::vector<std::string> sceneNames;  // every scene in the file (may be empty names; empty if none)
    std::vector<std::string> variantNames;  // KHR_materials_variants, in file order (empty: none)

    SceneFeatures features() const;  // computed on each call (scene.cpp)
};

// KHR_materials_variants: gives every primitive mapped for the variant called `name` that variant's material
// (the others keep theirs). Throws std::invalid_argument naming the variant and listing the file's variants.
void applyMaterialVariant(Scene& scene, const std::string& name);

}  // namespace idk::scene
