#pragma once

namespace exasph {

// The space-filling curve that orders particles and tree cells (names in config/choices.hpp).
enum class CurveKind { hilbert, morton };

} // namespace exasph
