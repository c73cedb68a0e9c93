#include "scenarios/output.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

namespace fognav::scenarios {
namespace {

std::string Read(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// a fresh folder of its own under the test's temporary folder
std::filesystem::path Folder(const std::string& name) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(Output, WritesTheWholeTextAndLeavesNoTemporaryFile) {
  const auto dir = Folder("output_whole");
  WriteFileAtomically((dir / "report.json").string(), "{\"success\": false}\n");
  WriteFileAtomically((dir / "report.json").string(), "{\"success\": true}\n");
  EXPECT_EQ(Read(dir / "report.json"), "{\"success\": true}\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "report.json.tmp"));
}

// A full disk (the temporary file is /dev/full): an OutputError naming the file and why, the
// old file as it was and no temporary file left
TEST(Output, FullDiskKeepsTheOldFile) {
  const auto dir = Folder("output_full");
  const std::string path = (dir / "report.json").string();
  std::ofstream(path) << "old";
  std::filesystem::create_symlink("/dev/full", path + ".tmp");
  try {
    WriteFileAtomically(path, std::string(100000, 'x'));
    FAIL() << "no error";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot write: No space left on device");
  }
  EXPECT_EQ(Read(path), "old");
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(path + ".tmp")));
}

// A folder that takes no files (as a read-only one; /proc/self refuses even root) and one that
// cannot be created
TEST(Output, UnwritableFolderIsAnOutputErrorNamingTheFile) {
  try {
    WriteFileAtomically("/proc/self/report.json", "{}");
    FAIL() << "no error";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()).find("/proc/self/report.json: cannot write: "), 0u) << e.what();
  }
  try {
    MakeOutputFolder("/proc/self/out");
    FAIL() << "no error";
  } catch (const OutputError& e) {
    EXPECT_EQ(std::string(e.what()).find("/proc/self/out: cannot create the output folder: "), 0u)
        << e.what();
  }
}

}  // namespace
}  // namespace fognav::scenarios
