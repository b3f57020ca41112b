// p4track calibrate intrinsics|rig|table: cameras against a board, ArUco markers on the table
// (paper §2), or the table's own corners and net posts. Always writes a rig file (DESIGN.md).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <memory>

#include "commands.h"
#include "p4/calib/intrinsics.h"
#include "p4/calib/marker_pose.h"
#include "p4/calib/pose_from_points.h"
#include "p4/core/error.h"
#include "p4/io/calib_files.h"
#include "p4/io/rig_file.h"

namespace p4::app {

void ParseSize(const std::string& text, const std::string& flag, int* w, int* h) {
  const auto x = text.find('x');
  try {
    if (x == std::string::npos) throw std::invalid_argument("no x");
    *w = std::stoi(text.substr(0, x));
    *h = std::stoi(text.substr(x + 1));
  } catch (const std::exception&) {
    throw Error(flag + ": expected WIDTHxHEIGHT, e.g. 1280x720 (got '" + text + "')");
  }
  if (*w < 64 || *h < 48 || *w > 7680 || *h > 4320 || *w % 2 || *h % 2) {
    throw Error(flag + ": width and height must be even, 64x48 to 7680x4320 (got '" + text + "')");
  }
}

namespace {

struct IntrinsicsArgs {
  std::string input, out, rig, name = "cam0", board = "chessboard", dictionary = "DICT_4X4_50";
  int cols = 9, rows = 6, max_frames = 300, step = 15, min_views = 8;
  double square = 0.025, marker = 0.0;
  bool fix_aspect = false, zero_tangent = false, fix_k3 = false;
};

struct RigArgs {
  std::string layout, intrinsics, out;
  std::vector<std::string> sources;
  int frames = 10, min_markers = 1;
};

struct TableArgs {
  std::vector<std::string> points;
  std::string size = "1280x720", intrinsics, out;
  double warn_px = 5.0;
};

// Cameras named as in the intrinsics rig (in the sources' order), or cam0, cam1, ...
std::vector<std::optional<Camera>> IntrinsicsFor(const std::string& path, int n) {
  std::vector<std::optional<Camera>> out(n);
  if (path.empty()) return out;
  const Rig rig = ReadRig(path);
  if (rig.size() != n) {
    throw Error(
        fmt::format("{}: {} camera(s), but {} source(s) given: the rig's cameras must be "
                    "the sources' cameras, in order",
                    path, rig.size(), n));
  }
  for (int i = 0; i < n; ++i) out[i] = rig.cameras[i];
  return out;
}

std::string Describe(const Camera& c) {
  const Eigen::Vector3d centre = c.Center();
  return fmt::format("f {:.1f} px, centre ({:.3f}, {:.3f}, {:.3f}) m", c.fx, centre.x(), centre.y(),
                     centre.z());
}

int RunIntrinsics(const IntrinsicsArgs& a) {
  calib::BoardSpec spec;
  spec.type =
      a.board == "charuco" ? calib::BoardSpec::Type::kCharuco : calib::BoardSpec::Type::kChessboard;
  spec.cols = a.cols, spec.rows = a.rows, spec.square = a.square, spec.marker = a.marker;
  spec.dictionary = a.dictionary;
  std::string why;
  if (!spec.IsValid(&why)) throw Error("board: " + why);
  const auto frames = ReadGrayFrames(a.input, a.max_frames, a.step);
  spdlog::info("looking for the board in {} image(s) of {}", frames.size(), a.input);
  std::vector<calib::BoardView> views;
  std::vector<std::string> view_names;
  int width = 0, height = 0, rejected = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto& f = frames[i];
    if (width == 0) width = f.gray.cols, height = f.gray.rows;
    if (f.gray.cols != width || f.gray.rows != height) {
      throw Error(fmt::format("{}: {}x{}, but the first image is {}x{}: one camera at a time",
                              f.name, f.gray.cols, f.gray.rows, width, height));
    }
    calib::BoardView view;
    if (calib::DetectBoard(f.gray, spec, &view, &why)) {
      views.push_back(std::move(view));
      view_names.push_back(f.name);
    } else {
      ++rejected;
      spdlog::info("  rejected {}: {}", f.name, why);
    }
    if ((i + 1) % 20 == 0) spdlog::info("  {}/{} images", i + 1, frames.size());
  }
  calib::IntrinsicsOptions options;
  options.fix_aspect_ratio = a.fix_aspect;
  options.zero_tangential = a.zero_tangent;
  options.fix_k3 = a.fix_k3;
  options.min_views = a.min_views;
  const auto result = calib::CalibrateIntrinsics(views, width, height, a.name, options, &why);
  if (!result) throw Error(a.input + ": " + why);
  for (std::size_t k = 0; k < result->dropped.size(); ++k) {
    spdlog::info(
        "  dropped {}: reprojection {:.2f} px, far above the others (blurred or "
        "mis-detected board)",
        view_names[result->dropped[k]], result->dropped_rms_px[k]);
  }
  const Camera& c = result->camera;
  spdlog::info("{}: {} of {} images used, {} rejected, {} dropped", a.name, result->used.size(),
               frames.size(), rejected, result->dropped.size());
  spdlog::info(
      "  fx {:.2f} +- {:.2f}  fy {:.2f} +- {:.2f}  cx {:.2f} +- {:.2f}  cy {:.2f} +- {:.2f}", c.fx,
      result->fx_sigma, c.fy, result->fy_sigma, c.cx, result->cx_sigma, c.cy, result->cy_sigma);
  spdlog::info("  distortion k1 {:.5f} k2 {:.5f} p1 {:.5f} p2 {:.5f} k3 {:.5f}", c.distortion[0],
               c.distortion[1], c.distortion[2], c.distortion[3], c.distortion[4]);
  spdlog::info("  RMS reprojection error {:.3f} px (good: below 0.5 px)", result->rms_px);
  // Into an existing rig (replacing that camera's intrinsics) or a new one.
  Rig rig;
  if (!a.rig.empty()) rig = ReadRig(a.rig);
  const int index = rig.Find(a.name);
  if (index >= 0) {
    Camera& old = rig.cameras[index];
    const Rigid3d pose = old.cam_from_world;
    old = c;
    old.cam_from_world = pose;
    spdlog::warn("{}: intrinsics of {} replaced; calibrate its pose again (calibrate rig|table)",
                 a.rig, a.name);
  } else {
    rig.cameras.push_back(c);
  }
  WriteRig(rig, a.out, {{a.name, result->rms_px}});
  spdlog::info("wrote {}", a.out);
  return 0;
}

int RunRig(const RigArgs& a) {
  const calib::MarkerLayout layout = ReadMarkerLayout(a.layout);
  const int n = static_cast<int>(a.sources.size());
  const auto intrinsics = IntrinsicsFor(a.intrinsics, n);
  spdlog::info("{}: {} marker(s) of {}", a.layout, layout.corners.size(), layout.dictionary);
  Rig rig;
  std::map<std::string, double> errors;
  std::vector<std::string> failures;
  for (int i = 0; i < n; ++i) {
    const std::string name = intrinsics[i] ? intrinsics[i]->name : "cam" + std::to_string(i);
    const auto frames = ReadGrayFrames(a.sources[i], a.frames, 1);
    const int width = frames[0].gray.cols, height = frames[0].gray.rows;
    if (intrinsics[i] && (intrinsics[i]->width != width || intrinsics[i]->height != height)) {
      throw Error(fmt::format("{}: {}x{} images, but {} in {} is {}x{}", a.sources[i], width,
                              height, name, a.intrinsics, intrinsics[i]->width,
                              intrinsics[i]->height));
    }
    std::vector<std::vector<calib::MarkerObservation>> seen;
    seen.reserve(frames.size());
    for (const auto& f : frames) seen.push_back(calib::DetectMarkers(f.gray, layout.dictionary));
    std::string why;
    const auto result =
        calib::SolveMarkerPose(intrinsics[i], name, width, height, calib::AverageObservations(seen),
                               layout, a.min_markers, &why);
    if (!result) {
      failures.push_back(fmt::format("{} ({}): {}", name, a.sources[i], why));
      continue;
    }
    std::string ids;
    for (int id : result->used) ids += (ids.empty() ? "" : " ") + std::to_string(id);
    spdlog::info("{}: markers {} over {} frame(s); reprojection RMS {:.3f} px, worst {:.3f} px; {}",
                 name, ids, frames.size(), result->fit.rms_px, result->fit.max_px,
                 Describe(result->fit.camera));
    for (int id : result->dropped) {
      spdlog::warn("{}: marker {} left out: it fits far worse than the others (moved? bent?)", name,
                   id);
    }
    if (!intrinsics[i]) {
      spdlog::warn(
          "{}: no --intrinsics: focal length estimated from the markers, lens "
          "distortion assumed zero",
          name);
    }
    rig.cameras.push_back(result->fit.camera);
    errors[name] = result->fit.rms_px;
  }
  if (!failures.empty()) {
    std::string message = "cannot calibrate every camera, nothing written:";
    for (const auto& f : failures) message += "\n  " + f;
    throw Error(message);
  }
  WriteRig(rig, a.out, errors);
  spdlog::info("wrote {}", a.out);
  return 0;
}

int RunTable(const TableArgs& a) {
  int width = 0, height = 0;
  ParseSize(a.size, "--size", &width, &height);
  const int n = static_cast<int>(a.points.size());
  const auto intrinsics = IntrinsicsFor(a.intrinsics, n);
  Rig rig;
  std::map<std::string, double> errors;
  for (int i = 0; i < n; ++i) {
    const std::string name = intrinsics[i] ? intrinsics[i]->name : "cam" + std::to_string(i);
    const auto points = ReadPointMatches(a.points[i]);
    std::string why;
    const auto fit = intrinsics[i] ? calib::SolvePose(*intrinsics[i], points, &why)
                                   : calib::SolvePoseAndFocal(name, width, height, points, &why);
    if (!fit) throw Error(fmt::format("{} ({}): {}", name, a.points[i], why));
    spdlog::info("{}: {} points; reprojection RMS {:.2f} px, worst {:.2f} px; {}{}", name,
                 points.size(), fit->rms_px, fit->max_px, Describe(fit->camera),
                 intrinsics[i] ? "" : " (focal length estimated)");
    if (fit->rms_px > a.warn_px) {
      spdlog::warn("{}: {:.1f} px is large: check the points' order and coordinates in {}", name,
                   fit->rms_px, a.points[i]);
    }
    rig.cameras.push_back(fit->camera);
    errors[name] = fit->rms_px;
  }
  WriteRig(rig, a.out, errors);
  spdlog::info("wrote {}", a.out);
  return 0;
}

}  // namespace

