// idk_main.cpp: the `idk` command line (DESIGN.md "Programs"): dispatches to a subcommand and turns every
// error into one line on stderr and an exit code: 1 any error, 2 usage, 3 device lost, 4 out of device memory
// (README "Exit codes"). A failed render writes no output file (images and videos are renamed into place last).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "core/cli.hpp"
#include "vk/check.hpp"

namespace {

const char* const kHelp =
    "idk - the idk-vk renderer (a Vulkan port of IDKEngine)\n"
    "\n"
    "usage: idk <command> [options]\n"
    "\n"
    "commands:\n"
    "  info     the Vulkan device, its limits and the capability ladders (--json for machines)\n"
    "  render   render a glTF scene (or the embedded Cornell box) to a PNG or EXR image\n"
    "  bvh      build the BVH of a scene and print its statistics (SAH, EPO, depth, stack, build time)\n"
    "  compare  error metrics of an image against a reference (RMSE, relative MSE, PSNR, FLIP) and CI gates\n"
    "  merge    combine path-traced sample ranges (render --sample-range) into one image\n"
    "  farm     split a replay video or a path-traced still into chunks: Slurm job arrays or local processes\n"
    "  conformance  run every GPU kernel on every rung of this device against its CPU oracle (driver self-test)\n"
    "  help     this text; `idk <command> --help` describes one command\n";

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
        std::fputs(kHelp, stdout);
        return args.empty() ? 2 : 0;
    }
    std::string command = args[0];
    std::vector<std::string> rest(args.begin() + 1, args.end());
    try {
        if (command == "info") return idk::app::runInfo(rest);
        if (command == "render") return idk::app::runRender(rest);
        if (command == "bvh") return idk::app::runBvh(rest);
        if (command == "compare") return idk::app::runCompare(rest);
        if (command == "merge") return idk::app::runMerge(rest);
        if (command == "farm") return idk::app::runFarm(rest);
        if (command == "conformance") return idk::app::runConformance(rest);
        std::fprintf(stderr, "idk: unknown command '%s' (see `idk help`)\n", command.c_str());
        return 2;
    } catch (const idk::core::CliError& e) {
        std::fprintf(stderr, "idk %s: %s (see `idk %s --help`)\n", command.c_str(), e.what(), command.c_str());
        return 2;
    } catch (const idk::vk::DeviceLostError& e) {
        std::fprintf(stderr,
                     "idk %s: device lost: the GPU or its driver failed during the work (VK_ERROR_DEVICE_LOST); "
                     "nothing was written. Run it again; if it repeats, try --fallback or a smaller --size. (%s)\n",
                     command.c_str(), e.what());
        return 3;
    } catch (const idk::vk::OutOfDeviceMemoryError& e) {
        std::fprintf(stderr,
                     "idk %s: out of device memory (VK_ERROR_OUT_OF_DEVICE_MEMORY); nothing was written. Try a "
                     "smaller --size or a smaller scene. (%s)\n",
                     command.c_str(), e.what());
        return 4;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "idk %s: error: %s\n", command.c_str(), e.what());
        return 1;
    }
}
