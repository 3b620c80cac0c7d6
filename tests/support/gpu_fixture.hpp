// gpu_fixture.hpp: the Vulkan device shared by the GPU tests of one process (validation always on), and a
// GoogleTest fixture that fails a test when the validation layer reported an error during it.
#pragma once
#include <gtest/gtest.h>

#include "vk/context.hpp"
#include "vk/shader_library.hpp"

namespace idk::test {

vk::Context& sharedContext();        // created on first use; validation on; staging forced if IDK_FORCE_STAGING=1
vk::ShaderLibrary& sharedShaders();  // over the build's SPIR-V

class GpuTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;  // EXPECTs no new validation errors, and prints them if any
    vk::Context& ctx() { return sharedContext(); }
    vk::ShaderLibrary& shaders() { return sharedShaders(); }

private:
    uint32_t errorsBefore_ = 0;
};

}  // namespace idk::test
