#include "p4/track/stroke_fit.h"

#include <ceres/ceres.h>
#include <ceres/dynamic_autodiff_cost_function.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>

namespace p4::track {
namespace {

// A scale within this many sigmas of its bound rests on it (the solver stops a hair inside it:
// 0.7012 for a bound of 0.7).
constexpr double kAtBoundSigmas = 0.1;

inline double Value(double x) { return x; }
template <typename J, int N>
double Value(const ceres::Jet<J, N>& x) {
  return x.a;
}

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;

// Advances (p, v) by dt (either sign) under the Magnus vector b, in equal steps of at most
// max_step (the Kalman filter's midpoint step, flight_model.h).
template <typename T>
void Advance(Vec3<T>* p, Vec3<T>* v, const Vec3<T>& b, const T& dt, const FlightModel& m,
             double max_step) {
  const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(Value(dt)) / max_step)));
  const T h = dt / T(steps);
  for (int i = 0; i < steps; ++i) MidpointStep(p, v, b, h, m.gravity, m.drag_per_mass);
}

// Integrates a piece (x[0..2] position, x[3..5] velocity, x[6..8] Magnus vector, at t0) to t.
template <typename T>
void Propagate(const T* x, double t0, const T& t, const FlightModel& m, double max_step,
               Vec3<T>* position, Vec3<T>* velocity) {
  *position = Vec3<T>(x[0], x[1], x[2]);
  *velocity = Vec3<T>(x[3], x[4], x[5]);
  Advance(position, velocity, Vec3<T>(x[6], x[7], x[8]), T(t - T(t0)), m, max_step);
}

// sqrt(rho(s) / s) for a residual block of squared norm s: scaling the residuals by it makes
// their squares sum to the robust cost rho (Huber: linear beyond a; Cauchy: logarithmic), as
// Ceres' HuberLoss(a) and CauchyLoss(b) define it.
template <typename T>
T HuberScale(const T& s, double a) {
  if (s <= T(a * a)) return T(1.0);
  return ceres::sqrt((T(2.0 * a) * ceres::sqrt(s) - T(a * a)) / s);
}
template <typename T>
T CauchyScale(const T& s, double b) {
  if (s < T(1e-12)) return T(1.0);
  return ceres::sqrt(T(b * b) * ceres::log(T(1.0) + s / T(b * b)) / s);
}

// Every view of a piece in one pass of the integration, outwards from t0 (a block per view would
// integrate from t0 to each: quadratic in the views). Per view: two bearing residuals across the
// ray (in sigmas, Huber loss) and the diameter's distance times the piece's scale (Cauchy loss;
// 0 without a diameter), the losses folded into the residuals (a loss's threshold <= 0: none).
// Parameters: the piece, the scale.
struct PieceCost {
  PieceCost(std::vector<BearingObservation> observations, double t0, const FlightModel& m,
            double step, double huber, double cauchy)
      : obs(std::move(observations)),
        t0(t0),
        model(m),
        max_step(step),
        huber(huber),
        cauchy(cauchy) {
    for (const auto& o : obs) {
      e1.push_back(o.direction.unitOrthogonal());
      e2.push_back(o.direction.cross(e1.back()));
    }
  }
  template <typename T>
  bool operator()(T const* const* params, T* r) const {
    const T* x = params[0];
    const T scale_distance = params[1][0];
    const Vec3<T> b(x[6], x[7], x[8]);
    const int n = static_cast<int>(obs.size());
    int first_after = 0;
    while (first_after < n && obs[first_after].t < t0) ++first_after;
    for (const int dir : {1, -1}) {
      Vec3<T> p(x[0], x[1], x[2]), v(x[3], x[4], x[5]);
      double t = t0;
      for (int k = dir > 0 ? first_after : first_after - 1; k >= 0 && k < n; k += dir) {
        Advance(&p, &v, b, T(obs[k].t - t), model, max_step);
        t = obs[k].t;
        const Vec3<T> to = p - obs[k].origin.cast<T>();
        const T range = to.norm() + T(1e-9);
        T* rk = r + 3 * k;
        rk[0] = e1[k].cast<T>().dot(to) / range / T(obs[k].angle_sigma);
        rk[1] = e2[k].cast<T>().dot(to) / range / T(obs[k].angle_sigma);
        if (huber > 0.0) {
          const T scale = HuberScale(T(rk[0] * rk[0] + rk[1] * rk[1]), huber);
          rk[0] *= scale;
          rk[1] *= scale;
        }
        rk[2] = T(0.0);
        if (obs[k].distance > 0.0) {
          const T d = (range - scale_distance * obs[k].distance) / T(obs[k].distance_sigma);
          rk[2] = cauchy > 0.0 ? d * CauchyScale(T(d * d), cauchy) : d;
        }
      }
    }
    return true;
  }
  std::vector<BearingObservation> obs;  // in increasing time
  double t0;
  FlightModel model;
  double max_step, huber, cauchy;
  std::vector<Eigen::Vector3d> e1, e2;
};

