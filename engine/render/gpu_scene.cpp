// gpu_scene.cpp: packing scene::Scene into the GPU scene's arrays (pure) and uploading them; placeholder
// textures, deduplicated samplers, and setTexture's material patching. Ports IDKEngine's ModelManager /
// ModelLoader GPU-side layout (one mesh per primitive, one draw command per mesh instance).
#include "render/gpu_scene.hpp"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

#include "core/log.hpp"
#include "passes/indirect_draw.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::render {
namespace {

// Columns of det(M) * inverse-transpose(M): finite for singular (zero-scale) matrices too.
glm::mat3 cofactor(const glm::mat3& m) {
    return glm::mat3(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
}

gpu::GpuTextureSlot slotFor(const std::optional<scene::TextureRef>& ref, uint32_t placeholder,
                            const TextureBindings& b) {
    gpu::GpuTextureSlot s{};
    s.texture = placeholder;
    s.samplerIndex = b.defaultSampler;
    s.row0 = glm::vec3(1.0f, 0.0f, 0.0f);
    s.row1 = glm::vec3(0.0f, 1.0f, 0.0f);
    if (!ref) return s;
    if (ref->texture < b.textureSamplers.size()) s.samplerIndex = b.textureSamplers[ref->texture];
    s.texCoord = ref->texCoord;
    // KHR_texture_transform: uv' = offset + R(rotation) * (scale * uv), R = [cos -sin; sin cos] as the
    // extension's GLSL builds it (columns (cos, sin) and (-sin, cos)).
    float c = std::cos(ref->rotation), sn = std::sin(ref->rotation);
    s.row0 = glm::vec3(c * ref->scale.x, -sn * ref->scale.y, ref->offset.x);
    s.row1 = glm::vec3(sn * ref->scale.x, c * ref->scale.y, ref->offset.y);
    return s;
}

uint32_t alphaModeOf(scene::AlphaMode mode) {
    switch (mode) {
        case scene::AlphaMode::Mask:
            return gpu::kAlphaMask;
        case scene::AlphaMode::Blend:
            return gpu::kAlphaBlend;
        default:
            return gpu::kAlphaOpaque;
    }
}

gpu::GpuMaterial packMaterial(const scene::Material& m, const TextureBindings& b) {
    gpu::GpuMaterial g{};
    g.baseColorFactor = m.baseColorFactor;
    g.emissiveFactor = m.emissive;
    g.metallicFactor = m.metallic;
    g.roughnessFactor = m.roughness;
    g.normalScale = m.normalScale;
    g.occlusionStrength = m.occlusionStrength;
    g.alphaCutoff = m.alphaCutoff;
    g.alphaMode = alphaModeOf(m.alphaMode);
    g.flags = (m.doubleSided ? gpu::kMaterialDoubleSided : 0u) | (m.unlit ? gpu::kMaterialUnlit : 0u);
    g.slots[gpu::kSlotBaseColor] = slotFor(m.baseColorTexture, b.white, b);
    g.slots[gpu::kSlotMetallicRoughness] = slotFor(m.metallicRoughnessTexture, b.white, b);
    g.slots[gpu::kSlotNormal] = slotFor(m.normalTexture, b.flatNormal, b);
    g.slots[gpu::kSlotOcclusion] = slotFor(m.occlusionTexture, b.white, b);
    g.slots[gpu::kSlotEmissive] = slotFor(m.emissiveTexture, b.white, b);
    // KHR_materials_specular / _clearcoat / _sheen textures: white placeholders multiply by 1.
    g.slots[gpu::kSlotSpecular] = slotFor(m.specularTexture, b.white, b);
    g.slots[gpu::kSlotSpecularColor] = slotFor(m.specularColorTexture, b.white, b);
    g.slots[gpu::kSlotClearcoat] = slotFor(m.clearcoatTexture, b.white, b);
    g.slots[gpu::kSlotClearcoatRoughness] = slotFor(m.clearcoatRoughnessTexture, b.white, b);
    g.slots[gpu::kSlotSheenColor] = slotFor(m.sheenColorTexture, b.white, b);
    g.slots[gpu::kSlotSheenRoughness] = slotFor(m.sheenRoughnessTexture, b.white, b);
    // KHR_materials_iridescence, clearcoat normal and anisotropy textures (the last two read only with their flag).
    g.slots[gpu::kSlotIridescence] = slotFor(m.iridescenceTexture, b.white, b);
    g.slots[gpu::kSlotIridescenceThickness] = slotFor(m.iridescenceThicknessTexture, b.white, b);
    g.slots[gpu::kSlotClearcoatNormal] = slotFor(m.clearcoatNormalTexture, b.flatNormal, b);
    g.slots[gpu::kSlotAnisotropy] = slotFor(m.anisotropyTexture, b.white, b);
    g.specular = m.specular;
    g.specularColor = m.specularColor;
    g.clearcoat = m.clearcoat;
    g.clearcoatRoughness = m.clearcoatRoughness;
    g.sheenColor = m.sheenColor;
    g.sheenRoughness = m.sheenRoughness;
    g.anisotropyStrength = m.anisotropyStrength;
    g.anisotropyRotation = m.anisotropyRotation;
    // KHR_materials_diffuse_transmission (its textures only when the factor can transmit), _dispersion.
    const bool diffuseTransmits = !m.unlit && m.diffuseTransmission > 0.0f;
    g.slots[gpu::kSlotDiffuseTransmission] =
        slotFor(diffuseTransmits ? m.diffuseTransmissionTexture : std::nullopt, b.white, b);
    g.slots[gpu::kSlotDiffuseTransmissionColor] =
        slotFor(diffuseTransmits ? m.diffuseTransmissionColorTexture : std::nullopt, b.white, b);
    g.diffuseTransmission = m.diffuseTransmission;
    g.diffuseTransmissionColor = m.diffuseTransmissionColor;
    g.dispersion = m.dispersion;
    if (diffuseTransmits) g.flags |= gpu::kMaterialDiffuseTransmission;
    if (!m.unlit && m.dispersion > 0.0f) g.flags |= gpu::kMaterialDispersion;
    g.iridescence = m.iridescence;
    g.iridescenceIor = m.iridescenceIor;
    g.iridescenceThicknessMin = m.iridescenceThicknessMin;
    g.iridescenceThicknessMax = m.iridescenceThicknessMax;
    g.clearcoatNormalScale = m.clearcoatNormalScale;
    // KHR_materials_transmission / _ior / _volume: the screen-space transmission pass reads them.
    const bool transmits = !m.unlit && m.transmission > 0.0f;
    g.slots[gpu::kSlotTransmission] = slotFor(transmits ? m.transmissionTexture : std::nullopt, b.white, b);
    g.slots[gpu::kSlotThickness] = slotFor(transmits ? m.thicknessTexture : std::nullopt, b.white, b);
    g.transmission = m.transmission;
    g.ior = m.ior;
    g.thickness = m.thickness;
    g.attenuationDistance = std::isfinite(m.attenuationDistance) ? m.attenuationDistance : 0.0f;
    g.attenuationColor = m.attenuationColor;
    if (transmits) g.flags |= gpu::kMaterialTransmission;
    if (transmits && m.thickness > 0.0f) g.flags |= gpu::kMaterialVolume;
    if (!m.unlit) {
        if (m.specular != 1.0f || m.specularColor != glm::vec3(1.0f) || m.specularTexture || m.specularColorTexture)
            g.flags |= gpu::kMaterialSpecular;
        if (m.clearcoat > 0.0f) g.flags |= gpu::kMaterialClearcoat;
        if (glm::any(glm::greaterThan(m.sheenColor, glm::vec3(0.0f)))) g.flags |= gpu::kMaterialSheen;
        if (m.anisotropyStrength > 0.0f) g.flags |= gpu::kMaterialAnisotropy;
        if (m.iridescence > 0.0f) g.flags |= gpu::kMaterialIridescence;
        if (m.clearcoat > 0.0f && m.clearcoatNormalTexture) g.flags |= gpu::kMaterialClearcoatNormal;
        if (m.anisotropyStrength > 0.0f && m.anisotropyTexture) g.flags |= gpu::kMaterialAnisotropyTexture;
    }
    return g;
}

// The scene texture each slot of a material samples (UINT32_MAX: none), indexed by gpu::kSlot*.
std::array<uint32_t, gpu::kSlotCount> slotTextures(const scene::Material& m) {
    const std::optional<scene::TextureRef>* refs[gpu::kSlotCount] = {
        &m.baseColorTexture,   &m.metallicRoughnessTexture,  &m.normalTexture,       &m.occlusionTexture,
        &m.emissiveTexture,    &m.specularTexture,           &m.specularColorTexture, &m.clearcoatTexture,
        &m.clearcoatRoughnessTexture, &m.sheenColorTexture, &m.sheenRoughnessTexture,
        &m.diffuseTransmissionTexture, &m.diffuseTransmissionColorTexture, &m.iridescenceTexture,
        &m.iridescenceThicknessTexture, &m.clearcoatNormalTexture, &m.anisotropyTexture, &m.transmissionTexture,
        &m.thicknessTexture};
    std::array<uint32_t, gpu::kSlotCount> t;
    for (uint32_t s = 0; s < gpu::kSlotCount; ++s) t[s] = *refs[s] ? (*refs[s])->texture : UINT32_MAX;
    if (m.unlit || !(m.diffuseTransmission > 0.0f))  // packMaterial binds white there: nothing to stream
        t[gpu::kSlotDiffuseTransmission] = t[gpu::kSlotDiffuseTransmissionColor] = UINT32_MAX;
    if (m.unlit || !(m.transmission > 0.0f)) t[gpu::kSlotTransmission] = t[gpu::kSlotThickness] = UINT32_MAX;
    return t;
}

// Slots whose texture holds colour (sampled through an sRGB view); the rest hold data.
bool isColorSlot(uint32_t slot) {
    return slot == gpu::kSlotBaseColor || slot == gpu::kSlotEmissive || slot == gpu::kSlotSpecularColor ||
           slot == gpu::kSlotSheenColor || slot == gpu::kSlotDiffuseTransmissionColor;
}

gpu::GpuLight packLight(const scene::Light& l) {
    gpu::GpuLight g{};
    g.position = l.position;
    g.type = l.type == scene::LightType::Directional ? gpu::kLightDirectional
             : l.type == scene::LightType::Spot      ? gpu::kLightSpot
                                                     : gpu::kLightPoint;
    float len = glm::length(l.direction);
    g.direction = len > 0.0f ? l.direction / len : glm::vec3(0.0f, 0.0f, -1.0f);
    g.range = l.range;
    g.intensity = l.color * l.intensity;
    float cosOuter = std::cos(l.outerConeAngle), cosInner = std::cos(l.innerConeAngle);
    g.spotScale = 1.0f / std::max(0.001f, cosInner - cosOuter);
    g.spotOffset = -cosOuter * g.spotScale;
    return g;
}

}  // namespace

vk::SamplerDesc samplerDesc(const scene::Sampler& s) {
    vk::SamplerDesc d;
    d.filter = s.magFilter == 9728 ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
    // 9984 NEAREST_MIPMAP_NEAREST, 9985 LINEAR_MIPMAP_NEAREST: nearest mip; everything else: linear mip.
    d.mipmap =
        (s.minFilter == 9984 || s.minFilter == 9985) ? VK_SAMPLER_MIPMAP_MODE_NEAREST : VK_SAMPLER_MIPMAP_MODE_LINEAR;
    // vk::SamplerDesc has one address mode for both axes: wrapS decides (glTF assets rarely differ).
    d.address = s.wrapS == 33071   ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE
                : s.wrapS == 33648 ? VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT
                                   : VK_SAMPLER_ADDRESS_MODE_REPEAT;
    d.maxAnisotropy = (s.minFilter == 9728 || s.minFilter == 9729) ? 1.0f : 8.0f;  // IDKEngine: 8x when mipmapped
    return d;
}

gpu::GpuInstance packInstance(const glm::mat4& world, uint32_t mesh) {
    glm::mat3 m3(world);
    float det = glm::determinant(m3);
    gpu::GpuInstance gi{};
    gi.model = world;
    gi.normalMatrix = cofactor(m3) * (det < 0.0f ? -1.0f : 1.0f);  // direction of the inverse-transpose
    gi.mesh = mesh;
    gi.flags = det < 0.0f ? gpu::kInstanceMirrored : 0u;
    return gi;
}

GpuSceneData packGpuScene(const scene::Scene& scene, const TextureBindings& b) {
    GpuSceneData out;
    out.features = scene.features();
    for (const scene::Material& m : scene.materials) out.materials.push_back(packMaterial(m, b));
    const auto defaultMaterial = uint32_t(out.materials.size());
    out.materials.push_back(packMaterial(scene::Material{}, b));  // glTF default: white, metallic 1, roughness 1

    out.textureUses.resize(scene.textures.size());
    for (uint32_t mi = 0; mi < scene.materials.size(); ++mi) {
        std::array<uint32_t, gpu::kSlotCount> used = slotTextures(scene.materials[mi]);
        for (uint32_t s = 0; s < gpu::kSlotCount; ++s)
            if (used[s] < out.textureUses.size()) out.textureUses[used[s]].push_back({mi, s});
    }

    // Optional vertex streams exist only when some primitive has the attribute (the others get the default).
    bool anyColors = false, anyUv1 = false;
    for (const scene::Mesh& mesh : scene.meshes)
        for (const scene::Primitive& prim : mesh.primitives) {
            anyColors |= !prim.colors.empty();
            anyUv1 |= !prim.uv1.empty();
        }

    // Meshes: every primitive's vertices and indices appended to the merged buffers.
    std::vector<uint32_t> firstMesh;
    for (const scene::Mesh& mesh : scene.meshes) {
        firstMesh.push_back(uint32_t(out.meshes.size()));
        for (const scene::Primitive& prim : mesh.primitives) {
            gpu::GpuMesh gm{};
            gm.firstIndex = uint32_t(out.indices.size());
            gm.indexCount = uint32_t(prim.indices.size());
            gm.baseVertex = int32_t(out.vertices.size());
            gm.material = prim.material && *prim.material < scene.materials.size() ? *prim.material : defaultMaterial;
            out.meshes.push_back(gm);
            for (size_t v = 0; v < prim.positions.size(); ++v) {
                gpu::GpuVertex gv{};
                gv.position = prim.positions[v];
                gv.normal = v < prim.normals.size() ? prim.normals[v] : glm::vec3(0.0f, 0.0f, 1.0f);
                gv.uv0 = v < prim.uv0.size() ? prim.uv0[v] : glm::vec2(0.0f);
                gv.tangent = v < prim.tangents.size() ? prim.tangents[v] : glm::vec4(0.0f);  // w = 0: derive
                out.vertices.push_back(gv);
                if (anyColors) out.colors.push_back(v < prim.colors.size() ? prim.colors[v] : glm::vec4(1.0f));
                if (anyUv1) out.uv1.push_back(v < prim.uv1.size() ? prim.uv1[v] : glm::vec2(0.0f));
            }
            out.indices.insert(out.indices.end(), prim.indices.begin(), prim.indices.end());
        }
    }

    // Skinned/morphed (node, primitive) pairs get deformed vertex copies, which their draws use.
    out.deformation = packDeformation(scene, firstMesh, out);

    // Instances: one per (node instance, primitive) with indices; draw i draws instance i.
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const scene::Instance& inst = scene.instances[i];
        if (inst.mesh >= scene.meshes.size()) continue;
        const auto& prims = scene.meshes[inst.mesh].primitives;
        for (uint32_t p = 0; p < prims.size(); ++p) {
            const gpu::GpuMesh& gm = out.meshes[firstMesh[inst.mesh] + p];
            if (gm.indexCount == 0) continue;
            out.instances.push_back(packInstance(inst.world, firstMesh[inst.mesh] + p));
            out.drawInstance.push_back(i);
            const int32_t base = out.deformation.baseVertex(inst.node, firstMesh[inst.mesh] + p, gm.baseVertex);
            // BLEND and transmissive primitives keep their slot with no instance: the transparency and the
            // transmission passes draw them, sorted.
            const uint32_t count = drawnForward(out.materials[gm.material]) ? 0u : 1u;
            out.draws.push_back(VkDrawIndexedIndirectCommand{gm.indexCount, count, gm.firstIndex, base, 0});
        }
    }
    for (const scene::Light& l : scene.lights) out.lights.push_back(packLight(l));
    return out;
}

