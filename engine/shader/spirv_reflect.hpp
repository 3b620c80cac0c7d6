// spirv_reflect.hpp: what a pipeline needs to know about one SPIR-V module, read straight from its words:
// entry point and stage, workgroup size (LocalSize, LocalSizeId and the WorkgroupSize built-in, with the
// specialization constants behind them), push-constant bytes, descriptor sets and bindings, spec-constant ids.
#pragma once

#include "shader/shader_stage.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace idk::shader {

// Malformed or unsupported SPIR-V. what() names the problem and the word index; word() returns that index.
class ReflectError : public std::runtime_error {
public:
    ReflectError(const std::string& what, size_t word);
    size_t word() const noexcept { return word_; }

private:
    size_t word_;
};

enum class DescriptorKind : uint8_t {
    Sampler,
    CombinedImageSampler,
    SampledImage,
    StorageImage,
    UniformTexelBuffer,
    StorageTexelBuffer,
    UniformBuffer,
    StorageBuffer,
    InputAttachment,
    AccelerationStructure,
};

struct DescriptorBinding {
    uint32_t set = 0;
    uint32_t binding = 0;
    DescriptorKind kind = DescriptorKind::StorageBuffer;
    uint32_t count = 1;  // array length; 0 for a runtime-sized (bindless) array
};

struct ShaderInfo {
    std::string entryPoint;                 // the first OpEntryPoint of the module
    ShaderStage stage = ShaderStage::Compute;
    uint32_t spirvVersion = 0;              // header word 1, e.g. 0x00010600 for SPIR-V 1.6
    // Workgroup size with specialization-constant defaults applied; {0,0,0} when the module declares none
    // (every non-compute-like stage). localSizeSpecIds[i] is the SpecId that overrides dimension i, if any.
    std::array<uint32_t, 3> localSize{};
    std::array<std::optional<uint32_t>, 3> localSizeSpecIds{};
    uint32_t pushConstantBytes = 0;         // max over members of Offset + size; 0 without a push block
    uint32_t descriptorSetMask = 0;         // bit s set when set s (s < 32) has a binding
    std::vector<DescriptorBinding> bindings;  // one per (set, binding), sorted; aliases are merged
    std::vector<uint32_t> specConstantIds;    // sorted, unique
    std::vector<uint32_t> capabilities;       // raw spv::Capability values, in module order
    bool uses64BitPointers = false;           // PhysicalStorageBuffer64 addressing (buffer_reference)
};

// Parses a whole module. Throws ReflectError on a bad magic number, a truncated header or instruction, an id
// out of bounds, a module without an entry point, or a push-constant/array size that depends on something
// other than a constant or a specialization-constant default.
ShaderInfo reflectSpirv(std::span<const uint32_t> words);

// The bindings of one descriptor set, sorted by binding number.
std::vector<DescriptorBinding> bindingsInSet(const ShaderInfo& info, uint32_t set);

std::string_view toString(DescriptorKind kind) noexcept;

}  // namespace idk::shader
