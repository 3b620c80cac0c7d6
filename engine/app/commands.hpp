// commands.hpp: the `idk` subcommands. Each takes the arguments after its name and returns the exit code.
#pragma once
#include <string>
#include <vector>

namespace idk::app {

int runInfo(const std::vector<std::string>& args);
int runRender(const std::vector<std::string>& args);
int runBvh(const std::vector<std::string>& args);
int runCompare(const std::vector<std::string>& args);

extern const char* const kInfoHelp;
extern const char* const kRenderHelp;
extern const char* const kBvhHelp;
extern const char* const kCompareHelp;

}  // namespace idk::app
