// scene.hpp: the CPU scene as flat arrays (meshes, materials, textures, nodes, placed instances, cameras and
// lights, world-space bounds), filled by loadGltf(). Plain structs, no behaviour. This is the minimal first
// version: the full material model, animation, skins, morph targets and decoded textures come later.
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

// One triangle list. All arrays are per vertex and have positions.size() entries (uv0 may be empty).
struct Primitive {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;    // always present: computed flat (per triangle) when the file has none
    std::vector<glm::vec2> uv0;        // TEXCOORD_0, empty when the primitive has none
    std::vector<uint32_t> indices;     // triangle list, 3 per triangle, each < positions.size()
    std::optional<uint32_t> material;  // index into Scene::materials; empty: the glTF default material
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;  // only triangle primitives; points/lines are dropped (with a warning)
};

enum class AlphaMode { Opaque, Mask, Blend };

// A reference from a material to Scene::textures, with its KHR_texture_transform (identity when absent):
// uv' = offset + rotate(rotation) * (scale * uv), as the extension defines it.
struct TextureRef {
    uint32_t texture = 0;   // index into Scene::textures
    uint32_t texCoord = 0;  // which TEXCOORD_n set (only 0 is loaded so far)
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;  // radians
    glm::vec2 scale{1.0f};
};

struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};  // linear RGBA
    float metallic = 1.0f;
    float roughness = 1.0f;
    glm::vec3 emissive{0.0f};  // emissiveFactor * KHR_materials_emissive_strength
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;
    std::optional<TextureRef> baseColorTexture;
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

// An image is recorded, not decoded: either a file next to the asset or the encoded bytes (PNG/JPEG...) that
// were embedded (GLB buffer view or data URI). Decoding happens later on worker threads.
struct Image {
    std::string name;
    std::filesystem::path path;    // absolute/resolved file path for external images, else empty
    std::string mimeType;          // may be empty for external files
    std::vector<uint8_t> encoded;  // embedded bytes, empty for external images
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
};

// One drawn copy of a mesh: a node of the default scene that references a mesh with primitives.
struct Instance {
    uint32_t mesh = 0;
    uint32_t node = 0;
    glm::mat4 world{1.0f};
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

struct Scene {
    std::filesystem::path sourcePath;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Image> images;
    std::vector<Node> nodes;
    std::vector<uint32_t> rootNodes;    // the default scene's root nodes
    std::vector<Instance> instances;    // default scene only, in depth-first node order
    std::vector<Camera> cameras;        // default scene only
    std::vector<Light> lights;          // default scene only
    Aabb bounds;                        // world-space AABB of all instanced vertices (empty if none)
    std::vector<std::string> warnings;  // non-fatal problems found while loading
};

}  // namespace idk::scene
