#include "p4/eval/findable.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "p4/core/table.h"
#include "p4/geometry/sphere_depth.h"

namespace p4 {

FindableCounter::FindableCounter(const Rig& rig, std::vector<TruthRow> truth,
                                 std::vector<std::vector<float>> visibility,
                                 const segment::BallColour& ball, double exposure_s,
                                 const FindableOptions& options)
    : rig_(rig),
      truth_(std::move(truth)),
      visibility_(std::move(visibility)),
      ball_(ball),
      exposure_s_(exposure_s),
      options_(options),
      searches_(rig.cameras.size()),
      finders_(rig.cameras.size()),
      found_(truth_.size(), std::vector<char>(rig.cameras.size(), 0)) {
  for (const Camera& camera : rig_.cameras) {
    backgrounds_.emplace_back(camera.width, camera.height, options_.background);
  }
}

bool FindableCounter::Seen(std::size_t row, int camera) const {
  if (!truth_[row].in_play) return false;
  if (row >= visibility_.size()) return true;
  const auto& shares = visibility_[row];
  return camera >= static_cast<int>(shares.size()) || shares[camera] >= options_.min_visibility;
}

void FindableCounter::Add(int camera, TimeNs t, const ImageView& image) {
  if (camera < 0 || camera >= rig_.size()) return;
  segment::BackgroundModel& background = backgrounds_[camera];
  if (background.width() != (image.width & ~1) || background.height() != (image.height & ~1)) {
    background = segment::BackgroundModel(image.width, image.height, options_.background);
  }
  // The finder runs on every frame (its "still" test remembers the last one).
  candidates_.clear();
  if (background.ready()) {
    finders_[camera].Find(image, background, ball_, options_.finder, &candidates_);
  }
  const double seconds = ToSeconds(t);
  const auto row = std::lower_bound(truth_.begin(), truth_.end(), seconds - 5e-4,
                                    [](const TruthRow& r, double s) { return r.t < s; });
  if (background.ready() && row != truth_.end() && std::abs(row->t - seconds) <= 5e-4) {
    const std::size_t k = static_cast<std::size_t>(row - truth_.begin());
    const Camera& cam = rig_.cameras[camera];
    const double depth = (cam.cam_from_world * row->position).z();
    const auto centre = cam.Project(row->position);
    // The image motion over the exposure, from the projections a millisecond either side.
    const double h = 1e-3;
    const auto a = cam.Project(row->position - h * row->velocity);
    const auto b = cam.Project(row->position + h * row->velocity);
    if (Seen(k, camera) && depth > 0.0 && centre && a && b) {
      const Eigen::Vector2d motion = (*b - *a) * (exposure_s_ / (2.0 * h));
      const Eigen::Vector2d direction =
          motion.norm() > 1e-9 ? Eigen::Vector2d(motion.normalized()) : Eigen::Vector2d::UnitX();
      const double diameter = SphereDiameterPx(cam, row->position, table::kBallRadius);
      const bool found =
          searches_[camera]
              .Find(image, background, ball_, centre->x(), centre->y(), direction.x(),
                    direction.y(), motion.norm(), diameter, options_.search)
              .has_value();
      const bool started = std::any_of(candidates_.begin(), candidates_.end(), [&](const auto& s) {
        return std::hypot(s.cx - centre->x(), s.cy - centre->y()) <=
               std::max(options_.finder_match_px, 0.5 * s.length_px);
      });
      found_[k][camera] = found ? (started ? 2 : 1) : 0;
    }
  }
  background.Update(image);
}

FindableReport FindableCounter::Report() const {
  FindableReport report;
  const int n = rig_.size();
  report.camera_seen.assign(n, 0);
  report.camera_found.assign(n, 0);
  report.camera_started.assign(n, 0);
  for (std::size_t k = 0; k < truth_.size(); ++k) {
    int seen = 0, found = 0, started = 0;
    for (int c = 0; c < n; ++c) {
      if (!Seen(k, c)) continue;
      ++seen, ++report.camera_seen[c];
      if (found_[k][c]) ++found, ++report.camera_found[c];
      if (found_[k][c] == 2) ++started, ++report.camera_started[c];
    }
    if (seen < options_.min_views) continue;
    ++report.frames_seen;
    if (found >= options_.min_views) ++report.frames_findable;
    if (started >= options_.min_views) ++report.frames_startable;
  }
  return report;
}

}  // namespace p4
