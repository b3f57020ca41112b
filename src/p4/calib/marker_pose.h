// The rig from ArUco markers at known places on or beside the table (paper §2 used ARToolKit
// markers on the table corners): find the markers in a camera's still image, match them to the
// layout by id and solve the camera's pose over all their corners.
//
// Frames: world metres (DESIGN.md); corners in OpenCV's order (top-left, top-right,
// bottom-right, bottom-left of the marker image), pixels in the distorted image.
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "p4/calib/pose_from_points.h"

namespace p4::calib {

struct MarkerLayout {
  std::string dictionary = "DICT_4X4_50";
  std::map<int, std::array<Eigen::Vector3d, 4>> corners;  // by marker id, world
};

struct MarkerObservation {
  int id = 0;
  std::array<Eigen::Vector2d, 4> corners;
};

// Markers of `dictionary` in a grey image (OpenCV's detector), corners refined to sub-pixel by
// RefineMarkerCorners.
std::vector<MarkerObservation> DetectMarkers(const cv::Mat& gray, const std::string& dictionary);

// Each corner moved to the crossing of the marker's two outer edges, each edge a line fitted to
// sub-pixel edge points (the centroid of the intensity gradient across the black border / white
// quiet zone boundary). OpenCV 4.6's corner refinements look at a window around the corner,
// which on markers of 20-40 px also sees the marker's bits; the edges see only the border.
// A corner whose edges are not found (occluded) is kept as it was.
void RefineMarkerCorners(const cv::Mat& gray, std::array<Eigen::Vector2d, 4>* corners);

// The corners of each marker averaged over several frames of a still camera (noise down by the
// square root of the frames); a marker found in fewer than half the frames is left out.
std::vector<MarkerObservation> AverageObservations(
    const std::vector<std::vector<MarkerObservation>>& frames);

struct MarkerPoseResult {
  PoseFit fit;
  std::vector<int> used;     // ids of the layout's markers the pose rests on
  std::vector<int> unknown;  // ids seen but not in the layout
  std::vector<int> dropped;  // ids of the layout left out: their corners fit 3x worse than most
};

// The pose of a camera from its observed markers. `intrinsics` gives K and distortion; when it
// is nullopt the focal length is estimated too (principal point at the centre, no distortion)
// and `width` x `height` must be the image size. nullopt with *error (naming what is missing)
// when fewer than `min_markers` markers of the layout are seen or the pose fails.
std::optional<MarkerPoseResult> SolveMarkerPose(const std::optional<Camera>& intrinsics,
                                                const std::string& name, int width, int height,
                                                const std::vector<MarkerObservation>& observed,
                                                const MarkerLayout& layout, int min_markers,
                                                std::string* error);

}  // namespace p4::calib
