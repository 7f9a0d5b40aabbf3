// DeviceLists and DeviceBuffer (tree/device_lists.hpp): the neighbour search of
// tree/batch_search.hpp on the device, one thread per particle.
#include <algorithm>

#include <cuda_runtime.h>

#include "check.cuh"
#include "exasph/tree/device_lists.hpp"
#include "grid.cuh"

namespace exasph {

DeviceBuffer::~DeviceBuffer() {
    release();
}

void* DeviceBuffer::reserve(std::size_t bytes) {
    if (bytes <= bytes_ && ptr_) return ptr_;
    release();
    cuda::check(cudaMalloc(&ptr_, bytes == 0 ? 1 : bytes), "allocating device memory");
    bytes_ = bytes;
    return ptr_;
}

void DeviceBuffer::release() {
    if (ptr_) cudaFree(ptr_);
    ptr_ = nullptr;
    bytes_ = 0;
}

namespace {

using cuda::blocks_for;
using cuda::kThreads;

// Pass 1: the count of every list; pass 2 (index non-null): the lists, at their slots. Slot s
// is particle member[s] (member null: s).
template <class T>
__global__ void search_kernel(TreeView<T> owned, TreeView<T> halos, SearchView<T> p, Box<T> box,
                              bool symmetric, std::uint32_t n, const std::uint32_t* member,
                              std::uint32_t* count, const std::uint64_t* offset,
                              std::uint32_t* index) {
    const std::uint32_t s = blockIdx.x * blockDim.x + threadIdx.x;
    if (s >= n) return;
    const std::uint32_t i = member ? member[s] : s;
    if (!index) {
        count[s] = search_particle(owned, halos, p, box, symmetric, i, nullptr, 1, 0);
        return;
    }
    const NeighbourSpan sp = BatchLayout::span(index, offset, count, s);
    search_particle(owned, halos, p, box, symmetric, i, const_cast<std::uint32_t*>(sp.index),
                    kBatch, sp.count);
}

// The node arrays of both trees, copied after each other into one device buffer.
template <class T>
void copy_trees(const Octree<T>& owned, const Octree<T>* halos, DeviceBuffer& buf,
                TreeView<T>& own_view, TreeView<T>& halo_view) {
    const std::size_t n_own = owned.nodes().size();
    const std::size_t n_halo = halos ? halos->nodes().size() : 0;
    auto* nodes =
        static_cast<OctreeNode<T>*>(buf.reserve((n_own + n_halo) * sizeof(OctreeNode<T>)));
    cuda::check(cudaMemcpy(nodes, owned.nodes().data(), n_own * sizeof(OctreeNode<T>),
                           cudaMemcpyHostToDevice),
                "copying the tree to the device");
    if (n_halo)
        cuda::check(cudaMemcpy(nodes + n_own, halos->nodes().data(), n_halo * sizeof(OctreeNode<T>),
                               cudaMemcpyHostToDevice),
                    "copying the halo tree to the device");
    own_view = {nodes, std::uint32_t(n_own)};
    halo_view = {nodes + n_own, std::uint32_t(n_halo)};
}

} // namespace

template <class T>
typename DeviceLists<T>::Result
DeviceLists<T>::build(const Octree<T>& owned, const Octree<T>* halos, const SearchView<T>& p,
                      const Box<T>& box, NeighbourCriterion crit, std::uint32_t n_owned,
                      const std::uint8_t* active) {
    T hmax = owned.empty() ? T(0) : owned.nodes()[0].hmax;
    if (halos && !halos->empty()) hmax = std::max(hmax, halos->nodes()[0].hmax);
    check_periodic_reach(box, hmax);
    TreeView<T> own, halo;
    copy_trees(owned, halos, nodes_, own, halo);
    n_ = BatchLayout::select_members(active, n_owned, host_members_);
    const std::uint32_t* member = nullptr;
    if (!host_members_.empty()) {
        auto* m = static_cast<std::uint32_t*>(member_.reserve(n_ * sizeof(std::uint32_t)));
        cuda::check(
            cudaMemcpy(m, host_members_.data(), n_ * sizeof(std::uint32_t), cudaMemcpyHostToDevice),
            "copying the active particles");
        member = m;
    }
    const bool sym = crit == NeighbourCriterion::symmetric;
    auto* count = static_cast<std::uint32_t*>(count_.reserve(n_ * sizeof(std::uint32_t)));
    if (n_ > 0) {
        search_kernel<<<blocks_for(n_), kThreads>>>(own, halo, p, box, sym, std::uint32_t(n_),
                                                    member, count, nullptr, nullptr);
        cuda::check(cudaGetLastError(), "launching the neighbour count");
    }
    host_count_.resize(n_);
    cuda::check(
        cudaMemcpy(host_count_.data(), count, n_ * sizeof(std::uint32_t), cudaMemcpyDeviceToHost),
        "counting neighbours");
    max_count_ = BatchLayout::size_batches(host_count_, host_offset_);
    auto* offset =
        static_cast<std::uint64_t*>(offset_.reserve(host_offset_.size() * sizeof(std::uint64_t)));
    cuda::check(cudaMemcpy(offset, host_offset_.data(), host_offset_.size() * sizeof(std::uint64_t),
                           cudaMemcpyHostToDevice),
                "copying the batch offsets");
    auto* index =
        static_cast<std::uint32_t*>(index_.reserve(host_offset_.back() * sizeof(std::uint32_t)));
    if (n_ > 0) {
        search_kernel<<<blocks_for(n_), kThreads>>>(own, halo, p, box, sym, std::uint32_t(n_),
                                                    member, count, offset, index);
        cuda::check(cudaGetLastError(), "launching the neighbour search");
    }
    cuda::check(cudaDeviceSynchronize(), "searching neighbours");
    std::uint64_t pairs = 0;
    for (std::uint32_t c : host_count_) pairs += c;
    return {max_count_, max_count_ > ngmax_, pairs};
}

template <class T>
std::vector<std::uint32_t> DeviceLists<T>::list(std::uint32_t i) const {
    if (!host_members_.empty()) {
        const auto it = std::lower_bound(host_members_.begin(), host_members_.end(), i);
        if (it == host_members_.end() || *it != i) return {};
        i = std::uint32_t(it - host_members_.begin());
    }
    if (i >= host_count_.size()) return {};
    std::vector<std::uint32_t> out(host_count_[i]);
    const std::uint64_t first = host_offset_[i / kBatch] + i % kBatch;
    for (std::uint32_t n = 0; n < out.size(); ++n)
        cuda::check(cudaMemcpy(&out[n], index() + first + std::uint64_t(n) * kBatch,
                               sizeof(std::uint32_t), cudaMemcpyDeviceToHost),
                    "reading a neighbour list");
    return out;
}

// The CPU lists free their memory for the domain sync's peak; the sync does not use device
// memory, so the device lists keep theirs for the next build (no cudaMalloc per step).
template <class T>
void DeviceLists<T>::release() {}

template class DeviceLists<double>;

} // namespace exasph
