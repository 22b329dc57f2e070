// Atomic file replacement and whole-file reads.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/scratch_folder.hpp"
#include "util/atomic_file.hpp"

namespace sandtin {
namespace {

namespace fs = std::filesystem;

class AtomicFile : public test::ScratchFolderTest {
  protected:
    AtomicFile() : ScratchFolderTest("atomic") {}

    static std::vector<std::uint8_t> pattern(std::size_t n, std::uint8_t seed) {
        std::vector<std::uint8_t> v(n);
        for (std::size_t i = 0; i < n; ++i)
            v[i] = static_cast<std::uint8_t>(seed + i * 31 + (i >> 8));
        return v;
    }
};

TEST_F(AtomicFile, WriteThenReadBack) {
    const fs::path p = dir_ / "a.bin";
    for (std::size_t n :
         {std::size_t{0}, std::size_t{1}, std::size_t{4096}, (std::size_t{1} << 20) + 17}) {
        const auto data = pattern(n, static_cast<std::uint8_t>(n));
        write_file_atomically(p, data);
        EXPECT_EQ(read_file(p), data) << n;
        EXPECT_EQ(fs::file_size(p), n);
    }
    // Only the target remains: no temporaries left behind after successful writes.
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_))
        ++entries;
    EXPECT_EQ(entries, 1u);
}

TEST_F(AtomicFile, ReplacingKeepsTheFilesPermissionsAndANewFileFollowsTheUmask) {
    const fs::path p = dir_ / "private.bin";
    write_file_atomically(p, pattern(10, 1));
    fs::permissions(p, fs::perms::owner_read | fs::perms::owner_write);
    write_file_atomically(p, pattern(20, 2));
    EXPECT_EQ(fs::status(p).permissions(), fs::perms::owner_read | fs::perms::owner_write);
    fs::permissions(p, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                           fs::perms::group_write);
    write_file_atomically(p, pattern(30, 3));
    EXPECT_EQ(fs::status(p).permissions(), fs::perms::owner_read | fs::perms::owner_write |
                                               fs::perms::group_read | fs::perms::group_write);
    EXPECT_EQ(read_file(p), pattern(30, 3));
    // A new file: 0666 less the umask, as the shell's own files are.
    const mode_t mask = ::umask(027);
    write_file_atomically(dir_ / "new.bin", pattern(5, 4));
    ::umask(mask);
    EXPECT_EQ(fs::status(dir_ / "new.bin").permissions(),
              fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
}

TEST_F(AtomicFile, SavingThroughALinkUpdatesTheFileItPointsTo) {
    fs::create_directories(dir_ / "shared");
    const fs::path real = dir_ / "shared" / "scene.bin";
    write_file_atomically(real, pattern(10, 1));
    fs::create_symlink(fs::path("shared") / "scene.bin", dir_ / "link.bin");  // relative
    fs::create_symlink(dir_ / "link.bin", dir_ / "link2.bin");                // a chain
    write_file_atomically(dir_ / "link2.bin", pattern(40, 7));
    EXPECT_TRUE(fs::is_symlink(dir_ / "link.bin"));
    EXPECT_TRUE(fs::is_symlink(dir_ / "link2.bin"));
    EXPECT_EQ(read_file(real), pattern(40, 7));
    // A dangling link: the file is created where it points.
    fs::create_symlink(fs::path("shared") / "new.bin", dir_ / "dangling.bin");
    write_file_atomically(dir_ / "dangling.bin", pattern(3, 9));
    EXPECT_TRUE(fs::is_symlink(dir_ / "dangling.bin"));
    EXPECT_EQ(read_file(dir_ / "shared" / "new.bin"), pattern(3, 9));
    // A loop of links is an error naming the path, not a hang.
    fs::create_symlink(dir_ / "loop-b", dir_ / "loop-a");
    fs::create_symlink(dir_ / "loop-a", dir_ / "loop-b");
    try {
        write_file_atomically(dir_ / "loop-a", pattern(3, 9));
        ADD_FAILURE() << "a loop of links was written through";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("loop-a"), std::string::npos) << e.what();
    }
}

