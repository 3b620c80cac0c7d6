// vrs_ladder_test.cpp: the "vrs" capability ladder (engine/vk/features.cpp) with fake device capabilities: the KHR
// attachment rung where the device has attachment rates and a texel size the classifier can tile by, else the NV
// shading-rate image, else the software rung with a reason naming what is missing (lavapipe's case); forcing a
// hardware rung the device lacks is refused with that reason (the CLI then exits 2: tests/cli, case vrs).
#include <gtest/gtest.h>

#include <stdexcept>

#include "vk/features.hpp"

namespace idk::vk {
namespace {

Ladder vrsLadder(const DeviceCapabilities& c, const LadderChoice& choice = {}, std::string* error = nullptr) {
    for (const Ladder& l : buildLadders(c, choice, error))
        if (l.id == "vrs") return l;
    throw std::logic_error("no vrs ladder");
}

DeviceCapabilities withKhr(VkExtent2D min, VkExtent2D max) {
    DeviceCapabilities c;
    c.fragmentShadingRate = true;
    c.shadingRateAttachmentTexel = {min, max, 2};
    return c;
}

DeviceCapabilities withNv(VkExtent2D texel) {
    DeviceCapabilities c;
    c.shadingRateImageNv = true;
    c.shadingRateTexelNv = texel;
    return c;
}

TEST(VrsLadder, LavapipeLikeDeviceTakesTheSoftwareRungAndSaysWhy) {
    DeviceCapabilities c;  // neither extension (lavapipe)
    c.cpuDevice = true;
    const Ladder l = vrsLadder(c);
    EXPECT_EQ(l.chosen, Rung::Fallback);
    EXPECT_EQ(l.chosenMechanism, "compute-side coarse shading");
    EXPECT_NE(l.reason.find("device lacks VK_KHR_fragment_shading_rate"), std::string::npos) << l.reason;
    EXPECT_NE(l.reason.find("device lacks VK_NV_shading_rate_image"), std::string::npos) << l.reason;
}

TEST(VrsLadder, KhrAttachmentRungWhereTheDeviceHasIt) {
    const Ladder l = vrsLadder(withKhr({8, 8}, {32, 32}));
    EXPECT_EQ(l.chosen, Rung::Native);
    EXPECT_EQ(l.chosenMechanism, "VK_KHR_fragment_shading_rate");
    EXPECT_NE(l.options[0].note.find("16x16"), std::string::npos) << l.options[0].note;  // the tile it will use
}

TEST(VrsLadder, KhrIsPreferredOverNvAndNvServesWhenKhrCannot) {
    DeviceCapabilities both = withKhr({16, 16}, {16, 16});
    both.shadingRateImageNv = true;
    both.shadingRateTexelNv = {16, 16};
    EXPECT_EQ(vrsLadder(both).chosenMechanism, "VK_KHR_fragment_shading_rate");
    EXPECT_EQ(vrsLadder(withNv({16, 16})).chosenMechanism, "VK_NV_shading_rate_image");
    // A KHR device whose texels allow no classifier tile falls to NV, and the reason says why KHR was passed over.
    DeviceCapabilities badKhr = withKhr({64, 64}, {64, 64});
    badKhr.shadingRateImageNv = true;
    badKhr.shadingRateTexelNv = {16, 16};
    const Ladder l = vrsLadder(badKhr);
    EXPECT_EQ(l.chosenMechanism, "VK_NV_shading_rate_image");
    EXPECT_NE(l.reason.find("64x64..64x64"), std::string::npos) << l.reason;
}

TEST(VrsLadder, UnusableTexelsFallBackToSoftware) {
    const Ladder l = vrsLadder(withNv({16, 8}));
    EXPECT_EQ(l.chosen, Rung::Fallback);
    EXPECT_NE(l.reason.find("16x8"), std::string::npos) << l.reason;
}

TEST(VrsLadder, ForcingAHardwareRungTheDeviceLacksIsRefused) {
    std::string error;
    const Ladder l = vrsLadder(DeviceCapabilities{}, LadderChoice{false, {{"vrs", Rung::Native}}}, &error);
    EXPECT_EQ(l.chosen, Rung::Fallback);
    EXPECT_NE(error.find("--rung vrs=native"), std::string::npos) << error;
    EXPECT_NE(error.find("VK_KHR_fragment_shading_rate"), std::string::npos) << error;
    EXPECT_NE(error.find("vrs=fallback"), std::string::npos) << error;  // what this device can run
}

TEST(VrsLadder, ForcingNativeTakesWhicheverHardwareMechanismExists) {
    std::string error;
    const Ladder l = vrsLadder(withNv({16, 16}), LadderChoice{true, {{"vrs", Rung::Native}}}, &error);
    EXPECT_TRUE(error.empty()) << error;
    EXPECT_EQ(l.chosenMechanism, "VK_NV_shading_rate_image");  // over --fallback
    EXPECT_EQ(vrsLadder(withKhr({8, 8}, {32, 32}), LadderChoice{true, {}}).chosen, Rung::Fallback);  // --fallback
}

}  // namespace
}  // namespace idk::vk
