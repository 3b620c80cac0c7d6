// gltf_compression.cpp: compressed geometry for the loader (IDKEngine's ModelLoader supports neither):
// EXT_meshopt_compression bufferViews decoded with meshoptimizer (vertex/index codecs and the octahedral,
// quaternion and exponential filters) and KHR_draco_mesh_compression primitives decoded with Draco's C++ API.
// Every size, stride and mode is validated first: the decoders only assert their preconditions.
#include <algorithm>
#include <limits>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>
#include <meshoptimizer.h>

#include "scene/gltf_internal.hpp"

namespace idk::scene::gltf {

namespace {

constexpr size_t kMaxDecodedBytes = size_t{1} << 30;  // one decoded bufferView or Draco attribute, at most 1 GiB
constexpr size_t kMaxDracoPoints = size_t{1} << 26;

std::string stringOr(const tinygltf::Value& object, const char* key, const std::string& fallback) {
    if (!object.IsObject() || !object.Has(key)) return fallback;
    const auto& v = object.Get(key);
    return v.IsString() ? v.Get<std::string>() : fallback;
}

}  // namespace

void decodeMeshoptViews(const Ctx& ctx, tinygltf::Model& model) {
    const size_t viewCount = model.bufferViews.size();
    for (size_t v = 0; v < viewCount; ++v) {
        const tinygltf::Value* ext = extension(model.bufferViews[v].extensions, "EXT_meshopt_compression");
        if (ext == nullptr) continue;
        const std::string where = "bufferView " + str(v) + " EXT_meshopt_compression";
        if (!ext->IsObject()) ctx.fail(where + ": not an object");
        const auto buffer = indexOr(ctx, *ext, "buffer", where);
        const size_t offset = indexOr(ctx, *ext, "byteOffset", where).value_or(0);
        const auto length = indexOr(ctx, *ext, "byteLength", where);
        const auto stride = indexOr(ctx, *ext, "byteStride", where);
        const auto count = indexOr(ctx, *ext, "count", where);
        if (!buffer || !length || !stride || !count)
            ctx.fail(where + ": buffer, byteLength, byteStride and count are required");
        if (*buffer >= model.buffers.size())
            ctx.fail(where + ": buffer " + str(size_t(*buffer)) + " out of range (file has " +
                     str(model.buffers.size()) + ")");
        const auto& source = model.buffers[*buffer].data;
        if (offset > source.size() || *length > source.size() - offset)
            ctx.fail(where + ": compressed range (offset " + str(offset) + ", length " + str(size_t(*length)) +
                     ") extends past the end of buffer " + str(size_t(*buffer)) + " (" + str(source.size()) +
                     " bytes)");
        const std::string mode = stringOr(*ext, "mode", "");
        const std::string filter = stringOr(*ext, "filter", "NONE");
        const size_t n = *count, s = *stride;
        if (mode == "ATTRIBUTES") {
            if (s == 0 || s > 256 || s % 4 != 0)
                ctx.fail(where + ": ATTRIBUTES byteStride " + str(s) + " must be a multiple of 4 in 4..256");
        } else if (mode == "TRIANGLES" || mode == "INDICES") {
            if (s != 2 && s != 4) ctx.fail(where + ": " + mode + " byteStride " + str(s) + " must be 2 or 4");
            if (mode == "TRIANGLES" && n % 3 != 0)
                ctx.fail(where + ": TRIANGLES count " + str(n) + " is not a multiple of 3");
        } else {
            ctx.fail(where + ": unknown mode '" + mode + "'");
        }
        if (filter != "NONE" && mode != "ATTRIBUTES") ctx.fail(where + ": filter " + filter + " needs ATTRIBUTES mode");
        if ((filter == "OCTAHEDRAL" && s != 4 && s != 8) || (filter == "QUATERNION" && s != 8))
            ctx.fail(where + ": filter " + filter + " does not allow byteStride " + str(s));
        if (filter != "NONE" && filter != "OCTAHEDRAL" && filter != "QUATERNION" && filter != "EXPONENTIAL")
            ctx.fail(where + ": unknown filter '" + filter + "'");
        if (n > kMaxDecodedBytes / s) ctx.fail(where + ": " + str(n) + " x " + str(s) + " bytes is too large");

        ctx.charge(uint64_t(n) * s, where);
        std::vector<unsigned char> out(n * s);
        const unsigned char* compressed = source.data() + offset;
        int rc = 0;
        if (mode == "ATTRIBUTES")
            rc = meshopt_decodeVertexBuffer(out.data(), n, s, compressed, *length);
        else if (mode == "TRIANGLES")
            rc = meshopt_decodeIndexBuffer(out.data(), n, s, compressed, *length);
        else
            rc = meshopt_decodeIndexSequence(out.data(), n, s, compressed, *length);
        if (rc != 0) ctx.fail(where + ": meshopt " + mode + " data is corrupt (decoder error " + str(rc) + ")");
        if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), n, s);
        if (filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), n, s);
        if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), n, s);

        tinygltf::Buffer decoded;
        decoded.name = "meshopt-decoded bufferView " + str(v);
        decoded.data = std::move(out);
        model.buffers.push_back(std::move(decoded));
        auto& view = model.bufferViews[v];
        view.buffer = int(model.buffers.size() - 1);
        view.byteOffset = 0;
        view.byteLength = n * s;
        view.byteStride = mode == "ATTRIBUTES" ? s : 0;
    }
}

