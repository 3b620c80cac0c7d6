// fuzz_support.hpp: helpers shared by the harnesses (see fuzz_target.hpp for the two builds).
#pragma once

#include <filesystem>

#include "fuzz_target.hpp"

namespace idk::fuzz {

// An empty temporary folder, created on first use and made the process's working folder (see the .cpp for why);
// removed at exit. The glTF harness names its input as a file in it, so external URIs resolve into nothing.
const std::filesystem::path& emptyWorkingFolder();

}  // namespace idk::fuzz
