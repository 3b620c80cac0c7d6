// reload_test.cpp: hot reload through glslang at run time: a good edit rebuilds the dependent pipeline in place
// (the new code runs), a broken edit returns the compiler's message naming the file and keeps the old pipeline.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "support/gpu_fixture.hpp"
#include "vk/bindless.hpp"
#include "vk/transfer.hpp"

namespace idk::test {
namespace {

class ReloadTest : public GpuTest {
protected:
    struct Push {
        uint32_t count, value, buffer;
    };
    std::string source() {
        std::ifstream f(std::string(shaders::kShaderSourceDir) + "/conformance/fill.comp.glsl");
        std::stringstream s;
        s << f.rdbuf();
        return s.str();
    }
    uint32_t runFill(const vk::Pipeline& pipeline) {
        vk::Buffer b = ctx().createBuffer({64 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUsage::GpuOnly, "f"});
        vk::StorageBufferIndex index = ctx().bindless().addBuffer(b.buffer);
        Push push{64, 5, index.value};
        ctx().runImmediate([&](VkCommandBuffer cmd) {
            vk::bindPipeline(cmd, pipeline);
            ctx().bindless().bind(cmd);
            vk::pushConstants(cmd, ctx(), push);
            vkCmdDispatch(cmd, 1, 1, 1);
        });
        uint32_t first = vk::downloadBuffer<uint32_t>(ctx(), b, 1)[0];
        ctx().bindless().release(index);
        ctx().destroyDeferred(b);
        return first;
    }
};

TEST_F(ReloadTest, GoodEditRebuildsAndBadEditKeepsTheOldPipeline) {
    vk::ShaderLibrary library(ctx());
    const vk::Pipeline& fill = library.compute({vk::ShaderId::conformance_fill_comp, {}, sizeof(Push), {{64, 1, 1}}});
    EXPECT_EQ(runFill(fill), 5u);

    std::string edited = source();
    size_t at = edited.find("= p.value;");
    ASSERT_NE(at, std::string::npos);
    edited.replace(at, 10, "= p.value * 3u;");
    vk::ReloadResult ok = library.reload(vk::ShaderId::conformance_fill_comp, edited);
    EXPECT_TRUE(ok.ok) << ok.message;
    EXPECT_EQ(ok.rebuiltPipelines, 1u);
    EXPECT_EQ(runFill(fill), 15u);  // same Pipeline object, new code

    std::string broken = edited + "\nthis is not glsl;\n";
    vk::ReloadResult bad = library.reload(vk::ShaderId::conformance_fill_comp, broken);
    EXPECT_FALSE(bad.ok);
    EXPECT_NE(bad.message.find("fill.comp.glsl"), std::string::npos) << bad.message;
    EXPECT_EQ(runFill(fill), 15u);  // the last good pipeline still runs
}

TEST_F(ReloadTest, EditThatBreaksThePushContractIsRefused) {
    vk::ShaderLibrary library(ctx());
    const vk::Pipeline& fill = library.compute({vk::ShaderId::conformance_fill_comp, {}, sizeof(Push), {{64, 1, 1}}});
    std::string edited = source();
    size_t at = edited.find("uint bufferIndex;");
    ASSERT_NE(at, std::string::npos);
    edited.insert(at, "uint extra; ");
    vk::ReloadResult r = library.reload(vk::ShaderId::conformance_fill_comp, edited);
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.message.find("push"), std::string::npos) << r.message;
    EXPECT_EQ(runFill(fill), 5u);
}

}  // namespace
}  // namespace idk::test
