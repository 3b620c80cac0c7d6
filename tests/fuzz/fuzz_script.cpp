// fuzz_script.cpp: libFuzzer harness for the viewer's input-script parser (viewer::parseInputScriptText, what
// `idk-viewer --script F` runs). Contract (input.hpp): bad input throws std::runtime_error "NAME:LINE: cause"; an
// accepted script gives events sorted by frame, key events with a known key, resize events within 1..16384.
#include <algorithm>
#include <string>

#include "fuzz_support.hpp"
#include "viewer/input.hpp"

IDK_FUZZ_TARGET(script) {
    using idk::fuzz::violation;
    using idk::viewer::ScriptAction;
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const auto events = idk::viewer::parseInputScriptText(text, "fuzz.txt");
        if (!std::is_sorted(events.begin(), events.end(), [](const auto& a, const auto& b) { return a.frame < b.frame; }))
            violation("script", "events not sorted by frame");
        for (const auto& e : events) {
            if ((e.action == ScriptAction::Down || e.action == ScriptAction::Up) && e.key < 0)
                violation("script", "key event without a key");
            if (e.action == ScriptAction::Resize &&
                !(e.value.x >= 1 && e.value.y >= 1 && e.value.x <= 16384 && e.value.y <= 16384))
                violation("script", "resize outside 1..16384");
        }
    } catch (const idk::fuzz::ContractViolation&) {
        throw;
    } catch (const std::runtime_error& e) {
        if (std::string(e.what()).rfind("fuzz.txt:", 0) != 0)
            violation("script", std::string("error without NAME:LINE: ") + e.what());
    } catch (const std::exception& e) {
        violation("script", std::string("undocumented exception: ") + e.what());
    }
    return 0;
}
