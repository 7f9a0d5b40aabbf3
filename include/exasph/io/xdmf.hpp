#pragma once
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "exasph/util/error.hpp"

namespace exasph {

// XDMF sidecar so that ParaView (Xdmf3 reader) opens a snapshot as points with all its fields.
// `h5_name` is the snapshot's file name relative to the XDMF file, `group` the HDF5 group holding
// 1-D double datasets x, y, z and the scalar fields.
inline std::string xdmf_text(const std::string& h5_name, const std::string& group, std::uint64_t n,
                             double time, const std::vector<std::string>& scalars) {
    auto item = [&](const std::string& name) {
        return "        <DataItem Dimensions=\"" + std::to_string(n) +
               "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + h5_name + ":" + group +
               "/" + name + "</DataItem>\n";
    };
    std::string s = "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
                    "<Xdmf Version=\"3.0\">\n  <Domain>\n    <Grid Name=\"particles\" "
                    "GridType=\"Uniform\">\n";
    char tbuf[64];
    std::snprintf(tbuf, sizeof tbuf, "%.17g", time);
    s += "      <Time Value=\"" + std::string(tbuf) + "\"/>\n";
    s += "      <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + std::to_string(n) +
         "\" NodesPerElement=\"1\"/>\n";
    s += "      <Geometry GeometryType=\"X_Y_Z\">\n" + item("x") + item("y") + item("z") +
         "      </Geometry>\n";
    for (const auto& name : scalars) {
        if (name == "x" || name == "y" || name == "z") continue;
        s += "      <Attribute Name=\"" + name + "\" AttributeType=\"Scalar\" Center=\"Node\">\n" +
             item(name) + "      </Attribute>\n";
    }
    s += "    </Grid>\n  </Domain>\n</Xdmf>\n";
    return s;
}

inline void write_text_file(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::trunc);
    out << text;
    out.close();
    if (!out) throw Error(path + ": cannot write", 3);
}

} // namespace exasph
