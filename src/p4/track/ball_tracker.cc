#include "p4/track/ball_tracker.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "p4/core/table.h"
#include "p4/track/flight_model.h"

namespace p4::track {

FlightModel FlightModelOf(const TrackerOptions& o) {
  FlightModel model;
  model.gravity = o.kalman.gravity;
  model.drag_per_mass = o.kalman.drag_per_mass;
  model.ball_radius = o.ball_radius;
  model.restitution = o.bounce_restitution;
  model.friction = o.bounce_friction;
  return model;
}

bool TrackerOptions::IsValid(std::string* error) const {
  if (!kalman.IsValid(error)) return false;
  if (!fall.IsValid(error)) return false;
  if (!(gate_chi2 > 0.0) || !(max_coast_s >= 0.0) || !(max_speed > 0.0)) {
    if (error) *error = "gate, coast time and speed must be positive";
    return false;
  }
  if (!(bounce_restitution > 0.0 && bounce_restitution <= 1.0)) {
    if (error) *error = "bounce restitution must be in (0, 1]";
    return false;
  }
  if (!(net_speed_kept >= -1.0 && net_speed_kept <= 1.0) || !(net_speed_sigma >= 0.0) ||
      !(net_side_sigma >= 0.0)) {
    if (error) *error = "net_speed_kept must be in [-1, 1], the net's sigmas >= 0";
    return false;
  }
  return true;
}

BallTracker::BallTracker(const TrackerOptions& options)
    : options_(options), filter_(options.kalman) {}

void BallTracker::PredictWithBounce(KalmanFilter* filter, double dt, const TrackerOptions& o) {
  const Vector6d& x = filter->state();
  const double r = o.ball_radius;
  // The ball meets the net's plane (x = 0) when its centre comes within r of it, from its side.
  if (o.net_model && std::abs(x(0)) > r && x(0) * x(3) < 0.0) {
    const double contact = (std::abs(x(0)) - r) / std::abs(x(3));  // s, drag neglected
    if (contact <= dt) {
      KalmanFilter at = *filter;
      PredictWithTable(&at, contact, o);
      const Vector6d& s = at.state();
      if (table::MeetsNet(s(1), s(2), r) && s(0) * x(0) > 0.0) {
        const double across = std::abs(s(3));
        Matrix6d d = Matrix6d::Identity();
        d.diagonal().tail<3>() = Eigen::Vector3d(o.net_speed_kept, 0.5, 0.5);
        Matrix6d unknown = Matrix6d::Zero();
        unknown.diagonal().tail<3>() = Eigen::Vector3d(std::max(1.0, o.net_speed_sigma * across),
                                                       o.net_side_sigma, o.net_side_sigma)
                                           .cwiseAbs2();
        at.Apply(d, unknown);
        PredictWithTable(&at, std::max(dt - contact, 1e-9), o);
        *filter = at;
        return;
      }
    }
  }
  PredictWithTable(filter, dt, o);
}

void BallTracker::PredictWithTable(KalmanFilter* filter, double dt, const TrackerOptions& o) {
  const Vector6d& x = filter->state();
  const double z0 = x(2) - o.ball_radius, vz = x(5), g = o.kalman.gravity;
  double hit = -1.0;
  if (o.bounce_model && z0 >= 0.0) {
    // z0 + vz t - g t^2 / 2 = 0, first positive root within the step.
    const double disc = vz * vz + 2.0 * g * z0;
    if (g > 0.0 && disc >= 0.0) {
      const double t = (vz + std::sqrt(disc)) / g;
      if (t >= 0.0 && t <= dt) hit = t;
    }
  }
  if (hit < 0.0) {
    filter->Predict(dt);
    return;
  }
  filter->Predict(std::max(hit, 1e-9));
  const Vector6d& at = filter->state();
  if (!table::OnSurface(at(0), at(1))) {  // passes beside the table: no bounce
    filter->Predict(dt - hit);
    return;
  }
  // Reflect at the table (restitution and friction), with more uncertainty for the spin.
  const Matrix6d d = BounceMatrix(at, o.bounce_restitution, o.bounce_friction);
  // Spin and friction change the velocity at the bounce in ways the model does not know.
  Matrix6d spin = Matrix6d::Zero();
  spin.diagonal().tail<3>() = Eigen::Vector3d(1.5, 1.0, 1.0).cwiseAbs2();
  filter->Apply(d, spin);
  filter->Predict(std::max(dt - hit, 1e-9));
}

void BallTracker::Start(TimeNs t, const Measurement& m, const Velocity& velocity) {
  Vector6d x;
  x << m.position, velocity.mean;
  Matrix6d p = Matrix6d::Zero();
  p.topLeftCorner<3, 3>() = m.covariance;
  p.bottomRightCorner<3, 3>() = velocity.covariance;
  filter_.Reset(x, p);
  Began(t);
}

void BallTracker::Began(TimeNs t) {
  tracking_ = true;
  ended_not_falling_ = false;
  last_t_ = last_update_t_ = last_fix_t_ = t;
  last_position_ = filter_.state().head<3>();
  pending_.reset();
  recent_.clear();
  ++restarts_;
  Record(t, nullptr);
}

void BallTracker::Record(TimeNs t, const KalmanFilter* prior, double innovation_chi2) {
  if (!(options_.history_s > 0.0)) return;
  FilterStep step;
  step.t = t;
  step.state = filter_.state();
  step.covariance = filter_.covariance();
  step.start = prior == nullptr;
  step.innovation_chi2 = innovation_chi2;
  if (prior) {
    step.prior_state = prior->state();
    step.prior_covariance = prior->covariance();
    step.transition = prior->transition();
  } else {
    step.prior_state = step.state;
    step.prior_covariance = step.covariance;
  }
  history_.push_back(step);
  const auto kept = std::find_if(history_.begin(), history_.end(), [&](const FilterStep& s) {
    return t - s.t <= FromSeconds(options_.history_s);
  });
  history_.erase(history_.begin(), kept);
}

std::optional<BallTracker::Velocity> BallTracker::PendingVelocity(TimeNs t,
                                                                  const Measurement& m) const {
  if (!pending_ || t - pending_->first >= FromSeconds(0.05)) return std::nullopt;
  const double dt = ToSeconds(t - pending_->first);
  Velocity v;
  v.mean = (m.position - pending_->second.position) / dt;
  const double sigma = options_.init_velocity_sigma;
  v.covariance = (m.covariance + pending_->second.covariance) / (dt * dt) +
                 sigma * sigma * Eigen::Matrix3d::Identity();
  // Too fast even allowing for the measurements' noise (3 sigma along the worst direction).
  const double worst = std::sqrt(v.covariance.eigenvalues().real().maxCoeff());
  if (v.mean.norm() - 3.0 * worst > options_.max_speed) return std::nullopt;
  if (worst > options_.max_speed) v.mean.setZero();  // the difference says nothing: no guess
  return v;
}

std::optional<TrackedState> BallTracker::Step(TimeNs t, const std::optional<Measurement>& m) {
  TrackedState out;
  out.t = t;
  bool used = false;
  if (!tracking_) {
    if (!m) {
      pending_.reset();
      return std::nullopt;
    }
    if (options_.kalman.noise == KalmanOptions::Noise::kPaper) {
      // The paper's start (§3.3): x0 = (0, 0, 0, 1, 1, 1), P0 = I, then the first correction.
      filter_.ResetPaper();
      filter_.Update(m->position, m->covariance);
      Began(t);
    } else if (const auto v = PendingVelocity(t, *m)) {
      // Two measurements close in time: their difference gives the velocity.
      Start(t, *m, *v);
    } else {
      // The first one is reported as it is and kept for the next.
      pending_ = std::make_pair(t, *m);
      out.position = m->position;
      out.measured = true;
      out.cameras = m->cameras;
      out.residual_px = m->residual_px;
      return out;
    }
    used = true;
  } else {
    filter_.ResetTransition();
    PredictWithBounce(&filter_, ToSeconds(t - last_t_), options_);
    const KalmanFilter prior = filter_;
    const int restarts = restarts_;
    last_t_ = t;
    double innovation_chi2 = 0.0;
    if (m) {
      const double d2 = filter_.Mahalanobis2(m->position, m->covariance);
      if (d2 <= options_.gate_chi2) {
        innovation_chi2 = d2;
        filter_.Update(m->position, m->covariance);
        last_update_t_ = t;
        last_position_ = filter_.state().head<3>();
        pending_.reset();
        used = true;
      } else if (options_.restart_on_refusal) {
        // Refused: a sound multi-camera measurement restarts the track at once (a hit), with the
        // velocity from where the ball was; a lesser one waits for a second that agrees with it.
        if (m->cameras >= 2 && m->residual_px <= options_.sound_residual_px) {
          const double gap = ToSeconds(t - last_update_t_);
          const Eigen::Vector3d v = gap > 0 ? Eigen::Vector3d((m->position - last_position_) / gap)
                                            : Eigen::Vector3d::Zero();
          if (v.norm() <= options_.max_speed) {
            const double sigma = 2.0 * options_.init_velocity_sigma;
            Start(t, *m, {v, sigma * sigma * Eigen::Matrix3d::Identity()});
            used = true;
          }
        }
        if (!used) {
          if (const auto v = PendingVelocity(t, *m)) {
            Start(t, *m, *v);
            used = true;
          } else {
            pending_ = std::make_pair(t, *m);
          }
        }
      }
    }
    if (restarts == restarts_) Record(t, &prior, innovation_chi2);  // a restart recorded itself
    if (used && (m->cameras >= 2 || options_.one_view_holds_track)) last_fix_t_ = t;
    if (ToSeconds(t - last_fix_t_) > options_.max_coast_s) {
      tracking_ = false;
      return std::nullopt;
    }
  }
  out.measured = used;
  if (used) {
    out.cameras = m->cameras;
    out.residual_px = m->residual_px;
  }
  out.position = filter_.state().head<3>();
  out.velocity = filter_.state().tail<3>();
  if (used && options_.fall.window_s > 0.0 &&
      options_.kalman.noise == KalmanOptions::Noise::kAcceleration) {
    recent_.push_back({t, m->position, m->covariance});
    const auto old = std::find_if(recent_.begin(), recent_.end(), [&](const FallPoint& p) {
      return t - p.t <= FromSeconds(options_.fall.window_s);
    });
    recent_.erase(recent_.begin(), old);
    if (JudgeFall(recent_, options_.fall, FlightModelOf(options_)).not_falling) {
      tracking_ = false;
      ended_not_falling_ = true;
      return std::nullopt;
    }
  }
  return out;
}

std::optional<KalmanFilter> BallTracker::PredictedFilter(TimeNs t) const {
  if (!tracking_) return std::nullopt;
  KalmanFilter copy = filter_;
  PredictWithBounce(&copy, ToSeconds(t - last_t_), options_);
  return copy;
}

std::optional<std::pair<Eigen::Vector3d, Eigen::Matrix3d>> BallTracker::Predict(TimeNs t) const {
  const auto f = PredictedFilter(t);
  if (!f) return std::nullopt;
  return std::make_pair(Eigen::Vector3d(f->state().head<3>()),
                        Eigen::Matrix3d(f->covariance().topLeftCorner<3, 3>()));
}

std::optional<Eigen::Vector3d> BallTracker::PredictVelocity(TimeNs t) const {
  const auto f = PredictedFilter(t);
  if (!f) return std::nullopt;
  return Eigen::Vector3d(f->state().tail<3>());
}

std::optional<Eigen::Vector3d> BallTracker::PredictPosition(TimeNs t) const {
  const auto p = Predict(t);
  if (!p) return std::nullopt;
  return p->first;
}

}  // namespace p4::track
