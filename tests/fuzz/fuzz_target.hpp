// fuzz_target.hpp: how a harness in tests/fuzz/ defines its entry point, once for two builds.
//   * build-fuzz/ (clang, -DIDK_FUZZ_LIBFUZZER, scripts/fuzz.sh): IDK_FUZZ_TARGET(name) is libFuzzer's
//     LLVMFuzzerTestOneInput, one harness per executable.
//   * the normal g++ build (tests/unit/fuzz): IDK_FUZZ_TARGET(name) defines a function registered under `name`, so
//     one gtest binary replays the committed seeds and every kept crash input through every harness (in both CI
//     passes, the second under ASan+UBSan).
// A harness calls the code under test, lets through only the exceptions its API documents for bad input, and checks
// properties of what it returns; anything else is a contract violation: abort() under libFuzzer (a crash it keeps),
// a ContractViolation exception in the replay test (a test failure naming the input).
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace idk::fuzz {

using Entry = int (*)(const uint8_t* data, size_t size);
struct Harness {
    std::string name;
    Entry entry;
};
inline std::vector<Harness>& harnesses() {
    static std::vector<Harness> all;
    return all;
}
struct Register {
    Register(const char* name, Entry entry) { harnesses().push_back({name, entry}); }
};

struct ContractViolation : std::logic_error {
    using std::logic_error::logic_error;
};
[[noreturn]] void violation(const char* harness, const std::string& what);

}  // namespace idk::fuzz

#ifdef IDK_FUZZ_LIBFUZZER
#define IDK_FUZZ_TARGET(name) extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
#else
#define IDK_FUZZ_TARGET(name)                                                      \
    static int idkFuzz_##name(const uint8_t* data, size_t size);                   \
    static const idk::fuzz::Register idkFuzzRegister_##name(#name, &idkFuzz_##name); \
    static int idkFuzz_##name(const uint8_t* data, size_t size)
#endif