// A piece passes its junction (t, x, y, z).
struct JunctionCost {
  JunctionCost(double t0, double sigma, const FlightModel& m, double step)
      : t0(t0), sigma(sigma), model(m), max_step(step) {}
  template <typename T>
  bool operator()(const T* piece, const T* junction, T* r) const {
    Vec3<T> p, v;
    Propagate(piece, t0, junction[0], model, max_step, &p, &v);
    for (int i = 0; i < 3; ++i) r[i] = (p(i) - junction[1 + i]) / T(sigma);
    return true;
  }
  double t0, sigma;
  FlightModel model;
  double max_step;
};

// A bounce's junction lies on its plane.
struct PlaneCost {
  PlaneCost(double plane_z, double sigma) : plane_z(plane_z), sigma(sigma) {}
  template <typename T>
  bool operator()(const T* junction, T* r) const {
    r[0] = (junction[3] - T(plane_z)) / T(sigma);
    return true;
  }
  double plane_z, sigma;
};

// At a bounce the velocity after is the velocity before mapped by the table (restitution e on the
// normal part, friction mu taking some of the horizontal), give or take what the spin changes:
// the tracker's bounce map (flight_model.h) as a soft prior.
struct BouncePrior {
  BouncePrior(double t0_before, double t0_after, const FlightModel& m, double step,
              double sigma_horizontal, double sigma_vertical)
      : t0_before(t0_before),
        t0_after(t0_after),
        model(m),
        max_step(step),
        sigma_h(sigma_horizontal),
        sigma_v(sigma_vertical) {}
  template <typename T>
  bool operator()(const T* before, const T* after, const T* junction, T* r) const {
    Vec3<T> pb, vb, pa, va;
    Propagate(before, t0_before, junction[0], model, max_step, &pb, &vb);
    Propagate(after, t0_after, junction[0], model, max_step, &pa, &va);
    const T e = T(model.restitution);
    const T vh = ceres::sqrt(vb.x() * vb.x() + vb.y() * vb.y() + T(1e-12));
    T loss = T(model.friction) * (T(1.0) + e) * ceres::abs(vb.z());
    if (loss > T(0.4) * vh) loss = T(0.4) * vh;
    const T keep = T(1.0) - loss / vh;
    r[0] = (va.x() - keep * vb.x()) / T(sigma_h);
    r[1] = (va.y() - keep * vb.y()) / T(sigma_h);
    r[2] = (va.z() + e * vb.z()) / T(sigma_v);
    return true;
  }
  double t0_before, t0_after;
  FlightModel model;
  double max_step, sigma_h, sigma_v;
};

// A service toss goes near vertically upwards: its horizontal velocity ~ N(0, sigma^2).
struct UprightPrior {
  explicit UprightPrior(double sigma) : sigma(sigma) {}
  template <typename T>
  bool operator()(const T* piece, T* r) const {
    r[0] = piece[3] / T(sigma);
    r[1] = piece[4] / T(sigma);
    return true;
  }
  double sigma;
};

