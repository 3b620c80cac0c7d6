// render_graph_compile_test.cpp: compile() without a GPU: ordering (stable, after() edges, WAR), culling
// (transitive, side effects, imported/persistent outputs, marked outputs), planned barriers per pass,
// resolved descriptions, clear errors for malformed graphs, and the text/Graphviz dumps.
#include "fake_backend.hpp"

#include <gtest/gtest.h>

namespace idk::graph {
namespace {

using testing::absoluteDesc;
using testing::colorDesc;
using testing::FakeBackend;

constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags2 kFragment = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;

class GraphCompile : public ::testing::Test {
protected:
    FakeBackend backend;
    ResourcePool pool{backend};
    RenderGraph graph{pool, VkExtent2D{64, 32}};

    // Expects compile() to throw a GraphError whose message contains every fragment.
    void expectError(std::initializer_list<std::string_view> fragments) {
        try {
            graph.compile();
            ADD_FAILURE() << "compile() did not throw";
        } catch (const GraphError& e) {
            const std::string message = e.what();
            for (std::string_view f : fragments) EXPECT_NE(message.find(f), std::string::npos) << "missing '" << f << "' in: " << message;
        }
    }
};

// ---- Ordering ----

TEST_F(GraphCompile, LinearChainInDeclarationOrder) {
    TextureHandle a, b;
    graph.addPass("first", [&](PassBuilder& p) { a = p.write(p.create("a", colorDesc()), Access::ColorWrite); }, {});
    graph.addPass("second", [&](PassBuilder& p) {
        p.read(a, Access::SampledRead, kCompute);
        b = p.write(p.create("b", colorDesc()), Access::StorageWrite, kCompute);
    }, {});
    graph.addPass("third", [&](PassBuilder& p) {
        p.read(b, Access::SampledRead, kFragment);
        p.sideEffect();
    }, {});
    graph.compile();
    EXPECT_EQ(graph.executionOrder(), (std::vector<std::string>{"first", "second", "third"}));
}

TEST_F(GraphCompile, IndependentPassesKeepDeclarationOrder) {
    for (const char* name : {"c", "a", "b"}) graph.addPass(name, [](PassBuilder& p) { p.sideEffect(); }, {});
    graph.compile();
    EXPECT_EQ(graph.executionOrder(), (std::vector<std::string>{"c", "a", "b"}));
}

TEST_F(GraphCompile, AfterMovesAPassBehindALaterOne) {
    graph.addPass("late", [](PassBuilder& p) { p.sideEffect(); p.after("early"); }, {});
    graph.addPass("other", [](PassBuilder& p) { p.sideEffect(); }, {});
    graph.addPass("early", [](PassBuilder& p) { p.sideEffect(); }, {});
    graph.compile();
    // "other" is free first (declaration index 1 < 2), then "early", then "late" once it is ready.
    EXPECT_EQ(graph.executionOrder(), (std::vector<std::string>{"other", "early", "late"}));
}

TEST_F(GraphCompile, WriteAfterReadOrdersReadersBeforeTheNextWriter) {
    BufferHandle v1, v2;
    graph.addPass("produce", [&](PassBuilder& p) { v1 = p.write(p.create("buf", BufferDesc{256}), Access::StorageWrite, kCompute); }, {});
    graph.addPass("read", [&](PassBuilder& p) { p.read(v1, Access::StorageRead, kCompute); p.sideEffect(); }, {});
    graph.addPass("overwrite", [&](PassBuilder& p) {
        v2 = p.write(v1, Access::StorageWrite, kCompute);
        p.after("consume");   // pulls the overwrite after a later pass; the reader must still come first
    }, {});
    graph.addPass("consume", [&](PassBuilder& p) { p.sideEffect(); }, {});
    graph.markOutput(v2);
    graph.compile();
    EXPECT_EQ(graph.executionOrder(), (std::vector<std::string>{"produce", "read", "consume", "overwrite"}));
    // The overwrite waits on the reader (WAR) and on the first write (WAW).
    const auto barriers = graph.barriersBefore("overwrite");
    ASSERT_EQ(barriers.size(), 1u);
    EXPECT_EQ(barriers[0].kind, ResourceKind::Buffer);
    EXPECT_EQ(barriers[0].srcStages, kCompute);
    EXPECT_EQ(barriers[0].srcAccess, VK_ACCESS_2_NONE);   // already flushed for the reader
    EXPECT_EQ(barriers[0].dstAccess, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

// ---- Culling ----

TEST_F(GraphCompile, PassWhoseOutputNobodyReadsIsCulled) {
    graph.addPass("unused", [&](PassBuilder& p) { p.write(p.create("x", colorDesc()), Access::ColorWrite); }, {});
    graph.addPass("kept", [](PassBuilder& p) { p.sideEffect(); }, {});
    graph.compile();
    EXPECT_TRUE(graph.isCulled("unused"));
    EXPECT_FALSE(graph.isCulled("kept"));
    EXPECT_TRUE(graph.barriersBefore("unused").empty());
    EXPECT_EQ(graph.executionOrder(), (std::vector<std::string>{"kept"}));
    EXPECT_TRUE(graph.aliasingPlan().slots.empty()) << "resources of culled passes get no memory";
}

TEST_F(GraphCompile, CullingIsTransitive) {
    TextureHandle a, b;
    graph.addPass("a", [&](PassBuilder& p) { a = p.write(p.create("ta", colorDesc()), Access::ColorWrite); }, {});
    graph.addPass("b", [&](PassBuilder& p) {
        p.read(a, Access::SampledRead);
        b = p.write(p.create("tb", colorDesc()), Access::ColorWrite);
    }, {});
    graph.addPass("c", [&](PassBuilder& p) { p.read(b, Access::SampledRead); }, {});
    graph.compile();
    EXPECT_TRUE(graph.isCulled("a"));
    EXPECT_TRUE(graph.isCulled("b"));
    EXPECT_TRUE(graph.isCulled("c"));
    EXPECT_TRUE(graph.executionOrder().empty());
}

TEST_F(GraphCompile, SideEffectKeepsThePassAndEverythingItNeeds) {
    TextureHandle a, b;
    graph.addPass("a", [&](PassBuilder& p) { a = p.write(p.create("ta", colorDesc()), Access::ColorWrite); }, {});
    graph.addPass("b", [&](PassBuilder& p) {
        p.read(a, Access::SampledRead);
        b = p.write(p.create("tb", colorDesc()), Access::ColorWrite);
    }, {});
    graph.addPass("readback", [&](PassBuilder& p) { p.read(b, Access::TransferSrc); p.sideEffect(); }, {});
    graph.addPass("dead", [&](PassBuilder& p) { p.read(a, Access::SampledRead); }, {});
    graph.compile();
    EXPECT_EQ(graph.executionOrder(), (std::vector<std::string>{"a", "b", "readback"}));
    EXPECT_TRUE(graph.isCulled("dead"));
}

TEST_F(GraphCompile, WritingAnImportedResourceKeepsThePass) {
    const TextureHandle swapchain = graph.importTexture("swapchain", PhysicalTexture{.format = VK_FORMAT_B8G8R8A8_UNORM}, {});
    graph.addPass("ui", [&](PassBuilder& p) { p.write(swapchain, Access::ColorWrite); }, {});
    graph.compile();
    EXPECT_FALSE(graph.isCulled("ui"));
}

TEST_F(GraphCompile, MarkedOutputKeepsItsProducer) {
    TextureHandle out;
    graph.addPass("producer", [&](PassBuilder& p) { out = p.write(p.create("t", colorDesc()), Access::ColorWrite); }, {});
    graph.markOutput(out);
    graph.compile();
    EXPECT_FALSE(graph.isCulled("producer"));
}

TEST_F(GraphCompile, WriteKeepsThePreviousVersionsProducerAlive) {
    // A partial write (storage image) builds on the earlier contents: the earlier writer stays.
    TextureHandle v1, v2;
    graph.addPass("clear", [&](PassBuilder& p) { v1 = p.write(p.create("t", colorDesc()), Access::TransferDst); }, {});
    graph.addPass("splat", [&](PassBuilder& p) { v2 = p.write(v1, Access::StorageWrite, kCompute); }, {});
    graph.markOutput(v2);
    graph.compile();
    EXPECT_EQ(graph.executionOrder(), (std::vector<std::string>{"clear", "splat"}));
}

// ---- Barriers and descriptions ----

TEST_F(GraphCompile, PlansEveryBarrierBeforeEachPass) {
    TextureHandle depth, color;
    graph.addPass("prepass", [&](PassBuilder& p) { depth = p.write(p.create("depth", colorDesc(VK_FORMAT_D32_SFLOAT)), Access::DepthWrite); }, {});
    graph.addPass("shade", [&](PassBuilder& p) {
        p.read(depth, Access::DepthRead);
        color = p.write(p.create("color", colorDesc()), Access::ColorWrite);
    }, {});
    graph.addPass("post", [&](PassBuilder& p) {
        p.read(color, Access::SampledRead, kCompute);
        p.read(depth, Access::SampledRead, kCompute);
        p.sideEffect();
    }, {});
    graph.compile();
    const auto pre = graph.barriersBefore("prepass");
    ASSERT_EQ(pre.size(), 1u);
    EXPECT_EQ(pre[0].oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(pre[0].newLayout, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(graph.resourceName(pre[0].resource), "depth");

    const auto shade = graph.barriersBefore("shade");
    ASSERT_EQ(shade.size(), 2u);
    EXPECT_EQ(shade[0].oldLayout, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(shade[0].newLayout, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
    // Every layout transition also waits on the shaders that ran before, with their storage writes (the prepass
    // is a draw: its vertex and fragment shaders): graph_plan.cpp, for the synchronization validation layer.
    constexpr VkPipelineStageFlags2 kDrawShaders = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | kFragment;
    EXPECT_EQ(shade[0].srcAccess, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(shade[1].newLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);

    const auto post = graph.barriersBefore("post");
    ASSERT_EQ(post.size(), 2u);
    EXPECT_EQ(post[0].srcStages, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | kDrawShaders);
    EXPECT_EQ(post[0].srcAccess, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(post[0].dstStages, kCompute);
    EXPECT_EQ(post[0].dstAccess, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    EXPECT_EQ(post[1].oldLayout, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
    EXPECT_EQ(post[1].newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(post[1].srcAccess, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

TEST_F(GraphCompile, ResolvesRelativeExtentsMipsAndDerivedUsage) {
    TextureHandle half, hiz;
    TextureDesc halfDesc = colorDesc(VK_FORMAT_R16G16B16A16_SFLOAT);
    halfDesc.scaleX = halfDesc.scaleY = 0.5f;
    TextureDesc hizDesc = absoluteDesc(100, 40, VK_FORMAT_R32_SFLOAT);
    hizDesc.mips = 0;
    graph.addPass("a", [&](PassBuilder& p) {
        half = p.write(p.create("half", halfDesc), Access::ColorWrite);
        hiz = p.write(p.create("hiz", hizDesc), Access::StorageWrite, kCompute);
    }, {});
    graph.addPass("b", [&](PassBuilder& p) {
        p.read(half, Access::SampledRead);
        p.read(hiz, Access::SampledRead);
        p.sideEffect();
    }, {});
    graph.compile();
    const TextureInfo& h = graph.textureInfo(half);
    EXPECT_EQ(h.extent.width, 32u);
    EXPECT_EQ(h.extent.height, 16u);
    EXPECT_EQ(h.usage, VkImageUsageFlags{VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
    const TextureInfo& z = graph.textureInfo(hiz);
    EXPECT_EQ(z.mips, 7u);   // 100 -> 50 -> 25 -> 12 -> 6 -> 3 -> 1
    EXPECT_EQ(z.usage, VkImageUsageFlags{VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT});
}

TEST_F(GraphCompile, HostReadBufferIsHostVisible) {
    BufferHandle counts;
    graph.addPass("count", [&](PassBuilder& p) { counts = p.write(p.create("counts", BufferDesc{64}), Access::StorageWrite, kCompute); }, {});
    graph.addPass("readback", [&](PassBuilder& p) { p.read(counts, Access::HostRead); p.sideEffect(); }, {});
    graph.compile();
    EXPECT_TRUE(graph.bufferInfo(counts).hostVisible);
    EXPECT_EQ(graph.bufferInfo(counts).usage, VkBufferUsageFlags{VK_BUFFER_USAGE_STORAGE_BUFFER_BIT});
    const auto b = graph.barriersBefore("readback");
    ASSERT_EQ(b.size(), 1u);
    EXPECT_EQ(b[0].dstStages, VK_PIPELINE_STAGE_2_HOST_BIT);
}

// ---- Errors ----

TEST_F(GraphCompile, ErrorReadOfNeverWrittenResource) {
    graph.addPass("reader", [&](PassBuilder& p) { p.read(p.create("ghost", colorDesc()), Access::SampledRead); p.sideEffect(); }, {});
    expectError({"pass 'reader'", "'ghost'", "never-written"});
}

TEST_F(GraphCompile, ErrorCycle) {
    TextureHandle t;
    graph.addPass("a", [&](PassBuilder& p) { t = p.write(p.create("t", colorDesc()), Access::ColorWrite); p.after("b"); }, {});
    graph.addPass("b", [&](PassBuilder& p) { p.read(t, Access::SampledRead); p.sideEffect(); }, {});
    expectError({"cycle", "'a'", "'b'", "after()", "'t' v1"});
}

TEST_F(GraphCompile, ErrorTwoPassesWritingTheSameVersion) {
    TextureHandle v0;
    graph.addPass("a", [&](PassBuilder& p) { v0 = p.create("t", colorDesc()); p.write(v0, Access::ColorWrite); p.sideEffect(); }, {});
    graph.addPass("b", [&](PassBuilder& p) { p.write(v0, Access::ColorWrite); p.sideEffect(); }, {});
    expectError({"pass 'b'", "'t'", "pass 'a' already wrote", "write conflict"});
}

TEST_F(GraphCompile, ErrorReadOfOverwrittenVersion) {
    TextureHandle v1;
    graph.addPass("a", [&](PassBuilder& p) { v1 = p.write(p.create("t", colorDesc()), Access::StorageWrite); p.sideEffect(); }, {});
    graph.addPass("b", [&](PassBuilder& p) { p.write(v1, Access::StorageWrite); p.sideEffect(); }, {});
    graph.addPass("c", [&](PassBuilder& p) { p.read(v1, Access::StorageRead); p.sideEffect(); }, {});
    expectError({"pass 'c'", "'t' version 1", "pass 'b' already overwrote"});
}

TEST_F(GraphCompile, ErrorUnknownHandle) {
    graph.addPass("a", [&](PassBuilder& p) { p.read(TextureHandle{}, Access::SampledRead); p.sideEffect(); }, {});
    graph.addPass("b", [&](PassBuilder& p) { p.read(BufferHandle{42, 0}, Access::StorageRead); p.sideEffect(); }, {});
    expectError({"pass 'a' uses an unknown texture handle", "pass 'b' uses an unknown buffer handle (resource #42"});
}

TEST_F(GraphCompile, ErrorHandleOfTheWrongKind) {
    const BufferHandle buffer = graph.createBuffer("buf", BufferDesc{16});
    graph.addPass("a", [&](PassBuilder& p) { p.read(TextureHandle{buffer.resource, 0}, Access::SampledRead); }, {});
    expectError({"pass 'a' uses an unknown texture handle"});
}

TEST_F(GraphCompile, ErrorDuplicatePassNames) {
    graph.addPass("same", [](PassBuilder& p) { p.sideEffect(); }, {});
    graph.addPass("same", [](PassBuilder& p) { p.sideEffect(); }, {});
    expectError({"duplicate pass name 'same'", "#0", "#1"});
}

TEST_F(GraphCompile, ErrorDuplicateResourceNames) {
    graph.createTexture("t", colorDesc());
    graph.addPass("a", [](PassBuilder& p) { p.create("t", colorDesc()); }, {});
    expectError({"pass 'a'", "'t'", "already exists"});
}

TEST_F(GraphCompile, ErrorAccessNotValidForKindOrDirection) {
    graph.addPass("a", [&](PassBuilder& p) { p.write(p.create("b", BufferDesc{16}), Access::ColorWrite); }, {});
    graph.addPass("b", [&](PassBuilder& p) { p.read(p.create("t", colorDesc()), Access::StorageWrite); }, {});
    graph.addPass("c", [&](PassBuilder& p) { p.write(p.create("u", colorDesc()), Access::ColorWrite, kCompute); }, {});
    expectError({"pass 'a' writes buffer 'b' as ColorWrite, which is not valid for a buffer",
                 "pass 'b' declares StorageWrite on 't' with read(); use write()",
                 "pass 'c' names pipeline stages COMPUTE that ColorWrite cannot happen in"});
}

TEST_F(GraphCompile, ErrorSameResourceTwiceInOnePass) {
    graph.addPass("a", [&](PassBuilder& p) {
        const TextureHandle t = p.write(p.create("t", colorDesc()), Access::StorageWrite);
        p.read(t, Access::SampledRead);
    }, {});
    expectError({"pass 'a' declares 't' twice"});
}

TEST_F(GraphCompile, ErrorUnknownAfterTargetAndHistory) {
    graph.addPass("a", [&](PassBuilder& p) {
        p.after("nobody");
        p.read(p.history("never_persistent"), Access::SampledRead);
        p.sideEffect();
    }, {});
    expectError({"pass 'a' must run after 'nobody'", "history('never_persistent')"});
}

TEST_F(GraphCompile, ErrorMissingFormatAndZeroSize) {
    graph.addPass("a", [&](PassBuilder& p) {
        p.write(p.create("t", TextureDesc{}), Access::StorageWrite);
        p.write(p.create("b", BufferDesc{}), Access::StorageWrite);
        p.sideEffect();
    }, {});
    expectError({"texture 't' has no format", "buffer 'b' has size 0"});
}

TEST_F(GraphCompile, ErrorPresentInsideAPass) {
    const TextureHandle swapchain = graph.importTexture("swapchain", PhysicalTexture{.format = VK_FORMAT_B8G8R8A8_UNORM}, {});
    graph.addPass("a", [&](PassBuilder& p) { p.read(swapchain, Access::Present); p.sideEffect(); }, {});
    expectError({"Present is only valid as the FinalUse"});
}

TEST_F(GraphCompile, ExecuteAlsoReportsCompileErrors) {
    graph.addPass("reader", [&](PassBuilder& p) { p.read(p.create("ghost", colorDesc()), Access::SampledRead); p.sideEffect(); }, {});
    EXPECT_THROW(graph.execute(testing::fakeCmd()), GraphError);
}

TEST_F(GraphCompile, InspectionBeforeCompileThrows) {
    EXPECT_THROW(graph.executionOrder(), GraphError);
}

// ---- Dumps ----

TEST_F(GraphCompile, TextAndGraphvizDumps) {
    TextureHandle color;
    graph.addPass("draw", [&](PassBuilder& p) { color = p.write(p.create("color", colorDesc()), Access::ColorWrite); }, {});
    graph.addPass("blit", [&](PassBuilder& p) { p.read(color, Access::TransferSrc); p.sideEffect(); }, {});
    graph.addPass("debug_view", [&](PassBuilder& p) { p.read(color, Access::SampledRead); }, {});
    graph.compile();
    const std::string text = graph.toText();
    EXPECT_NE(text.find("[0] draw"), std::string::npos) << text;
    EXPECT_NE(text.find("[1] blit"), std::string::npos) << text;
    EXPECT_NE(text.find("culled: debug_view"), std::string::npos) << text;
    EXPECT_NE(text.find("barrier image 'color' UNDEFINED->COLOR_ATTACHMENT [ALL_COMMANDS:MEMORY_WRITE -> "
                        "COLOR_ATTACHMENT_OUTPUT:COLOR_ATTACHMENT_WRITE]"), std::string::npos) << text;
    EXPECT_NE(text.find("COLOR_ATTACHMENT->TRANSFER_SRC"), std::string::npos) << text;
    const std::string dot = graph.toGraphviz();
    EXPECT_EQ(dot.rfind("digraph render_graph {", 0), 0u);
    EXPECT_NE(dot.find("debug_view\\n(culled)"), std::string::npos) << dot;
    EXPECT_NE(dot.find("lightgrey"), std::string::npos);
    EXPECT_NE(dot.find("color v1"), std::string::npos);
    EXPECT_EQ(dot.back(), '\n');
}

}  // namespace
}  // namespace idk::graph
