// fuzz_support.cpp: what every harness shares: reporting a contract violation (abort under libFuzzer so it keeps
// the input, an exception in the replay test) and the empty working folder the glTF harness loads from.
#include "fuzz_support.hpp"

#include <cstdio>
#include <cstdlib>
#include <unistd.h>

namespace idk::fuzz {

void violation(const char* harness, const std::string& what) {
#ifdef IDK_FUZZ_LIBFUZZER
    std::fprintf(stderr, "fuzz_%s: contract violation: %s\n", harness, what.c_str());
    std::abort();
#else
    throw ContractViolation(std::string("fuzz_") + harness + ": " + what);
#endif
}

namespace {
std::filesystem::path makeEmptyFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "idk_fuzz_XXXXXX").string();
    if (!::mkdtemp(pattern.data())) {
        std::perror("idk fuzz: mkdtemp");
        std::abort();
    }
    return pattern;
}
}  // namespace

const std::filesystem::path& emptyWorkingFolder() {
    static const std::filesystem::path folder = [] {
        std::filesystem::path f = makeEmptyFolder();
        std::atexit([] {
            std::error_code ignored;
            std::filesystem::remove(emptyWorkingFolder(), ignored);  // fails (harmlessly) if not empty
        });
        // tinygltf looks for a relative URI in the base folder and then in "." (the process's working folder):
        // both must be this empty folder, or a fuzz input could read whatever file sits next to the fuzzer.
        std::filesystem::current_path(f);
        return f;
    }();
    return folder;
}

}  // namespace idk::fuzz
