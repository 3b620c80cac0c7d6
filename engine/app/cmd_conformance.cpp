// cmd_conformance.cpp: `idk conformance`: a driver self-test. Runs every registered conformance check
// (engine/conformance: GPU kernels against their CPU oracles with the tests' tolerances) on every rung the chosen
// device has, prints kernel / rung / result / error / time, optionally writes JSON and JUnit XML, and exits 0 only
// when nothing failed (a rung the device lacks is skipped, with the reason). The ctest label conformance runs the
// same checks (tests/conformance/registry/).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "app/cli_context.hpp"
#include "app/commands.hpp"
#include "conformance/conformance.hpp"
#include "core/atomic_file.hpp"
#include "core/cli.hpp"
#include "vk/shader_library.hpp"

namespace idk::app {

const char* const kConformanceHelp =
    "usage: idk conformance [--json FILE] [--junit FILE] [--filter PATTERN] [--device N] [--list]\n"
    "                       [--shader-dir DIR] [--no-validation] [--rung LADDER=RUNG ...]\n"
    "  runs every conformance check (kernel vs. CPU oracle) on every rung the device has; exit 0 only if all pass\n"
    "  --json FILE      results as JSON          --junit FILE   results as JUnit XML (CI dashboards)\n"
    "  --filter P       only checks whose 'kernel [rung]' contains P (or matches the glob P, with * or ?)\n"
    "  --device N       the Nth Vulkan device (0-based, in the loader's order; default: the best one)\n"
    "  --list           print the checks and exit\n"
    "  --shader-dir DIR GLSL that replaces the build's: DIR/<folder>/<entry>.<stage>.glsl recompiles that shader,\n"
    "                   DIR/gl/*.comp.glsl replaces a GL-interop source (tests use it to plant a broken kernel)\n";

namespace {

std::string xmlEscape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '&': out += "&amp;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string junit(const std::vector<conformance::Outcome>& outcomes, const std::string& device) {
    size_t failures = 0, skipped = 0;
    double seconds = 0.0;
    for (const auto& o : outcomes) {
        failures += o.status == conformance::Status::Fail;
        skipped += o.status == conformance::Status::Skip;
        seconds += o.seconds;
    }
    std::ostringstream x;
    x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n  <testsuite name=\"idk conformance on "
      << xmlEscape(device) << "\" tests=\"" << outcomes.size() << "\" failures=\"" << failures << "\" skipped=\""
      << skipped << "\" time=\"" << seconds << "\">\n";
    for (const auto& o : outcomes) {
        x << "    <testcase classname=\"conformance." << xmlEscape(o.kernel.substr(0, o.kernel.find('/'))) << "\" name=\""
          << xmlEscape(o.kernel + " [" + o.rung + "]") << "\" time=\"" << o.seconds << "\"";
        if (o.status == conformance::Status::Pass) {
            x << "/>\n";
            continue;
        }
        x << ">\n      <" << (o.status == conformance::Status::Fail ? "failure" : "skipped") << " message=\""
          << xmlEscape(o.message) << "\"/>\n    </testcase>\n";
    }
    x << "  </testsuite>\n</testsuites>\n";
    return x.str();
}

}  // namespace

int runConformance(const std::vector<std::string>& argv) {
    core::CliArgs args = core::parseCli(
        argv, {{"--no-validation", "--list", "--help"}, {"--json", "--junit", "--filter", "--device", "--shader-dir", "--rung"}});
    if (args.has("--help")) {
        std::fputs(kConformanceHelp, stdout);
        return 0;
    }
    if (!args.positional.empty()) throw core::CliError("unexpected argument '" + args.positional[0] + "'");
    const std::vector<conformance::PlannedRun> runs = conformance::selectRuns(args.get("--filter", ""));
    if (args.has("--list")) {
        for (const auto& r : runs) std::printf("%s  (%s)\n", r.name().c_str(), r.check->tolerance.c_str());
        return 0;
    }
    if (runs.empty()) throw core::CliError("--filter '" + args.get("--filter", "") + "' matches no check (see --list)");
    vk::ContextDesc desc = contextDescFromCli(args);
    if (auto device = args.get("--device")) {
        const double n = core::parseNumber("--device", *device);
        if (n < 0 || n != double(uint32_t(n))) throw core::CliError("--device '" + *device + "': give a device index 0, 1, ...");
        desc.deviceIndex = uint32_t(n);
    }
    std::unique_ptr<vk::Context> ctx;
    try {
        ctx = createContext(desc);
    } catch (const vk::DeviceIndexError& e) {
        throw core::CliError("--device " + *args.get("--device") + ": " + e.what());  // a usage error: exit 2
    }
    vk::ShaderLibrary shaders(*ctx);
    const std::filesystem::path shaderDir = args.get("--shader-dir", "");
    if (!shaderDir.empty()) conformance::overrideShaders(shaders, shaderDir);

    std::printf("conformance on %s (%s)\n  %-48s %-11s %-6s %-10s %-8s %s\n", ctx->info().name.c_str(),
                ctx->info().driverName.c_str(), "kernel", "rung", "result", "max error", "time", "note");
    std::vector<conformance::Outcome> outcomes;
    std::string failed;
    for (const conformance::PlannedRun& r : runs) {
        conformance::Outcome o = conformance::run(r, *ctx, shaders, shaderDir);
        std::printf("  %-48s %-11s %-6s %-10.3g %6.2f s  %s\n", o.kernel.c_str(), o.rung.c_str(),
                    conformance::statusName(o.status), o.maxError, o.seconds, o.message.c_str());
        std::fflush(stdout);
        if (o.status == conformance::Status::Fail) failed += "\n  " + r.name() + ": " + o.message;
        outcomes.push_back(std::move(o));
    }
    size_t passed = 0, skipped = 0;
    for (const auto& o : outcomes) {
        passed += o.status == conformance::Status::Pass;
        skipped += o.status == conformance::Status::Skip;
    }
    const size_t failures = outcomes.size() - passed - skipped;
    std::printf("%zu checks: %zu passed, %zu failed, %zu skipped\n", outcomes.size(), passed, failures, skipped);

    if (auto path = args.get("--json")) {
        nlohmann::json j;
        j["device"] = {{"name", ctx->info().name}, {"driver", ctx->info().driverName}};
        j["glInterop"] = {{"available", ctx->capabilities().glInterop}, {"note", ctx->capabilities().glInteropNote}};
        j["checks"] = nlohmann::json::array();
        for (const auto& o : outcomes)
            j["checks"].push_back({{"kernel", o.kernel}, {"rung", o.rung}, {"result", conformance::statusName(o.status)},
                                   {"maxError", o.maxError}, {"seconds", o.seconds}, {"tolerance", o.tolerance},
                                   {"message", o.message}});
        j["passed"] = passed;
        j["failed"] = failures;
        j["skipped"] = skipped;
        core::writeFileAtomically(*path, j.dump(2) + "\n");
    }
    if (auto path = args.get("--junit")) core::writeFileAtomically(*path, junit(outcomes, ctx->info().name));
    if (failures) {
        std::fprintf(stderr, "idk conformance: %zu check(s) failed on %s:%s\n", failures, ctx->info().name.c_str(),
                     failed.c_str());
        return 1;
    }
    return 0;
}

}  // namespace idk::app
