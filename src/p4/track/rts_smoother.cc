#include "p4/track/rts_smoother.h"

#include <Eigen/Cholesky>

namespace p4::track {

std::vector<SmoothedState> SmoothSteps(std::span<const FilterStep> steps) {
  const int n = static_cast<int>(steps.size());
  std::vector<SmoothedState> out(steps.size());
  for (int k = n - 1; k >= 0; --k) {
    const FilterStep& s = steps[k];
    out[k] = {s.t, s.state, s.covariance};
    // The newest step of a track is as filtered.
    if (k == n - 1 || steps[k + 1].start) continue;
    const FilterStep& next = steps[k + 1];
    // Gain C = P_k F^T (P-_{k+1})^-1, i.e. C^T = (P-_{k+1})^-1 F P_k (both symmetric).
    const Eigen::LDLT<Matrix6d> prior(next.prior_covariance);
    const Matrix6d gain = prior.solve(next.transition * s.covariance).transpose();
    out[k].state += gain * (out[k + 1].state - next.prior_state);
    out[k].covariance += gain * (out[k + 1].covariance - next.prior_covariance) * gain.transpose();
    out[k].covariance = 0.5 * (out[k].covariance + out[k].covariance.transpose());
  }
  return out;
}

}  // namespace p4::track