TEST_F(AtomicFile, CheckWritableNamesWhatStandsInTheWay) {
    const auto message = [](const fs::path& p) -> std::string {
        try {
            check_writable(p);
        } catch (const std::runtime_error& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(message(dir_ / "fine.bin"), "");
    EXPECT_FALSE(fs::exists(dir_ / "fine.bin"));  // asking writes nothing
    EXPECT_NE(message(dir_ / "missing" / "x.bin").find("does not exist"), std::string::npos);
    write_file_atomically(dir_ / "plain", pattern(1, 1));
    EXPECT_NE(message(dir_ / "plain" / "x.bin").find("is not a folder"), std::string::npos);
    fs::create_directories(dir_ / "sub");
    EXPECT_NE(message(dir_ / "sub").find("it is a folder"), std::string::npos);
    // Through a link, the folder that counts is the one the link leads to.
    fs::create_symlink(dir_ / "missing" / "x.bin", dir_ / "link.bin");
    EXPECT_NE(message(dir_ / "link.bin").find("does not exist"), std::string::npos);
}

TEST_F(AtomicFile, InterruptedWriteKeepsTheOldContent) {
    const fs::path p = dir_ / "b.bin";
    const auto old_data = pattern(1000, 1);
    write_file_atomically(p, old_data);
    const auto new_data = pattern(3u << 20, 2);
    std::size_t calls = 0;
    try {
        write_file_atomically(p, new_data, [&](std::size_t written) {
            ++calls;
            return written < (std::size_t{1} << 20);
        });
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("interrupted"), std::string::npos) << e.what();
    }
    EXPECT_EQ(calls, 1u);
    EXPECT_EQ(read_file(p), old_data);
    // A new file whose first save is interrupted never appears.
    const fs::path q = dir_ / "c.bin";
    EXPECT_THROW(write_file_atomically(q, old_data, [](std::size_t) { return false; }),
                 std::runtime_error);
    EXPECT_FALSE(fs::exists(q));
}

TEST_F(AtomicFile, ErrorsNameThePath) {
    const fs::path missing_dir = dir_ / "no" / "such" / "dir" / "x.bin";
    try {
        write_file_atomically(missing_dir, pattern(10, 3));
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("x.bin"), std::string::npos) << e.what();
    }
    try {
        (void)read_file(dir_ / "absent.bin");
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("absent.bin"), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)read_file(dir_), std::runtime_error);
}

TEST_F(AtomicFile, DevicesPipesAndFoldersAreRefusedAndLeftInPlace) {
    // A save renames its temporary over the target: over a device or a pipe that would delete
    // it (as root, `-o /dev/null` replaced the system's). They are refused, and stay.
    const fs::path fifo = dir_ / "pipe.stl";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::vector<fs::path> special{fifo};
    // A character device like /dev/null's (1, 3) needs root; without it the pipe stands alone.
    const fs::path device = dir_ / "null.sandtin";
    if (::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) special.push_back(device);
    fs::create_directories(dir_ / "folder.sandtin");
    special.push_back(dir_ / "folder.sandtin");
    // Through a link too: what counts is what the link leads to.
    fs::create_symlink(fifo, dir_ / "link.stl");
    special.push_back(dir_ / "link.stl");
    for (const fs::path& p : special) {
        for (const bool ask_first : {true, false}) {
            try {
                if (ask_first) {
                    check_writable(p);
                } else {
                    write_file_atomically(p, pattern(10, 5));
                }
                ADD_FAILURE() << p << " was accepted";
            } catch (const std::runtime_error& e) {
                const std::string m = e.what();
                EXPECT_NE(m.find(p.string()), std::string::npos) << m;
                EXPECT_NE(m.find("only replaces regular files"), std::string::npos) << m;
            }
        }
    }
    EXPECT_TRUE(fs::is_fifo(fifo));
    EXPECT_TRUE(fs::is_symlink(dir_ / "link.stl"));
    EXPECT_TRUE(fs::is_directory(dir_ / "folder.sandtin"));
    if (special.size() == 4) {
        EXPECT_TRUE(fs::is_character_file(device));
    }
    // Nothing was left behind: the pipe, the link, the folder and perhaps the device only.
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_))
        ++entries;
    EXPECT_EQ(entries, special.size());
    // Reading one says what it is rather than that it does not exist.
    try {
        (void)read_file(fifo);
        ADD_FAILURE() << "a pipe was read";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
}

