// spirv_reflect.cpp: a single pass over the SPIR-V words records, per id, the defining instruction and its
// decorations (niagara style); the result is then derived from those records: stage, workgroup size, block sizes
// of push constants (offsets, array/matrix strides, nested structs), descriptor bindings and spec constants.
#include "shader/spirv_reflect.hpp"

#include <glslang/SPIRV/spirv.hpp>  // spv:: enums (glslang-dev's copy of the Khronos SPIR-V header)

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <map>
#include <utility>

namespace idk::shader {

ReflectError::ReflectError(const std::string& what, size_t word)
    : std::runtime_error("SPIR-V: " + what + " (at word " + std::to_string(word) + ")"), word_(word) {}

namespace {

constexpr uint32_t kMagic = 0x07230203u;
constexpr uint32_t kHeaderWords = 5;
constexpr uint32_t kMaxIdBound = 1u << 22;  // far above any real shader; bounds the per-id table
constexpr uint32_t kNone = ~0u;
constexpr int kMaxTypeDepth = 64;

struct IdInfo {
    uint32_t opcode = 0;
    uint32_t at = 0;            // word index of the defining instruction
    uint32_t typeId = 0;        // result type (constants, variables)
    uint32_t storageClass = kNone;
    uint32_t set = kNone;
    uint32_t binding = kNone;
    uint32_t specId = kNone;
    uint32_t arrayStride = 0;
    bool workgroupSizeBuiltIn = false;
    bool block = false;
    bool bufferBlock = false;
};

struct MemberLayout {
    uint32_t offset = kNone;
    uint32_t matrixStride = 0;
    bool rowMajor = false;
};

class Module {
public:
    explicit Module(std::span<const uint32_t> words) : words_(words) {}

    ShaderInfo reflect();

private:
    uint32_t word(uint32_t at) const { return words_[at]; }
    uint32_t wordCount(uint32_t at) const { return words_[at] >> 16; }

    [[noreturn]] void fail(const std::string& what, size_t at) const { throw ReflectError(what, at); }

    uint32_t checkedId(uint32_t id, uint32_t at) const {
        if (id == 0 || id >= ids_.size()) {
            fail("id %" + std::to_string(id) + " outside the id bound " + std::to_string(ids_.size()), at);
        }
        return id;
    }
    const IdInfo& def(uint32_t id, uint32_t at) const {
        const IdInfo& info = ids_[checkedId(id, at)];
        if (info.opcode == 0) {
            fail("id %" + std::to_string(id) + " is used but never defined", at);
        }
        return info;
    }

    void parseInstruction(uint32_t at, uint32_t opcode, uint32_t count);
    std::string readString(uint32_t at, uint32_t first, uint32_t end) const;

    uint64_t constantValue(uint32_t id, uint32_t at) const;
    std::optional<uint32_t> specIdOf(uint32_t id) const;
    uint64_t typeSize(uint32_t typeId, const MemberLayout& layout, int depth, uint32_t from) const;
    uint64_t structSize(uint32_t structId, int depth) const;

    void resolveWorkgroupSize(ShaderInfo& info) const;
    void collectBindings(ShaderInfo& info) const;

    std::span<const uint32_t> words_;
    std::vector<IdInfo> ids_;
    std::map<std::pair<uint32_t, uint32_t>, MemberLayout> members_;  // (struct id, member index)
    std::vector<uint32_t> capabilities_;
    uint32_t addressingModel_ = 0;

