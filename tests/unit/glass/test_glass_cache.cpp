// The glass cache (glass_cache_file.hpp): one binary format in every build, so that a build
// without HDF5 makes each block once too (issue 18, criterion 5); a damaged file is never used.
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <omp.h>

#include "exasph/glass/glass_cache.hpp"

using namespace exasph;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() /
                         ("exasph_glass_cache_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::vector<double> some_points(std::uint64_t side) {
    std::vector<double> p(3 * side * side * side);
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = double(i % 97) / 97.0;
    return p;
}

} // namespace

TEST(GlassCache, FileRoundTripsBitwiseAndRejectsAnythingElse) {
    const auto dir = fresh_dir("file");
    const std::string path = (dir / "g.bin").string();
    const auto points = some_points(4);
    ASSERT_TRUE(write_glass_cache(path, 4, 100, points));
    auto back = read_glass_cache(path, 4, 100);
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(*back, points);
    EXPECT_FALSE(read_glass_cache(path, 5, 100).has_value()); // other side
    EXPECT_FALSE(read_glass_cache(path, 4, 150).has_value()); // other neighbour count
    EXPECT_FALSE(read_glass_cache((dir / "absent.bin").string(), 4, 100).has_value());

    const auto size = fs::file_size(path);
    { // one flipped bit in a coordinate
        std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(100);
        char c = 0;
        f.read(&c, 1);
        c ^= 0x10;
        f.seekp(100);
        f.write(&c, 1);
    }
    EXPECT_FALSE(read_glass_cache(path, 4, 100).has_value());
    ASSERT_TRUE(write_glass_cache(path, 4, 100, points));
    fs::resize_file(path, size - 8); // cut short (no hash)
    EXPECT_FALSE(read_glass_cache(path, 4, 100).has_value());
    fs::remove_all(dir);
}

TEST(GlassCache, SecondRunReadsTheBlockTheFirstMadeAndADamagedFileIsMadeAgain) {
    omp_set_num_threads(1); // beside other tests under ctest -j2 (busy-waiting threads)
    const auto dir = fresh_dir("block");
    ::setenv("EXASPH_GLASS_DIR", dir.c_str(), 1);
    const auto made = glass_block(8, 100, MPI_COMM_WORLD, nullptr);
    const std::string path = glass_cache_path(8, 100);
    ASSERT_TRUE(fs::exists(path)) << path;
    ASSERT_EQ(made.size(), 3u * 512u);
    for (double p : made) {
        EXPECT_GE(p, 0.0);
        EXPECT_LT(p, 1.0);
    }
    const auto time_written = fs::last_write_time(path);
    EXPECT_EQ(glass_block(8, 100, MPI_COMM_WORLD, nullptr), made); // from the file
    EXPECT_EQ(fs::last_write_time(path), time_written);

    fs::resize_file(path, fs::file_size(path) - 1);
    EXPECT_EQ(glass_block(8, 100, MPI_COMM_WORLD, nullptr), made); // made again, same seed
    EXPECT_TRUE(read_glass_cache(path, 8, 100).has_value());       // and the file replaced
    ::unsetenv("EXASPH_GLASS_DIR");
    fs::remove_all(dir);
}
