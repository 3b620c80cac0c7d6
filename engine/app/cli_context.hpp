// cli_context.hpp: the Vulkan context every `idk` command that touches the device creates, configured by the
// options they all share: --no-validation (skip the validation layer), --fallback (take the portable rung of
// every capability ladder) and --rung LADDER=RUNG (repeatable: force one ladder's rung, e.g. to dodge a driver
// bug). A malformed --rung, or one the device cannot run, is a usage error (exit 2) listing the valid names.
#pragma once
#include <memory>
#include <stdexcept>

#include "core/cli.hpp"
#include "vk/context.hpp"

namespace idk::app {

inline vk::ContextDesc contextDescFromCli(const core::CliArgs& args) {
    vk::ContextDesc desc;
    desc.validation = desc.validation && !args.has("--no-validation");
    desc.forceFallbackRungs = args.has("--fallback");
    desc.probeGlInterop = true;  // `idk info` shows the GL rungs, and --rung LADDER=gl-interop can run them
    for (const std::string& spec : args.getAll("--rung")) {
        try {
            desc.forcedRungs.push_back(vk::parseRungForce(spec));
        } catch (const std::invalid_argument& e) {
            throw core::CliError(e.what());
        }
    }
    return desc;
}

// Throws core::CliError when a --rung could not be taken on this device.
inline void checkForcedRungs(const vk::Context& ctx) {
    if (!ctx.forcedRungError().empty())
        throw core::CliError(ctx.forcedRungError() + " on " + ctx.info().name + " (`idk info` lists what it has)");
}

// The context of a command: the device, then checkForcedRungs.
inline std::unique_ptr<vk::Context> createContext(const vk::ContextDesc& desc) {
    auto ctx = std::make_unique<vk::Context>(desc);
    checkForcedRungs(*ctx);
    return ctx;
}

}  // namespace idk::app
