#include "p4/track/flight_check.h"

#include <algorithm>
#include <cmath>

#include "p4/core/table.h"

namespace p4::track {
namespace {

constexpr double kStepS = 0.0025;  // integration step of a side's flight

bool Measured(const FrameSetResult& r) { return r.measurement.has_value() && !r.tentative; }
// A measured row of the flights the check judges: not one placed on a short flight between two
// contacts (TrackedState::between_contacts), which neither side's flight holds.
bool Judged(const FrameSetResult& r) {
  return Measured(r) && !(r.state && r.state->between_contacts);
}

// Position and velocity at times[0] (relative times dt[k]) of the rows, under the model's
// gravity and the drag of their mean velocity; *rms: the rows' 3D RMS residual.
Vector6d FitSide(const std::vector<double>& dt, const std::vector<Eigen::Vector3d>& p,
                 const FlightModel& model, double* rms) {
  const int n = static_cast<int>(dt.size());
  Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
  for (double d : dt) normal += Eigen::Vector2d(1.0, d) * Eigen::RowVector2d(1.0, d);
  const Eigen::Matrix2d inverse = normal.inverse();
  const auto line = [&](const Eigen::Vector3d& accel, Eigen::Vector3d* p0, Eigen::Vector3d* v0) {
    Eigen::Matrix<double, 2, 3> rhs = Eigen::Matrix<double, 2, 3>::Zero();
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d q = p[k] - 0.5 * dt[k] * dt[k] * accel;
      rhs.row(0) += q.transpose();
      rhs.row(1) += dt[k] * q.transpose();
    }
    const Eigen::Matrix<double, 2, 3> solution = inverse * rhs;
    *p0 = solution.row(0).transpose();
    *v0 = solution.row(1).transpose();
  };
  Eigen::Vector3d p0, v0;
  line(Eigen::Vector3d(0.0, 0.0, -model.gravity), &p0, &v0);
  const Eigen::Vector3d accel =
      Eigen::Vector3d(0.0, 0.0, -model.gravity) - model.drag_per_mass * v0.norm() * v0;
  line(accel, &p0, &v0);
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    sum += (p0 + dt[k] * v0 + 0.5 * dt[k] * dt[k] * accel - p[k]).squaredNorm();
  }
  *rms = std::sqrt(sum / n);
  Vector6d x;
  x << p0, v0;
  return x;
}

// The state x carried by h seconds (either sign) under gravity and drag, reflected where its
// centre meets the table top (going back in time, the bounce undone).
Vector6d Carry(Vector6d x, double h, const FlightModel& model) {
  const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(h) / kStepS)));
  const double step = h / steps;
  const double r = model.ball_radius;
  for (int s = 0; s < steps; ++s) {
    const double z_before = x(2);
    x = DragStep(x, step, model.gravity, model.drag_per_mass);
    if (x(2) < r && z_before >= r && table::OnSurface(x(0), x(1))) {
      x(2) = 2.0 * r - x(2);
      if (step > 0.0) {
        x = BounceMatrix(x, model.restitution, model.friction) * x;
      } else {  // x's velocity is the one after the bounce: the one before, undone
        Vector6d before = x;
        before(5) = -x(5) / model.restitution;
        const Matrix6d d = BounceMatrix(before, model.restitution, model.friction);
        for (int k = 3; k < 6; ++k) x(k) /= d(k, k);
      }
    }
  }
  return x;
}

}  // namespace

bool FlightCheckOptions::IsValid(std::string* error) const {
  if (!(horizon_s > 0.0) || side_rows < 2 || min_side_rows < 2 || min_side_rows > side_rows) {
    if (error) *error = "flight check: horizon_s > 0 and 2 <= min_side_rows <= side_rows";
    return false;
  }
  if (!(side_rms_m > 0.0) || !(offset_m >= 0.0) || !(model_accel >= 0.0)) {
    if (error) *error = "flight check: side_rms_m > 0, offset_m and model_accel >= 0";
    return false;
  }
  return true;
}

FlightCheck::FlightCheck(const FlightCheckOptions& options)
    : options_(options), horizon_(FromSeconds(options.horizon_s)) {}

std::vector<FlightCheck::Row> FlightCheck::SideRows(int i, int direction,
                                                    bool skip_suspects) const {
  std::vector<Row> rows;
  const TimeNs t = held_[i].result.t;
  const auto take = [&](TimeNs ti, const Eigen::Vector3d& p) {
    if (std::abs(ti - t) > horizon_) return false;
    rows.push_back({ti, p});
    return static_cast<int>(rows.size()) < options_.side_rows;
  };
  const int n = static_cast<int>(held_.size());
  for (int j = i + direction; j >= 0 && j < n; j += direction) {
    const Held& h = held_[j];
    if (!Judged(h.result) || (skip_suspects && h.score > 1.0)) continue;
    if (!take(h.result.t, h.result.measurement->position)) return rows;
  }
  if (direction < 0) {
    for (auto it = past_.rbegin(); it != past_.rend(); ++it) {
      if (!take(it->t, it->position)) return rows;
    }
  }
  return rows;
}

