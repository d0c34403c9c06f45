#pragma once
// Internal invariants, kept apart from user errors (core/error.h): an sl::Error is bad input and
// names the file and key at fault; a failed check is a bug in shaftlab itself, whatever the input
// (an index past its array, a count that cannot be, a geometric precondition its caller owed).
// It prints what failed, where, and the values involved, then aborts, so that a debugger or a
// core dump holds the state (pbrt's CHECK, Filament's Panic).
//   SL_CHECK(condition)           always, in every build;
//   SL_CHECK_INDEX(index, size)   always: 0 <= index < size;
//   SL_DCHECK(condition)          debug builds only (the hot paths: NDEBUG leaves the condition
//   SL_DCHECK_INDEX(index, size)  unevaluated, so it costs nothing in Release).

#include <cstdint>
#include <string>

namespace sl::detail {

[[noreturn]] void check_failed(const char* condition, const char* file, int line,
                               const std::string& values);
std::string index_values(long long index, long long size);

}  // namespace sl::detail

#define SL_CHECK(condition)                                                 \
    do {                                                                    \
        if (!(condition)) [[unlikely]] {                                    \
            ::sl::detail::check_failed(#condition, __FILE__, __LINE__, ""); \
        }                                                                   \
    } while (false)

#define SL_CHECK_INDEX(index, size)                                                  \
    do {                                                                             \
        const long long sl_check_index_ = static_cast<long long>(index);             \
        const long long sl_check_size_ = static_cast<long long>(size);               \
        if (sl_check_index_ < 0 || sl_check_index_ >= sl_check_size_) [[unlikely]] { \
            ::sl::detail::check_failed(                                              \
                "0 <= " #index " < " #size, __FILE__, __LINE__,                      \
                ::sl::detail::index_values(sl_check_index_, sl_check_size_));        \
        }                                                                            \
    } while (false)

#ifdef NDEBUG
#define SL_DCHECK(condition) \
    do {                     \
    } while (false && (condition))
#define SL_DCHECK_INDEX(index, size) \
    do {                             \
    } while (false && ((index) < (size)))
#else
#define SL_DCHECK(condition) SL_CHECK(condition)
#define SL_DCHECK_INDEX(index, size) SL_CHECK_INDEX(index, size)
#endif
