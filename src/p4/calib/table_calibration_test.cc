// `calibrate table` on real data: two phones (1280x720, 30 fps, focal length unknown) with six
// clicked table points each; their ball detections triangulated with the calibrated rig must put
// the bounces on the table.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "p4/calib/pose_from_points.h"
#include "p4/core/table.h"
#include "p4/geometry/triangulation.h"
#include "p4/io/calib_files.h"
#include "p4/io/csv.h"
#include "p4/sync/offset_search.h"

namespace p4::calib {
namespace {

const std::string kPhones = std::string(P4_SHARED_DATA) + "/detections/two_phones_30fps";

std::map<int, Eigen::Vector2d> Detections(const std::string& path) {
  std::map<int, Eigen::Vector2d> by_frame;
  const auto rows = ReadCsv(path, "frame,t,u,v");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    by_frame[static_cast<int>(CsvNumber(path, i, rows[i][0]))] = {CsvNumber(path, i, rows[i][2]),
                                                                  CsvNumber(path, i, rows[i][3])};
  }
  return by_frame;
}

std::vector<Camera> CalibratedPhones() {
  std::vector<Camera> cameras;
  for (int c = 0; c < 2; ++c) {
    const auto points =
        ReadPointMatches(kPhones + "/cam" + std::to_string(c) + "_table_points.csv");
    std::string error;
    const auto fit = SolvePoseAndFocal("cam" + std::to_string(c), 1280, 720, points, &error);
    EXPECT_TRUE(fit) << error;
    if (!fit) return {};
    std::printf("cam%d: f %.1f px, rms %.2f px, worst %.2f px\n", c, fit->camera.fx, fit->rms_px,
                fit->max_px);
    EXPECT_LT(fit->rms_px, 4.0);
    // Phones: 26-30 mm equivalent lenses, about 0.8-1.1 x the image width.
    EXPECT_GT(fit->camera.fx, 800.0);
    EXPECT_LT(fit->camera.fx, 1500.0);
    cameras.push_back(fit->camera);
  }
  return cameras;
}

struct Bounces {
  double median_abs_z = 0.0;  // m
  double on_table = 0.0;      // share inside the outline (+10 cm)
  double median_reprojection_px = 0.0;
  int count = 0;
};

// The bounces of the ball's 3D points by cam0's frame: local minima of z, falling then rising.
Bounces BouncesOf(const std::map<int, Eigen::Vector3d>& track, std::vector<double> residuals) {
  std::vector<double> z;
  int on_table = 0;
  for (const auto& [f, p] : track) {
    const auto a = track.find(f - 1), b = track.find(f + 1), a2 = track.find(f - 2),
               b2 = track.find(f + 2);
    if (a == track.end() || b == track.end() || a2 == track.end() || b2 == track.end()) continue;
    const bool falls = a2->second.z() > a->second.z() && a->second.z() > p.z();
    const bool rises = b2->second.z() > b->second.z() && b->second.z() > p.z();
    if (falls && rises && p.z() < 0.3 && std::abs(p.x()) < 2.0 && std::abs(p.y()) < 1.5) {
      z.push_back(std::abs(p.z()));
      on_table +=
          std::abs(p.x()) < table::kHalfLength + 0.1 && std::abs(p.y()) < 0.5 * table::kWidth + 0.1;
    }
  }
  Bounces b;
  b.count = static_cast<int>(z.size());
  if (z.empty()) return b;
  std::sort(z.begin(), z.end());
  std::sort(residuals.begin(), residuals.end());
  b.median_abs_z = z[z.size() / 2];
  b.on_table = static_cast<double>(on_table) / z.size();
  b.median_reprojection_px = residuals.empty() ? 0.0 : residuals[residuals.size() / 2];
  return b;
}

TEST(CalibrateTable, RealPhonesOffsetFoundFromTheBall) {
  // The phones' clocks found from the ball (p4_sync), sub-frame, against today's manual whole-
  // frame offset: the bounces must be at least as low and as much on the table.
  const auto cameras = CalibratedPhones();
  ASSERT_EQ(cameras.size(), 2u);
  const auto d0 = Detections(kPhones + "/cam0_detections.csv");
  const auto d1 = Detections(kPhones + "/cam1_detections.csv");
  std::vector<std::vector<sync::FrameCandidates>> frames(2);
  for (int c = 0; c < 2; ++c) {
    for (const auto& [f, px] : c == 0 ? d0 : d1) frames[c].push_back({f / 30.0, {px}});
  }
  const auto tracks0 = sync::LinkTracks(frames[0]), tracks1 = sync::LinkTracks(frames[1]);
  const sync::OffsetResult found = sync::FindOffset(cameras[0], tracks0, cameras[1], tracks1);
  ASSERT_TRUE(found.found) << found.why;
  std::printf("offset %+.5f s +- %.3f ms (%.2f frames), %d of %d points agree, %.2f px RMS\n",
              found.offset_s, 1e3 * found.sigma_s, found.offset_s * 30.0, found.agreements,
              found.points, found.rms_px);
  // The manual way: cam1's frame f + o with cam0's frame f, the o of the best median residual.
  const auto triangulate = [&](const Eigen::Vector2d& a,
                               const Eigen::Vector2d& b) -> std::optional<PointEstimate> {
    return TriangulateObservations(cameras, std::vector<Observation>{{0, a}, {1, b}});
  };
  int manual = 0;
  double manual_median = 1e9;
  for (int o = -5; o <= 5; ++o) {
    std::vector<double> residuals;
    for (const auto& [f, px] : d0) {
      const auto it = d1.find(f + o);
      if (it == d1.end()) continue;
      if (const auto p = triangulate(px, it->second)) residuals.push_back(p->mean_reprojection_px);
    }
    if (residuals.size() < 100) continue;
    std::nth_element(residuals.begin(), residuals.begin() + residuals.size() / 2, residuals.end());
    if (residuals[residuals.size() / 2] < manual_median) {
      manual_median = residuals[residuals.size() / 2], manual = o;
    }
  }
  // world = offset + stamp of cam1: its frame f + o at cam0's f is an offset of -o / 30.
  EXPECT_NEAR(found.offset_s, -manual / 30.0, 0.5 / 30.0);
  std::map<int, Eigen::Vector3d> whole, sub;
  std::vector<double> whole_res, sub_res;
  for (const auto& [f, px] : d0) {
    if (const auto it = d1.find(f + manual); it != d1.end()) {
      const auto p = triangulate(px, it->second);
      if (p && p->mean_reprojection_px < 3.0)
        whole[f] = p->point, whole_res.push_back(p->mean_reprojection_px);
    }
    // cam1 between its two frames around cam0's time.
    const double s = (f / 30.0 - found.offset_s) / found.rate * 30.0;
    const auto a = d1.find(static_cast<int>(std::floor(s))),
               b = d1.find(static_cast<int>(std::floor(s)) + 1);
    if (a == d1.end() || b == d1.end()) continue;
    const double w = s - std::floor(s);
    const auto p = triangulate(px, (1.0 - w) * a->second + w * b->second);
    if (p && p->mean_reprojection_px < 3.0)
      sub[f] = p->point, sub_res.push_back(p->mean_reprojection_px);
  }
  const Bounces m = BouncesOf(whole, whole_res), a = BouncesOf(sub, sub_res);
  std::printf(
      "manual frame offset %d: %d bounces, median |z| %.3f m, %.0f %% on the table, median "
      "reprojection %.2f px\nfound offset: %d bounces, median |z| %.3f m, %.0f %% on the "
      "table, median reprojection %.2f px\n",
      manual, m.count, m.median_abs_z, 100 * m.on_table, m.median_reprojection_px, a.count,
      a.median_abs_z, 100 * a.on_table, a.median_reprojection_px);
  ASSERT_GE(a.count, 5);
  EXPECT_LE(a.median_abs_z, m.median_abs_z + 0.005);
  EXPECT_GE(a.on_table, m.on_table - 0.05);
  EXPECT_LT(a.median_reprojection_px, m.median_reprojection_px);
}

TEST(CalibrateTable, RealPhonesPutTheBouncesOnTheTable) {
  const auto cameras = CalibratedPhones();
  ASSERT_EQ(cameras.size(), 2u);
  const auto d0 = Detections(kPhones + "/cam0_detections.csv");
  const auto d1 = Detections(kPhones + "/cam1_detections.csv");
  // The phones' frames are matched by index ("roughly synchronised"): pick the offset of cam1's
  // frames that makes the views agree best.
  int best_offset = 0;
  double best_median = 1e9;
  for (int offset = -5; offset <= 5; ++offset) {
    std::vector<double> residuals;
    for (const auto& [f, px] : d0) {
      const auto it = d1.find(f + offset);
      if (it == d1.end()) continue;
      const std::vector<Observation> obs{{0, px}, {1, it->second}};
      if (const auto p = TriangulateObservations(cameras, obs)) {
        residuals.push_back(p->mean_reprojection_px);
      }
    }
    if (residuals.size() < 100) continue;
    std::nth_element(residuals.begin(), residuals.begin() + residuals.size() / 2, residuals.end());
    if (residuals[residuals.size() / 2] < best_median) {
      best_median = residuals[residuals.size() / 2], best_offset = offset;
    }
  }
  std::printf("frame offset %d, median reprojection %.2f px\n", best_offset, best_median);
  // Points of consecutive frames; a bounce is a local minimum of z between frames where the ball
  // falls and then rises, over the table.
  std::map<int, Eigen::Vector3d> track;
  for (const auto& [f, px] : d0) {
    const auto it = d1.find(f + best_offset);
    if (it == d1.end()) continue;
    const std::vector<Observation> obs{{0, px}, {1, it->second}};
    const auto p = TriangulateObservations(cameras, obs);
    if (p && p->mean_reprojection_px < 3.0) track[f] = p->point;
  }
  std::vector<Eigen::Vector3d> bounces;
  for (const auto& [f, p] : track) {
    const auto a = track.find(f - 1), b = track.find(f + 1), a2 = track.find(f - 2),
               b2 = track.find(f + 2);
    if (a == track.end() || b == track.end() || a2 == track.end() || b2 == track.end()) continue;
    const bool falls = a2->second.z() > a->second.z() && a->second.z() > p.z();
    const bool rises = b2->second.z() > b->second.z() && b->second.z() > p.z();
    if (falls && rises && p.z() < 0.3 && std::abs(p.x()) < 2.0 && std::abs(p.y()) < 1.5) {
      bounces.push_back(p);
    }
  }
  std::printf("%zu frames triangulated, %zu bounces\n", track.size(), bounces.size());
  ASSERT_GE(bounces.size(), 5u);
  std::vector<double> z;
  int on_table = 0;
  for (const auto& p : bounces) {
    z.push_back(p.z());
    // The ball's centre at a bounce frame (30 fps: up to 33 ms from the contact) is within a few
    // centimetres of the surface, inside the outline with a margin for the same reason.
    on_table +=
        std::abs(p.x()) < table::kHalfLength + 0.1 && std::abs(p.y()) < 0.5 * table::kWidth + 0.1;
  }
  std::sort(z.begin(), z.end());
  const double median_z = z[z.size() / 2];
  std::printf("bounce z: median %.3f m, min %.3f, max %.3f; %d of %zu inside the outline\n",
              median_z, z.front(), z.back(), on_table, bounces.size());
  EXPECT_LT(std::abs(median_z), 0.06);
  EXPECT_GE(on_table, static_cast<int>(0.9 * bounces.size()));
}

}  // namespace
}  // namespace p4::calib
