// registered_checks_test.cpp: every conformance check of engine/conformance (the registry `idk conformance`
// runs) as one ctest case per check and rung, on a context that probed the GL-interop rung, validation on. A
// rung the device lacks is skipped with the ladder's reason; a failure prints the check's messages.
#include <gtest/gtest.h>

#include <cctype>
#include <memory>
#include <ostream>

#include "conformance/conformance.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"

namespace idk::conformance {
void PrintTo(const PlannedRun& run, std::ostream* os) { *os << run.name(); }  // gtest's parameter text
}  // namespace idk::conformance

namespace idk::test {
namespace {

struct Device {
    std::unique_ptr<vk::Context> ctx;
    std::unique_ptr<vk::ShaderLibrary> shaders;
};

Device& device() {
    static Device d = [] {
        vk::ContextDesc desc;
        desc.validation = true;
        desc.probeGlInterop = true;
        Device made;
        made.ctx = std::make_unique<vk::Context>(desc);
        made.shaders = std::make_unique<vk::ShaderLibrary>(*made.ctx);
        return made;
    }();
    return d;
}

class RegisteredCheck : public ::testing::TestWithParam<conformance::PlannedRun> {};

TEST_P(RegisteredCheck, MatchesItsOracle) {
    Device& d = device();
    const conformance::Outcome o = conformance::run(GetParam(), *d.ctx, *d.shaders);
    if (o.status == conformance::Status::Skip) GTEST_SKIP() << o.message;
    EXPECT_EQ(o.status, conformance::Status::Pass) << GetParam().name() << " (" << o.tolerance << "): " << o.message;
    std::cout << "[ check ] " << GetParam().name() << ": max error " << o.maxError << ", " << o.seconds << " s\n";
}

// gtest names: letters, digits and underscores ("float_atomics_splat_gl_interop").
std::string testName(const ::testing::TestParamInfo<conformance::PlannedRun>& info) {
    std::string text = info.param.check->kernel;
    if (info.param.rung) text += std::string("_") + vk::rungName(*info.param.rung);
    std::string name;
    for (char c : text) {
        const bool keep = std::isalnum(static_cast<unsigned char>(c));
        if (keep || (!name.empty() && name.back() != '_')) name += keep ? c : '_';
    }
    return name;
}

INSTANTIATE_TEST_SUITE_P(Registry, RegisteredCheck, ::testing::ValuesIn(conformance::allRuns()), testName);

}  // namespace
}  // namespace idk::test
