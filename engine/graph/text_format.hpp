// text_format.hpp: strformat("pass '{}' reads '{}'", a, b): "{}" placeholders filled by streaming the
// arguments in order (g++ 12 has no <format>); hex() for masks. Used for messages and dumps only.
#pragma once
#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>

namespace idk::graph {
namespace detail {
inline void formatTo(std::ostringstream& out, std::string_view fmt) { out << fmt; }
template <class T, class... Rest>
void formatTo(std::ostringstream& out, std::string_view fmt, const T& value, const Rest&... rest) {
    const size_t at = fmt.find("{}");
    if (at == std::string_view::npos) {
        out << fmt;
        return;
    }
    out << fmt.substr(0, at) << value;
    formatTo(out, fmt.substr(at + 2), rest...);
}
}  // namespace detail

template <class... Args>
std::string strformat(std::string_view fmt, const Args&... args) {
    std::ostringstream out;
    detail::formatTo(out, fmt, args...);
    return out.str();
}

inline std::string hex(uint64_t value) {
    std::ostringstream out;
    out << "0x" << std::hex << value;
    return out.str();
}

}  // namespace idk::graph
