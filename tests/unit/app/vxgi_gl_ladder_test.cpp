// vxgi_gl_ladder_test.cpp: the "vxgi-gl-accumulate" ladder (engine/vk/features.cpp) without a device: the GL
// program of VXGI's gl-interop rung is the RGBA16F-image one (native) only where the probed GL context has
// GL_NV_shader_atomic_fp16_vector, else the float-buffer one (fallback, GL_NV_shader_atomic_float); a forced native
// rung without the extension is refused naming it; without a GL context both name the probe's reason.
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

DeviceCapabilities llvmpipeLike() {  // GL interop with GL_NV_shader_atomic_float only
    DeviceCapabilities c;
    c.glInterop = true;
    c.glAtomicFloat = true;
    c.glInteropNote = "OpenGL 4.5 (Core Profile) Mesa, llvmpipe; sync: cpu";
    return c;
}

TEST(VxgiGlLadder, Fp16VectorProgramOnlyWithTheExtension) {
    DeviceCapabilities c = llvmpipeLike();
    Ladder l = find(buildLadders(c), "vxgi-gl-accumulate");
    EXPECT_EQ(l.chosen, Rung::Fallback);
    EXPECT_EQ(l.reason, "the OpenGL context lacks GL_NV_shader_atomic_fp16_vector");
    EXPECT_TRUE(l.options.back().available);

    c.glAtomicFp16Vector = true;
    l = find(buildLadders(c), "vxgi-gl-accumulate");
    EXPECT_EQ(l.chosen, Rung::Native);
    EXPECT_NE(l.chosenMechanism.find("GL_NV_shader_atomic_fp16_vector"), std::string::npos);

    DeviceCapabilities none;  // no GL context: the probe's reason on both rungs
    none.glInteropNote = "IDK_GL_INTEROP=off";
    l = find(buildLadders(none), "vxgi-gl-accumulate");
    EXPECT_FALSE(l.options[0].available);
    EXPECT_EQ(l.options[0].note, "IDK_GL_INTEROP=off");
    EXPECT_FALSE(l.options[1].available);
}

TEST(VxgiGlLadder, ForcingTheFp16ProgramWithoutTheExtensionNamesIt) {
    std::string error;
    const std::vector<Ladder> l = buildLadders(
        llvmpipeLike(), LadderChoice{false, {parseRungForce("vxgi-gl-accumulate=native")}}, &error);
    EXPECT_EQ(error,
              "--rung vxgi-gl-accumulate=native: the OpenGL context lacks GL_NV_shader_atomic_fp16_vector (rungs "
              "this device can run: vxgi-gl-accumulate=fallback)");
    EXPECT_EQ(find(l, "vxgi-gl-accumulate").chosen, Rung::Fallback);
}

}  // namespace
}  // namespace idk::vk