std::optional<DracoGeometry> decodeDraco(const Ctx& ctx, const tinygltf::Primitive& prim, const std::string& where) {
    const tinygltf::Value* ext = extension(prim.extensions, "KHR_draco_mesh_compression");
    if (ext == nullptr) return std::nullopt;
    const std::string what = where + " KHR_draco_mesh_compression";
    if (!ext->IsObject()) ctx.fail(what + ": not an object");
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP)
        ctx.fail(what + ": Draco data needs a triangle primitive (mode " + str(prim.mode) + ")");
    const auto viewIndex = indexOr(ctx, *ext, "bufferView", what);
    if (!viewIndex) ctx.fail(what + ": bufferView is required");
    if (*viewIndex >= ctx.model.bufferViews.size())
        ctx.fail(what + ": bufferView " + str(size_t(*viewIndex)) + " out of range (file has " +
                 str(ctx.model.bufferViews.size()) + ")");
    const size_t length = ctx.model.bufferViews[*viewIndex].byteLength;
    const ByteRange range = checkedRange(ctx, int(*viewIndex), 0, length, 1, false, what);

    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(range.base), length);
    const auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
    if (!type.ok()) ctx.fail(what + ": not Draco data (" + type.status().error_msg_string() + ")");
    if (type.value() != draco::TRIANGULAR_MESH) ctx.fail(what + ": the Draco data is a point cloud, not a mesh");
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) ctx.fail(what + ": Draco decoding failed: " + decoded.status().error_msg_string());
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (!mesh) ctx.fail(what + ": Draco decoding returned no mesh");

    DracoGeometry out;
    out.vertexCount = mesh->num_points();
    if (out.vertexCount > kMaxDracoPoints) ctx.fail(what + ": " + str(out.vertexCount) + " points is too many");
    const size_t faces = mesh->num_faces();
    if (faces > kMaxDecodedBytes / 12) ctx.fail(what + ": " + str(faces) + " faces is too many");
    ctx.charge(uint64_t(faces) * 12, what + " indices");
    out.indices.resize(faces * 3);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
        for (int k = 0; k < 3; ++k) out.indices[size_t(f.value()) * 3 + size_t(k)] = mesh->face(f)[k].value();

    if (!ext->Has("attributes") || !ext->Get("attributes").IsObject()) ctx.fail(what + ": attributes are required");
    const auto& attributes = ext->Get("attributes");
    for (const std::string& name : attributes.Keys()) {
        const auto id = indexOr(ctx, attributes, name.c_str(), what + " attributes");
        const draco::PointAttribute* attr = mesh->GetAttributeByUniqueId(*id);
        if (attr == nullptr)
            ctx.fail(what + ": attribute " + name + " (unique id " + str(size_t(*id)) + ") is not in the Draco data");
        const int comps = attr->num_components();
        if (comps < 1 || comps > 4) ctx.fail(what + ": attribute " + name + " has " + str(comps) + " components");
        if (!attr->is_mapping_identity() && attr->indices_map_size() < out.vertexCount)
            ctx.fail(what + ": attribute " + name + " maps fewer values than the mesh has points");
        // The glTF accessor may mark integer data normalized even when the Draco attribute is not.
        float scale = 0.0f;  // nonzero: divide integer values by the type's maximum here
        if (const auto it = prim.attributes.find(name); it != prim.attributes.end() && it->second >= 0 &&
                                                        size_t(it->second) < ctx.model.accessors.size()) {
            if (ctx.model.accessors[size_t(it->second)].normalized && !attr->normalized()) {
                switch (attr->data_type()) {
                    case draco::DT_INT8: scale = 1.0f / 127.0f; break;
                    case draco::DT_UINT8: scale = 1.0f / 255.0f; break;
                    case draco::DT_INT16: scale = 1.0f / 32767.0f; break;
                    case draco::DT_UINT16: scale = 1.0f / 65535.0f; break;
                    default: break;
                }
            }
        }
        DecodedAttribute values;
        values.components = comps;
        ctx.charge(uint64_t(out.vertexCount) * size_t(comps) * sizeof(float), what + " attribute " + name);
        values.values.resize(out.vertexCount * size_t(comps));
        for (draco::PointIndex p(0); p < mesh->num_points(); ++p) {
            const draco::AttributeValueIndex index = attr->mapped_index(p);
            if (index.value() >= attr->size())
                ctx.fail(what + ": attribute " + name + " point " + str(size_t(p.value())) + " maps past its values");
            float* dst = values.values.data() + size_t(p.value()) * size_t(comps);
            if (!attr->ConvertValue<float>(index, int8_t(comps), dst))
                ctx.fail(what + ": attribute " + name + " cannot be converted to floats");
            if (scale != 0.0f)
                for (int c = 0; c < comps; ++c) dst[c] = std::max(dst[c] * scale, -1.0f);
        }
        out.attributes[name] = std::move(values);
    }
    for (const uint32_t i : out.indices)
        if (i >= out.vertexCount)
            ctx.fail(what + ": index " + str(size_t(i)) + " out of range (" + str(out.vertexCount) + " points)");
    return out;
}

}  // namespace idk::scene::gltf