// The spin is unknown but bounded: a weak prior b ~ N(0, sigma^2).
struct MagnusPrior {
  explicit MagnusPrior(double sigma) : sigma(sigma) {}
  template <typename T>
  bool operator()(const T* piece, T* r) const {
    for (int i = 0; i < 3; ++i) r[i] = piece[6 + i] / T(sigma);
    return true;
  }
  double sigma;
};

// The diameters' common bias is unknown but bounded: their distances' scale ~ N(1, sigma^2).
struct ScalePrior {
  explicit ScalePrior(double sigma) : sigma(sigma) {}
  template <typename T>
  bool operator()(const T* scale, T* r) const {
    r[0] = (scale[0] - T(1.0)) / T(sigma);
    return true;
  }
  double sigma;
};

// A contact's time, known to lie in an interval: its middle, with the interval's uniform spread.
struct ContactTimePrior {
  ContactTimePrior(double mean, double sigma) : mean(mean), sigma(sigma) {}
  template <typename T>
  bool operator()(const T* junction, T* r) const {
    r[0] = (junction[0] - T(mean)) / T(sigma);
    return true;
  }
  double mean, sigma;
};

// Each piece's scale about the fit's common one (StrokeFitOptions::piece_scale_sigma).
struct PieceScalePrior {
  explicit PieceScalePrior(double sigma) : sigma(sigma) {}
  template <typename T>
  bool operator()(const T* piece, const T* common, T* r) const {
    r[0] = (piece[0] - common[0]) / T(sigma);
    return true;
  }
  double sigma;
};

using PieceParams = std::array<double, 9>;

PieceParams ToParams(const FlightPiece& piece) {
  PieceParams x;
  for (int i = 0; i < 6; ++i) x[i] = piece.state(i);
  for (int i = 0; i < 3; ++i) x[6 + i] = piece.magnus(i);
  return x;
}

}  // namespace

bool StrokeFitOptions::IsValid(std::string* error) const {
  if (!(magnus_sigma > 0.0 && toss_magnus_sigma > 0.0 && toss_horizontal_sigma > 0.0 &&
        contact_sigma > 0.0 && distance_scale_sigma >= 0.0 && piece_scale_sigma >= 0.0 &&
        huber_sigmas > 0.0 && distance_loss_sigmas > 0.0 && max_step > 0.0 && max_iterations > 0 &&
        model.gravity > 0.0 && model.drag_per_mass >= 0.0)) {
    *error = "stroke fit: sigmas, step, iterations and gravity must be positive, drag >= 0";
    return false;
  }
  return true;
}

