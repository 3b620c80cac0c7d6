// viewer_options_test.cpp: idk-viewer's command line takes the scene options every program shares
// (app/scene_options.hpp): --allow-external-uris and --max-memory reach the loader's options; both off by default.
// The path-traced mode's options (--pathtrace, --denoise, --max-depth, --seed) default to `idk render --pathtrace`'s.
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

TEST(ViewerOptions, PathTracedModeOptions) {
    const ViewerOptions d = parseViewerOptions({});
    EXPECT_FALSE(d.pathTrace.enabled);
    EXPECT_FALSE(d.pathTrace.denoise);
    EXPECT_EQ(d.pathTrace.maxDepth, 8u);
    EXPECT_EQ(d.pathTrace.seed, 0u);
    const ViewerOptions o = parseViewerOptions({"--pathtrace", "--denoise", "--max-depth", "3", "--seed", "17"});
    EXPECT_TRUE(o.pathTrace.enabled);
    EXPECT_TRUE(o.pathTrace.denoise);
    EXPECT_EQ(o.pathTrace.maxDepth, 3u);
    EXPECT_EQ(o.pathTrace.seed, 17u);
    EXPECT_THROW(parseViewerOptions({"--max-depth", "0"}), core::CliError);
    EXPECT_THROW(parseViewerOptions({"--max-depth", "2.5"}), core::CliError);
    EXPECT_THROW(parseViewerOptions({"--seed", "-1"}), core::CliError);
}

}  // namespace
}  // namespace idk::viewer
