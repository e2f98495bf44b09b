// core/file_io.hpp: readers that take regular files only, with a cap; outputs written
// together or not at all, replacing only regular files; stale temporaries removed.
#include "asperity/core/file_io.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "asperity/core/error.hpp"

namespace {

namespace fs = std::filesystem;
using asperity::InvalidInput;
using namespace asperity::core;

struct TempDir {
  fs::path path;
  TempDir() {
    std::string t = (fs::temp_directory_path() / "asperity-file-io-XXXXXX").string();
    path = mkdtemp(t.data());
  }
  ~TempDir() { fs::remove_all(path); }
};

std::string slurp(const fs::path& p) {
  return read_input_file(p.string(), 1 << 20, "the output");
}

std::string message_of(const auto& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(ReadInputFile, RegularFilesOnlyWithinTheCap) {
  TempDir d;
  const auto f = d.path / "a.txt";
  std::ofstream(f) << "hello";
  EXPECT_EQ(read_input_file(f.string(), 5, "the file"), "hello");
  EXPECT_NE(message_of([&] {
              (void)read_input_file(f.string(), 4, "the file");
            }).find("is 5 bytes, more than the 4 bytes this reader accepts"),
            std::string::npos);
  EXPECT_NE(message_of([&] {
              (void)read_input_file(d.path.string(), 100, "the case file");
            }).find("the case file is not a regular file (it is a directory)"),
            std::string::npos);
  EXPECT_NE(message_of([] {
              (void)read_input_file("/dev/zero", 100, "the file");
            }).find("not a regular file (it is a character device)"),
            std::string::npos);
  EXPECT_NE(message_of([&] {
              (void)read_input_file((d.path / "none").string(), 9, "the file");
            }).find("No such file or directory"),
            std::string::npos);
}

TEST(RequireUtf8, AcceptsUtf8AndNamesTheFirstBadByte) {
  EXPECT_NO_THROW(require_utf8("a = \"\xC2\xB5m \xE2\x80\x93 \xF0\x9F\x98\x80\"\n", "f", "x"));
  for (const char* bad : {"\xC0\xAF", "\xED\xA0\x80", "\xF4\x90\x80\x80", "\xE2\x80", "\xFF"}) {
    const std::string text = std::string("ok\nab") + bad;
    EXPECT_NE(message_of([&] {
                require_utf8(text, "f.toml", "the case file");
              }).find("f.toml:2:3: the case file is not valid UTF-8"),
              std::string::npos)
        << bad;
  }
}

TEST(OutputSet, AllOrNothing) {
  TempDir d;
  const auto a = d.path / "a.csv", b = d.path / "b.csv";
  {
    OutputSet set;
    set.add(a.string(), "1\n");
    set.add(b.string(), "2\n");
    EXPECT_FALSE(fs::exists(a));  // nothing in place before commit()
  }
  EXPECT_TRUE(fs::is_empty(d.path));  // destroyed uncommitted: temporaries removed
  {
    OutputSet set;
    set.add(a.string(), "1\n");
    EXPECT_THROW(set.add((d.path / "missing" / "b.csv").string(), "2\n"), InvalidInput);
  }
  EXPECT_TRUE(fs::is_empty(d.path));
  OutputSet set;
  set.add(a.string(), "1\n");
  set.add(b.string(), "2\n");
  set.commit();
  EXPECT_EQ(slurp(a), "1\n");
  EXPECT_EQ(slurp(b), "2\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(d.path), fs::directory_iterator{}), 2);
}

TEST(OutputSet, ReplacesOnlyRegularFiles) {
  TempDir d;
  write_output_file("/dev/null", "written through, not replaced");
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_NE(message_of([&] { write_output_file(d.path.string(), "x"); }).find("is a directory"),
            std::string::npos);
  std::ofstream(d.path / "real.csv") << "old";
  fs::create_symlink("real.csv", d.path / "link.csv");
  write_output_file((d.path / "link.csv").string(), "new");
  EXPECT_TRUE(fs::is_symlink(d.path / "link.csv"));
  EXPECT_EQ(slurp(d.path / "real.csv"), "new");
  fs::create_symlink("nowhere.csv", d.path / "dangling.csv");
  EXPECT_NE(message_of([&] {
              write_output_file((d.path / "dangling.csv").string(), "x");
            }).find("symbolic link to nothing"),
            std::string::npos);
  EXPECT_NE(message_of([] {
              write_output_file("/dev/full", "x");
            }).find("cannot write \"/dev/full\": No space left on device"),
            std::string::npos);
}

TEST(StaleTemporaries, OnlyThoseOfGoneProcessesAndEarlierVersions) {
  TempDir d;
  const pid_t child = fork();
  if (child == 0) _exit(0);
  waitpid(child, nullptr, 0);  // a PID that no longer runs
  const std::string gone = ".f.csv.tmp-" + std::to_string(child) + "-deadbeef";
  const std::string live = ".f.csv.tmp-" + std::to_string(getpid()) + "-0badf00d";
  const std::string earlier = ".f.csv.tmp-0123abcd";
  const std::string other = ".g.csv.tmp-" + std::to_string(child) + "-deadbeef";
  for (const auto& n : {gone, live, earlier, other}) std::ofstream(d.path / n) << "partial";
  EXPECT_EQ(remove_stale_temporaries(d.path / "f.csv"), 2u);
  EXPECT_FALSE(fs::exists(d.path / gone));
  EXPECT_FALSE(fs::exists(d.path / earlier));
  EXPECT_TRUE(fs::exists(d.path / live));   // a running process's (this one)
  EXPECT_TRUE(fs::exists(d.path / other));  // another target's
}

}  // namespace
