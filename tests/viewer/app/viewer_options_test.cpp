// viewer_options_test.cpp: idk-viewer's command line takes the scene options every program shares
// (app/scene_options.hpp): --allow-external-uris reaches the loader's options, and is off by default.
#include <gtest/gtest.h>

#include "viewer/options.hpp"

namespace idk::viewer {
namespace {

TEST(ViewerOptions, SharesTheSceneLoadingOptions) {
    EXPECT_FALSE(parseViewerOptions({"scene.gltf"}).load.allowExternalUris);
    const ViewerOptions o = parseViewerOptions({"scene.gltf", "--allow-external-uris"});
    EXPECT_TRUE(o.load.allowExternalUris);
    ASSERT_TRUE(o.scene.has_value());
    EXPECT_EQ(*o.scene, "scene.gltf");
}

}  // namespace
}  // namespace idk::viewer