namespace {

template <class T>
vk::Buffer uploadArray(vk::Context& ctx, const std::vector<T>& values, VkBufferUsageFlags usage, const char* name,
                       const char* category) {
    if (values.empty()) return {};
    vk::BufferDesc desc;
    desc.size = values.size() * sizeof(T);
    desc.usage = usage;
    desc.name = name;
    desc.category = category;
    return vk::createBufferWithData(ctx, desc, values.data(), desc.size);
}

vk::Image placeholder(vk::Context& ctx, VkFormat format, const void* texel, VkDeviceSize bytes, const char* name) {
    vk::ImageDesc desc;
    desc.format = format;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.name = name;
    desc.category = "textures";
    vk::Image image = ctx.createImage(desc);
    vk::uploadImage(ctx, image, texel, bytes, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    return image;
}

}  // namespace

GpuScene::GpuScene(vk::Context& ctx, const scene::Scene& scene, GpuSceneContents contents) : ctx_(ctx) {
    // A throw part-way (a buffer over the device's maxBufferSize, out of memory) skips the destructor: release
    // what was already created here.
    try {
        create(scene, contents);
    } catch (...) {
        release();
        throw;
    }
}

void GpuScene::create(const scene::Scene& scene, GpuSceneContents contents) {
    vk::Context& ctx = ctx_;
    TextureBindings b;
    if (!scene.meshes.empty()) {
        const uint8_t white[4] = {255, 255, 255, 255};
        // Half floats so (0.5, 0.5) remaps to exactly 0 (8-bit 128/255 would tilt the normal by 0.2 degrees).
        const uint16_t flat[4] = {glm::packHalf1x16(0.5f), glm::packHalf1x16(0.5f), glm::packHalf1x16(1.0f),
                                  glm::packHalf1x16(1.0f)};
        white_ = placeholder(ctx, VK_FORMAT_R8G8B8A8_UNORM, white, sizeof(white), "placeholder white");
        flatNormal_ = placeholder(ctx, VK_FORMAT_R16G16B16A16_SFLOAT, flat, sizeof(flat), "placeholder normal");
        whiteIndex_ = ctx.bindless().addSampled(white_.view);
        flatNormalIndex_ = ctx.bindless().addSampled(flatNormal_.view);
        b.white = whiteIndex_.value;
        b.flatNormal = flatNormalIndex_.value;

        // One bindless sampler per distinct sampler state (glTF samplers: 8x anisotropic when mipmapped).
        std::map<std::tuple<int, int, int>, uint32_t> unique;
        auto samplerFor = [&](const scene::Sampler& s) {
            vk::SamplerDesc d = samplerDesc(s);
            auto key = std::make_tuple(int(d.filter), int(d.mipmap) * 16 + int(d.maxAnisotropy), int(d.address));
            auto it = unique.find(key);
            if (it != unique.end()) return it->second;
            samplers_.push_back(ctx.bindless().addSampler(d));
            return unique[key] = samplers_.back().value;
        };
        // Slots without a texture sample a 1x1 placeholder: no anisotropy (lavapipe's anisotropic path returns
        // 0 when the UV derivatives are zero, e.g. for primitives without TEXCOORD_0).
        scene::Sampler plain;
        plain.minFilter = 9729;
        b.defaultSampler = samplerFor(plain);
        for (const scene::Texture& t : scene.textures) b.textureSamplers.push_back(samplerFor(t.sampler));
    }
    data_ = packGpuScene(scene, b);

    constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    materials_ = uploadArray(ctx, data_.materials, kStorage, "scene materials", "materials");
    if (contents == GpuSceneContents::MaterialsOnly) return;
    vertices_ = uploadArray(ctx, data_.vertices, kStorage, "scene vertices", "geometry");
    indices_ = uploadArray(ctx, data_.indices, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "scene indices", "geometry");
    meshes_ = uploadArray(ctx, data_.meshes, kStorage, "scene meshes", "geometry");
    instances_ = uploadArray(ctx, data_.instances, kStorage, "scene instances", "instances");
    if (!data_.draws.empty()) {  // the commands and the count word of passes/indirect_draw.hpp
        const std::vector<uint8_t> bytes = passes::withCountWord(data_.draws);
        vk::BufferDesc desc;
        desc.size = bytes.size();
        desc.usage = VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
        desc.name = "scene draw commands";
        desc.category = "instances";
        draws_ = vk::createBufferWithData(ctx, desc, bytes.data(), desc.size);
    }
    lights_ = uploadArray(ctx, data_.lights, kStorage, "scene lights", "lights");
    colors_ = uploadArray(ctx, data_.colors, kStorage, "scene vertex colors", "geometry");
    uv1_ = uploadArray(ctx, data_.uv1, kStorage, "scene uv1", "geometry");
    if (!data_.deformation.jobs.empty() || data_.features.hasAnimations)
        animation_ = std::make_unique<GpuAnimation>(ctx, data_, scene);
}

GpuScene::~GpuScene() {
    release();
}

void GpuScene::release() {
    for (vk::Buffer* b :
         {&vertices_, &indices_, &meshes_, &instances_, &draws_, &materials_, &lights_, &colors_, &uv1_}) {
        if (*b) ctx_.destroyDeferred(*b);
    }
    if (white_) {
        ctx_.bindless().release(whiteIndex_);
        ctx_.bindless().release(flatNormalIndex_);
        ctx_.destroyDeferred(white_);
        ctx_.destroyDeferred(flatNormal_);
    }
    for (vk::SamplerIndex s : samplers_) ctx_.bindless().release(s);
}

void GpuScene::setTexture(uint32_t sceneTextureIndex, vk::SampledIndex texture,
                          std::optional<vk::SamplerIndex> sampler) {
    if (sceneTextureIndex >= data_.textureUses.size()) {
        throw std::out_of_range("GpuScene::setTexture: texture " + std::to_string(sceneTextureIndex) +
                                " out of range (scene has " + std::to_string(data_.textureUses.size()) + ")");
    }
    for (const TextureSlotRef& use : data_.textureUses[sceneTextureIndex]) {
        gpu::GpuTextureSlot& slot = data_.materials[use.material].slots[use.slot];
        slot.texture = texture.value;
        if (sampler) slot.samplerIndex = sampler->value;
        materialsDirty_ = true;
    }
}

bool GpuScene::textureIsColor(uint32_t t) const {
    if (t >= data_.textureUses.size()) return false;
    return std::any_of(data_.textureUses[t].begin(), data_.textureUses[t].end(), [](const TextureSlotRef& u) {
        return isColorSlot(u.slot);
    });
}

bool GpuScene::textureIsData(uint32_t t) const {
    if (t >= data_.textureUses.size()) return false;
    return std::any_of(data_.textureUses[t].begin(), data_.textureUses[t].end(), [](const TextureSlotRef& u) {
        return !isColorSlot(u.slot);
    });
}

}  // namespace idk::render
