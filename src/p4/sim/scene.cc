#include "p4/sim/scene.h"

#include "p4/core/table.h"

namespace p4::sim {

std::vector<MarkerQuad> TableCornerMarkers(double size_m) {
  std::vector<MarkerQuad> markers;
  const double inset = 0.01 + table::kEdgeLineWidth;
  int id = 0;
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {1.0, -1.0}) {
      // The marker's top edge faces the net; its x axis runs along +y for A's end markers.
      const double x_out = sx * (table::kHalfLength - inset);
      const double x_in = x_out - sx * size_m;
      const double y_out = sy * (table::kHalfWidth - inset);
      const double y_in = y_out - sy * size_m;
      const double y0 = std::min(y_out, y_in), y1 = std::max(y_out, y_in);
      MarkerQuad m;
      m.id = id++;
      if (sx < 0) {  // seen from A's end: image "up" is +x, image "right" is -y
        m.corners = {Eigen::Vector3d(x_in, y1, 0.0), Eigen::Vector3d(x_in, y0, 0.0),
                     Eigen::Vector3d(x_out, y0, 0.0), Eigen::Vector3d(x_out, y1, 0.0)};
      } else {  // seen from B's end: "up" is -x, "right" is +y
        m.corners = {Eigen::Vector3d(x_in, y0, 0.0), Eigen::Vector3d(x_in, y1, 0.0),
                     Eigen::Vector3d(x_out, y1, 0.0), Eigen::Vector3d(x_out, y0, 0.0)};
      }
      markers.push_back(m);
    }
  }
  return markers;
}

}  // namespace p4::sim
