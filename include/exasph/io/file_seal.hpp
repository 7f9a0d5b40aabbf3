#pragma once
// A checkpoint's seal: the hash of every byte of the file, kept in the file's first bytes (an
// HDF5 user block, which HDF5 skips), verified before HDF5 parses anything. HDF5 1.10 is not
// robust against damaged bytes (fuzzing found it reading out of bounds on altered files,
// docs/resilience.md), so a checkpoint damaged on disk must be refused before it reaches it.
//
// User block layout (kSealBytes, the rest zero): 8 bytes "EXSEAL01", uint64 file size, uint64
// chunk size, uint64 hash. The hash covers the bytes after the user block in chunks of a fixed
// size (each chunk hashed by one rank, chunk c by rank c mod P; the chunk hashes chained in
// order), so it does not depend on the rank count that computes it.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include "exasph/util/mpi.hpp"

#include "exasph/util/checksum.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

inline constexpr std::uint64_t kSealBytes = 512; // HDF5's smallest user block
inline constexpr char kSealMagic[8] = {'E', 'X', 'S', 'E', 'A', 'L', '0', '1'};
inline constexpr std::uint64_t kSealChunk = 64ull << 20;

namespace detail {

// A file descriptor closed on every path out.
struct Fd {
    int fd;
    explicit Fd(const std::string& path, int flags) : fd(::open(path.c_str(), flags)) {}
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

// Hash of bytes [begin, end) of the file, as 64-bit words (the last one zero-padded).
inline std::uint64_t hash_range(int fd, std::uint64_t begin, std::uint64_t end, bool& ok) {
    HashChain h(end - begin);
    std::vector<unsigned char> buf(std::size_t(1) << 20);
    for (std::uint64_t at = begin; at < end;) {
        const std::size_t want = std::size_t(std::min<std::uint64_t>(buf.size(), end - at));
        const ssize_t got = ::pread(fd, buf.data(), want, off_t(at));
        if (got != ssize_t(want)) {
            ok = false;
            return 0;
        }
        for (std::size_t i = 0; i < want; i += 8) {
            std::uint64_t w = 0;
            std::memcpy(&w, buf.data() + i, std::min<std::size_t>(8, want - i));
            h.add(w);
        }
        at += want;
    }
    return h.value();
}

// The seal's hash of a file of `size` bytes, all ranks together; ok false on a read error.
inline std::uint64_t seal_hash(const std::string& path, std::uint64_t size, MPI_Comm comm,
                               bool& ok) {
    int rank = 0, nranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &nranks);
    const std::uint64_t body = size > kSealBytes ? size - kSealBytes : 0;
    const std::uint64_t nchunks = (body + kSealChunk - 1) / kSealChunk;
    std::vector<std::uint64_t> chunk_hash(nchunks, 0);
    int good = 1;
    Fd f(path, O_RDONLY);
    good = f.fd >= 0;
    for (std::uint64_t c = std::uint64_t(rank); good && c < nchunks; c += std::uint64_t(nranks)) {
        bool read_ok = true;
        const std::uint64_t b = kSealBytes + c * kSealChunk;
        chunk_hash[c] = hash_range(f.fd, b, std::min(size, b + kSealChunk), read_ok);
        good = read_ok;
    }
    MPI_Allreduce(MPI_IN_PLACE, &good, 1, MPI_INT, MPI_MIN, comm);
    MPI_Allreduce(MPI_IN_PLACE, chunk_hash.data(), int(nchunks), MPI_UINT64_T, MPI_BXOR, comm);
    ok = good != 0;
    HashChain h(size);
    for (std::uint64_t v : chunk_hash) h.add(v);
    return h.value();
}

inline std::uint64_t file_size(const std::string& path) {
    Fd f(path, O_RDONLY);
    const off_t end = f.fd < 0 ? -1 : ::lseek(f.fd, 0, SEEK_END);
    return end < 0 ? 0 : std::uint64_t(end);
}

} // namespace detail

// Seals a complete file written with a kSealBytes user block (after every rank closed it).
// Collective; throws exit 3 when it cannot read or write the file.
inline void seal_file(const std::string& path, MPI_Comm comm) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    std::uint64_t size = rank == 0 ? detail::file_size(path) : 0;
    MPI_Bcast(&size, 1, MPI_UINT64_T, 0, comm);
    bool ok = size > kSealBytes;
    const std::uint64_t hash = ok ? detail::seal_hash(path, size, comm, ok) : 0;
    int written = 1;
    if (rank == 0 && ok) {
        unsigned char head[32];
        const std::uint64_t words[3] = {size, kSealChunk, hash};
        std::memcpy(head, kSealMagic, 8);
        std::memcpy(head + 8, words, 24);
        detail::Fd f(path, O_WRONLY);
        written = f.fd >= 0 && ::pwrite(f.fd, head, 32, 0) == 32 && ::fsync(f.fd) == 0;
    }
    MPI_Bcast(&written, 1, MPI_INT, 0, comm);
    if (!ok || !written) throw Error(path + ": cannot seal the written file (I/O error)", 3, true);
}

// Verifies a file's seal before anything parses it; throws exit 2 naming what is wrong.
// Collective.
inline void verify_seal(const std::string& path, MPI_Comm comm, const std::string& what) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    std::uint64_t head[4] = {0, 0, 0, 0}; // magic, size, chunk, hash
    std::uint64_t size = 0;
    int readable = 1;
    if (rank == 0) {
        detail::Fd f(path, O_RDONLY);
        readable = f.fd >= 0;
        if (readable && ::pread(f.fd, head, 32, 0) != 32) head[0] = 0;
        size = detail::file_size(path);
    }
    MPI_Bcast(&readable, 1, MPI_INT, 0, comm);
    MPI_Bcast(head, 4, MPI_UINT64_T, 0, comm);
    MPI_Bcast(&size, 1, MPI_UINT64_T, 0, comm);
    if (!readable) throw input_error(path + ": no such file or not readable", true);
    if (std::memcmp(head, kSealMagic, 8) != 0)
        throw input_error(path + ": not " + what + " (no exasph seal in its first bytes)", true);
    if (head[2] != kSealChunk || head[1] != size)
        throw input_error(path + ": file checksum mismatch (" + std::to_string(size) +
                              " bytes, sealed with " + std::to_string(head[1]) +
                              "): truncated or altered; not restarting",
                          true);
    bool ok = true;
    const std::uint64_t hash = detail::seal_hash(path, size, comm, ok);
    if (!ok) throw input_error(path + ": cannot read the file", true);
    if (hash != head[3])
        throw input_error(path + ": file checksum mismatch (sealed " + hex64(head[3]) +
                              ", contents " + hex64(hash) + "): the file was altered or " +
                              "corrupted; not restarting",
                          true);
}

} // namespace exasph