FlightPiece QuadraticPiece(std::span<const BearingObservation> observations) {
  const int n = static_cast<int>(observations.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(3 * n, 9);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(3 * n);
  const double t0 = observations.front().t;
  for (int i = 0; i < n; ++i) {
    const BearingObservation& o = observations[i];
    const double dt = o.t - t0;
    Eigen::Matrix<double, 3, 9> m;  // p(t) = m * (p0, v0, a)
    m << Eigen::Matrix3d::Identity(), dt * Eigen::Matrix3d::Identity(),
        0.5 * dt * dt * Eigen::Matrix3d::Identity();
    // Across the ray: e . (p - origin) = 0, in sigmas at the observed distance (or 3 m).
    const Eigen::Vector3d e1 = o.direction.unitOrthogonal(), e2 = o.direction.cross(e1);
    const double across = o.angle_sigma * (o.distance > 0.0 ? o.distance : 3.0);
    a.row(3 * i) = e1.transpose() * m / across;
    a.row(3 * i + 1) = e2.transpose() * m / across;
    b(3 * i) = e1.dot(o.origin) / across;
    b(3 * i + 1) = e2.dot(o.origin) / across;
    if (o.distance > 0.0) {  // along it: d . (p - origin) = distance
      a.row(3 * i + 2) = o.direction.transpose() * m / o.distance_sigma;
      b(3 * i + 2) = (o.direction.dot(o.origin) + o.distance) / o.distance_sigma;
    }
  }
  // A weak pull of the acceleration towards gravity keeps short pieces well posed.
  Eigen::MatrixXd prior = Eigen::MatrixXd::Zero(3, 9);
  prior.rightCols<3>() = Eigen::Matrix3d::Identity() / 10.0;
  Eigen::MatrixXd aa(3 * n + 3, 9);
  aa << a, prior;
  Eigen::VectorXd bb(3 * n + 3);
  bb << b, Eigen::Vector3d(0.0, 0.0, -9.81) / 10.0;
  const Eigen::Matrix<double, 9, 1> x = aa.colPivHouseholderQr().solve(bb);
  // p(t) at the middle observation.
  const double dt = observations[n / 2].t - t0;
  FlightPiece piece;
  piece.t0 = t0 + dt;
  piece.state << x.segment<3>(0) + dt * x.segment<3>(3) + 0.5 * dt * dt * x.segment<3>(6),
      x.segment<3>(3) + dt * x.segment<3>(6);
  return piece;
}

Vector6d PieceStateAt(const FlightPiece& piece, double t, const FlightModel& model,
                      double max_step) {
  const PieceParams x = ToParams(piece);
  Eigen::Vector3d p, v;
  Propagate(x.data(), piece.t0, t, model, max_step, &p, &v);
  Vector6d out;
  out << p, v;
  return out;
}

Vector6d StrokeStateAt(const Stroke& stroke, double t, const FlightModel& model, double max_step) {
  size_t i = 0;
  while (i < stroke.junctions.size() && t > stroke.junctions[i].t) ++i;
  return PieceStateAt(stroke.pieces[i], t, model, max_step);
}

std::optional<Stroke> FitStroke(std::span<const std::vector<BearingObservation>> observations,
                                const Stroke& guess, const StrokeFitOptions& options,
                                const LeadIn* lead_in) {
  const size_t n = guess.pieces.size();
  if (n == 0 || observations.size() != n || guess.junctions.size() + 1 != n) return std::nullopt;
  for (const auto& obs : observations) {
    if (obs.size() < 3) return std::nullopt;
  }
  using JunctionParams = std::array<double, 4>;
  const auto to_params = [](const Junction& j) -> JunctionParams {
    return {j.t, j.point.x(), j.point.y(), j.point.z()};
  };
  std::vector<PieceParams> pieces(n);
  std::vector<JunctionParams> junctions(n - 1);
  for (size_t i = 0; i < n; ++i) pieces[i] = ToParams(guess.pieces[i]);
  for (size_t i = 0; i + 1 < n; ++i) junctions[i] = to_params(guess.junctions[i]);

  ceres::Problem problem;
  const FlightModel& model = options.model;
  const double step = options.max_step;
  double distance_scale = 1.0;
  problem.AddParameterBlock(&distance_scale, 1);
  // Only an anchor fixes the scale: a contact with a known plane or the lead-in's end (in free
  // flight gravity's pull alone would, but the spin's Magnus pull confounds it).
  // Without a lead-in, a start on a plane: the first piece left a contact with it (a bounce
  // whose arrival no view saw) at guess.start->t or later.
  const bool starts_on_plane = lead_in == nullptr && guess.start && guess.start->on_plane;
  const bool anchored = lead_in != nullptr || starts_on_plane ||
                        std::any_of(guess.junctions.begin(), guess.junctions.end(),
                                    [](const Junction& j) { return j.on_plane; });
  const double lower = std::max(0.1, 1.0 - 3.0 * options.distance_scale_sigma);
  const double upper = 1.0 + 3.0 * options.distance_scale_sigma;
  const auto bound = [&](double* scale) {
    problem.SetParameterLowerBound(scale, 0, lower);
    problem.SetParameterUpperBound(scale, 0, upper);
  };
  if (options.distance_scale_sigma > 0.0 && anchored) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<ScalePrior, 1, 1>(
                                 new ScalePrior(options.distance_scale_sigma)),
                             nullptr, &distance_scale);
    // No further than 3 sigmas: where only a scale far off would reconcile the diameters with the
    // bearings, the fit is wrong, and its diameters' residuals should say so.
    bound(&distance_scale);
  } else {
    problem.SetParameterBlockConstant(&distance_scale);
  }
  // Each piece's own scale, tied to the common one (piece_scale_sigma 0: the common one).
  const bool per_piece =
      options.piece_scale_sigma > 0.0 && options.distance_scale_sigma > 0.0 && anchored;
  std::vector<double> piece_scale(n, 1.0);
  for (size_t i = 0; i < n && per_piece; ++i) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PieceScalePrior, 1, 1, 1>(
                                 new PieceScalePrior(options.piece_scale_sigma)),
                             nullptr, &piece_scale[i], &distance_scale);
    bound(&piece_scale[i]);  // as the common one: a piece that slid is still seen to disagree
  }
  for (size_t i = 0; i < n; ++i) {
    const double t0 = guess.pieces[i].t0;
    auto* cost = new ceres::DynamicAutoDiffCostFunction<PieceCost, 9>(new PieceCost(
        observations[i], t0, model, step, options.huber_sigmas, options.distance_loss_sigmas));
    cost->AddParameterBlock(9);
    cost->AddParameterBlock(1);
    cost->SetNumResiduals(3 * static_cast<int>(observations[i].size()));
    problem.AddResidualBlock(cost, nullptr, pieces[i].data(),
                             per_piece ? &piece_scale[i] : &distance_scale);
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<MagnusPrior, 3, 9>(new MagnusPrior(
            guess.pieces[i].toss ? options.toss_magnus_sigma : options.magnus_sigma)),
        nullptr, pieces[i].data());
    if (guess.pieces[i].toss) {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<UprightPrior, 2, 9>(
                                   new UprightPrior(options.toss_horizontal_sigma)),
                               nullptr, pieces[i].data());
    }
  }
  // Junction j joins `before` (params, t0, sigma) and `after`, between two times.
  const auto join = [&](double* before, double before_t0, double before_sigma, size_t after,
                        const Junction& guess_j, double* j, double from_t, double to_t) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<JunctionCost, 3, 9, 4>(
                                 new JunctionCost(before_t0, before_sigma, model, step)),
                             nullptr, before, j);
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<JunctionCost, 3, 9, 4>(
            new JunctionCost(guess.pieces[after].t0, options.contact_sigma, model, step)),
        nullptr, pieces[after].data(), j);
    if (guess_j.on_plane) {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PlaneCost, 1, 4>(
                                   new PlaneCost(guess_j.point.z(), options.contact_sigma)),
                               nullptr, j);
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<BouncePrior, 3, 9, 9, 4>(
              new BouncePrior(before_t0, guess.pieces[after].t0, model, step,
                              options.bounce_sigma_horizontal, options.bounce_sigma_vertical)),
          nullptr, before, pieces[after].data(), j);
    }
    problem.SetParameterLowerBound(j, 0, from_t);
    problem.SetParameterUpperBound(j, 0, to_t);
  };
  for (size_t i = 0; i + 1 < n; ++i) {
    join(pieces[i].data(), guess.pieces[i].t0, options.contact_sigma, i + 1, guess.junctions[i],
         junctions[i].data(), observations[i].back().t, observations[i + 1].front().t);
  }
  PieceParams lead{};
  JunctionParams start{};
  Junction start_guess;
  if (lead_in) {
    lead = ToParams(lead_in->piece);
    const double t_first = observations[0].front().t;
    if (guess.start) {
      start_guess = *guess.start;
    } else {
      start_guess.t = std::min(t_first, 0.5 * (lead_in->after_t + t_first));
      start_guess.point = PieceStateAt(lead_in->piece, start_guess.t, model, step).head<3>();
    }
    start_guess.t = std::clamp(start_guess.t, lead_in->after_t, t_first);
    start = to_params(start_guess);
    problem.AddParameterBlock(lead.data(), 9);
    problem.SetParameterBlockConstant(lead.data());
    join(lead.data(), lead_in->piece.t0, lead_in->sigma, 0, start_guess, start.data(),
         lead_in->after_t, t_first);
  } else if (starts_on_plane) {
    const double t_first = observations[0].front().t;
    const double earliest = std::min(guess.start->t, t_first);
    start_guess = *guess.start;
    start_guess.t = 0.5 * (earliest + t_first);
    const Vector6d x = PieceStateAt(guess.pieces[0], start_guess.t, model, step);
    start_guess.point = {x(0), x(1), guess.start->point.z()};  // z: the plane's height
    start = to_params(start_guess);
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<JunctionCost, 3, 9, 4>(
            new JunctionCost(guess.pieces[0].t0, options.contact_sigma, model, step)),
        nullptr, pieces[0].data(), start.data());
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PlaneCost, 1, 4>(
                                 new PlaneCost(guess.start->point.z(), options.contact_sigma)),
                             nullptr, start.data());
    // Any time in the interval: its middle, give or take its uniform spread (the scale the
    // contact fixes is only as good as this time: the piece rises |vz| sigma_t about it).
    if (t_first - earliest > 1e-6) {
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<ContactTimePrior, 1, 4>(new ContactTimePrior(
              0.5 * (earliest + t_first), (t_first - earliest) / std::sqrt(12.0))),
          nullptr, start.data());
      problem.SetParameterLowerBound(start.data(), 0, earliest);
      problem.SetParameterUpperBound(start.data(), 0, t_first);
    } else {
      problem.SetManifold(start.data(), new ceres::SubsetManifold(4, {0}));
    }
  }

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  if (!summary.IsSolutionUsable()) return std::nullopt;

  const auto to_junction = [](const JunctionParams& p, bool on_plane) {
    Junction j;
    j.t = p[0];
    j.point = {p[1], p[2], p[3]};
    j.on_plane = on_plane;
    return j;
  };
  Stroke out;
  out.pieces.resize(n);
  double sum = 0.0;
  int count = 0;
  for (size_t i = 0; i < n; ++i) {
    for (double v : pieces[i]) {
      if (!std::isfinite(v)) return std::nullopt;
    }
    FlightPiece& piece = out.pieces[i];
    piece.t0 = guess.pieces[i].t0;
    piece.toss = guess.pieces[i].toss;
    for (int k = 0; k < 6; ++k) piece.state(k) = pieces[i][k];
    for (int k = 0; k < 3; ++k) piece.magnus(k) = pieces[i][6 + k];
    // The report: the fit's own residuals, without the losses.
    const PieceCost report(observations[i], piece.t0, model, step, 0.0, 0.0);
    std::vector<double> r(3 * observations[i].size());
    const double scale_i = per_piece ? piece_scale[i] : distance_scale;
    const double* params[] = {pieces[i].data(), &scale_i};
    report(params, r.data());
    std::vector<double> distance_shares;
    for (size_t k = 0; k < observations[i].size(); ++k) {
      sum += r[3 * k] * r[3 * k] + r[3 * k + 1] * r[3 * k + 1];
      count += 2;
      const BearingObservation& o = observations[i][k];
      if (o.distance > 0.0) {
        distance_shares.push_back(std::abs(r[3 * k + 2]) * o.distance_sigma /
                                  (scale_i * o.distance));
      }
    }
    if (!distance_shares.empty()) {
      const auto mid = distance_shares.begin() + distance_shares.size() / 2;
      std::nth_element(distance_shares.begin(), mid, distance_shares.end());
      out.median_distance_error = std::max(out.median_distance_error, *mid);
    }
  }
  for (size_t i = 0; i + 1 < n; ++i) {
    out.junctions.push_back(to_junction(junctions[i], guess.junctions[i].on_plane));
  }
  if (lead_in || starts_on_plane) out.start = to_junction(start, starts_on_plane);
  out.rms_bearing = std::sqrt(sum / std::max(1, count));
  out.distance_scale = distance_scale;
  if (options.distance_scale_sigma > 0.0 && anchored) {
    const double margin = kAtBoundSigmas * options.distance_scale_sigma;
    const auto at_bound = [&](double scale) {
      return scale <= lower + margin || scale >= upper - margin;
    };
    out.scale_at_bound =
        at_bound(distance_scale) ||
        (per_piece && std::any_of(piece_scale.begin(), piece_scale.end(), at_bound));
  }
  return out;
}

}  // namespace p4::track
