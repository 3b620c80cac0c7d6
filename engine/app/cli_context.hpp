// cli_context.hpp: the Vulkan context every `idk` command that touches the device creates, configured by the two
// options they all share: --no-validation (skip the validation layer) and --fallback (take the portable rung of
// every capability ladder).
#pragma once
#include "core/cli.hpp"
#include "vk/context.hpp"

namespace idk::app {

inline vk::ContextDesc contextDescFromCli(const core::CliArgs& args) {
    vk::ContextDesc desc;
    desc.validation = desc.validation && !args.has("--no-validation");
    desc.forceFallbackRungs = args.has("--fallback");
    return desc;
}

}  // namespace idk::app
