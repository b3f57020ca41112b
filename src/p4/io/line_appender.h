// A run's append-only text file (trajectory.csv, detections.csv, events.jsonl) that a crash
// leaves whole: each Append is one write(2) of whole lines, so a kill -9 stops between rows,
// never inside one (a power cut may still tear the last: resuming drops it, readers skip it).
//
// Resuming (track --resume): the run is made again from its start and is deterministic, so the
// lines it appends are checked against those already in the file until they run out, and only
// the rest is written: the file ends as an uninterrupted run's would. A line that differs is an
// error (another P4, other options, other sources).
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>

namespace p4 {

class LineAppender {
 public:
  // Creates (truncates) `path`; with `resume`, opens it as it is, its incomplete last line (if
  // any) dropped. Throws p4::Error naming the file.
  LineAppender(const std::string& path, bool resume);
  ~LineAppender();
  LineAppender(const LineAppender&) = delete;
  LineAppender& operator=(const LineAppender&) = delete;

  // Appends whole lines ('\n' after each). Throws p4::Error naming the file on a write failure
  // or, when resuming, on a line that differs from the one already there.
  void Append(std::string_view lines);

  // Resuming: lines found again so far, and whether the file's own lines have all been found.
  int64_t lines_found() const { return found_; }
  bool caught_up() const { return !existing_.is_open(); }
  const std::string& path() const { return path_; }

 private:
  void Write(std::string_view bytes);

  std::string path_;
  int fd_ = -1;
  std::ifstream existing_;  // resuming: the lines to find again
  int64_t found_ = 0;
};

}  // namespace p4
