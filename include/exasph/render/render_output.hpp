#pragma once
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/io/atomic_output.hpp"
#include "exasph/io/h5_file.hpp"
#include "exasph/io/xdmf.hpp"
#include "exasph/render/picture.hpp"
#include "exasph/render/png.hpp"
#include "exasph/render/render_plane.hpp"

namespace exasph {

inline const char* axis_name(int a) {
    return a == 0 ? "x" : (a == 1 ? "y" : "z");
}

// PREFIX.h5: the image as an ny x nx dataset "image" (row j at v = lo + (j + 1/2) dv) with what
// it shows as attributes. Rank 0 only (MPI_COMM_SELF).
inline void write_render_grid(const std::string& path, const std::vector<double>& image,
                              const RenderPlane& g, const RenderSpec& s, double time,
                              const std::string& unit) {
    h5::File file = h5::File::create(temporary_name(path), MPI_COMM_SELF);
    h5::Group root(file, "/", false);
    h5::write_double_rows(root, "image", image.data(), std::uint64_t(g.n[1]), std::uint64_t(g.n[0]),
                          0, std::uint64_t(g.n[1]));
    h5::write_attribute(root, "field", s.field);
    h5::write_attribute(root, "mode", std::string(s.project ? "projection" : "slice"));
    h5::write_attribute(root, "axis", std::string(axis_name(s.axis)));
    h5::write_attribute(root, "plane_axes", std::string(axis_name(g.u)) + axis_name(g.v));
    h5::write_attribute(root, "region", std::vector<double>{g.lo[0], g.hi[0], g.lo[1], g.hi[1]});
    if (!s.project) h5::write_attribute(root, "at", g.at);
    h5::write_attribute(root, "time", time);
    h5::write_attribute(root, "unit", s.project ? unit + "*length" : unit);
    file.close();
    std::filesystem::rename(temporary_name(path), path);
}

// PREFIX.xdmf: the grid as an image in its place in the box (a 3DCoRectMesh one point thick
// along the normal; XDMF lists z, y, x, and the pixels' u index runs fastest, as x, y, x do for
// the normals z, y, x).
inline std::string render_xdmf(const std::string& h5_name, const RenderPlane& g,
                               const RenderSpec& s, double time) {
    int dims[3];
    double origin[3], spacing[3];
    dims[2 - g.u] = g.n[0], dims[2 - g.v] = g.n[1], dims[2 - g.w] = 1;
    origin[2 - g.u] = g.lo[0] + 0.5 * g.d[0], origin[2 - g.v] = g.lo[1] + 0.5 * g.d[1];
    origin[2 - g.w] = g.at;
    spacing[2 - g.u] = g.d[0], spacing[2 - g.v] = g.d[1], spacing[2 - g.w] = 1.0;
    // A stream, not a fixed buffer: the field and file names have no length limit.
    std::ostringstream xml;
    xml << std::setprecision(17); // as %.17g: every double read back exactly
    const auto triple = [&](const auto* v) { xml << v[0] << ' ' << v[1] << ' ' << v[2]; };
    xml << "    <Grid Name=\"render\" GridType=\"Uniform\">\n      <Time Value=\"" << time
        << "\"/>\n      <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"";
    triple(dims);
    xml << "\"/>\n      <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
           "        <DataItem Dimensions=\"3\" Format=\"XML\">";
    triple(origin);
    xml << "</DataItem>\n        <DataItem Dimensions=\"3\" Format=\"XML\">";
    triple(spacing);
    xml << "</DataItem>\n      </Geometry>\n      <Attribute Name=\"" << s.field
        << "\" AttributeType=\"Scalar\" Center=\"Node\">\n        <DataItem Dimensions=\"";
    triple(dims);
    xml << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5_name
        << ":/image</DataItem>\n      </Attribute>\n    </Grid>\n";
    return xdmf_document(xml.str());
}

// PREFIX.png, PREFIX.h5 and PREFIX.xdmf (rank 0).
inline void write_render_outputs(const std::string& prefix, const std::vector<double>& image,
                                 const RenderPlane& g, const RenderSpec& s, double time,
                                 const std::string& unit) {
    const Canvas cv = picture(image, g.n[0], g.n[1], s.log);
    write_png(prefix + ".png", cv.width, cv.height, cv.rgb);
    write_render_grid(prefix + ".h5", image, g, s, time, unit);
    const std::string h5_name = std::filesystem::path(prefix + ".h5").filename().string();
    write_text_file_atomically(prefix + ".xdmf", render_xdmf(h5_name, g, s, time));
}

} // namespace exasph
