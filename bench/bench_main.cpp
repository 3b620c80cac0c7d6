// bench_main.cpp: idk_bench's main(): creates the shared Vulkan device first (so its name, driver and
// capability ladders land in the results' context), runs the selected benchmarks, then releases the device
// before static destructors run. Engine log messages are printed once each: a benchmark loads the same
// file hundreds of times and would repeat its warnings.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <set>
#include <string>

#include "bench_support.hpp"
#include "core/log.hpp"

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    std::set<std::string> seen;
    idk::core::setLogSink([&seen](idk::core::LogLevel level, std::string_view message) {
        if (level >= idk::core::LogLevel::Warning && seen.emplace(message).second) {
            std::fprintf(stderr, "idk_bench: %.*s\n", int(message.size()), message.data());
        }
    });
    idk::bench::createDevice();
    benchmark::RunSpecifiedBenchmarks();
    idk::bench::destroyDevice();
    benchmark::Shutdown();
    idk::core::setLogSink({});
    return 0;
}
