#pragma once
// A test fixture with a folder of its own: <temp>/sandtin-<prefix>-<test name>-<pid>, emptied
// before each test and removed after it, so tests (and test processes run side by side by
// ctest -j) never see each other's files.

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>
#include <utility>

namespace sandtin::test {

class ScratchFolderTest : public ::testing::Test {
  protected:
    /// `prefix` names the suite in the folder's name.
    explicit ScratchFolderTest(std::string prefix) : prefix_(std::move(prefix)) {}

    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               ("sandtin-" + prefix_ + "-" + std::string(info->name()) + "-" +
                std::to_string(::getpid()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::filesystem::path dir_;  ///< the test's own folder

  private:
    std::string prefix_;
};

}  // namespace sandtin::test
