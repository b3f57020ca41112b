// Union-find over run-length runs (paper §3.1): the root of a run with path compression, and the
// union of two runs' sets (the smaller index becomes the root). Internal to p4_segment.
#pragma once

#include <vector>

#include "p4/segment/blob_finder.h"

namespace p4::segment::internal {

inline int FindRoot(std::vector<Run>& runs, int i) {
  int root = i;
  while (runs[root].parent != root) root = runs[root].parent;
  while (runs[i].parent != root) {  // path compression
    const int next = runs[i].parent;
    runs[i].parent = root;
    i = next;
  }
  return root;
}

inline void Unite(std::vector<Run>& runs, int a, int b) {
  a = FindRoot(runs, a);
  b = FindRoot(runs, b);
  if (a == b) return;
  if (a < b) {
    runs[b].parent = a;
  } else {
    runs[a].parent = b;
  }
}

// Joins the runs [row_begin, end) of a row with the touching runs [above_begin, above_end) of the
// row above (8-connected). Runs of each row are in increasing x.
inline void JoinWithRowAbove(std::vector<Run>& runs, std::size_t above_begin, std::size_t above_end,
                             std::size_t row_begin) {
  std::size_t above = above_begin;
  for (std::size_t r = row_begin; r < runs.size(); ++r) {
    while (above < above_end && runs[above].x1 < runs[r].x0) ++above;
    for (std::size_t a = above; a < above_end && runs[a].x0 <= runs[r].x1; ++a) {
      Unite(runs, static_cast<int>(a), static_cast<int>(r));
    }
  }
}

}  // namespace p4::segment::internal