TEST_F(AtomicFile, ALongButLegalNameCanBeSaved) {
    // 250 bytes: legal (the limit is 255), though the temporary beside it must not add a
    // prefix and a suffix to all of it.
    const fs::path p = dir_ / (std::string(242, 'f') + ".sandtin");
    ASSERT_EQ(p.filename().string().size(), 250u);
    write_file_atomically(p, pattern(100, 6));
    EXPECT_EQ(read_file(p), pattern(100, 6));
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_))
        ++entries;
    EXPECT_EQ(entries, 1u);
}

TEST_F(AtomicFile, FilesSavedTogetherChangeNothingWhenOneCannotBeWritten) {
    // A mesh and its material and textures: when the last cannot be written, the others keep
    // their old content and no temporary is left.
    const fs::path a = dir_ / "m.obj", b = dir_ / "m.mtl";
    write_file_atomically(a, pattern(10, 1));
    write_file_atomically(b, pattern(20, 2));
    const auto new_a = pattern(30, 3), new_b = pattern(40, 4), new_c = pattern(50, 5);
    const auto entries = [&] {
        std::size_t n = 0;
        for ([[maybe_unused]] const auto& e : fs::recursive_directory_iterator(dir_))
            ++n;
        return n;
    };
    // Its folder is missing: the temporaries of the first two were already written.
    const std::vector<FileToWrite> missing{
        {a, new_a}, {b, new_b}, {dir_ / "no" / "m_albedo.png", new_c}};
    EXPECT_THROW(write_files_atomically(missing), std::runtime_error);
    EXPECT_EQ(read_file(a), pattern(10, 1));
    EXPECT_EQ(read_file(b), pattern(20, 2));
    EXPECT_EQ(entries(), 2u);
    // A folder in its place: refused before anything is written.
    fs::create_directories(dir_ / "m_normal.png");
    const std::vector<FileToWrite> blocked{{a, new_a}, {b, new_b}, {dir_ / "m_normal.png", new_c}};
    EXPECT_THROW(write_files_atomically(blocked), std::runtime_error);
    EXPECT_EQ(read_file(a), pattern(10, 1));
    EXPECT_EQ(read_file(b), pattern(20, 2));
    EXPECT_EQ(entries(), 3u);
    // All writable: all replaced.
    const std::vector<FileToWrite> fine{{a, new_a}, {b, new_b}, {dir_ / "m_albedo.png", new_c}};
    write_files_atomically(fine);
    EXPECT_EQ(read_file(a), new_a);
    EXPECT_EQ(read_file(b), new_b);
    EXPECT_EQ(read_file(dir_ / "m_albedo.png"), new_c);
    EXPECT_EQ(entries(), 4u);
}

TEST_F(AtomicFile, ReadRefusesFilesAboveTheLimit) {
    const fs::path p = dir_ / "big.bin";
    write_file_atomically(p, pattern(5000, 4));
    EXPECT_THROW((void)read_file(p, 4999), std::runtime_error);
    EXPECT_EQ(read_file(p, 5000).size(), 5000u);
}

}  // namespace
}  // namespace sandtin
