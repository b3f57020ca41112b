// Inputs of `p4track calibrate` (DESIGN.md, docs/DECISIONS.md): the marker layout (markers.yaml,
// as the simulator writes it), a camera's table points (CSV `u,v,x,y,z`), and the grey frames of
// a folder of images, one image or a video.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "p4/calib/marker_pose.h"
#include "p4/calib/pose_from_points.h"

namespace p4 {

// markers.yaml: `dictionary` and `markers: [{id, corners}]`, corners 4 world points (a 4x3
// matrix or a list of 4 [x, y, z]) in OpenCV's corner order. Throws p4::Error naming the file,
// the marker and the field.
calib::MarkerLayout ReadMarkerLayout(const std::string& path);

// CSV with header `u,v,x,y,z` (pixels, world metres). Throws p4::Error naming file and line.
std::vector<calib::PointMatch> ReadPointMatches(const std::string& path);

struct GrayFrame {
  std::string name;  // file name, or "frame N" of a video
  cv::Mat gray;      // CV_8UC1
};

// Grey frames from a folder (its .jpg/.jpeg/.png/.bmp/.tif files, sorted by name), a pattern of
// image files (`folder/left*.jpg`, shell wildcards in the file name), one image file, or a video
// (every `video_step`-th frame, at most `max_frames`). Throws p4::Error when the path does not
// exist, holds no image, or an image cannot be read.
std::vector<GrayFrame> ReadGrayFrames(const std::string& path, int max_frames, int video_step);

}  // namespace p4
