#pragma once
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <zlib.h>

#include "exasph/util/error.hpp"

namespace exasph {

// A small PNG writer: 8-bit RGB, no row filter, the rows deflated by zlib; the chunk layout and
// CRCs as the PNG specification (RFC 2083) defines them.
inline void put_be32(std::string& s, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) s += char((v >> shift) & 0xFF);
}

inline std::string png_chunk(const std::string& type, const std::string& data) {
    std::string s;
    put_be32(s, std::uint32_t(data.size()));
    const std::string body = type + data;
    s += body;
    put_be32(
        s, std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
    return s;
}

inline std::string zlib_compressed(const std::string& raw) {
    uLongf size = compressBound(uLong(raw.size()));
    std::string z(size, '\0');
    if (compress2(reinterpret_cast<Bytef*>(z.data()), &size,
                  reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()), 6) != Z_OK)
        throw Error("PNG: zlib could not compress the image", 3);
    z.resize(size);
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
        << png_chunk("IHDR", header) << png_chunk("IDAT", zlib_compressed(raw))
        << png_chunk("IEND", "");
    out.close();
    if (!out) throw Error(path + ": cannot write", 3);
}

} // namespace exasph
