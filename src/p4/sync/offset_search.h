// The time offset (and clock drift) of a camera against a reference camera, found from the
// ball's own motion (beyond the paper, whose cameras were triggered together).
//
// Camera b's clock maps to the reference's (world) time as t = offset + rate * stamp (the rig's
// CameraClock, geometry/camera_clock.h). Where b sees the ball at stamp s, the reference's track
// of the ball must cross the epipolar line of b's pixel at world time offset + rate * s.
//   1. Coarse: every point of b's tracks votes for offset = t* - s at each crossing t* of that
//      line by the reference's tracks (between consecutive points); votes go into bins over
//      +-max_offset_s; the true offset collects a vote from nearly every point, chance crossings
//      spread evenly.
//   2. Fine: the offset (and, over long recordings, the rate) that minimises the robust sum of
//      epipolar distances between b's points and the reference's track interpolated at their
//      world times (iteratively reweighted Gauss-Newton), with its standard deviation from the
//      residuals: the larger of the points' own and that of b's tracks taken as the samples (a
//      track's points share its lean, the lit half and the background behind it, so hundreds of
//      points of a few flights know the offset only as well as those flights do).
// The fine fit runs from each of the highest coarse peaks; the offset where most points agree
// wins; with fit_line_times a last fit adds both cameras' line times (rows read one after
// another): b's point at row v was exposed at offset + rate * (s + L_b v), the reference's point
// at row u at its time + L_r u. Refuses (found = false, `why` says) when too few points agree or a
// second offset is nearly as good.
//
// Reference track times are world seconds (the reference's clock applied, rows' delays
// included); b's are its own stamps (its row delays included). Pixels are each camera's real
// (distorted) ones. Pure.
#pragma once

#include <string>
#include <vector>

#include "p4/geometry/camera.h"
#include "p4/sync/track_2d.h"

namespace p4::sync {

struct OffsetOptions {
  double max_offset_s = 5.0;  // search +- this
  double bin_s = 0.002;       // coarse bins
  double inlier_px = 3.0;     // an epipolar distance that agrees (reference's ideal pixels)
  double huber_px = 1.0;      // the fine fit's robust loss: quadratic within, linear beyond
  // Points that agree at the offset found: this many, and as many as b takes frames in
  // min_agreeing_s (40 at 60 fps, 17 at 25 fps: the ball's motion seen by both that long).
  int min_agreements = 12;
  double min_agreeing_s = 0.67;
  int peaks = 5;                 // coarse peaks fitted finely (10 ms apart at least)
  double max_second_peak = 0.6;  // a second offset where this share as many points agree refuses
  double max_interpolation_gap_s = 0.05;  // reference points farther apart are not joined
  double min_crossing_px = 0.2;  // a segment must cross a line by this much (not run along it)
  // The rate is fitted when b's agreeing points span this long (drift of 50 ppm moves the
  // offset by 0.5 ms in 10 s); else rate = 1.
  double min_span_for_rate_s = 20.0;
  // An offset within this many of its sigmas of 0 (and no drift fitted) is 0: cameras started
  // together (one trigger, one recorder) are in step, not off by the search's noise.
  double in_step_sigmas = 2.5;
  // Rolling shutter (phones, most webcams): also fit b's and the reference's line times (each
  // row's delay after the one above), as additions to those the tracks' times already hold, from
  // how the offset that fits varies with the rows the ball is seen on. The crossings fix the
  // cameras' timing against each other far better than against the picture's own rows, so each
  // camera's readout (line time x height) has a prior of readout_prior of its frame period
  // (measured from its tracks' stamps), readout_prior_sigma of it a standard deviation (costing
  // as much as a point 1 px off): a rolling shutter reads a frame out within its period.
  bool fit_line_times = false;
  double readout_prior = 0.5;
  double readout_prior_sigma = 0.25;

  bool IsValid(std::string* error) const;
};

struct OffsetResult {
  bool found = false;
  std::string why;        // when not found: what was missing
  double offset_s = 0.0;  // world time of b's stamp 0
  double rate = 1.0;      // world seconds per second of b's clock
  bool rate_fitted = false;
  bool in_step = false;  // the offset found was within in_step_sigmas of 0: taken as 0
  // Standard deviation of the offset: b's tracks as the samples (with line times fitted, the
  // points' own).
  double sigma_s = 0.0;
  int agreements = 0;       // b's points within inlier_px at the offset found
  int points = 0;           // b's points that could be compared (the reference's track there)
  double rms_px = 0.0;      // of the agreeing points' epipolar distances
  double peak_ratio = 0.0;  // points agreeing at the runner-up offset over those at the best
  // With fit_line_times: the line times found, added to those the tracks' times held (s a row).
  bool line_times_fitted = false;
  double line_time_s = 0.0, reference_line_time_s = 0.0;
};

OffsetResult FindOffset(const Camera& reference, const std::vector<Track2d>& reference_tracks,
                        const Camera& b, const std::vector<Track2d>& b_tracks,
                        const OffsetOptions& options = {});

}  // namespace p4::sync
