// gpu_fixture.cpp: one context per test process; validation errors are counted per test.
#include "support/gpu_fixture.hpp"

#include <cstdlib>
#include <memory>
#include <string>

namespace idk::test {
namespace {
std::unique_ptr<vk::Context> gContext;
std::unique_ptr<vk::ShaderLibrary> gShaders;

// Destroy the library before the context while the process is still whole: static destructors run after
// Mesa's own exit handlers have torn lavapipe down, so the release happens in GoogleTest's environment teardown.
class ReleaseBeforeExit : public ::testing::Environment {
public:
    void TearDown() override {
        gShaders.reset();
        gContext.reset();
    }
};
}  // namespace

vk::Context& sharedContext() {
    if (!gContext) {
        vk::ContextDesc desc;
        desc.validation = true;
        const char* staging = std::getenv("IDK_FORCE_STAGING");
        if (staging) desc.forceStaging = std::string(staging) == "1";
        const char* sync = std::getenv("IDK_SYNC_VALIDATION");
        if (sync) desc.syncValidation = std::string(sync) == "1";
        gContext = std::make_unique<vk::Context>(desc);
        ::testing::AddGlobalTestEnvironment(new ReleaseBeforeExit);  // GoogleTest owns and deletes it
    }
    return *gContext;
}

vk::ShaderLibrary& sharedShaders() {
    if (!gShaders) gShaders = std::make_unique<vk::ShaderLibrary>(sharedContext());
    return *gShaders;
}

void GpuTest::SetUp() { errorsBefore_ = sharedContext().validationErrors(); }

void GpuTest::TearDown() {
    vk::Context& c = sharedContext();
    c.waitIdle();
    uint32_t errors = c.validationErrors() - errorsBefore_;
    if (errors != 0) {
        std::string all;
        for (const std::string& m : c.validationMessages()) all += "\n  " + m;
        ADD_FAILURE() << errors << " Vulkan validation error(s) during this test:" << all;
    }
}

}  // namespace idk::test
