// `calibrate table` on real data: two phones (1280x720, 30 fps, focal length unknown) with six
// clicked table points each; their ball detections triangulated with the calibrated rig must put
// the bounces on the table.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "p4/calib/pose_from_points.h"
#include "p4/core/table.h"
#include "p4/geometry/triangulation.h"
#include "p4/io/calib_files.h"
#include "p4/io/csv.h"

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
