#pragma once
#include <array>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "exasph/config/config.hpp"

namespace exasph {

// The names of a closed choice's values, as the command line, output files and the run header
// spell them.
template <class E>
struct Choices;
template <>
struct Choices<CurveKind> {
    static constexpr std::array<std::pair<std::string_view, CurveKind>, 2> values{
        {{"hilbert", CurveKind::hilbert}, {"morton", CurveKind::morton}}};
};
template <>
struct Choices<SdcPolicy> {
    static constexpr std::array<std::pair<std::string_view, SdcPolicy>, 3> values{
        {{"rollback", SdcPolicy::rollback}, {"abort", SdcPolicy::abort}, {"off", SdcPolicy::off}}};
};
template <>
struct Choices<RollbackStore> {
    static constexpr std::array<std::pair<std::string_view, RollbackStore>, 2> values{
        {{"disk", RollbackStore::disk}, {"memory", RollbackStore::memory}}};
};

template <>
struct Choices<Scheme> {
    static constexpr std::array<std::pair<std::string_view, Scheme>, 5> values{
        {{"std", Scheme::std_sph},
         {"ve", Scheme::ve},
         {"wc", Scheme::wc},
         {"pe", Scheme::pe},
         {"sh", Scheme::sh}}};
};

template <>
struct Choices<BackendChoice> {
    static constexpr std::array<std::pair<std::string_view, BackendChoice>, 3> values{
        {{"cpu", BackendChoice::cpu},
         {"cuda", BackendChoice::cuda},
         {"auto", BackendChoice::automatic}}};
};

template <>
struct Choices<TimeStepping> {
    static constexpr std::array<std::pair<std::string_view, TimeStepping>, 2> values{
        {{"global", TimeStepping::global}, {"block", TimeStepping::block}}};
};

template <>
struct Choices<Balance> {
    static constexpr std::array<std::pair<std::string_view, Balance>, 2> values{
        {{"count", Balance::count}, {"cost", Balance::cost}}};
};

template <class E>
std::string_view choice_name(E e) {
    for (const auto& [name, value] : Choices<E>::values)
        if (value == e) return name;
    return "?";
}

template <class E>
std::optional<E> choice_from_name(std::string_view name) {
    for (const auto& [n, value] : Choices<E>::values)
        if (n == name) return value;
    return std::nullopt;
}

// "a, b or c": the names of a choice, for help and error messages.
template <class E>
std::string choice_list() {
    std::string s;
    const auto& v = Choices<E>::values;
    for (std::size_t i = 0; i < v.size(); ++i)
        s += std::string(i == 0 ? "" : (i + 1 == v.size() ? " or " : ", ")) +
             std::string(v[i].first);
    return s;
}

// The number the whole of `text` spells (no trailing characters), or nothing.
inline std::optional<double> parse_number(const std::string& text) {
    try {
        std::size_t used = 0;
        const double v = std::stod(text, &used);
        if (used == text.size()) return v;
    } catch (const std::exception&) {
    }
    return std::nullopt;
}

// Numbers in the run header and in messages: %g, which prints integers without a fraction.
// A number exactly (17 significant digits) as parse_number and TOML read it back (inf, nan);
// with `decimal`, a finite one keeps a decimal point or an exponent (10.0, not 10), so that a
// reader telling counts from times (-w) takes it as a time.
inline std::string exact_number(double v, bool decimal = false) {
    if (v != v) return "nan";
    if (v - v != 0) return v > 0 ? "inf" : "-inf";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    std::string s = buf;
    return decimal && s.find_first_of(".eE") == std::string::npos ? s + ".0" : s;
}

inline std::string format_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

} // namespace exasph
