#pragma once
// The subset of MPI that exasph calls, for a build without MPI (CMake EXASPH_MPI=OFF): one
// process, one rank. Collectives copy, messages to oneself wait in a mailbox until received.
// Included through util/mpi.hpp only; never beside a real <mpi.h>.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <stdexcept>
#include <vector>

using MPI_Comm = int;
using MPI_Datatype = int; // the size in bytes of one element: all a single rank needs
using MPI_Op = int;
using MPI_Info = int;
using MPI_Request = int; // index of a pending receive, or -1 (complete)
struct MPI_Status {
    int MPI_SOURCE = 0, MPI_TAG = 0;
    int bytes = 0;
};
using MPI_User_function = void(void*, void*, int*, MPI_Datatype*);

inline constexpr MPI_Comm MPI_COMM_WORLD = 0, MPI_COMM_SELF = 1;
inline constexpr MPI_Datatype MPI_CHAR = 1, MPI_BYTE = 1, MPI_INT = 4, MPI_DOUBLE = 8,
                              MPI_UINT64_T = 8;
inline constexpr MPI_Op MPI_SUM = 1, MPI_MIN = 2, MPI_MAX = 3, MPI_BXOR = 4;
inline constexpr MPI_Info MPI_INFO_NULL = 0;
inline constexpr int MPI_SUCCESS = 0, MPI_ANY_SOURCE = -1, MPI_THREAD_FUNNELED = 1,
                     MPI_COMM_TYPE_SHARED = 1;
inline void* const MPI_IN_PLACE = reinterpret_cast<void*>(std::intptr_t(1));
inline MPI_Status* const MPI_STATUS_IGNORE = nullptr;
inline MPI_Status* const MPI_STATUSES_IGNORE = nullptr;

namespace exasph::serial_mpi {

struct Message {
    int tag;
    std::vector<unsigned char> bytes;
};
struct Receive {
    void* buf;
    std::size_t capacity;
    int tag;
};
struct State {
    bool finalized = false;
    std::deque<Message> mailbox;
    std::vector<Receive> receives;
};
inline State& state() {
    static State s;
    return s;
}

// The first message with `tag`, moved into buf (at most capacity bytes); its size.
inline int take(int tag, void* buf, std::size_t capacity) {
    auto& box = state().mailbox;
    for (auto it = box.begin(); it != box.end(); ++it) {
        if (it->tag != tag) continue;
        if (it->bytes.size() > capacity)
            throw std::runtime_error("serial MPI: message longer than the receive buffer");
        const int n = int(it->bytes.size());
        if (n) std::memcpy(buf, it->bytes.data(), it->bytes.size());
        box.erase(it);
        return n;
    }
    throw std::runtime_error("serial MPI: a receive with no matching send (would deadlock)");
}

inline void copy(const void* send, void* recv, int count, MPI_Datatype type) {
    if (send != MPI_IN_PLACE && count > 0) std::memmove(recv, send, std::size_t(count) * type);
}

} // namespace exasph::serial_mpi

