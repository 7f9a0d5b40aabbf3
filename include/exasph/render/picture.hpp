#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace exasph {

// An RGB picture of an image with its colour bar and the bar's numbers.
struct Canvas {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb; // rows top to bottom

    Canvas(int w, int h) : width(w), height(h), rgb(std::size_t(w) * h * 3, 255) {}
    void set(int x, int y, std::array<unsigned char, 3> c) {
        if (x < 0 || y < 0 || x >= width || y >= height) return;
        std::copy(c.begin(), c.end(), rgb.begin() + (std::size_t(y) * width + x) * 3);
    }
};

// The viridis colour map, linear between five of its colours; t in [0, 1], NaN grey.
inline std::array<unsigned char, 3> colour_of(double t) {
    static constexpr double kAnchor[5][3] = {
        {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
    if (std::isnan(t)) return {128, 128, 128};
    const double s = std::clamp(t, 0.0, 1.0) * 4.0;
    const int i = std::min(int(s), 3);
    std::array<unsigned char, 3> c{};
    for (int k = 0; k < 3; ++k)
        c[k] = (unsigned char)std::lround(kAnchor[i][k] +
                                          (s - i) * (kAnchor[i + 1][k] - kAnchor[i][k]));
    return c;
}

// 5 x 7 glyphs of the characters that %.3g prints (rows top to bottom, bit 4 the left column).
inline const unsigned char* glyph(char c) {
    static const std::string kChars = "0123456789.-+e";
    static const unsigned char kRows[][7] = {
        {14, 17, 19, 21, 25, 17, 14}, {4, 12, 4, 4, 4, 4, 14},   {14, 17, 1, 2, 4, 8, 31},
        {31, 2, 4, 2, 1, 17, 14},     {2, 6, 10, 18, 31, 2, 2},  {31, 16, 30, 1, 1, 17, 14},
        {6, 8, 16, 30, 17, 17, 14},   {31, 1, 2, 4, 8, 8, 8},    {14, 17, 17, 14, 17, 17, 14},
        {14, 17, 17, 15, 1, 2, 12},   {0, 0, 0, 0, 0, 12, 12},   {0, 0, 0, 31, 0, 0, 0},
        {0, 4, 4, 31, 4, 4, 0},       {0, 0, 14, 17, 31, 16, 14}};
    const auto at = kChars.find(c);
    return at == std::string::npos ? nullptr : kRows[at];
}

inline void draw_text(Canvas& cv, int x, int y, const std::string& text, int scale) {
    for (char ch : text) {
        if (const unsigned char* rows = glyph(ch))
            for (int r = 0; r < 7; ++r)
                for (int col = 0; col < 5; ++col)
                    if (rows[r] & (16 >> col))
                        for (int a = 0; a < scale; ++a)
                            for (int b = 0; b < scale; ++b)
                                cv.set(x + col * scale + b, y + r * scale + a, {0, 0, 0});
        x += 6 * scale;
    }
}

// The colour scale's ends: the finite values' range (the positive values' with `log`).
inline std::array<double, 2> value_range(const std::vector<double>& v, bool log) {
    double lo = INFINITY, hi = -INFINITY;
    for (double x : v)
        if (std::isfinite(x) && (!log || x > 0)) lo = std::min(lo, x), hi = std::max(hi, x);
    if (!(lo <= hi)) return {0.0, 1.0};
    return {lo, hi > lo ? hi : lo + (lo == 0 ? 1.0 : std::abs(lo) * 1e-12)};
}

// The image (nx x ny values, row j at v index j: drawn bottom-up) and a colour bar with its
// lowest, middle and highest values (geometric middle with `log`).
inline Canvas picture(const std::vector<double>& image, int nx, int ny, bool log) {
    const auto [lo, hi] = value_range(image, log);
    auto scaled = [&, lo = lo, hi = hi](double x) {
        if (log) return x > 0 ? std::log(x / lo) / std::log(hi / lo) : NAN;
        return (x - lo) / (hi - lo);
    };
    const double mid = log ? std::sqrt(lo * hi) : 0.5 * (lo + hi);
    const double values[3] = {hi, mid, lo};
    std::string labels[3];
    std::size_t longest = 0;
    for (int k = 0; k < 3; ++k) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3g", values[k]);
        labels[k] = text, longest = std::max(longest, labels[k].size());
    }
    // The labels' column fits the longest (6 scaled pixels a character, 6 before, 4 after):
    // "-5.57e+04" is 9 characters.
    constexpr int kBar = 24, kGap = 12, kScale = 2;
    const int label_width = 10 + 6 * kScale * int(longest);
    Canvas cv(nx + kGap + kBar + label_width, std::max(ny, 60));
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            cv.set(i, ny - 1 - j, colour_of(scaled(image[std::size_t(j) * nx + i])));
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < kBar; ++x)
            cv.set(nx + kGap + x, y, colour_of(1.0 - double(y) / (ny - 1)));
    const int ys[3] = {0, ny / 2 - 7, ny - 7 * kScale};
    for (int k = 0; k < 3; ++k)
        draw_text(cv, nx + kGap + kBar + 6, std::max(0, ys[k]), labels[k], kScale);
    return cv;
}

} // namespace exasph
