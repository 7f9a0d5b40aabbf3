#pragma once
#include <array>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "exasph/util/error.hpp"

namespace exasph {

// A minimal PNG writer (no library): 8-bit RGB, no row filter, the pixels in stored
// (uncompressed) deflate blocks of a zlib stream; chunk CRCs and the zlib Adler-32 as the PNG
// specification (RFC 2083) and zlib (RFC 1950/1951) define them.
inline std::uint32_t png_crc(const std::string& bytes) {
    static const auto table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t n = 0; n < 256; ++n) {
            std::uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    std::uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : bytes) c = table[(c ^ b) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

inline void put_be32(std::string& s, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) s += char((v >> shift) & 0xFF);
}

inline std::string png_chunk(const std::string& type, const std::string& data) {
    std::string s;
    put_be32(s, std::uint32_t(data.size()));
    const std::string body = type + data;
    s += body;
    put_be32(s, png_crc(body));
    return s;
}

// The zlib stream of `raw` in stored blocks (at most 65535 bytes each).
inline std::string zlib_stored(const std::string& raw) {
    std::string z = "\x78\x01";
    std::uint32_t a = 1, b = 0;
    for (unsigned char c : raw) {
        a = (a + c) % 65521u;
        b = (b + a) % 65521u;
    }
    std::size_t pos = 0;
    do {
        const std::size_t len = std::min<std::size_t>(65535, raw.size() - pos);
        const bool last = pos + len == raw.size();
        z += char(last ? 1 : 0);
        z += char(len & 0xFF);
        z += char(len >> 8);
        z += char(~len & 0xFF);
        z += char((~len >> 8) & 0xFF);
        z.append(raw, pos, len);
        pos += len;
    } while (pos < raw.size());
    put_be32(z, (b << 16) | a);
    return z;
}

// Writes `rgb` (width x height pixels, rows top to bottom, 3 bytes each) as a PNG file.
inline void write_png(const std::string& path, int width, int height,
                      const std::vector<unsigned char>& rgb) {
    std::string header;
    put_be32(header, std::uint32_t(width));
    put_be32(header, std::uint32_t(height));
    header +=
        std::string("\x08\x02\x00\x00\x00", 5); // 8 bits, RGB, deflate, no filter, no interlace
    std::string raw;
    raw.reserve(std::size_t(height) * (3 * std::size_t(width) + 1));
    for (int y = 0; y < height; ++y) {
        raw += '\0'; // filter: none
        raw.append(reinterpret_cast<const char*>(rgb.data()) + std::size_t(y) * 3 * width,
                   3 * std::size_t(width));
    }
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << "\x89PNG\r\n\x1a\n"
        << png_chunk("IHDR", header) << png_chunk("IDAT", zlib_stored(raw))
        << png_chunk("IEND", "");
    out.close();
    if (!out) throw Error(path + ": cannot write", 3);
}

} // namespace exasph