    bool haveEntry_ = false;
    uint32_t entryAt_ = 0;
    uint32_t entryModel_ = 0;
    uint32_t entryFunction_ = 0;
    std::string entryName_;
    std::optional<std::array<uint32_t, 3>> localSize_;     // LocalSize literals
    std::optional<std::array<uint32_t, 3>> localSizeIds_;  // LocalSizeId operands
    uint32_t localSizeAt_ = 0;
};

std::string Module::readString(uint32_t at, uint32_t first, uint32_t end) const {
    std::string s;
    for (uint32_t w = first; w < end; ++w) {
        for (int byte = 0; byte < 4; ++byte) {
            const char c = static_cast<char>((words_[w] >> (8 * byte)) & 0xffu);
            if (c == '\0') {
                return s;
            }
            s.push_back(c);
        }
    }
    fail("string literal without a terminating NUL", at);
}

void Module::parseInstruction(uint32_t at, uint32_t opcode, uint32_t count) {
    auto need = [&](uint32_t minimum) {
        if (count < minimum) {
            fail("instruction with opcode " + std::to_string(opcode) + " has " + std::to_string(count) +
                     " words, needs at least " + std::to_string(minimum),
                 at);
        }
    };
    auto defineResult = [&](uint32_t resultWord, uint32_t typeWord) {
        const uint32_t id = checkedId(word(at + resultWord), at);
        IdInfo& info = ids_[id];
        info.opcode = opcode;
        info.at = at;
        if (typeWord != 0) {
            info.typeId = word(at + typeWord);
        }
        return id;
    };

    switch (opcode) {
        case spv::OpCapability:
            need(2);
            capabilities_.push_back(word(at + 1));
            break;
        case spv::OpMemoryModel:
            need(3);
            addressingModel_ = word(at + 1);
            break;
        case spv::OpEntryPoint:
            need(4);
            if (!haveEntry_) {
                haveEntry_ = true;
                entryAt_ = at;
                entryModel_ = word(at + 1);
                entryFunction_ = checkedId(word(at + 2), at);
                entryName_ = readString(at, at + 3, at + count);
            }
            break;
        case spv::OpExecutionMode:
        case spv::OpExecutionModeId:
            need(3);
            if (word(at + 2) == spv::ExecutionModeLocalSize || word(at + 2) == spv::ExecutionModeLocalSizeId) {
                need(6);
                // Modes are keyed by function; entry points are declared first, so the target is known here.
                if (haveEntry_ && word(at + 1) == entryFunction_) {
                    const std::array<uint32_t, 3> xyz = {word(at + 3), word(at + 4), word(at + 5)};
                    (word(at + 2) == spv::ExecutionModeLocalSize ? localSize_ : localSizeIds_) = xyz;
                    localSizeAt_ = at;
                }
            }
            break;
        case spv::OpDecorate: {
            need(3);
            IdInfo& info = ids_[checkedId(word(at + 1), at)];
            const uint32_t decoration = word(at + 2);
            switch (decoration) {
                case spv::DecorationSpecId:
                    need(4);
                    info.specId = word(at + 3);
                    break;
                case spv::DecorationBlock: info.block = true; break;
                case spv::DecorationBufferBlock: info.bufferBlock = true; break;
                case spv::DecorationArrayStride:
                    need(4);
                    info.arrayStride = word(at + 3);
                    break;
                case spv::DecorationBuiltIn:
                    need(4);
                    info.workgroupSizeBuiltIn = word(at + 3) == spv::BuiltInWorkgroupSize;
                    break;
                case spv::DecorationDescriptorSet:
                    need(4);
                    info.set = word(at + 3);
                    break;
                case spv::DecorationBinding:
                    need(4);
                    info.binding = word(at + 3);
                    break;
                default: break;
            }
            break;
        }
        case spv::OpMemberDecorate: {
            need(4);
            const uint32_t structId = checkedId(word(at + 1), at);
            const uint32_t decoration = word(at + 3);
            if (decoration == spv::DecorationOffset || decoration == spv::DecorationMatrixStride ||
                decoration == spv::DecorationRowMajor || decoration == spv::DecorationColMajor) {
                MemberLayout& m = members_[{structId, word(at + 2)}];
                if (decoration == spv::DecorationOffset) {
                    need(5);
                    m.offset = word(at + 4);
                } else if (decoration == spv::DecorationMatrixStride) {
                    need(5);
                    m.matrixStride = word(at + 4);
                } else {
                    m.rowMajor = decoration == spv::DecorationRowMajor;
                }
            }
            break;
        }
        // Types: result id in word 1.
        case spv::OpTypeInt:
        case spv::OpTypeFloat:
            need(3);
            defineResult(1, 0);
            break;
        case spv::OpTypeVector:
        case spv::OpTypeMatrix:
            need(4);
            defineResult(1, 0);
            break;
        case spv::OpTypeArray:
            need(4);
            defineResult(1, 0);
            break;
        case spv::OpTypeImage:
            need(9);
            defineResult(1, 0);
            break;
        case spv::OpTypeRuntimeArray:
        case spv::OpTypeSampledImage:
            need(3);
            defineResult(1, 0);
            break;
        case spv::OpTypePointer: {
            need(4);
            const uint32_t id = defineResult(1, 0);
            ids_[id].storageClass = word(at + 2);
            ids_[id].typeId = word(at + 3);
            break;
        }
        case spv::OpTypeBool:
        case spv::OpTypeVoid:
        case spv::OpTypeSampler:
        case spv::OpTypeStruct:
        case spv::OpTypeFunction:
        case spv::OpTypeAccelerationStructureKHR:
        case spv::OpTypeRayQueryKHR:
            need(2);
            defineResult(1, 0);
            break;
        // Constants: result type in word 1, result id in word 2.
        case spv::OpConstant:
        case spv::OpSpecConstant:
            need(4);
            defineResult(2, 1);
            break;
        case spv::OpConstantTrue:
        case spv::OpConstantFalse:
        case spv::OpSpecConstantTrue:
        case spv::OpSpecConstantFalse:
        case spv::OpConstantNull:
        case spv::OpConstantComposite:
        case spv::OpSpecConstantComposite:
        case spv::OpSpecConstantOp:
            need(3);
            defineResult(2, 1);
            break;
        case spv::OpVariable: {
            need(4);
            const uint32_t id = defineResult(2, 1);
            ids_[id].storageClass = word(at + 3);
            break;
        }
        default:
            break;
    }
}

uint64_t Module::constantValue(uint32_t id, uint32_t at) const {
    const IdInfo& c = def(id, at);
    switch (c.opcode) {
        case spv::OpConstant:
        case spv::OpSpecConstant: {
            const uint32_t count = wordCount(c.at);
            uint64_t value = word(c.at + 3);
            if (count >= 5) {
                value |= uint64_t(word(c.at + 4)) << 32;  // 64-bit literal: low word first
            }
            return value;
        }
        case spv::OpConstantTrue:
        case spv::OpSpecConstantTrue: return 1;
        case spv::OpConstantFalse:
        case spv::OpSpecConstantFalse:
        case spv::OpConstantNull: return 0;
        default:
            fail("cannot evaluate %" + std::to_string(id) + " (opcode " + std::to_string(c.opcode) +
                     ") as a scalar constant",
                 c.at);
    }
}

std::optional<uint32_t> Module::specIdOf(uint32_t id) const {
    if (id < ids_.size() && ids_[id].specId != kNone) {
        return ids_[id].specId;
    }
    return std::nullopt;
}

uint64_t Module::structSize(uint32_t structId, int depth) const {
    const IdInfo& s = ids_[structId];
    const uint32_t memberCount = wordCount(s.at) - 2;
    uint64_t size = 0;
    uint64_t sequentialEnd = 0;  // used only if members carry no Offset (not an explicitly laid out block)
    for (uint32_t m = 0; m < memberCount; ++m) {
        const uint32_t memberType = word(s.at + 2 + m);
        const auto it = members_.find({structId, m});
        const MemberLayout layout = it != members_.end() ? it->second : MemberLayout{};
        const uint64_t memberSize = typeSize(memberType, layout, depth + 1, s.at);
        const uint64_t offset = layout.offset != kNone ? layout.offset : sequentialEnd;
        sequentialEnd = offset + memberSize;
        size = std::max(size, offset + memberSize);
    }
    return size;
}

uint64_t Module::typeSize(uint32_t typeId, const MemberLayout& layout, int depth, uint32_t from) const {
    if (depth > kMaxTypeDepth) {
        fail("type nesting deeper than " + std::to_string(kMaxTypeDepth), from);
    }
    const IdInfo& t = def(typeId, from);
    switch (t.opcode) {
        case spv::OpTypeInt:
        case spv::OpTypeFloat: return word(t.at + 2) / 8;
        case spv::OpTypeBool: return 4;
        case spv::OpTypeVector: return word(t.at + 3) * typeSize(word(t.at + 2), layout, depth + 1, t.at);
        case spv::OpTypeMatrix: {
            const uint32_t columnType = word(t.at + 2);
            const uint32_t columns = word(t.at + 3);
            const IdInfo& column = def(columnType, t.at);
            if (column.opcode != spv::OpTypeVector) {
                fail("matrix column type %" + std::to_string(columnType) + " is not a vector", t.at);
            }
            const uint32_t rows = word(column.at + 3);
            if (layout.matrixStride == 0) {
                return columns * typeSize(columnType, layout, depth + 1, t.at);
            }
            return uint64_t(layout.rowMajor ? rows : columns) * layout.matrixStride;
        }
        case spv::OpTypeArray: {
            const uint64_t length = constantValue(word(t.at + 3), t.at);
            const uint64_t stride =
                t.arrayStride != 0 ? t.arrayStride : typeSize(word(t.at + 2), layout, depth + 1, t.at);
            return length * stride;
        }
        case spv::OpTypeRuntimeArray: return 0;
        case spv::OpTypeStruct: return structSize(typeId, depth);
        case spv::OpTypePointer: return 8;  // PhysicalStorageBuffer pointer (buffer_reference)
        default:
            fail("type %" + std::to_string(typeId) + " (opcode " + std::to_string(t.opcode) +
                     ") has no size in an explicit layout",
                 t.at);
    }
}

void Module::resolveWorkgroupSize(ShaderInfo& info) const {
    // Precedence (SPIR-V spec): the WorkgroupSize built-in constant, then LocalSizeId, then LocalSize.
    for (uint32_t id = 1; id < ids_.size(); ++id) {
        const IdInfo& c = ids_[id];
        if (!c.workgroupSizeBuiltIn || c.opcode == 0) {
            continue;
        }
        if ((c.opcode != spv::OpConstantComposite && c.opcode != spv::OpSpecConstantComposite) ||
            wordCount(c.at) != 6) {
            fail("WorkgroupSize built-in %" + std::to_string(id) + " is not a 3-component constant", c.at);
        }
        for (int i = 0; i < 3; ++i) {
            const uint32_t component = word(c.at + 3 + i);
            info.localSize[i] = static_cast<uint32_t>(constantValue(component, c.at));
            info.localSizeSpecIds[i] = specIdOf(component);
        }
        return;
    }
    if (localSizeIds_) {
        for (int i = 0; i < 3; ++i) {
            const uint32_t component = (*localSizeIds_)[i];
            info.localSize[i] = static_cast<uint32_t>(constantValue(component, localSizeAt_));
            info.localSizeSpecIds[i] = specIdOf(component);
        }
    } else if (localSize_) {
        info.localSize = *localSize_;
    }
}

void Module::collectBindings(ShaderInfo& info) const {
    std::map<std::pair<uint32_t, uint32_t>, DescriptorBinding> merged;
    for (uint32_t id = 1; id < ids_.size(); ++id) {
        const IdInfo& v = ids_[id];
        if (v.opcode != spv::OpVariable) {
            continue;
        }
        if (v.storageClass == spv::StorageClassPushConstant) {
            const IdInfo& pointer = def(v.typeId, v.at);
            if (pointer.opcode != spv::OpTypePointer) {
                fail("variable %" + std::to_string(id) + " does not have a pointer type", v.at);
            }
            const uint64_t bytes = typeSize(pointer.typeId, {}, 0, pointer.at);
            if (bytes > UINT32_MAX) {
                fail("push-constant block of " + std::to_string(bytes) + " bytes", v.at);
            }
            info.pushConstantBytes = std::max<uint32_t>(info.pushConstantBytes, static_cast<uint32_t>(bytes));
            continue;
        }
        if (v.storageClass != spv::StorageClassUniform && v.storageClass != spv::StorageClassUniformConstant &&
            v.storageClass != spv::StorageClassStorageBuffer) {
            continue;
        }
        if (v.set == kNone || v.binding == kNone) {
            continue;  // e.g. a plain uniform in a non-Vulkan module
        }
        DescriptorBinding b{v.set, v.binding, DescriptorKind::StorageBuffer, 1};
        const IdInfo& pointer = def(v.typeId, v.at);
        if (pointer.opcode != spv::OpTypePointer) {
            fail("variable %" + std::to_string(id) + " does not have a pointer type", v.at);
        }
        uint32_t typeId = pointer.typeId;
        const IdInfo* type = &def(typeId, v.at);
        if (type->opcode == spv::OpTypeArray) {
            b.count = static_cast<uint32_t>(constantValue(word(type->at + 3), type->at));
            typeId = word(type->at + 2);
            type = &def(typeId, type->at);
        } else if (type->opcode == spv::OpTypeRuntimeArray) {
            b.count = 0;
            typeId = word(type->at + 2);
            type = &def(typeId, type->at);
        }
        switch (type->opcode) {
            case spv::OpTypeSampler: b.kind = DescriptorKind::Sampler; break;
            case spv::OpTypeSampledImage: b.kind = DescriptorKind::CombinedImageSampler; break;
            case spv::OpTypeAccelerationStructureKHR: b.kind = DescriptorKind::AccelerationStructure; break;
            case spv::OpTypeImage: {
                const uint32_t dim = word(type->at + 3);
                const uint32_t sampled = word(type->at + 7);  // 1: sampled, 2: storage
                if (dim == spv::DimBuffer) {
                    b.kind = sampled == 2 ? DescriptorKind::StorageTexelBuffer : DescriptorKind::UniformTexelBuffer;
                } else if (dim == spv::DimSubpassData) {
                    b.kind = DescriptorKind::InputAttachment;
                } else {
                    b.kind = sampled == 2 ? DescriptorKind::StorageImage : DescriptorKind::SampledImage;
                }
                break;
            }
            case spv::OpTypeStruct:
                if (v.storageClass == spv::StorageClassStorageBuffer || type->bufferBlock) {
                    b.kind = DescriptorKind::StorageBuffer;
                } else {
                    b.kind = DescriptorKind::UniformBuffer;
                }
                break;
            default:
                fail("descriptor variable %" + std::to_string(id) + " has an unsupported type (opcode " +
                         std::to_string(type->opcode) + ")",
                     v.at);
        }
        auto [it, inserted] = merged.try_emplace({b.set, b.binding}, b);
        if (!inserted) {
            // Aliased declarations of one binding (bindless arrays per image dimension or element type).
            if (it->second.kind != b.kind) {
                fail("set " + std::to_string(b.set) + " binding " + std::to_string(b.binding) + " is declared as " +
                         std::string(toString(it->second.kind)) + " and as " + std::string(toString(b.kind)),
                     v.at);
            }
            if (it->second.count != 0) {
                it->second.count = b.count == 0 ? 0 : std::max(it->second.count, b.count);
            }
        }
    }
    for (const auto& [key, b] : merged) {
        if (b.set < 32) {
            info.descriptorSetMask |= 1u << b.set;
        }
        info.bindings.push_back(b);
    }
}

ShaderInfo Module::reflect() {
    if (words_.size() < kHeaderWords) {
        fail("truncated header: " + std::to_string(words_.size()) + " words, a module needs at least 5",
             words_.size());
    }
    if (words_[0] != kMagic) {
        const bool swapped = words_[0] == 0x03022307u;
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%08x", words_[0]);
        fail(std::string("bad magic number ") + hex + (swapped ? " (byte-swapped module)" : ", expected 0x07230203"),
             0);
    }
    const uint32_t bound = words_[3];
    // The per-id table costs ~40 bytes an id: refuse bounds no real module of this length would have.
    if (bound == 0 || bound > kMaxIdBound || bound > std::max<size_t>(65536, words_.size() * 64)) {
        fail("id bound " + std::to_string(bound) + " out of range for a module of " +
                 std::to_string(words_.size()) + " words",
             3);
    }
    ids_.assign(bound, IdInfo{});

    ShaderInfo info;
    info.spirvVersion = words_[1];

    uint32_t at = kHeaderWords;
    while (at < words_.size()) {
        const uint32_t count = wordCount(at);
        const uint32_t opcode = word(at) & 0xffffu;
        if (count == 0) {
            fail("instruction with word count 0 (opcode " + std::to_string(opcode) + ")", at);
        }
        if (count > words_.size() - at) {
            fail("truncated instruction: opcode " + std::to_string(opcode) + " needs " + std::to_string(count) +
                     " words, " + std::to_string(words_.size() - at) + " left",
                 at);
        }
        parseInstruction(at, opcode, count);
        at += count;
    }
    if (!haveEntry_) {
        fail("no OpEntryPoint in the module", words_.size());
    }

    info.entryPoint = entryName_;
    switch (entryModel_) {
        case spv::ExecutionModelGLCompute: info.stage = ShaderStage::Compute; break;
        case spv::ExecutionModelVertex: info.stage = ShaderStage::Vertex; break;
        case spv::ExecutionModelFragment: info.stage = ShaderStage::Fragment; break;
        case spv::ExecutionModelGeometry: info.stage = ShaderStage::Geometry; break;
        case spv::ExecutionModelTessellationControl: info.stage = ShaderStage::TessControl; break;
        case spv::ExecutionModelTessellationEvaluation: info.stage = ShaderStage::TessEvaluation; break;
        case spv::ExecutionModelMeshEXT:
        case spv::ExecutionModelMeshNV: info.stage = ShaderStage::Mesh; break;
        case spv::ExecutionModelTaskEXT:
        case spv::ExecutionModelTaskNV: info.stage = ShaderStage::Task; break;
        default: fail("unsupported execution model " + std::to_string(entryModel_), entryAt_);
    }

    resolveWorkgroupSize(info);
    collectBindings(info);
    for (uint32_t id = 1; id < ids_.size(); ++id) {
        if (ids_[id].specId != kNone) {
            info.specConstantIds.push_back(ids_[id].specId);
        }
    }
    std::sort(info.specConstantIds.begin(), info.specConstantIds.end());
    info.specConstantIds.erase(std::unique(info.specConstantIds.begin(), info.specConstantIds.end()),
                               info.specConstantIds.end());
    info.capabilities = capabilities_;
    info.uses64BitPointers =
        addressingModel_ == spv::AddressingModelPhysicalStorageBuffer64 ||
        std::find(capabilities_.begin(), capabilities_.end(), uint32_t(spv::CapabilityPhysicalStorageBufferAddresses)) !=
            capabilities_.end();
    return info;
}

}  // namespace

ShaderInfo reflectSpirv(std::span<const uint32_t> words) {
    return Module(words).reflect();
}

std::vector<DescriptorBinding> bindingsInSet(const ShaderInfo& info, uint32_t set) {
    std::vector<DescriptorBinding> out;
    for (const DescriptorBinding& b : info.bindings) {
        if (b.set == set) {
            out.push_back(b);
        }
    }
    return out;
}

std::string_view toString(DescriptorKind kind) noexcept {
    switch (kind) {
        case DescriptorKind::Sampler: return "sampler";
        case DescriptorKind::CombinedImageSampler: return "combined image sampler";
        case DescriptorKind::SampledImage: return "sampled image";
        case DescriptorKind::StorageImage: return "storage image";
        case DescriptorKind::UniformTexelBuffer: return "uniform texel buffer";
        case DescriptorKind::StorageTexelBuffer: return "storage texel buffer";
        case DescriptorKind::UniformBuffer: return "uniform buffer";
        case DescriptorKind::StorageBuffer: return "storage buffer";
        case DescriptorKind::InputAttachment: return "input attachment";
        case DescriptorKind::AccelerationStructure: return "acceleration structure";
    }
    return "unknown";
}

}  // namespace idk::shader
