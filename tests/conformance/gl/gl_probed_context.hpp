// gl_probed_context.hpp: the Vulkan context of the GL-interop tests (gl_interop_test.cpp, gl_sync_test.cpp,
// vxgi_gl_fp16_test.cpp): validation on, the OpenGL context probed (so the interop ladders are filled from what
// llvmpipe's GL offers), and optional forced rungs.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "vk/context.hpp"

namespace idk::test {

inline std::unique_ptr<vk::Context> glProbedContext(std::vector<vk::RungForce> forced = {}) {
    vk::ContextDesc desc;
    desc.validation = true;
    desc.probeGlInterop = true;
    desc.forcedRungs = std::move(forced);
    return std::make_unique<vk::Context>(desc);
}

}  // namespace idk::test
