#pragma once
#include "exasph/kernel/kernel_table.hpp"
#include "exasph/kernel/sinc_kernel.hpp"

namespace exasph::testref {

// The default kernel of a run (sinc, n = 6), tabulated once per test program.
inline const KernelTable<double>& sinc6() {
    static const KernelTable<double> table(sinc_kernel(6.0));
    return table;
}

} // namespace exasph::testref
