// viewer_options_test.cpp: idk-viewer's command line takes the scene options every program shares
// (app/scene_options.hpp): --allow-external-uris and --max-memory reach the loader's options; both off by default.
#include <gtest/gtest.h>

#include "core/cli.hpp"
#include "viewer/options.hpp"

namespace idk::viewer {
namespace {

TEST(ViewerOptions, SharesTheSceneLoadingOptions) {
    EXPECT_FALSE(parseViewerOptions({"scene.gltf"}).load.allowExternalUris);
    const ViewerOptions o = parseViewerOptions({"scene.gltf", "--allow-external-uris"});
    EXPECT_TRUE(o.load.allowExternalUris);
    ASSERT_TRUE(o.scene.has_value());
    EXPECT_EQ(*o.scene, "scene.gltf");
    EXPECT_EQ(o.load.maxMemoryBytes, 0u);
    EXPECT_EQ(parseViewerOptions({"--max-memory", "64M"}).load.maxMemoryBytes, uint64_t{64} << 20);
    EXPECT_EQ(parseViewerOptions({"--max-memory=2g"}).load.maxMemoryBytes, uint64_t{2} << 30);
    EXPECT_THROW(parseViewerOptions({"--max-memory", "lots"}), core::CliError);
    EXPECT_THROW(parseViewerOptions({"--max-memory", "0"}), core::CliError);
}

}  // namespace
}  // namespace idk::viewer
