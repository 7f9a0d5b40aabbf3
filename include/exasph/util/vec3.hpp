#pragma once
#include "exasph/util/annotate.hpp"

namespace exasph {

// Small value type for 3-vectors. Used in kernels; particle data itself stays in SoA arrays.
template <class T>
struct Vec3 {
    T x{}, y{}, z{};

    EXASPH_HD constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
    EXASPH_HD constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    EXASPH_HD constexpr Vec3 operator*(T s) const { return {x * s, y * s, z * s}; }
    EXASPH_HD constexpr Vec3& operator+=(const Vec3& o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    EXASPH_HD constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

template <class T>
EXASPH_HD constexpr T dot(const Vec3<T>& a, const Vec3<T>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <class T>
EXASPH_HD constexpr Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

template <class T>
EXASPH_HD constexpr T norm2(const Vec3<T>& a) {
    return dot(a, a);
}

} // namespace exasph
