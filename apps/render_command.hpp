#pragma once
// `exasph render SNAPSHOT`: a slice or a projection of a snapshot's field (include/exasph/render).
#include <cstdio>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"
#include <CLI/CLI.hpp>

#include "exasph/kernel/sinc_kernel.hpp"
#include "exasph/render/render_image.hpp"
#include "exasph/render/render_output.hpp"

struct RenderCommand {
    std::string snapshot;
    exasph::RenderSpec spec;
    std::string axis = "z";
    std::vector<double> region;
    std::string out; // "" : beside the snapshot
};

inline void add_render_command(CLI::App& app, RenderCommand& rc) {
    auto* sub = app.add_subcommand(
        "render", "Draw a snapshot's field: a slice (SPH interpolation normalised by the "
                  "kernel's sum) or a projection along an axis (its integral: for rho the column "
                  "density), as PREFIX.png with a colour bar, PREFIX.h5 (the grid) and "
                  "PREFIX.xdmf (ParaView opens it as an image); runs under mpirun too");
    sub->add_option("snapshot", rc.snapshot, "Snapshot file (snapshot_SSSSSS.h5)")
        ->required()
        ->check(CLI::ExistingFile);
    sub->add_option(
           "--field", rc.spec.field,
           "Field to draw, by exasph's name (rho, u, vx, h, p, ...; a field the snapshot holds)")
        ->capture_default_str();
    sub->add_flag("--project", rc.spec.project, "Integrate along the axis instead of slicing");
    sub->add_option("--axis", rc.axis, "Slice normal or line of sight")
        ->check(CLI::IsMember({"x", "y", "z"}))
        ->capture_default_str();
    sub->add_option("--at", rc.spec.at, "Slice position on the axis (default: the box's middle)");
    sub->add_option("--resolution", rc.spec.nx, "Pixels along the plane's first axis")
        ->check(CLI::Range(8, 16384))
        ->capture_default_str();
    sub->add_option("--region", rc.region,
                    "Plane region ulo,uhi,vlo,vhi (plane axes: x,y for --axis z; x,z for y; y,z "
                    "for x; default: the box)")
        ->delimiter(',')
        ->expected(4);
    sub->add_flag("--log", rc.spec.log, "Logarithmic colour scale (the grid stays linear)");
    sub->add_option(
        "--out", rc.out,
        "Output prefix (default: the snapshot's path without .h5, then _FIELD_slice_AXIS "
        "or _FIELD_projection_AXIS)");
}

inline int run_render(RenderCommand rc) {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    rc.spec.axis = rc.axis[0] - 'x';
    if (rc.region.size() == 4)
        for (int k = 0; k < 4; ++k) rc.spec.region[k] = rc.region[k];
    const auto particles =
        exasph::read_render_particles(rc.snapshot, rc.spec.field, MPI_COMM_WORLD);
    const exasph::RenderPlane plane(rc.spec, particles.box);
    const exasph::KernelTable<double> kernel(exasph::sinc_kernel(particles.kernel_exponent));
    const auto image =
        exasph::render_image(particles, plane, kernel, rc.spec.project, MPI_COMM_WORLD);
    if (rank != 0) return 0;
    std::string prefix = rc.out;
    if (prefix.empty()) {
        prefix = rc.snapshot.size() > 3 && rc.snapshot.substr(rc.snapshot.size() - 3) == ".h5"
                     ? rc.snapshot.substr(0, rc.snapshot.size() - 3)
                     : rc.snapshot;
        prefix += "_" + rc.spec.field + (rc.spec.project ? "_projection_" : "_slice_") + rc.axis;
    }
    exasph::write_render_outputs(prefix, image, plane, rc.spec, particles.time, particles.unit);
    const auto [lo, hi] = exasph::value_range(image, false);
    std::printf("render: %s.png, .h5, .xdmf: %s %s %s, %d x %d pixels, t = %.6g, values %.6g .. "
                "%.6g\n",
                prefix.c_str(), rc.spec.field.c_str(),
                rc.spec.project ? "projected along" : "sliced across", rc.axis.c_str(), plane.n[0],
                plane.n[1], particles.time, lo, hi);
    return 0;
}
