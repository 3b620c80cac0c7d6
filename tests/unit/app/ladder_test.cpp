// ladder_test.cpp: the capability-ladder table (engine/vk/features.hpp) without a device: the first available rung
// and the reason naming what the better rungs lack, the CPU-device preference for our BVH over a software ray query,
// --fallback, --rung forcing (taken when the device has the rung, refused with a reason when not), and the
// LADDER=RUNG parser's errors listing the valid names.
#include <gtest/gtest.h>

#include <stdexcept>

#include "vk/features.hpp"

namespace idk::vk {
namespace {

const Ladder& find(const std::vector<Ladder>& ladders, const std::string& id) {
    for (const Ladder& l : ladders)
        if (l.id == id) return l;
    throw std::logic_error("no ladder " + id);
}

DeviceCapabilities gpuWithRayQuery() {
    DeviceCapabilities c;
    c.rayQuery = true;
    c.meshShaderExt = true;
    c.geometryShader = true;
    c.shaderOutputLayer = true;
    return c;
}

TEST(Ladders, BestAvailableRungWithItsReason) {
    DeviceCapabilities c = gpuWithRayQuery();
    std::vector<Ladder> l = buildLadders(c, LadderChoice{}, nullptr);
    EXPECT_EQ(find(l, "ray-traversal").chosen, Rung::Native);
    EXPECT_EQ(find(l, "mesh-shading").chosen, Rung::Native);
    EXPECT_EQ(find(l, "vrs").chosen, Rung::Fallback);
    EXPECT_NE(find(l, "vrs").reason.find("VK_KHR_fragment_shading_rate"), std::string::npos) << find(l, "vrs").reason;
    for (const Ladder& ladder : l) EXPECT_FALSE(ladder.reason.empty()) << ladder.id;
}

TEST(Ladders, CpuDevicePrefersOurBvhAndSaysWhy) {
    DeviceCapabilities c = gpuWithRayQuery();
    c.cpuDevice = true;
    const Ladder rt = find(buildLadders(c, LadderChoice{}, nullptr), "ray-traversal");
    EXPECT_EQ(rt.chosen, Rung::Fallback);
    EXPECT_EQ(rt.chosenMechanism, "compute BVH traversal");
    EXPECT_NE(rt.reason.find("CPU device"), std::string::npos) << rt.reason;
    // The other ladders are not affected by the device type.
    EXPECT_EQ(find(buildLadders(c, LadderChoice{}, nullptr), "mesh-shading").chosen, Rung::Native);
}

TEST(Ladders, ForcedRungsWinWhenTheDeviceHasThem) {
    DeviceCapabilities c = gpuWithRayQuery();
    c.cpuDevice = true;
    std::string error;
    std::vector<Ladder> l = buildLadders(
        c, LadderChoice{true, {{"ray-traversal", Rung::Native}, {"mesh-shading", Rung::Fallback}}}, &error);
    EXPECT_TRUE(error.empty()) << error;
    EXPECT_EQ(find(l, "ray-traversal").chosen, Rung::Native);  // over both the CPU preference and --fallback
    EXPECT_NE(find(l, "ray-traversal").reason.find("--rung ray-traversal=native"), std::string::npos);
    EXPECT_EQ(find(l, "mesh-shading").chosen, Rung::Fallback);
    EXPECT_EQ(find(l, "point-shadow-faces").chosen, Rung::Fallback);  // --fallback for the rest
    EXPECT_NE(find(l, "point-shadow-faces").reason.find("--fallback"), std::string::npos);
}

TEST(Ladders, ARungTheDeviceLacksIsRefusedWithTheReason) {
    DeviceCapabilities c;  // no ray query
    std::string error;
    std::vector<Ladder> l = buildLadders(c, LadderChoice{false, {{"ray-traversal", Rung::Native}}}, &error);
    EXPECT_NE(error.find("--rung ray-traversal=native"), std::string::npos) << error;
    EXPECT_NE(error.find("VK_KHR_ray_query"), std::string::npos) << error;
    EXPECT_EQ(find(l, "ray-traversal").chosen, Rung::Fallback);
}

TEST(Ladders, RungSpecsAreParsedAgainstTheTable) {
    const RungForce f = parseRungForce("vxgi-atomics=gl-interop");
    EXPECT_EQ(f.ladder, "vxgi-atomics");
    EXPECT_EQ(f.rung, Rung::GlInterop);
    for (const char* bad : {"ray-traversal", "warp=native", "ray-traversal=gl-interop", "mesh-shading=fast", "=native"}) {
        try {
            parseRungForce(bad);
            ADD_FAILURE() << "accepted " << bad;
        } catch (const std::invalid_argument& e) {
            // The message lists every ladder and its rungs.
            EXPECT_NE(std::string(e.what()).find("ray-traversal: native|fallback"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("vxgi-atomics: native|gl-interop|fallback"), std::string::npos);
        }
    }
    EXPECT_EQ(ladderRungList().size(), buildLadders(DeviceCapabilities{}).size());
}

}  // namespace
}  // namespace idk::vk
