#pragma once
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "exasph/util/error.hpp"

namespace exasph {

// How a CSV column prints its value: integers exactly, numbers with all 17 digits (a run's
// values round-trip), timings with 7.
enum class CsvFormat { integer, exact, timing };
struct CsvColumn {
    std::string name;
    CsvFormat format = CsvFormat::exact;
};

// A CSV file of one row per step (diagnostics.csv), flushed after every row so that a killed
// run keeps what it wrote. Appends when asked (a restart in the same directory) and writes the
// header only into an empty file.
class CsvTable {
  public:
    CsvTable(const std::filesystem::path& path, bool append, std::vector<CsvColumn> columns)
        : out_(path, append ? std::ios::app : std::ios::trunc), columns_(std::move(columns)),
          name_(path.filename().string()) {
        if (!out_) throw Error("cannot write " + path.string(), 3);
        if (append && std::filesystem::file_size(path) > 0) return;
        for (std::size_t c = 0; c < columns_.size(); ++c)
            out_ << (c ? "," : "") << columns_[c].name;
        out_ << "\n";
    }

    void write(const std::vector<double>& row) {
        if (row.size() != columns_.size()) throw Error(name_ + ": row of the wrong length");
        char buf[40];
        for (std::size_t c = 0; c < row.size(); ++c) {
            const CsvFormat f = columns_[c].format;
            if (f == CsvFormat::integer) std::snprintf(buf, sizeof buf, "%lld", (long long)row[c]);
            if (f == CsvFormat::exact) std::snprintf(buf, sizeof buf, "%.17g", row[c]);
            if (f == CsvFormat::timing) std::snprintf(buf, sizeof buf, "%.6e", row[c]);
            out_ << (c ? "," : "") << buf;
        }
        out_ << "\n";
        out_.flush();
        if (!out_) throw Error("write to " + name_ + " failed", 3);
    }

  private:
    std::ofstream out_;
    std::vector<CsvColumn> columns_;
    std::string name_;
};

// Before a restart appends to the table: keeps the header and the rows of steps up to `step`
// (the checkpoint's), dropping the rows a killed run wrote after it and a last row the kill cut
// short, so that the restarted run's rows follow on as an uninterrupted run's would. Rewritten
// under a temporary name; an absent file is left absent.
inline void keep_rows_through(const std::filesystem::path& path, std::int64_t step) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return;
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::string kept;
    for (std::size_t a = 0, b; (b = text.find('\n', a)) != std::string::npos; a = b + 1) {
        const std::string line = text.substr(a, b - a + 1);
        if (a == 0 || std::strtoll(line.c_str(), nullptr, 10) <= step) kept += line;
    }
    if (kept.size() == text.size()) return;
    const auto tmp = path.string() + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out << kept;
        if (!out.flush()) throw Error("cannot rewrite " + path.string(), 3);
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw Error("cannot rewrite " + path.string() + ": " + ec.message(), 3);
}

} // namespace exasph