inline int MPI_Init_thread(int*, char***, int required, int* provided) {
    *provided = required;
    return MPI_SUCCESS;
}
inline int MPI_Finalize() {
    exasph::serial_mpi::state().finalized = true;
    return MPI_SUCCESS;
}
inline int MPI_Finalized(int* flag) {
    *flag = exasph::serial_mpi::state().finalized;
    return MPI_SUCCESS;
}
inline int MPI_Abort(MPI_Comm, int code) {
    std::exit(code);
}
inline int MPI_Comm_rank(MPI_Comm, int* rank) {
    return *rank = 0, MPI_SUCCESS;
}
inline int MPI_Comm_size(MPI_Comm, int* size) {
    return *size = 1, MPI_SUCCESS;
}
inline int MPI_Comm_split_type(MPI_Comm comm, int, int, MPI_Info, MPI_Comm* out) {
    return *out = comm, MPI_SUCCESS;
}
inline int MPI_Comm_free(MPI_Comm*) {
    return MPI_SUCCESS;
}
inline int MPI_Barrier(MPI_Comm) {
    return MPI_SUCCESS;
}
inline int MPI_Bcast(void*, int, MPI_Datatype, int, MPI_Comm) {
    return MPI_SUCCESS;
}
inline int MPI_Allreduce(const void* send, void* recv, int count, MPI_Datatype type, MPI_Op,
                         MPI_Comm) {
    exasph::serial_mpi::copy(send, recv, count, type);
    return MPI_SUCCESS;
}
// Rank 0's result is undefined in MPI: left as it is.
inline int MPI_Exscan(const void*, void*, int, MPI_Datatype, MPI_Op, MPI_Comm) {
    return MPI_SUCCESS;
}
inline int MPI_Allgather(const void* send, int count, MPI_Datatype type, void* recv, int,
                         MPI_Datatype, MPI_Comm) {
    exasph::serial_mpi::copy(send, recv, count, type);
    return MPI_SUCCESS;
}
inline int MPI_Allgatherv(const void* send, int count, MPI_Datatype type, void* recv, const int*,
                          const int* displs, MPI_Datatype, MPI_Comm) {
    exasph::serial_mpi::copy(send, static_cast<char*>(recv) + displs[0] * type, count, type);
    return MPI_SUCCESS;
}
inline int MPI_Gather(const void* send, int count, MPI_Datatype type, void* recv, int, MPI_Datatype,
                      int, MPI_Comm) {
    exasph::serial_mpi::copy(send, recv, count, type);
    return MPI_SUCCESS;
}
inline int MPI_Gatherv(const void* send, int count, MPI_Datatype type, void* recv, const int*,
                       const int* displs, MPI_Datatype, int, MPI_Comm) {
    exasph::serial_mpi::copy(send, static_cast<char*>(recv) + displs[0] * type, count, type);
    return MPI_SUCCESS;
}
inline int MPI_Type_contiguous(int count, MPI_Datatype old, MPI_Datatype* out) {
    return *out = count * old, MPI_SUCCESS;
}
inline int MPI_Type_commit(MPI_Datatype*) {
    return MPI_SUCCESS;
}
inline int MPI_Type_free(MPI_Datatype*) {
    return MPI_SUCCESS;
}
inline int MPI_Op_create(MPI_User_function*, int, MPI_Op* op) {
    return *op = 4, MPI_SUCCESS;
}
inline int MPI_Op_free(MPI_Op*) {
    return MPI_SUCCESS;
}

// Point to point: only to and from rank 0 itself.
inline int MPI_Isend(const void* buf, int count, MPI_Datatype type, int, int tag, MPI_Comm,
                     MPI_Request* req) {
    const auto* p = static_cast<const unsigned char*>(buf);
    exasph::serial_mpi::state().mailbox.push_back(
        {tag, std::vector<unsigned char>(p, p + std::size_t(count) * type)});
    *req = -1;
    return MPI_SUCCESS;
}
inline int MPI_Irecv(void* buf, int count, MPI_Datatype type, int, int tag, MPI_Comm,
                     MPI_Request* req) {
    auto& receives = exasph::serial_mpi::state().receives;
    receives.push_back({buf, std::size_t(count) * type, tag});
    *req = int(receives.size() - 1);
    return MPI_SUCCESS;
}
inline int MPI_Waitall(int n, MPI_Request* reqs, MPI_Status*) {
    auto& receives = exasph::serial_mpi::state().receives;
    for (int k = 0; k < n; ++k) {
        if (reqs[k] < 0) continue;
        const auto& r = receives.at(std::size_t(reqs[k]));
        exasph::serial_mpi::take(r.tag, r.buf, r.capacity);
        reqs[k] = -1;
    }
    bool pending = false;
    for (int k = 0; k < n; ++k) pending |= reqs[k] >= 0;
    if (!pending) receives.clear();
    return MPI_SUCCESS;
}
// One rank's messages are all sent already: testing completes them.
inline int MPI_Testall(int n, MPI_Request* reqs, int* done, MPI_Status* st) {
    *done = 1;
    return MPI_Waitall(n, reqs, st);
}
inline int MPI_Probe(int, int tag, MPI_Comm, MPI_Status* st) {
    for (const auto& m : exasph::serial_mpi::state().mailbox)
        if (m.tag == tag) {
            if (st) *st = {0, tag, int(m.bytes.size())};
            return MPI_SUCCESS;
        }
    throw std::runtime_error("serial MPI: a probe with no matching send (would deadlock)");
}
inline int MPI_Get_count(const MPI_Status* st, MPI_Datatype type, int* count) {
    return *count = st->bytes / type, MPI_SUCCESS;
}
inline int MPI_Recv(void* buf, int count, MPI_Datatype type, int, int tag, MPI_Comm, MPI_Status*) {
    exasph::serial_mpi::take(tag, buf, std::size_t(count) * type);
    return MPI_SUCCESS;
}
