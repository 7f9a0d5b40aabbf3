#pragma once
#include <atomic>
#include <cstddef>
#include <new>
#include <stdexcept>
#include <vector>

// Where particle fields and kernel tables live. By default, ordinary host memory. A backend
// whose kernels read the same pointers on a device (the CUDA backend: managed memory, which
// migrates between host and device and which both address alike) installs its allocator once,
// before the first such array exists; from then on every FieldArray comes from it.
namespace exasph {

struct FieldMemory {
    void* (*allocate)(std::size_t bytes) = nullptr; // nullptr: operator new
    void (*release)(void* p) = nullptr;
    const char* name = "host";
};

namespace detail {
inline FieldMemory& field_memory_state() {
    static FieldMemory memory;
    return memory;
}
inline std::atomic<long>& live_field_arrays() {
    static std::atomic<long> live{0};
    return live;
}
} // namespace detail

inline const FieldMemory& field_memory() {
    return detail::field_memory_state();
}

// Installs `m` for every later FieldArray. Throws if any array is alive: it would be released by
// the wrong allocator.
inline void install_field_memory(const FieldMemory& m) {
    if (detail::live_field_arrays().load() != 0)
        throw std::logic_error("field memory changed while field arrays exist");
    detail::field_memory_state() = m;
}

// A stateless allocator that follows field_memory().
template <class T>
struct FieldAllocator {
    using value_type = T;
    FieldAllocator() = default;
    template <class U>
    FieldAllocator(const FieldAllocator<U>&) noexcept {}

    T* allocate(std::size_t n) {
        const FieldMemory& m = field_memory();
        void* p = m.allocate ? m.allocate(n * sizeof(T)) : ::operator new(n * sizeof(T));
        if (!p) throw std::bad_alloc();
        ++detail::live_field_arrays();
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t) noexcept {
        const FieldMemory& m = field_memory();
        m.release ? m.release(p) : ::operator delete(p);
        --detail::live_field_arrays();
    }
    template <class U>
    bool operator==(const FieldAllocator<U>&) const noexcept {
        return true;
    }
};

// The array type of particle fields and kernel tables.
template <class T>
using FieldArray = std::vector<T, FieldAllocator<T>>;

} // namespace exasph
