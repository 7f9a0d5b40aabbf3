// Parallel HDF5 wrappers, attributes: see include/exasph/io/h5_file.hpp.
#include <hdf5.h>

#include "exasph/io/h5_file.hpp"
#include "h5_errors.hpp"

namespace exasph::h5 {

namespace {

template <class V>
void write_attr(const Group& g, const std::string& name, hid_t type, const V* v, std::size_t n) {
    if (H5Aexists(g.id(), name.c_str()) > 0) H5Adelete(g.id(), name.c_str());
    hsize_t dims[1] = {n};
    hid_t space = n == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, dims, nullptr);
    hid_t attr = H5Acreate2(g.id(), name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
    herr_t st = attr < 0 ? -1 : H5Awrite(attr, type, v);
    if (attr >= 0) H5Aclose(attr);
    H5Sclose(space);
    if (st < 0) fail_write(g, "cannot write attribute " + where(g, name));
}

} // namespace

bool has_attribute(const Group& g, const std::string& name) {
    return H5Aexists(g.id(), name.c_str()) > 0;
}

void write_attribute(const Group& g, const std::string& name, double v) {
    write_attr(g, name, H5T_NATIVE_DOUBLE, &v, 1);
}
void write_attribute(const Group& g, const std::string& name, std::int64_t v) {
    write_attr(g, name, H5T_NATIVE_INT64, &v, 1);
}
void write_attribute(const Group& g, const std::string& name, const std::vector<double>& v) {
    write_attr(g, name, H5T_NATIVE_DOUBLE, v.data(), v.size());
}
void write_attribute(const Group& g, const std::string& name, const std::vector<std::int64_t>& v) {
    write_attr(g, name, H5T_NATIVE_INT64, v.data(), v.size());
}
void write_attribute(const Group& g, const std::string& name, const std::string& v) {
    if (H5Aexists(g.id(), name.c_str()) > 0) H5Adelete(g.id(), name.c_str());
    // Variable-length UTF-8, as h5py writes strings: Python readers get str, not bytes.
    hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t attr = H5Acreate2(g.id(), name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
    const char* text = v.c_str();
    herr_t st = attr < 0 ? -1 : H5Awrite(attr, type, &text);
    if (attr >= 0) H5Aclose(attr);
    H5Sclose(space);
    H5Tclose(type);
    if (st < 0) fail_write(g, "cannot write attribute " + where(g, name));
}

std::vector<double> read_attribute_doubles(const Group& g, const std::string& name) {
    hid_t attr = H5Aopen(g.id(), name.c_str(), H5P_DEFAULT);
    if (attr < 0) fail(g.file().path(), "missing attribute " + where(g, name), 2);
    hid_t space = H5Aget_space(attr);
    hssize_t n = H5Sget_simple_extent_npoints(space);
    H5Sclose(space);
    hid_t type = H5Aget_type(attr);
    H5T_class_t cls = H5Tget_class(type);
    H5Tclose(type);
    std::vector<double> out(n > 0 ? std::size_t(n) : 0);
    herr_t st = (cls == H5T_FLOAT || cls == H5T_INTEGER)
                    ? H5Aread(attr, H5T_NATIVE_DOUBLE, out.data())
                    : -1;
    H5Aclose(attr);
    if (st < 0) fail(g.file().path(), "attribute " + where(g, name) + " must be numeric", 2);
    return out;
}

std::string read_attribute_string(const Group& g, const std::string& name) {
    hid_t attr = H5Aopen(g.id(), name.c_str(), H5P_DEFAULT);
    if (attr < 0) fail(g.file().path(), "missing attribute " + where(g, name), 2);
    hid_t ftype = H5Aget_type(attr);
    std::string out;
    herr_t st = -1;
    if (H5Tget_class(ftype) == H5T_STRING && !H5Tis_variable_str(ftype)) {
        std::size_t size = H5Tget_size(ftype);
        std::vector<char> buf(size + 1, '\0');
        hid_t mtype = H5Tcopy(H5T_C_S1);
        H5Tset_size(mtype, size);
        H5Tset_cset(mtype, H5Tget_cset(ftype)); // h5py writes UTF-8
        st = H5Aread(attr, mtype, buf.data());
        H5Tclose(mtype);
        out = buf.data();
    } else if (H5Tget_class(ftype) == H5T_STRING) {
        char* s = nullptr;
        hid_t mtype = H5Tcopy(H5T_C_S1);
        H5Tset_size(mtype, H5T_VARIABLE);
        H5Tset_cset(mtype, H5Tget_cset(ftype));
        st = H5Aread(attr, mtype, &s);
        if (st >= 0 && s) out = s;
        if (s) H5free_memory(s);
        H5Tclose(mtype);
    }
    H5Tclose(ftype);
    H5Aclose(attr);
    if (st < 0) fail(g.file().path(), "attribute " + where(g, name) + " must be a string", 2);
    return out;
}

} // namespace exasph::h5
