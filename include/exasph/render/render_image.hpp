#pragma once
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/io/h5_file.hpp"
#include "exasph/io/root_attributes.hpp"
#include "exasph/io/snapshot_reader.hpp"
#include "exasph/render/splat.hpp"

namespace exasph {

// This rank's share of a snapshot's particles, as the renderer needs them.
struct RenderParticles {
    std::vector<SplatParticle> p;
    Box<double> box;
    double time = 0;
    std::string unit;        // of the rendered field ("" if the file names none)
    int kernel_exponent = 6; // the run's sinc exponent (param:kernel_exponent)
};

// Reads positions, h, m, rho and `field` of a snapshot (either format version): rank r of P
// reads particles [N r / P, N (r + 1) / P). A missing field is one line naming it (exit 2).
inline RenderParticles read_render_particles(const std::string& path, const std::string& field,
                                             MPI_Comm comm) {
    h5::File file = h5::File::open_read(path, comm);
    h5::Group root(file, "/", false);
    RenderParticles out;
    out.box = read_box<double>(root);
    if (h5::has_attribute(root, "param:kernel_exponent"))
        out.kernel_exponent = int(h5::read_attribute_doubles(root, "param:kernel_exponent").at(0));
    const SnapshotParticles snap(file, root);
    for (const std::string& name : std::vector<std::string>{"x", "y", "z", "h", "m", "rho", field})
        if (snap.dataset(name).empty())
            throw input_error(path + ": no field " + name + " in " + snap.group() +
                              (name == field ? "" : " (the renderer needs x, y, z, h, m, rho)"));
    out.time = snap.time();
    out.unit = snap.unit(field);
    int rank = 0, nranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &nranks);
    const std::uint64_t n = snap.size();
    const std::uint64_t lo = n * rank / nranks, count = n * (rank + 1) / nranks - lo;
    auto read = [&](const std::string& name) { return snap.read(name, lo, count); };
    const auto x = read("x"), y = read("y"), z = read("z"), h = read("h"), m = read("m"),
               rho = read("rho"), a = read(field);
    out.p.resize(count);
    for (std::uint64_t i = 0; i < count; ++i)
        out.p[i] = {{x[i], y[i], z[i]}, h[i], m[i] / rho[i], a[i]};
    return out;
}

// The image of `field` over every rank's particles, on rank 0 (empty elsewhere): a slice is
// num / den (NaN where no particle reaches), a projection num. Each thread splats its
// particles into its own buffers; the threads' and then the ranks' buffers are summed.
inline std::vector<double> render_image(const RenderParticles& in, const RenderPlane& g,
                                        const KernelTable<double>& kt, bool project,
                                        MPI_Comm comm) {
    const std::size_t np = g.pixels();
    std::vector<double> num(np, 0.0), den(project ? 0 : np, 0.0);
    const KernelView<double> k = kt.view();
    const std::optional<ProjectedKernel> f =
        project ? std::optional<ProjectedKernel>(kt) : std::nullopt;
    const auto n = static_cast<std::int64_t>(in.p.size());
#pragma omp parallel
    {
        std::vector<double> tn(np, 0.0), td(den.size(), 0.0);
#pragma omp for schedule(dynamic, 256)
        for (std::int64_t b = 0; b < n; ++b) {
            if (project)
                splat_column(g, *f, in.p[b], tn.data());
            else
                splat_slice(g, k, in.p[b], tn.data(), td.data());
        }
#pragma omp critical
        {
            for (std::size_t i = 0; i < np; ++i) num[i] += tn[i];
            for (std::size_t i = 0; i < td.size(); ++i) den[i] += td[i];
        }
    }
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    auto sum_over_ranks = [&](std::vector<double>& v) {
        if (!v.empty())
            MPI_Allreduce(MPI_IN_PLACE, v.data(), int(v.size()), MPI_DOUBLE, MPI_SUM, comm);
    };
    sum_over_ranks(num);
    sum_over_ranks(den);
    if (rank != 0) return {};
    if (!project)
        for (std::size_t i = 0; i < np; ++i)
            num[i] = den[i] > 0 ? num[i] / den[i] : std::numeric_limits<double>::quiet_NaN();
    return num;
}

} // namespace exasph