std::function<int()> AddCalibrateCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "calibrate", "Calibrate cameras: intrinsics from a board, the rig from markers or the table");
  cmd->require_subcommand(1);

  auto in = std::make_shared<IntrinsicsArgs>();
  CLI::App* ci = cmd->add_subcommand(
      "intrinsics", "K and lens distortion of one camera from chessboard or ChArUco images");
  ci->add_option("input", in->input, "Folder of images, one image, or a video of the board")
      ->required();
  ci->add_option("--out", in->out, "Rig file to write (rig.yaml)")->required();
  ci->add_option("--rig", in->rig, "Existing rig to update (the camera named --name)")
      ->check(CLI::ExistingFile);
  ci->add_option("--name", in->name, "Camera name")->capture_default_str();
  ci->add_option("--board", in->board, "chessboard or charuco")
      ->check(CLI::IsMember({"chessboard", "charuco"}))
      ->capture_default_str();
  ci->add_option("--cols", in->cols, "Chessboard: inner corners per row; ChArUco: squares")
      ->capture_default_str();
  ci->add_option("--rows", in->rows, "Chessboard: inner corners per column; ChArUco: squares")
      ->capture_default_str();
  ci->add_option("--square", in->square, "Square side, metres")->capture_default_str();
  ci->add_option("--marker", in->marker, "ChArUco: marker side, metres");
  ci->add_option("--dictionary", in->dictionary, "ChArUco: ArUco dictionary")
      ->capture_default_str();
  ci->add_flag("--fix-aspect", in->fix_aspect, "fx = fy");
  ci->add_flag("--zero-tangent", in->zero_tangent, "No tangential distortion (p1 = p2 = 0)");
  ci->add_flag("--fix-k3", in->fix_k3, "k3 = 0 (few views or a mild lens)");
  ci->add_option("--min-views", in->min_views, "Images with the board needed")
      ->check(CLI::Range(3, 1000))
      ->capture_default_str();
  ci->add_option("--max-frames", in->max_frames, "At most this many images or video frames")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  ci->add_option("--step", in->step, "Video: use every N-th frame")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();

  auto rg = std::make_shared<RigArgs>();
  CLI::App* cr = cmd->add_subcommand(
      "rig", "Each camera's pose from ArUco markers at known places on the table (paper §2)");
  cr->add_option("sources", rg->sources, "One per camera: a still image, a folder or a video")
      ->required();
  cr->add_option("--layout", rg->layout, "Marker layout (markers.yaml: id and world corners)")
      ->required()
      ->check(CLI::ExistingFile);
  cr->add_option("--intrinsics", rg->intrinsics,
                 "Rig with the cameras' intrinsics, in the sources' order (from calibrate "
                 "intrinsics); without it the focal length is estimated")
      ->check(CLI::ExistingFile);
  cr->add_option("--out", rg->out, "Rig file to write")->required();
  cr->add_option("--frames", rg->frames, "Frames averaged per camera (the cameras stand still)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cr->add_option("--min-markers", rg->min_markers, "Markers each camera must see")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();

  auto tb = std::make_shared<TableArgs>();
  CLI::App* ct = cmd->add_subcommand(
      "table", "Each camera's pose (and focal length) from image points of the table's features");
  ct->add_option("--points", tb->points,
                 "Per camera, in order: CSV u,v,x,y,z (table corners, net-post tops, ...)")
      ->required()
      ->check(CLI::ExistingFile);
  ct->add_option("--size", tb->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  ct->add_option("--intrinsics", tb->intrinsics,
                 "Rig with the cameras' intrinsics, in order; without it the focal length is "
                 "estimated (principal point at the centre, no distortion)")
      ->check(CLI::ExistingFile);
  ct->add_option("--out", tb->out, "Rig file to write")->required();
  ct->add_option("--warn-px", tb->warn_px, "Warn above this reprojection RMS")
      ->capture_default_str();

  return [=]() {
    if (ci->parsed()) return RunIntrinsics(*in);
    if (cr->parsed()) return RunRig(*rg);
    return RunTable(*tb);
  };
}

}  // namespace p4::app
