#pragma once
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "exasph/io/atomic_output.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// XDMF text so that ParaView (its Xdmf3 reader) opens the HDF5 snapshots: one sidecar per
// snapshot (snapshot_NNNNNN.xdmf) and the run's time series (snapshots.xdmf), a temporal
// collection of the sidecars' grids that ParaView animates.

// A dataset of the grid: `width` values per point (1: a scalar, 3: a vector).
struct XdmfField {
    std::string name;
    std::string unit;
    int width = 1;
};

// What a grid says about its run beyond the fields (XDMF Information elements: the scheme, the
// unit system), as name and value.
using XdmfInformation = std::vector<std::pair<std::string, std::string>>;

inline std::string xml_escaped(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        default:
            out += c;
        }
    }
    return out;
}

inline std::string xdmf_information(const std::string& indent, const std::string& name,
                                    const std::string& value) {
    return indent + "<Information Name=\"" + xml_escaped(name) + "\" Value=\"" +
           xml_escaped(value) + "\"/>\n";
}

// One snapshot's points as an XDMF Grid element: `h5_name` is the snapshot's file name relative
// to the XDMF file, `group` the HDF5 group holding the fields, `geometry` the N x 3 positions
// among them (the points; not repeated as an attribute).
inline std::string xdmf_grid(const std::string& h5_name, const std::string& group, std::uint64_t n,
                             double time, const std::string& geometry,
                             const std::vector<XdmfField>& fields, const XdmfInformation& info) {
    auto item = [&](const std::string& name, int width) {
        const std::string dims = std::to_string(n) + (width > 1 ? " " + std::to_string(width) : "");
        return "        <DataItem Dimensions=\"" + dims +
               "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + h5_name + ":" + group +
               "/" + name + "</DataItem>\n";
    };
    char tbuf[64];
    std::snprintf(tbuf, sizeof tbuf, "%.17g", time);
    std::string s = "    <Grid Name=\"particles\" GridType=\"Uniform\">\n";
    s += "      <Time Value=\"" + std::string(tbuf) + "\"/>\n";
    for (const auto& [name, value] : info) s += xdmf_information("      ", name, value);
    s += "      <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + std::to_string(n) +
         "\" NodesPerElement=\"1\"/>\n";
    // ParaView's readers (XDMF and Xdmf3) take points from one N x 3 dataset (XYZ).
    s += "      <Geometry GeometryType=\"XYZ\">\n" + item(geometry, 3) + "      </Geometry>\n";
    for (const auto& f : fields) {
        if (f.name == geometry) continue;
        s += "      <Attribute Name=\"" + f.name + "\" AttributeType=\"" +
             (f.width == 3 ? "Vector" : "Scalar") + "\" Center=\"Node\">\n";
        if (!f.unit.empty()) s += xdmf_information("        ", "unit", f.unit);
        s += item(f.name, f.width) + "      </Attribute>\n";
    }
    return s + "    </Grid>\n";
}

inline std::string xdmf_document(const std::string& grids) {
    return "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
           "<Xdmf Version=\"3.0\">\n  <Domain>\n" +
           grids + "  </Domain>\n</Xdmf>\n";
}

inline void write_text_file(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::trunc);
    out << text;
    out.close();
    if (!out) {
        std::error_code ec; // a full disk leaves no partial file behind
        std::filesystem::remove(path, ec);
        throw Error(path + ": cannot write", 3);
    }
}

// write_text_file under a temporary name, renamed when complete (a reader never sees half).
inline void write_text_file_atomically(const std::string& path, const std::string& text) {
    write_text_file(temporary_name(path), text);
    std::filesystem::rename(temporary_name(path), path);
}

// The step of a sidecar's name snapshot_NNNNNN.xdmf, or -1 for any other name.
inline std::int64_t sidecar_step(const std::string& name) {
    constexpr std::size_t kStem = 9, kDigits = 6; // "snapshot_", "NNNNNN"
    if (name.size() != kStem + kDigits + 5 || name.rfind("snapshot_", 0) != 0 ||
        name.substr(kStem + kDigits) != ".xdmf")
        return -1;
    const std::string digits = name.substr(kStem, kDigits);
    if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return -1;
    return std::stoll(digits);
}

// The Grid element of a sidecar this code wrote (empty if the file holds none).
inline std::string sidecar_grid(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    const std::string s = text.str();
    const std::size_t begin = s.find("    <Grid Name=\"particles\"");
    const std::string close = "    </Grid>\n";
    const std::size_t end = s.find(close, begin == std::string::npos ? 0 : begin);
    if (begin == std::string::npos || end == std::string::npos) return {};
    return s.substr(begin, end + close.size() - begin);
}

// DIR/snapshots.xdmf: the grids of DIR's sidecars up to `last_step`, in step order, as one
// temporal collection, rewritten under a temporary name and renamed (a reader never sees half
// of it). Built from the sidecars on disk, so that a restarted run's series holds the first
// run's snapshots; those beyond the restart step are left out until the run writes them anew.
inline void write_xdmf_time_series(const std::string& dir, std::int64_t last_step) {
    std::vector<std::pair<std::int64_t, std::filesystem::path>> sidecars;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        const std::int64_t step = sidecar_step(entry.path().filename().string());
        if (step >= 0 && step <= last_step) sidecars.emplace_back(step, entry.path());
    }
    std::sort(sidecars.begin(), sidecars.end());
    std::string grids;
    for (const auto& [step, path] : sidecars) grids += sidecar_grid(path);
    // Indent the sidecars' grids one level into the collection.
    std::string nested;
    std::istringstream lines(grids);
    for (std::string line; std::getline(lines, line);) nested += "  " + line + "\n";
    const std::string series = (std::filesystem::path(dir) / "snapshots.xdmf").string();
    write_text_file_atomically(series,
                               xdmf_document("    <Grid Name=\"snapshots\" GridType=\"Collection\" "
                                             "CollectionType=\"Temporal\">\n" +
                                             nested + "    </Grid>\n"));
}

} // namespace exasph
