#pragma once
#include <cstdio>
#include <filesystem>
#include <fstream>
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

} // namespace exasph