void FlightCheck::Score(int i, bool skip_suspects) {
  Held& held = held_[i];
  held.score = 0.0;
  const Eigen::Vector3d& p = held.result.measurement->position;
  double nearest = 0.0;
  for (int direction : {-1, 1}) {
    const std::vector<Row> rows = SideRows(i, direction, skip_suspects);
    if (static_cast<int>(rows.size()) < options_.min_side_rows) continue;
    std::vector<double> dt;
    std::vector<Eigen::Vector3d> positions;
    for (const Row& r : rows) {
      dt.push_back(ToSeconds(r.t - rows[0].t));
      positions.push_back(r.position);
    }
    double rms = 0.0;
    const Vector6d side = FitSide(dt, positions, options_.model, &rms);
    if (rows.size() >= 3 && rms > options_.side_rms_m) continue;
    const double h = ToSeconds(held.result.t - rows[0].t);
    const Vector6d at = Carry(side, h, options_.model);
    const double allowed = options_.offset_m + 0.5 * options_.model_accel * h * h;
    const double ratio = (at.head<3>() - p).norm() / allowed;
    // Kept when one side agrees: the score is the least ratio, the flight the nearer side's.
    if (held.score == 0.0 || ratio < held.score) held.score = std::max(ratio, 1e-12);
    if (nearest == 0.0 || std::abs(h) < nearest) {
      nearest = std::abs(h);
      held.on_flight = at;
    }
  }
}

void FlightCheck::Judge(TimeNs newest, bool all) {
  const int n = static_cast<int>(held_.size());
  for (int i = 0; i < n; ++i) {
    Held& h = held_[i];
    if (h.judged || !Judged(h.result) || (!all && h.result.t + horizon_ > newest)) continue;
    h.judged = true;
    Score(i, false);
  }
  while (true) {
    int worst = -1;
    for (int i = 0; i < n; ++i) {
      const Held& h = held_[i];
      if (!h.judged || !Judged(h.result) || h.score <= 1.0) continue;
      if (!all && h.result.t + 2 * horizon_ > newest) continue;
      if (worst < 0 || h.score > held_[worst].score) worst = i;
    }
    if (worst < 0) return;
    // Judged again without the other rows under suspicion: a wrong row just after a good one
    // must not take the good one with it.
    Score(worst, true);
    if (held_[worst].score <= 1.0) continue;
    FrameSetResult& r = held_[worst].result;
    ClearMeasurement(&r);
    if (r.state) {
      r.state->position = held_[worst].on_flight.head<3>();
      r.state->velocity = held_[worst].on_flight.tail<3>();
      r.state->residual_px = 0.0;
    }
    held_[worst].score = 0.0;
    ++dropped_;
    DropUnconfirmedStates(worst);
    for (int i = 0; i < n; ++i) {
      Held& h = held_[i];
      if (h.judged && Judged(h.result) && std::abs(h.result.t - r.t) <= horizon_) Score(i, false);
    }
  }
}

void FlightCheck::DropUnconfirmedStates(int i) {
  const int n = static_cast<int>(held_.size());
  const auto has_state = [&](int j) { return held_[j].result.state.has_value(); };
  int after = i + 1;  // the next measured row in the run (n or a row without a state: none)
  while (after < n && has_state(after) && !Measured(held_[after].result)) ++after;
  int before = i - 1;  // the last measured row before it in the run (-1 or stateless: none)
  while (before >= 0 && has_state(before) && !Measured(held_[before].result)) --before;
  const bool measured_after = after < n && has_state(after);
  // Past held_'s start the run goes on among the released rows.
  const bool measured_before = before >= 0 ? has_state(before) : released_run_measured_;
  if (measured_after && measured_before) return;  // a gap between two sightings: a row
  // No sighting after it: its state and the coast before it from the last sighting, to the
  // run's end. No sighting before it: from the run's start to the next sighting.
  const int from = before + 1;  // (held_[before], when there is one, is measured or stateless)
  int to = after;
  if (!measured_after) {
    while (to < n && has_state(to)) ++to;
  }
  for (int j = from; j < to; ++j) {
    if (!Measured(held_[j].result)) held_[j].result.state.reset();
  }
}

std::vector<FrameSetResult> FlightCheck::Push(FrameSetResult result) {
  const TimeNs newest = result.t;
  held_.push_back({std::move(result)});
  Judge(newest, false);
  std::vector<FrameSetResult> out;
  while (!held_.empty() && held_.front().result.t + 2 * horizon_ <= newest) {
    FrameSetResult& r = held_.front().result;
    if (Judged(r)) past_.push_back({r.t, r.measurement->position});
    released_run_measured_ = r.state && (released_run_measured_ || Measured(r));
    out.push_back(std::move(r));
    held_.pop_front();
  }
  if (!held_.empty()) {
    const TimeNs oldest = held_.front().result.t;
    while (!past_.empty() && oldest - past_.front().t > horizon_) past_.pop_front();
  }
  return out;
}

std::vector<FrameSetResult> FlightCheck::Flush() {
  Judge(0, true);
  std::vector<FrameSetResult> out;
  for (Held& h : held_) out.push_back(std::move(h.result));
  held_.clear();
  past_.clear();
  return out;
}

}  // namespace p4::track
