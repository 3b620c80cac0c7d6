// interop.h: lets one header define a GPU struct for both C++ and GLSL.
// C++ sees glm types in namespace idk::gpu; GLSL sees its built-in types. Storage buffers and push constants
// use scalar block layout on both sides (vec3 = 12 bytes, no padding to 16), and every struct gets a C++
// size assertion so a layout drift fails the build instead of corrupting data on the GPU.
#ifndef IDK_INTEROP_H
#define IDK_INTEROP_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace idk::gpu {
using uint = uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec2 = glm::uvec2;
using uvec3 = glm::uvec3;
using uvec4 = glm::uvec4;
using ivec2 = glm::ivec2;
using ivec4 = glm::ivec4;
using mat3 = glm::mat3;
using mat4 = glm::mat4;
using DeviceAddress = uint64_t;  // GLSL: a buffer_reference or uint64_t
}  // namespace idk::gpu
#define IDK_GPU_BEGIN namespace idk::gpu {
#define IDK_GPU_END }
#define IDK_GPU_SIZE(Type, bytes) static_assert(sizeof(Type) == (bytes), #Type " size differs from its GLSL scalar layout")
#define IDK_CONST(type, name, value) inline constexpr type name = value
#else
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#define DeviceAddress uint64_t
#define IDK_GPU_BEGIN
#define IDK_GPU_END
#define IDK_GPU_SIZE(Type, bytes)
#define IDK_CONST(type, name, value) const type name = value
#endif

// Functions shared by C++ and GLSL (one source, e.g. pt_sampling.h, agx.h): IDK_OUT / IDK_INOUT declare out
// parameters (C++ references, GLSL out/inout qualifiers); IDK_INLINE is C++'s inline for header functions (GLSL
// has no such keyword).
#ifdef __cplusplus
#define IDK_OUT(T) T&
#define IDK_INOUT(T) T&
#define IDK_INLINE inline
#else
#define IDK_OUT(T) out T
#define IDK_INOUT(T) inout T
#define IDK_INLINE
#endif

#endif
