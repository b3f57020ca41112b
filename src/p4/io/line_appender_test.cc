#include "p4/io/line_appender.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "p4/core/error.h"
#include "p4/io/csv.h"
#include "p4/io/event_files.h"

namespace p4 {
namespace {

namespace fs = std::filesystem;

std::string Slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path Temp(const std::string& name) { return fs::temp_directory_path() / ("p4_" + name); }

// A run made again after a crash: the lines already there are found, the torn one dropped, the
// rest appended; the file ends as an uninterrupted run's.
TEST(LineAppender, ResumingFindsTheLinesThereDropsATornOneAndAppendsTheRest) {
  const fs::path path = Temp("appender_resume.csv");
  {
    LineAppender a(path.string(), false);
    a.Append("h\n");
    a.Append("1,2\n2,3\n");
  }
  {
    std::ofstream torn(path, std::ios::app | std::ios::binary);
    torn << "3,";  // a row cut short
  }
  LineAppender b(path.string(), true);
  EXPECT_FALSE(b.caught_up());
  b.Append("h\n");
  b.Append("1,2\n2,3\n3,4\n");  // two found, one new in the same call
  EXPECT_EQ(b.lines_found(), 3);
  EXPECT_TRUE(b.caught_up());
  b.Append("4,5\n");
  EXPECT_EQ(Slurp(path), "h\n1,2\n2,3\n3,4\n4,5\n");
  fs::remove(path);
}

TEST(LineAppender, ALineThatDiffersIsAnErrorNamingTheFileAndLine) {
  const fs::path path = Temp("appender_differs.csv");
  {
    LineAppender a(path.string(), false);
    a.Append("h\n1,2\n");
  }
  LineAppender b(path.string(), true);
  b.Append("h\n");
  try {
    b.Append("1,3\n");
    ADD_FAILURE() << "a different line was taken";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    EXPECT_NE(what.find("line 2"), std::string::npos) << what;
  }
  // A new file (or resuming where there was none) starts empty.
  LineAppender c(Temp("appender_new.csv").string(), true);
  EXPECT_TRUE(c.caught_up());
  c.Append("x\n");
  EXPECT_EQ(Slurp(Temp("appender_new.csv")), "x\n");
  fs::remove(path);
  fs::remove(Temp("appender_new.csv"));
}

// Readers skip a last row torn by a crash, but not a malformed row elsewhere.
TEST(LineAppender, ReadersSkipATornLastRowOnly) {
  const fs::path csv = Temp("torn.csv");
  {
    std::ofstream f(csv);
    f << "a,b,c\n1,2,3\n4,5";
  }
  EXPECT_EQ(ReadCsv(csv.string(), "a,b,c").size(), 1u);
  {
    std::ofstream f(csv);
    f << "a,b,c\n1,2\n4,5,6\n";
  }
  EXPECT_THROW(ReadCsv(csv.string(), "a,b,c"), Error);
  const fs::path events = Temp("torn.jsonl");
  {
    std::ofstream f(events);
    f << R"({"t":1.0,"type":"bounce","x":0.5,"y":0.2,"z":0.0,"confidence":0.9})" << '\n'
      << R"({"t":1.2,"type":"bou)";
  }
  EXPECT_EQ(ReadEventsJsonl(events.string()).size(), 1u);
  fs::remove(csv);
  fs::remove(events);
}

}  // namespace
}  // namespace p4
