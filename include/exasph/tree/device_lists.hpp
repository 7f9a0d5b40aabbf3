#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "exasph/tree/batch_lists.hpp"
#include "exasph/tree/neighbour_search.hpp"
#include "exasph/tree/octree.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

// Device memory that grows and is never shrunk while the lists live (src/cuda/).
class DeviceBuffer {
  public:
    DeviceBuffer() = default;
    DeviceBuffer(const DeviceBuffer&) = delete;
    DeviceBuffer& operator=(const DeviceBuffer&) = delete;
    ~DeviceBuffer();
    // At least `bytes` bytes; the contents are not kept.
    void* reserve(std::size_t bytes);
    void* get() const { return ptr_; }
    std::size_t capacity() const { return bytes_; }
    void release();

  private:
    void* ptr_ = nullptr;
    std::size_t bytes_ = 0;
};

// The neighbour lists of the CUDA backend, in device memory: the search of
// tree/batch_search.hpp run one thread per particle (count, size the batches as BatchLists does,
// then write the interleaved lists). The trees are copied to the device each build. Same
// interface as NeighbourLists and BatchLists (with `active`: lists for the active particles
// only, slot s of particle member()[s]); the definitions are in src/cuda/device_lists.cu.
template <class T>
class DeviceLists {
  public:
    explicit DeviceLists(std::uint32_t ngmax = 150) : ngmax_(ngmax) {}

    struct Result {
        std::uint32_t max_count = 0;
        bool exceeded = false;
        std::uint64_t pairs = 0; // sum of the list lengths: the pair terms of one pass
    };

    // `active` is read on the host (the flags of the owned particles).
    Result build(const Octree<T>& owned, const Octree<T>* halos, const SearchView<T>& p,
                 const Box<T>& box, NeighbourCriterion crit, std::uint32_t n_owned,
                 const std::uint8_t* active = nullptr);

    std::size_t size() const { return n_; } // slots (particles with a list)
    std::uint32_t max_count() const { return max_count_; }
    // Device pointers for the launcher: the lists, the batches' first slots and the counts.
    const std::uint32_t* index() const { return static_cast<const std::uint32_t*>(index_.get()); }
    const std::uint64_t* offset() const { return static_cast<const std::uint64_t*>(offset_.get()); }
    const std::uint32_t* count() const { return static_cast<const std::uint32_t*>(count_.get()); }
    // The particle of each slot; nullptr: slot s is particle s.
    const std::uint32_t* member() const {
        return host_members_.empty() ? nullptr : static_cast<const std::uint32_t*>(member_.get());
    }
    // The list of particle i, copied to the host (tests, error messages).
    std::vector<std::uint32_t> list(std::uint32_t i) const;
    std::size_t bytes() const {
        return index_.capacity() + offset_.capacity() + count_.capacity() + nodes_.capacity() +
               member_.capacity();
    }
    void release();

  private:
    std::uint32_t ngmax_;
    std::uint32_t max_count_ = 0;
    std::size_t n_ = 0;
    std::vector<std::uint32_t> host_count_;
    std::vector<std::uint64_t> host_offset_;
    std::vector<std::uint32_t> host_members_;
    DeviceBuffer index_, offset_, count_, nodes_, member_;
};

} // namespace exasph
