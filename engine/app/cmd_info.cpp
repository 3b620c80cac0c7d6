// cmd_info.cpp: `idk info [--json]`: device, driver, API version, the limits that matter to the engine and
// the capability-ladder table (which rung each optional feature uses on this device, and why; the same objects
// `idk render --json` reports for the rungs that ran), the ladder/rung names --rung accepts, and the GL-interop
// probe's result (the OpenGL context and how the two APIs synchronise, or why the rung is absent).
// Shader features: the optional arithmetic types the shaders could use and whether they do (shaderFloat64: unused,
// every shader is single precision, the BVH traversal included; tests/unit/shader/spirv_capabilities_test.cpp).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>

#include "app/cli_context.hpp"
#include "app/commands.hpp"
#include "app/ladder_report.hpp"
#include "core/cli.hpp"
#include "gl/gl_sync.hpp"
#include "vk/context.hpp"

namespace idk::app {

const char* const kInfoHelp =
    "usage: idk info [--json] [--no-validation] [--fallback] [--rung LADDER=RUNG ...]\n"
    "  --json           machine-readable output\n"
    "  --no-validation  do not load the Vulkan validation layer\n"
    "  --fallback       show the ladders as they are when every feature is forced to its portable rung\n"
    "  --rung L=R       show them with ladder L forced to rung R (repeatable; exit 2 naming the valid ladders\n"
    "                   and rungs when L or R is unknown or the device cannot run R)\n";

namespace {

std::string versionString(uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
           std::to_string(VK_API_VERSION_PATCH(v));
}

const char* typeName(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
        default: return "other";
    }
}

// How the engine's shaders use the optional 64-bit arithmetic features, next to what the device supports.
nlohmann::json shaderFeatures(const vk::Context& ctx) {
    VkPhysicalDeviceFeatures f{};
    vkGetPhysicalDeviceFeatures(ctx.physicalDevice(), &f);
    return nlohmann::json::array(
        {{{"feature", "shaderFloat64"},
          {"use", "unused"},
          {"supported", f.shaderFloat64 == VK_TRUE},
          {"note", "no shader uses double precision (the BVH traversal is fp32 with exact edge signs)"}},
         {{"feature", "shaderInt64"},
          {"use", "required"},
          {"supported", f.shaderInt64 == VK_TRUE},
          {"note", "64-bit buffer device addresses; the BVH traversal's exact edge-sign fallback"}}});
}

nlohmann::json describe(const vk::Context& ctx) {
    const vk::DeviceInfo& d = ctx.info();
    const vk::DeviceCapabilities& c = ctx.capabilities();
    nlohmann::json j;
    j["device"] = {{"name", d.name},
                   {"type", typeName(d.type)},
                   {"driver", d.driverName},
                   {"driverInfo", d.driverInfo},
                   {"apiVersion", versionString(d.apiVersion)},
                   {"unifiedMemory", d.uma},
                   {"forcedStaging", ctx.desc().forceStaging}};
    j["shaderFeatures"] = shaderFeatures(ctx);
    j["limits"] = {{"maxImageDimension2D", d.limits.maxImageDimension2D},
                   {"maxImageDimension3D", d.limits.maxImageDimension3D},
                   {"maxStorageBufferRange", d.limits.maxStorageBufferRange},
                   {"maxPushConstantsSize", d.limits.maxPushConstantsSize},
                   {"maxComputeWorkGroupInvocations", d.limits.maxComputeWorkGroupInvocations},
                   {"maxComputeSharedMemorySize", d.limits.maxComputeSharedMemorySize},
                   {"subgroupSize", c.subgroupSize},
                   {"subgroupSizeRange", {c.minSubgroupSize, c.maxSubgroupSize}},
                   {"subgroupArithmetic", c.subgroupArithmetic},
                   {"timestampPeriodNs", d.timestampPeriodNs},
                   {"bindlessSampledImages", d.maxSampledImagesUpdateAfterBind},
                   {"bindlessStorageBuffers", d.maxStorageBuffersUpdateAfterBind}};
    j["glInterop"] = {{"available", c.glInterop}, {"note", c.glInteropNote}};
    // How the rung orders Vulkan and GL (gl/gl_sync.hpp): "semaphores" or "cpu-wait", and why; null without GL.
    if (const gl::GlContext* gl = ctx.glContext())
        j["glInterop"]["sync"] = {{"mode", gl::syncModeName(gl->sync().mode)}, {"why", gl->sync().why}};
    else
        j["glInterop"]["sync"] = nullptr;
    j["ladders"] = laddersJson(ctx.ladders());
    return j;
}

void printText(const nlohmann::json& j) {
    const auto& d = j["device"];
    std::printf("device:   %s (%s)\n", d["name"].get<std::string>().c_str(), d["type"].get<std::string>().c_str());
    std::printf("driver:   %s %s\n", d["driver"].get<std::string>().c_str(), d["driverInfo"].get<std::string>().c_str());
    std::printf("api:      Vulkan %s\n", d["apiVersion"].get<std::string>().c_str());
    std::printf("memory:   %s%s\n", d["unifiedMemory"].get<bool>() ? "unified" : "discrete",
                d["forcedStaging"].get<bool>() ? " (staging uploads forced)" : "");
    std::printf("\nshader features:\n");
    for (const auto& f : j["shaderFeatures"]) {
        const char* supported = f["supported"].get<bool>() ? "supported" : "not supported";
        std::printf("  %-32s %-9s (device: %s) %s\n", f["feature"].get<std::string>().c_str(),
                    f["use"].get<std::string>().c_str(), supported, f["note"].get<std::string>().c_str());
    }
    std::printf("\nlimits:\n");
    for (const auto& [key, value] : j["limits"].items()) std::printf("  %-32s %s\n", key.c_str(), value.dump().c_str());
    std::printf("\ngl interop: %s\n  %s\n", j["glInterop"]["available"].get<bool>() ? "available" : "absent",
                j["glInterop"]["note"].get<std::string>().c_str());
    std::printf("\ncapability ladders (--rung LADDER=RUNG forces one):\n  %-20s %-44s %-11s %s\n", "ladder",
                "feature", "rung", "mechanism");
    for (const auto& l : j["ladders"]) {
        std::printf("  %-20s %-44s %-11s %s\n", l["id"].get<std::string>().c_str(), l["feature"].get<std::string>().c_str(),
                    l["chosen"].get<std::string>().c_str(), l["mechanism"].get<std::string>().c_str());
        const std::string reason = l["reason"].get<std::string>();
        std::printf("      why: %s\n", reason.c_str());
        for (const auto& r : l["rungs"]) {
            const std::string note = r["note"].get<std::string>();
            if (!r["available"].get<bool>() && reason.find(note) == std::string::npos)
                std::printf("      not %s: %s\n", r["rung"].get<std::string>().c_str(), note.c_str());
        }
    }
    std::printf("\nrung names per ladder:\n");
    for (const std::string& line : vk::ladderRungList()) std::printf("  %s\n", line.c_str());
}

}  // namespace

int runInfo(const std::vector<std::string>& argv) {
    core::CliArgs args = core::parseCli(argv, {{"--json", "--no-validation", "--fallback", "--help"}, {"--rung"}});
    if (args.has("--help")) {
        std::fputs(kInfoHelp, stdout);
        return 0;
    }
    if (!args.positional.empty()) throw core::CliError("unexpected argument '" + args.positional[0] + "'");
    std::unique_ptr<vk::Context> ctx = createContext(contextDescFromCli(args));
    nlohmann::json j = describe(*ctx);
    j["rungNames"] = vk::ladderRungList();
    if (args.has("--json"))
        std::cout << j.dump(2) << "\n";
    else
        printText(j);
    return 0;
}

}  // namespace idk::app
