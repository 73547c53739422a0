#pragma once
// Included first in every translation unit that links the adapters (CMakeLists.txt).
//
// fmt 9 (Debian 12's) compiles libfmt.so with its formatting engine, detail::vformat_to<char>,
// but its headers do not declare that instantiation `extern`: every translation unit that logs
// through spdlog or calls fmt::format_to compiled an engine of its own, with a local copy of
// the float printer the linker cannot merge: 36 of them, about 0.4 MB of the gateway's code, all
// of it mapped and resident. Declared here, every caller uses the library's one
// (docs/decisions/0006).

#include <fmt/format.h>

// Only under GCC, which built Debian's libfmt: clang mangles this instantiation's name
// differently (the `std::is_same` inside its argument type), so its callers would find no
// definition; clang builds (sanitizers, fuzzers) keep their own engine.
#if !defined(FMT_HEADER_ONLY) && !defined(__clang__)
FMT_BEGIN_NAMESPACE
namespace detail {
extern template FMT_API void vformat_to<char>(buffer<char>&, basic_string_view<char>,
                                              basic_format_args<FMT_BUFFER_CONTEXT(char)>,
                                              locale_ref);
}  // namespace detail
FMT_END_NAMESPACE
#endif
