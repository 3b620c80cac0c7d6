// commands.hpp: the `idk` subcommands. Each takes the arguments after its name and returns the exit code.
#pragma once
#include <string>
#include <vector>

#include "vk/features.hpp"

namespace idk::app {

int runInfo(const std::vector<std::string>& args);
int runRender(const std::vector<std::string>& args);
// The same; for a rasterized render *rungsThatRan gets the capability ladders it consulted (benchmarks label
// their rows with them; path-traced and replay renders leave it unchanged).
int runRender(const std::vector<std::string>& args, std::vector<vk::Ladder>* rungsThatRan);
int runBvh(const std::vector<std::string>& args);
int runCompare(const std::vector<std::string>& args);
int runMerge(const std::vector<std::string>& args);
int runFarm(const std::vector<std::string>& args);
int runConformance(const std::vector<std::string>& args);

extern const char* const kInfoHelp;
extern const char* const kRenderHelp;
extern const char* const kBvhHelp;
extern const char* const kCompareHelp;
extern const char* const kMergeHelp;
extern const char* const kFarmHelp;
extern const char* const kConformanceHelp;

}  // namespace idk::app
