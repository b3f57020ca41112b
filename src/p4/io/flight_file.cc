#include "p4/io/flight_file.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "p4/core/error.h"
#include "p4/core/table.h"

namespace p4 {

RealFlight ReadTt3dFlight(const std::string& path, double start_s) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open");
  std::string line;
  std::getline(in, line);
  if (line.rfind("Timestamp,X,Y,Z", 0) != 0)
    throw Error(path + ": line 1: expected 'Timestamp,X,Y,Z'");
  std::vector<double> t;
  std::vector<Eigen::Vector3d> p;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    std::stringstream row(line);
    double v[4];
    char comma;
    if (!(row >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3]) ||
        !std::isfinite(v[0] + v[1] + v[2] + v[3])) {
      throw Error(path + ": line " + std::to_string(number) + ": expected 4 numbers");
    }
    if (!t.empty() && v[0] <= t.back()) {
      throw Error(path + ": line " + std::to_string(number) + ": time does not increase");
    }
    t.push_back(v[0]);
    p.emplace_back(v[2], -v[1], v[3]);
  }
  if (t.size() < 3) throw Error(path + ": fewer than 3 samples");
  RealFlight flight;
  const double t0 = t.front();
  const std::size_t n = t.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = i == 0 ? 0 : i - 1, b = i + 1 == n ? n - 1 : i + 1;
    sim::BallState s;
    s.position = p[i];
    s.velocity = (p[b] - p[a]) / (t[b] - t[a]);
    flight.trajectory.Append(t[i] - t0 + start_s, s);
    if (i > 0 && i + 1 < n && p[i].z() < 0.04 && p[i].z() <= p[i - 1].z() &&
        p[i].z() < p[i + 1].z() && table::OnSurface(p[i].x(), p[i].y())) {
      sim::TruthEvent e;
      e.t = t[i] - t0 + start_s;
      e.type = "bounce";
      e.side = table::SideOf(p[i].x());
      e.position = Eigen::Vector3d(p[i].x(), p[i].y(), 0.0);
      flight.bounces.push_back(e);
    }
  }
  flight.trajectory.EndSegment();
  flight.end_s = t.back() - t0 + start_s;
  return flight;
}

}  // namespace p4
