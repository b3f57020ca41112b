// One time-stamp of P4 (paper Figure 3): segment every camera's image inside the region of
// interest the filter predicts (falling back to the whole image), keep each camera's largest
// regions as candidates, find the candidates that agree across cameras by their epipolar lines
// and reprojection (paper §3.4), triangulate them (least squares over all agreeing views,
// §3.2) or, seen by one camera only, place the ball by its diameter; then filter (§3.3).
//
// Frames: images in each camera's pixels, points in the world frame (DESIGN.md). Pure: the
// images and their time come in as arguments; buffers are kept between calls.
#pragma once

#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "p4/core/image.h"
#include "p4/core/time.h"
#include "p4/geometry/rig.h"
#include "p4/geometry/triangulation.h"
#include "p4/segment/background_model.h"
#include "p4/segment/ball_colour.h"
#include "p4/segment/ball_edge.h"
#include "p4/segment/ball_outline.h"
#include "p4/segment/blob_finder.h"
#include "p4/segment/color_classes.h"
#include "p4/segment/foreground_finder.h"
#include "p4/segment/streak_finder.h"
#include "p4/segment/streak_search.h"
#include "p4/track/ball_tracker.h"
#include "p4/track/camera_pool.h"
#include "p4/track/epipolar_search.h"
#include "p4/track/track_initiator.h"

namespace p4::track {

struct FrameSetOptions {
  segment::SegmentOptions segment;  // mask is set from the classes ("ball*")
  int candidates_per_camera = 8;
  // Larger regions are not the ball (walls, shirts, lines), nor those wider than the ball a metre
  // from the camera (motion blur lengthens it, never widens it).
  int max_area_px = 4000;
  double max_elongation = 8.0;  // major / minor diameter: blur stretches a ball, a line more
  // A region that stays within static_px of the same place for static_frames frame sets is part
  // of the hall (a lamp, a white mark), not the ball in play.
  double static_px = 1.5;
  int static_frames = 30;
  double epipolar_px = 4.0;      // max distance of a candidate from another view's epipolar line
  double reprojection_px = 5.0;  // max reprojection error of an agreeing view
  // A third camera's region nearest where a pair of views places the ball (within
  // reprojection_px) but not of the ball's size there (max_size_ratio, min_fragment_ratio) is no
  // view of it: the pair stands without it (the ball before a shirt of its colour, merged with
  // it), or, when this is set, the pair is refused (the colour learner, whose candidates are
  // whatever moves: there such a region is most often the body the pair's pieces belong to).
  bool misfit_view_rejects_pair = false;
  // A region's ball diameter within this factor of the one expected where the filter predicts
  // the ball (down to 1 / factor - 0.25: a ball half hidden looks smaller); the prediction's
  // depth is known only to centimetres (one camera: decimetres).
  double max_size_ratio = 1.6;
  double min_size_ratio = 1.0 / 1.6 - 0.25;
  // Each agreeing view of a point found from two views or more: its diameter at most this factor
  // of the one expected at the point, plus view_size_margin_sigmas of the diameter's noise
  // (diameter_sigma: a ball of 3-5 px reads a pixel wide either way). There the expected size
  // is known to the point's millimetres: the ball's own views measure within 15 % of it (99 %
  // of the views the tracker took in sports tuning 8, 26, 28, 34 and white 4, 6: at most 1.30
  // where the view's centre was on the ball), while a view of the ball merged with the hitter's
  // hand or racket reads 1.5 times it (sports tuning 8: a row 50 mm off). Chosen on sports
  // tuning 1-18, 26, 28, 29, 34 (1.6 before; docs/DECISIONS.md).
  double max_view_size_ratio = 1.35;
  double view_size_margin_sigmas = 3.0;
  // Smaller views, down to this share, are a fragment (the lit part of a shaded ball the tables
  // took): such a hypothesis never starts a track and continues one only within
  // fragment_max_distance of the prediction. A fragment in a third camera joins no pair whose
  // two views are whole (the core of a fast ball's streak after a hit: sports tuning 8 lost the
  // flight's 3 sets before the recording's end, all of them points of two whole views).
  double min_fragment_ratio = 0.2;
  double fragment_max_distance = 0.1;  // m
  // A fragment's views are measured again by the ball's edge at the expected size
  // (FrameSetTracker::WholeFragments); those that hold are whole views.
  bool whole_fragments = true;
  // Where no whole hypothesis lies near the prediction (none at all without a track), each
  // camera's first search_views_per_camera views (nearest the predicted ball first; not streaks,
  // still spots or views cut by the image's edge; round by the edge fit) are looked for in the
  // other cameras along their epipolar segments, by the ball's edge (epipolar_search.h): the
  // tables may take nothing of a ball in dimmer light. The hall and the ball's radius of
  // `epipolar` are replaced by the tracker's. Cameras in step only (their images at the set's
  // time).
  bool search_epipolars = true;
  int search_views_per_camera = 3;
  EpipolarSearchOptions epipolar;
  // Where a ball can be: |x|, |y| and the height above the table top (m); the floor below.
  Eigen::Vector3d hall_half_size{8.0, 6.0, 5.0};
  bool use_roi = true;
  int roi_min_px = 40;   // the paper's fixed 40 px window...
  int roi_max_px = 240;  // ...grown with the predicted ball size and speed
  // The window is searched while the track has missed at most roi_max_missed of the camera's
  // frames; after that the whole image (a coasting filter's path runs on after a hit, into the
  // player's arm or onto a ball lying on the floor, which the window would take for the ball).
  int roi_max_missed = 1;
  // A track of 2+ cameras that has missed a set and past_end_min_coast_s while its flight carries
  // the ball past the table's end, away from the net, takes nothing: there the ball meets the
  // racket, and the coasting flight no longer says where it is, while the hitter's arm, racket
  // or shirt of the ball's colour lie on its path (phone tuning 3, 30 fps: after a hit the track
  // took pieces of the hitter's shirt for 0.37 s, 1-4 m off). A hit in 25 ms sends a ball of
  // 5 m/s 25 cm from the coasting flight: a view near it is then no sign of the ball; a set or
  // two missed at 240 fps is (white tuning 1 lost 10 sets before a hit with no time bound).
  // What the images show goes to the initiator, which replaces the track once it confirms a
  // flight: the return, or the ball flying on past a miss.
  bool past_end_takes_nothing = true;
  double past_end_min_coast_s = 0.025;
  bool single_camera_fallback = true;
  double pixel_sigma = 0.5;  // centroid noise, px (measurement covariances, views' weights)
  // The views of a triangulated point count by their centres' noise (TriangulationOptions):
  // pixel_sigma in the image plus centre_sigma_share of the ball's diameter. Measured on the
  // accepted views of sports tuning 1-18, 26, 28, 29, 34, 37-48 against the renderer's
  // projection: median error 0.2-0.34 px at every size, RMS 0.56 px at 7 px, 0.77 at 14, 1.07
  // at 25 (the tails of partly hidden and merged balls grow with the ball): RMS^2 ~ 0.5^2 +
  // (0.038 d)^2 (docs/DECISIONS.md, "Tracking").
  double centre_sigma_share = 0.038;
  // ...and a view m px short of the ball's size at the point is known to misfit_sigma_share * m
  // px more (a side hidden moves the centre by up to half the missing width; faint streaks
  // excepted). Measured on the same views: RMS error 1.17 / 1.64 / 1.93 / 2.58 px where a view
  // was 0.7-0.8 / 0.6-0.7 / 0.5-0.6 / under 0.5 of the ball's size (2.1 / 3.4 / 5.1 / 6.1 px
  // short), 0.33 px at 0.9-1.0. (Views over the size, 0.72 px at 1.1-1.3, keep pixel_sigma: so
  // weighed, a wrong third view of a webcam rig let its pair make rows 1-2 m off.)
  double misfit_sigma_share = 0.5;
  double diameter_sigma = 0.35;    // diameter noise, px (refined)
  double diameter_bias_px = 0.65;  // the binary region is this much narrower than the ball
  bool refine = true;              // the diameter from luma coverage (MeasureBall)
  // The window holds the ball only if a region there is the ball's size at the predicted point;
  // else the whole image is searched (after a hit the filter sends the ball into the arm).
  bool roi_needs_size = true;
  // Cameras out of step: a view is moved to the set's time by its image velocity from the
  // nearest view of its camera's last image within this gap and speed.
  double motion_max_gap_s = 0.05;
  double motion_max_px_s = 5000.0;
  bool edge_centre = true;           // the centre from the ball's edge (ball_edge.h)...
  double edge_max_elongation = 2.5;  // ...for views at most this much longer than wide
  // The diameter from the ball's edge too (the opposite rays' widths) where the edges found are
  // this round at most (major / minor): the moments of the luma's coverage lose a shaded ball's
  // dark half, the edges do not; a streak's edges are drawn in by its thinner ends (at 1 diameter
  // of blur by 7 %), so a longer shape keeps the moments' diameter. 0: never.
  double edge_diameter_max_elongation = 1.3;
  // A shaded ball's edge comes early where its shaded half nears the background's level, and
  // the centre found leans to the lit half (rows 2-4 mm high under lamps): where 2+ views fix
  // the point, each view's width short of the ball's there tells how much its faint side lost
  // (ShadedCentre), and the point is triangulated again from the centres moved back.
  bool shade_correction = true;
  segment::ShadeOptions shade;
  segment::EdgeCentreOptions edge;
  // A view of a hypothesis narrower than outline_short_ratio of the ball's size at its point
  // (its width across when the edge fit found no disc, else its diameter; not streaks, views
  // measured by coverage or cut by the image's edge) is measured again by the outline of a disc
  // of that size (segment/ball_outline.h, FrameSetTracker::OutlineShortViews): a lit cap over a
  // floor of the ball's hue, whose shaded half the tables and the edge rays lose. Where the fit
  // holds, its centre is the view's (whole: ShadedCentre leaves it).
  bool outline_short_views = true;
  double outline_short_ratio = 0.9;
  // ...and at least this share of it wide (a lit cap is half the ball or more; a speck is no
  // outline's guess), where the ball is at least outline_min_diameter_px wide there: the
  // contrast across a smaller circle (+-across_px) peaks as high for a speck half its size.
  double outline_min_ratio = 0.35;
  double outline_min_diameter_px = 8.0;
  // The outline's centre may lie from the view's by what the view lost on one side (half the
  // expected width less its own) and this much more (the blur of the cap's edge), px. Where the
  // view's faint side is known (its edge fit's or its camera's, segment::FaintSideVote), by
  // outline_sided_shift_share of the expected radius and the margin instead, but not more than
  // the margin toward the lit side.
  double outline_shift_margin_px = 1.0;
  double outline_sided_shift_share = 0.5;
  segment::OutlineOptions outline;
  // Beyond the paper: a background model per camera; once it is ready the ball is what differs
  // from it with the ball's colour mixed in (ForegroundFinder), and every candidate is measured
  // by its coverage of the pixels (centre at mid-exposure, area whatever the blur). The colour
  // look-up tables stay the first, fast search inside the predicted window. Off: the colour
  // tables alone (the paper's detector with today's refinements).
  bool use_background = false;
  // With the colour tables alone (use_background false): keep the background model anyway and
  // measure each colour region by its coverage (the centre of the whole ball, not of the pixels
  // the tables took: a shaded bottom falls out of the tables).
  bool measure_on_background = false;
  // With the colour tables: only blocks that differ from the background (by mask_sigmas, grown
  // by a block) can be the ball: a ball-coloured floor, banner or lamp never merges with it.
  bool mask_with_background = false;
  // With the colour tables alone: a ball over a floor, wall or banner of its colour merges with
  // it into one region too large for the ball. When a fresh window (the track measured in the
  // camera's last frame) holds no region of the ball's size, it is searched again on the blocks
  // that differ from the background only (as mask_with_background, in the window alone); in a
  // whole-image search, so are the boxes of the regions too large for a ball (wider than one a
  // metre from the camera, or over max_area_px). Regions found so are measured by coverage (the
  // mask's blocks take some of the floor). A camera keeps the background model this needs from
  // the frame whose whole image first shows such a region (no cost in a hall with none). Not in
  // cameras that look for streaks (a ball blurred over a long exposure differs from the
  // background by less than its noise).
  bool split_merged = true;
  // ...but only regions mostly of the hall: at most this share of their box's blocks differ from
  // the background (a floor with a player on it; a ball-coloured shirt that moves differs more,
  // and its pieces would pass for balls).
  double split_max_moving = 0.2;
  // ...and of what it finds there, only round pieces (major <= this times minor): an arm or a
  // shirt's edge that moved over a hall of the ball's colour is longer (and a ball blurred into
  // a streak over such a floor is lost).
  double split_max_elongation = 2.0;
  double mask_sigmas = 3.0;
  bool mask_grow = true;  // the mask grown by a block (the tables cut a ball's faint edge)
  // In a camera that keeps a background model: when the colour tables find as many regions as
  // they keep (SegmentOptions::max_regions, the largest), they search again on the blocks that
  // differ from the background only (as mask_with_background). A white hall's lines, lamps and
  // lettering are more, and larger than the ball: they crowded it out of the list (white tuning
  // 20: a ball tossed before a server's black shorts, which the background's own search joins
  // to it, lost in one camera for 0.5 s; docs/DECISIONS.md, "Detection"). Rigs of 2+ cameras:
  // one camera has no second view to refuse the players' moving pieces the search brings.
  bool mask_when_crowded = true;
  // Where the candidates are regions that differ from the background (use_background,
  // mask_with_background, or so searched again when crowded) and more than candidates_per_camera
  // remain, the roundest are kept, not the largest: what differs is mostly the players, whose
  // moving pieces are larger than the ball (the coverage over the area of the ellipse of the
  // region's moments: 1 for a disc, and for a ball blurred into a short streak).
  bool keep_roundest = true;
  // A faint blur streak looked for along the path the filter predicts (segment/streak_search.h)
  // when the window holds nothing of the ball's size: a webcam's 1/60-1/30 s exposure leaves a
  // ball a few levels over the table. Only one frame on from a measurement the filter took (a
  // coasting filter's path runs on through the racket after a hit). kAuto: in cameras whose
  // frame period is at least streak_min_frame_s (40 fps or slower), where exposures that long
  // are the rule; the camera then keeps a background model. The search reaches 3 sigmas of the
  // prediction, at least 4 px and at most streak.search_px.
  enum class Streaks { kOff, kAuto, kOn };
  Streaks streaks = Streaks::kAuto;
  double streak_min_frame_s = 0.025;
  segment::StreakSearchOptions streak;
  // With no track, or nothing of it where predicted, cameras that look for streaks also look
  // for them in the whole image (segment/streak_finder.h; each candidate then measured by the
  // streak search above), so a track can start from a ball that is nowhere sharp.
  bool streaks_anywhere = true;
  segment::StreakFinderOptions streak_finder;
  segment::BackgroundOptions background;
  segment::ForegroundOptions foreground;
  // In a camera with a background model (a white ball, a hall of the ball's colour, a webcam):
  // when a window region larger than the ball (its area over max_size_ratio^2 of the disc's, or
  // longer than max_size_ratio diameters) reaches the predicted place and no region of the
  // ball's size lies within a diameter of it (the ball meets a line, an arm or a shirt's edge of
  // its colour in the image), the disc of the ball's size there that stands out of its ring
  // (segment::FindDisc), within 3 sigmas of the prediction (at least 2 px, at most a diameter).
  // Rigs of 2+ cameras only: its size is the expected one, and one camera's depth is the ball's
  // measured size.
  bool disc_in_merged = true;
  segment::DiscSearchOptions disc_search;
  segment::BallColour ball_colour;
  double psf_sigma_px = 0.35;            // edge blur of lens and encoder (refined diameter)
  double max_prediction_distance = 0.6;  // m; candidates farther from the prediction are not it
  // A region that stood still since the last set (Detection::still: a floor patch of the ball's
  // colour, a spare ball, a lamp) is no lone view of a track predicted to cross more than this
  // many pixels of its camera in a frame period: the ball in flight moves (at the top of a toss,
  // or flying along the ray, it may stand still, and so does its prediction).
  double still_max_motion_px = 3.0;
  // Nor is a view longer than the ball blurred over a frame period (an exposure lasts at most
  // one): length <= blur_size_share x the larger of its diameter and the one expected at the
  // prediction, plus blur_motion_share x the predicted travel in a frame period, plus
  // blur_margin_px (a shoe, an arm or a shirt's edge of the ball's colour is long and slow; the
  // ball's own streak lies along its motion).
  double blur_size_share = 1.3;
  double blur_motion_share = 1.5;
  double blur_margin_px = 2.0;
  double single_view_depth_sigma = 1.0;  // m; depth of a lone view continuing a track
  // The hall about the table's centre where one camera's diameter may place the ball (m: half
  // its length and width, the highest centre; the floor is the lowest): farther is a misread.
  double hall_half_length = 6.0;
  double hall_half_width = 4.0;
  double hall_max_z = 3.0;
  // In a rig of several cameras a lone view's row is a measurement only where the depth along
  // its ray is known to this (m): by the smoothed track when lone views wait (below), else by the
  // filter's prediction, at once. Beyond it the row would be a guess, not a measurement.
  double single_view_max_depth_sigma = 0.02;
  // With confirm_tracks, a lone view continues the track while the filter knows its depth to
  // lone_view_depth_sigma (m): the view fixes the ball's direction, and its row waits in the
  // hold (ResultHold) until the track smoothed with the measurements after it (rts_smoother.h)
  // knows its depth to single_view_max_depth_sigma; if it never does (or no two-view
  // measurement follows it in the track), the row is no measurement. 0: only lone views whose
  // depth the filter knows to single_view_max_depth_sigma, as rows at once.
  double lone_view_depth_sigma = 0.3;
  // A lone view continuing a track lies within this squared Mahalanobis distance of the ball
  // predicted in its image (99 % of 2 degrees of freedom), and its diameter's depth within 3
  // sigmas of the predicted one.
  double lone_view_gate_chi2 = 9.21;
  // ...and only while the ball predicted in its image is known to this many of its diameters
  // (the largest sigma of the prediction projected): a track that coasted could take anything.
  double lone_view_image_sigma = 3.0;
  // ...and only while every measurement of that track agreed with the filter's prior within this
  // squared Mahalanobis distance (99 % of 3 degrees of freedom): across a hit the smoothed path
  // bends away from the ball on both sides.
  double lone_view_consistency_chi2 = 11.34;
  // When a track starts (a confirmed tracklet adopted), or a confirmed tracklet's flight is one
  // the track took again through its grown gate after coasting (a hit the hitter hid), the sets
  // of the hold before the flight's first point that have no measured row are looked at again,
  // newest first: in each, a camera's view within backfill_px of the flight carried back to that
  // time (the smoothed first state, gravity and drag, backwards) and no fragment (under
  // min_size_ratio of the ball's size there) is a view of the ball (the first frames after a
  // hit, which one camera saw and the tracklet could not take). A set of two views or more is a
  // row, their point, and corrects the flight; one view's ray corrects it across the ray, and
  // the view is a row on its ray at the flight's depth once that depth is known to
  // single_view_max_depth_sigma (from after it, or carried from the next fix further back: it
  // waits for it). A measured row ends the search (its views, if on the flight, are the last
  // fix, and its row their point), and so do more than backfill_max_missed sets in a row with no
  // view (the hit lies there: before it nothing lies on the flight carried back; one or two sets
  // with none are the ball hidden or missed in every camera for a moment). 0 px: off; >= 0.
  // Rigs of 2+ cameras.
  double backfill_px = 3.0;
  int backfill_max_missed = 2;
  // Where the search ends at a measured row of another flight (its views not on this one), a
  // contact lies between: the new flight carried back and the row's flight carried forward
  // meet there, at the time they are nearest, their velocities apart by more than this (m/s;
  // drag and gravity change a ball's by under 0.3 m/s in a frame of 60 fps). The single views
  // placed before that time were the ball before the hit, on the old flight: their depth along
  // the ray is not the new flight's (white tuning 23: the view on the ball within 0.2 px, its
  // row 319 mm off). 0: off.
  double backfill_contact_mps = 1.0;
  // Before that, the flight across a contact: where the newest set before the flight is a
  // measured row and every set between is free, one flight of constant acceleration through that
  // row's point and the new flight's smoothed states over its first bridge_span_s, fitting them
  // to bridge_max_rms with an acceleration a ball can have (gravity, drag, and the Magnus force
  // of FallCheckOptions::max_spin, + 2 m/s^2), is the ball between: each set's views within
  // backfill_px of it are rows (one view placed where the bridge crosses its ray), and the
  // search above is not made. The flight carried back alone has no spin: after a hit it drifts
  // 5-9 px within 0.1 s (white tuning 6), past backfill_px, and a single view placed at its
  // depth is 30-82 mm off; the row before the contact ties the bridge at its other end (the
  // first row after a hit, or one within the drift of it). 0 s: off.
  double bridge_span_s = 0.1;
  double bridge_max_rms = 0.005;  // m
  // Where the bridge does not hold, a short flight between two contacts: the ball hit into the
  // net, or onto the table's edge, flies a few sets that no tracklet can confirm (sports tuning
  // 11 at 60 fps: 3 sets between a hit at 16.8 m/s and the net). Two sets in a row among those
  // between, each with a point of two views of the ball's size (epipolar_px, reprojection_px,
  // max_view_size_ratio), give a flight; where it meets the flight before (the measured row's
  // state carried forward) and the new flight (its first step, smoothed, carried back) each
  // within contact_max_m, their velocities apart by more than backfill_contact_mps at both
  // meetings, the sets between take their views on it (backfill_px; one view placed where the
  // flight crosses its ray). At most contact_flight_max_s between the row and the new flight.
  // 0 m: off.
  double contact_max_m = 0.02;
  double contact_flight_max_s = 0.1;
  // Cameras segmented in parallel by this many threads (1: all on the caller's thread). Same
  // results either way; pays off for several large images searched whole.
  int threads = 1;
  TrackerOptions tracker;
  // A new track starts only from candidates that fly (TrackInitiator; one camera's placed by
  // their diameters, judged along and across the ray each by its own noise): until then a
  // time-stamp's measurement is tentative, and the time-stamps of the tracklet that confirms it
  // are revised (FrameSetResult::revisions; ResultHold applies them). Off: the filter starts
  // from any two measurements that agree (the paper's way).
  bool confirm_tracks = true;
  TrackInitiatorOptions initiator;
  // A point whose views stood still (Detection::still) in some cameras and moved in others,
  // where standing still says the ball flies along the still camera's ray, counts for nothing
  // toward a new track's confirmation by its travel (TrackletPoint::still_and_moving): a ball at
  // initiator.min_travel_speed stays within static_px over the camera's frame period only if it
  // flies within asin(this share) of the ray. Such views are most often a still speck (a lamp,
  // a player's shoulder) paired with something that moves, whose point flies along the speck's
  // ray as a ball would: webcam tuning 5, 6 and 8 started tracks 0.9-4.8 m off so once the
  // streak finder kept its still candidates that stand alone. In a fast camera a slow ball
  // stands still across a wide cone (at 240 fps a toss rising in view), and its stillness says
  // nothing; a slow ball anywhere still confirms by its toss or its fall. 0: they count.
  double still_and_moving_max_speed_share = 0.5;
  // A point whose every view is a faint streak whose summed difference from the background
  // does not unmix as the ball's colour at any shading (segment::StreakHit::colour_residual at
  // least this) does not count toward the points a new track's confirmation needs
  // (TrackletPoint::off_colour): skin, a sleeve or a shirt's edge brightening the floor moves
  // as a streak would. A streak's chroma is smeared by 4:2:0 and the encoder, but its sum over
  // the streak and a margin is kept. Measured on webcam tuning 2, 4 and 18 (the whole-image
  // finder's hits against the truth): the ball's 5-95th percentiles 0.00-0.85, other things'
  // median 0.88-1.00 (1: no positive share fits); at 0.9, 1-10 % of the ball's hits are off
  // colour, 40-70 % of the others. > 1: off.
  double off_colour_residual = 0.9;

  bool IsValid(std::string* error) const;
};

// One candidate region of one camera.
struct Detection {
  int camera = 0;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // the centre, moved to the set's time
  double diameter_px = 0.0;                         // the ball's diameter (blur-proof minor axis)
  int area_px = 0;
  bool accepted = false;                               // part of this time-stamp's measurement
  Eigen::Vector2d observed = Eigen::Vector2d::Zero();  // the centre as the camera saw it
  // A faint streak found along the predicted path (StreakView) or anywhere (StreakViews): its
  // diameter is the expected one or estimated from its share, its pixels mostly background (no
  // colour samples, little size evidence).
  bool streak = false;
  // A streak along a predicted path shorter than two diameters over a frame period (a disc: a
  // slow ball whose chroma the encoder smeared): no sign by itself that it moved (TrackletPoint).
  bool disc = false;
  // The region stood within static_px of the same place in the last set (a lamp, a letter, a
  // spare ball; the ball in flight moves, but for a moment at the top of a toss).
  bool still = false;
  // The region reaches the image's edge: the ball may be cut (or it is something larger coming
  // into view), so its diameter measures no depth.
  bool cut = false;
  // Its diameter is the coverage sum on the background: the whole disc, its shaded part too.
  bool by_coverage = false;
  // The disc of the ball's size found inside a larger region where the track predicts it
  // (FrameSetOptions::disc_in_merged): its size is the one expected, no evidence, and it is no
  // lone view (only another camera's view agreeing with it makes it the ball).
  bool in_merged = false;
  // The region's length along its major axis, px (0: not known, as for a streak found along a
  // path): a blurred ball is no longer than its disc plus its travel over the exposure.
  double length_px = 0.0;
  // Centre and diameter from the ball's edge, which came early on this side (unit image
  // direction, segment::EdgeCentre::faint; zero when not known): FrameSetTracker::ShadedCentre.
  Eigen::Vector2d faint = Eigen::Vector2d::Zero();
  // The width across of an edge fit that found the faint side but no disc (longer than
  // edge_diameter_max_elongation: the ball's shaded part lost in a floor of its shade, its lit
  // cap left), px; ShadedCentre measures what that side lost by it. 0: by diameter_px.
  double edge_width_px = 0.0;
  // Its centre is the outline's of a disc of the ball's size there (OutlineShortViews): no
  // faint side to move it back along.
  bool outlined = false;
  // Found outside the window a coasting track's prediction would have searched (roi_max_missed):
  // with 2+ cameras for a new track only, never a measurement of the coasting one (whose grown
  // gate would take a hand or a shirt anywhere in the image).
  bool outside = false;
  // A faint streak's segment::StreakHit::colour_residual (0: the ball's colour at some shading,
  // 1: none of it); 0 for a region of the colour tables.
  double colour_residual = 0.0;
};

struct CameraSearch {
  segment::Roi roi;        // the window searched first (empty: whole image)
  bool fell_back = false;  // nothing in the window: the whole image was searched
  bool present = false;    // the camera had an image in this set
};

// Where a frame set's time went (only with a stage clock; see SetStageClock).
struct StageTimes {
  TimeNs segment = 0;    // ROI prediction and segmentation of every camera
  TimeNs associate = 0;  // epipolar association, triangulation (or one view's depth)
  TimeNs filter = 0;     // the Kalman filter's step
};

// An earlier time-stamp, now known: a point of the tracklet that confirmed a track, or a lone
// view the smoothed track now places.
struct Revision {
  TimeNs t = 0;
  Measurement measurement;
  TrackedState state;
  std::vector<int> accepted;  // indices into that time-stamp's detections
  // No ball here after all: the time-stamp's state was the track's prediction past its last
  // measurement, and the track ended (or a new flight replaced it) without another: the state
  // goes (the other fields are not used).
  bool drop = false;
  // Not the ball: the track that measured it ended because it did not fall as a ball can
  // (BallTracker::ended_not_falling): the measurement goes with the state.
  bool not_ball = false;
};

struct FrameSetResult {
  TimeNs t = 0;
  StageTimes stages;
  std::optional<Measurement> measurement;
  std::optional<TrackedState> state;
  // The measurement is this time-stamp's best candidate but no confirmed track has taken it (yet),
  // or a lone view the track took whose depth is not known yet (lone_view_depth_sigma): a later
  // result's revisions may make it one; one still tentative when it is written is not the ball
  // (and its state no measured one).
  bool tentative = false;
  std::vector<Revision> revisions;  // of earlier time-stamps, oldest first
  bool new_track = false;           // a confirmed tracklet became the track at this time-stamp
  std::vector<Detection> detections;
  std::vector<CameraSearch> searches;  // one per camera of the rig
};

// The time-stamp keeps no measurement: none of its detections accepted, its state (if any) no
// measured one (position and velocity as they were).
void ClearMeasurement(FrameSetResult* result);

// How long the rows must be held (ResultHold) for the tracker's revisions to lose nothing: a
// tracklet's span (the initiator's max_span_s), and a track that ends as not falling
// (TrackerOptions::fall) one fall window after its tracklet takes back its rows.
double RowHoldSeconds(const FrameSetOptions& options);

class FrameSetTracker {
 public:
  // Preconditions: rig and options valid, classes valid and with a "ball" class.
  FrameSetTracker(const Rig& rig, const segment::ColorClassSet& classes,
                  const FrameSetOptions& options);

  // images[c] is camera c's frame at t, or nullopt when the camera has none in this set.
  // Cameras out of step: times[c] is image c's own time (its top row's, in the rig's clock;
  // empty: all at t, the earliest). With a track, each camera is searched where the ball is
  // predicted at its own time, and each view (at its time plus its row's delay, CameraClock) is
  // moved by the predicted image motion from then to t before the views are associated and
  // triangulated: the 3D measurement is at t.
  FrameSetResult Process(TimeNs t, std::span<const std::optional<ImageView>> images,
                         std::span<const TimeNs> times = {});
  // At the end of the recording (rigs of 2+ cameras): a flight the initiator could not confirm
  // for want of the sets after it (TrackInitiator::Finish), when the track did not take the last
  // set, becomes rows: revisions of the time-stamps the track did not take, for
  // ResultHold::Flush. Empty otherwise.
  std::vector<Revision> Finish();

  const BallTracker& tracker() const { return tracker_; }
  int taken_back() const { return taken_back_; }  // rows taken back as not the ball (not_ball)
  // Camera c's background model (empty unless a detector keeps one), as of the last Process.
  const segment::BackgroundModel& background(int c) const { return backgrounds_[c]; }

  // For benchmarks: a clock the tracker reads between its stages (injected, so the tracker
  // itself reads no clock). Empty (the default): stages are not timed.
  void SetStageClock(std::function<TimeNs()> clock) { clock_ = std::move(clock); }

 private:
  // One camera's part of a time-stamp: its ROI, segmentation, candidate filtering. Touches only
  // that camera's state (so cameras may run in parallel).
  // `velocity` and `covariance`: the predicted velocity and position covariance (with a track).
  // `window`: whether to search the window around `predicted` first (else the whole image).
  void SearchCamera(int c, const ImageView& image, const std::optional<Eigen::Vector3d>& predicted,
                    const std::optional<Eigen::Vector3d>& velocity,
                    const Eigen::Matrix3d& covariance, bool window, CameraSearch* search,
                    std::vector<Detection>* out);
  // Camera c's view of the ball inside a larger region where the track predicts it (at px in
  // its image, expected px wide; FrameSetOptions::disc_in_merged).
  std::optional<Detection> MergedDiscView(int c, const ImageView& image,
                                          const Eigen::Vector3d& predicted,
                                          const Eigen::Vector2d& px, double expected,
                                          const Eigen::Matrix3d& covariance);
  // options.foreground with the colour tables that judge a round region's core.
  segment::ForegroundOptions ForegroundWithTables() const;
  // Whether camera c looks for faint streaks (FrameSetOptions::streaks), and its view of one
  // along the predicted path.
  bool SearchesStreaks(int c) const;
  std::optional<Detection> StreakView(int c, const ImageView& image,
                                      const Eigen::Vector3d& predicted,
                                      const Eigen::Vector3d& velocity,
                                      const Eigen::Matrix3d& covariance);
  // The streaks anywhere in camera c's picture (StreakFinder; with no track, or nothing where
  // predicted), each measured by the streak search; their diameters from their shares about
  // the ball's size over the table.
  void StreakViews(int c, const ImageView& image, std::vector<Detection>* out);
  // A colour region of camera c measured by coverage on its background, if it differs from it
  // there (centre within half the region's diameter and 2 px of the region's).
  std::optional<segment::CoverageRegion> MeasureOnBackground(int c, const ImageView& image,
                                                             const segment::Region& region);
  // A region that cannot be the ball alone: over max_area_px, or wider than `largest` px (the
  // ball a metre from the camera; motion blur lengthens it, never widens it).
  bool TooLargeForBall(const segment::Region& region, double largest) const;
  // split_merged over the whole image: the boxes of camera c's first `found` colour regions
  // (regions_[c]) that are too large for a ball wider than `largest` px and mostly of the hall
  // are searched again on the blocks that differ from the background (the rest of the image as
  // before); of what is found inside them only the pieces measured by coverage and round stay.
  // regions_[c] and measured_[c] become the new regions and their coverage (outside the boxes
  // only when `measured`). Returns their number, or -1 when no region was too large (nothing
  // changed).
  int SplitMerged(int c, const ImageView& image, int found, double largest, bool measured);
  // Moves each view to the set's time t by its own image motion: the velocity from the nearest
  // view of the same camera's last image (Process). Remembers this set's views for the next.
  void MoveToSetTime(TimeNs t, const std::function<TimeNs(int)>& image_time,
                     const std::vector<CameraSearch>& searches,
                     std::vector<std::vector<Detection>>* candidates);
  // A 3D candidate: detections of several views that agree (epipolar, reprojection, size).
  struct Hypothesis {
    std::vector<std::pair<int, int>> members;  // (camera, candidate)
    PointEstimate estimate;
    double size_misfit = 0.0;  // sum over views of |log(measured / expected diameter)|
    bool fragment = false;     // a view below min_size_ratio (see there)
  };
  // Whether hypothesis h (at `position`) pairs views that stood still with views that moved,
  // and stillness in one of its cameras says the ball flies along its ray
  // (FrameSetOptions::still_and_moving_max_speed_share).
  bool StillAndMoving(const Hypothesis& h, const std::vector<std::vector<Detection>>& candidates,
                      const Eigen::Vector3d& position) const;
  // Whether the track, having missed a set, carries the ball past the table's end away from the
  // net at t (past_end_takes_nothing): then it takes no measurement.
  bool CoastsPastEnd(TimeNs t, const std::optional<Eigen::Vector3d>& predicted) const;
  // Whether a view of diameter_px may be the ball where expected_px is its expected diameter
  // (max_size_ratio, min_fragment_ratio).
  bool SizeFits(double diameter_px, double expected_px) const;
  // ...and a view of a point found from 2+ views (max_view_size_ratio, view_size_margin_sigmas).
  bool ViewSizeFits(double diameter_px, double expected_px) const;
  // Whether such a view is a fragment of the ball there (under min_size_ratio of expected_px).
  bool Fragment(double diameter_px, double expected_px) const;
  // The view's centre moved back from its faint side (segment::UnshadeCentre, options shade)
  // where expected_px is the ball's width at the point its views place it; its own centre
  // without a faint side or with shade_correction off. A view whose edge fit found no faint side
  // takes the side its camera's views agree on (segment::FaintSideVote), unless it is a streak
  // or measured by coverage (whose centre weighs the shaded part as much as the lit one).
  Eigen::Vector2d ShadedCentre(const Detection& view, double expected_px) const;
  // The side where the view's edge fit came early (Detection::faint), or, where it found none,
  // the side its camera's views agree on (not for streaks or views measured by coverage); zero
  // when neither is known.
  Eigen::Vector2d FaintSide(const Detection& view) const;
  // Every candidate that agrees across views (paper §3.4), best first (most views, then size).
  std::vector<Hypothesis> Hypotheses(const std::vector<std::vector<Detection>>& candidates) const;
  // A fragment's small views measured again by the ball's edge at the size the hypothesis
  // expects (the colour tables took the lit part; the edge shows the whole ball against the
  // hall): a view whose edge fit holds at that size (within max_size_ratio either way) takes its
  // centre and diameter. Not views measured by coverage (their size counts the shaded part),
  // streaks or views cut by the image's edge. Returns whether any view changed (the hypotheses
  // are then stale).
  // Short views of the hypotheses measured again by the outline of the ball's size at their
  // point (FrameSetOptions::outline_short_views), nearest the prediction first, each view once.
  // True if any view changed.
  bool OutlineShortViews(const std::vector<Hypothesis>& hypotheses,
                         const std::optional<Eigen::Vector3d>& predicted,
                         std::span<const std::optional<ImageView>> images,
                         std::vector<std::vector<Detection>>* candidates) const;
  bool WholeFragments(const std::vector<Hypothesis>& hypotheses,
                      std::span<const std::optional<ImageView>> images,
                      std::vector<std::vector<Detection>>* candidates) const;
  // search_epipolars: each find joins its camera's candidates; one whose two views place the
  // ball beyond 99 % of the prediction's covariance (plus a centimetre; lone_view_consistency_
  // chi2) is `outside`: for a new track only. Returns whether any joined (the hypotheses are
  // then stale). `in_step(c)`: camera c's image is at the set's time.
  bool SearchEpipolars(const std::vector<Hypothesis>& hypotheses,
                       const std::optional<Eigen::Vector3d>& predicted,
                       const Eigen::Matrix3d& predicted_covariance,
                       std::span<const std::optional<ImageView>> images,
                       const std::function<bool(int)>& in_step,
                       std::vector<std::vector<Detection>>* candidates) const;
  // The hypothesis nearest the prediction among those of most views (the best without one).
  // Fragments only near the prediction.
  const Hypothesis* Pick(const std::vector<Hypothesis>& hypotheses,
                         const std::optional<Eigen::Vector3d>& predicted) const;
  Measurement ToMeasurement(const Hypothesis& h) const;
  // A confirmed tracklet becomes the track: the filter replays its points; all but the last
  // become revisions of their time-stamps, the last is this time-stamp's state and measurement.
  void AdoptTracklet(const Tracklet& tracklet, FrameSetResult* result);
  // A confirmed tracklet whose flight the track follows already (it took this time-stamp's
  // measurement and the tracklet's last points): the points of that flight the filter refused
  // (not in taken_) become revisions, their states from a filter replaying the flight; the sets
  // before its first point with no row are back-filled from that filter (BackFill).
  void ReviseRefused(const Tracklet& tracklet, FrameSetResult* result);
  // The tracklet's points from its flight_start up to (not including) `end` replayed into a
  // fresh filter, returned: revisions of those the track did not take (ReviseRefused, Finish).
  BallTracker ReviseUntaken(const Tracklet& tracklet, std::size_t end,
                            FrameSetResult* result) const;
  // Revision::drop for each coasted_ time-stamp the track did not take (a revision may have
  // given it a measured state), before the result's other revisions; coasted_ cleared.
  void DropCoasted(FrameSetResult* result);
  // Keeps track_rows_ (the track's measured rows within RowHoldSeconds, from this result's
  // state and revisions; cleared when a flight was adopted at t); where the track ended at t as
  // not the ball, a Revision::not_ball for each of them first.
  void TakeBackRows(TimeNs t, bool not_ball, bool started, FrameSetResult* result);
  // The track took a measurement at t (within the hold).
  bool Taken(TimeNs t) const;
  // The revisions' time-stamps within the hold of `now` join taken_ (in order, once).
  void NoteTaken(TimeNs now, const std::vector<Revision>& revisions);
  // One-camera rig: the view placed by its diameter (`placed`, one per view of camera 0); with a
  // prediction, the one nearest it.
  // Not a view that cannot be the ball predicted (NotPredictedBall; `motion_px` per camera, NaN
  // where the track's velocity or the camera's frame period is not known).
  std::optional<Measurement> SingleView(const std::vector<Detection>& views,
                                        const std::vector<std::optional<Measurement>>& placed,
                                        const std::optional<Eigen::Vector3d>& predicted,
                                        const Eigen::Matrix3d& predicted_covariance,
                                        std::span<const double> motion_px,
                                        std::vector<std::pair<int, int>>* used) const;
  // A view placed by its diameter (paper §3.2), known across its ray to pixel_sigma and along it
  // to diameter_sigma; nullopt outside the hall (hall_half_length, hall_half_width, floor to
  // hall_max_z).
  std::optional<Measurement> SphereMeasurement(const Camera& camera, const Detection& d) const;
  // Several cameras, a track, no two views that agree: the view nearest the predicted one in
  // its image (Mahalanobis, the prediction's covariance projected; lone_view_gate_chi2,
  // lone_view_image_sigma), of the size the predicted depth gives and not NotPredictedBall's; its
  // measurement on its ray at the predicted depth, and how well the filter knows that depth.
  struct LoneView {
    Measurement measurement;
    std::pair<int, int> id;  // (camera, candidate)
    Eigen::Vector3d ray = Eigen::Vector3d::UnitZ();
    double depth_sigma = 0.0;  // m, the prediction's along the ray
  };
  std::optional<LoneView> NearestLoneView(const std::vector<std::vector<Detection>>& candidates,
                                          const Eigen::Vector3d& predicted,
                                          const Eigen::Matrix3d& predicted_covariance,
                                          std::span<const double> motion_px) const;
  // Per camera: how far the ball predicted at `predicted` with `velocity` crosses its image in a
  // frame period, px (NaN: the period or the projection unknown).
  std::vector<double> PredictedMotion(const Eigen::Vector3d& predicted,
                                      const Eigen::Vector3d& velocity) const;
  // A view that cannot be the ball predicted there: it stood still where the ball moves more
  // than still_max_motion_px, or it is longer than the ball blurred over a frame period
  // (blur_size_share, blur_motion_share, blur_margin_px). `motion_px`: PredictedMotion's (NaN,
  // nothing known of the ball's travel: neither is judged).
  bool NotPredictedBall(const Detection& d, double expected_px, double motion_px) const;
  // The lone views whose rows wait (lone_view_depth_sigma) that the smoothed track now places
  // (its depth along the ray known, its projection on the view, a two-view fix after it):
  // revisions of their time-stamps; those older than the hold are given up.
  void PlaceLoneViews(FrameSetResult* result);
  // A flight whose first point is at flight_t0 (a track just started, or one the track took
  // again after coasting), `steps` a filter's history whose last start is that point: the views
  // of that flight in the held sets before it (backfill_px), as revisions of their time-stamps.
  // A view it takes is no longer a waiting lone view (waiting_).
  void BackFill(std::span<const FilterStep> steps, TimeNs flight_t0, FrameSetResult* result);
  // The held sets after the flight's first point and before the track's last step that have no
  // row (no whole pair then: a camera's view a fragment, or no view; the tracklet's points were
  // not among them): each camera's view within backfill_px of the smoothed flight carried to the
  // set, two or more triangulated, one placed on its ray at the flight's depth (PlaceOnRay), as
  // revisions of their time-stamps.
  void FillGaps(std::span<const FilterStep> steps, TimeNs flight_t0, FrameSetResult* result);
  // A back-filled single view (r->accepted: its one detection in the set of r->t) placed on its
  // ray at the depth of `flight` (state at r->t) if `covariance` (the flight's position there)
  // knows it to single_view_max_depth_sigma: its measurement and velocity set.
  bool PlaceOnRay(const Vector6d& flight, const Eigen::Matrix3d& covariance, Revision* r) const;
  // A lone view of time-stamp t waits for its depth (waiting_).
  bool Waiting(TimeNs t) const;

  Rig rig_;
  TriangulationOptions triangulation_;  // the views' weights (pixel_sigma, centre_sigma_share)
  segment::ColorLut lut_;
  FrameSetOptions options_;
  // Per camera, places where regions keep appearing, with how many sets in a row they did.
  struct StaticSpot {
    Eigen::Vector2d pixel;
    int count = 0;
    bool seen = false;
  };
  // The index of the spot within static_px of pixel in static_spots_[camera], or -1.
  int SpotAt(int camera, const Eigen::Vector2d& pixel) const;
  // Sets in a row with a region within static_px of pixel, this one included.
  int SpotCount(int camera, const Eigen::Vector2d& pixel);
  // True when a region at pixel would be dropped as part of the hall (SpotCount would reach
  // static_frames); counts nothing.
  bool IsStaticSpot(int camera, const Eigen::Vector2d& pixel) const;
  void AgeStaticSpots(int camera, const CameraSearch& search);

  std::vector<segment::BlobFinder> finders_;
  std::vector<segment::BackgroundModel> backgrounds_;
  std::vector<segment::ForegroundFinder> foreground_finders_;
  std::vector<std::vector<segment::CoverageRegion>> coverage_;  // per camera
  // Per camera: its colour regions measured by coverage (when the background measures).
  std::vector<std::vector<std::optional<segment::CoverageRegion>>> measured_;
  std::vector<std::vector<StaticSpot>> static_spots_;
  // Per camera: the faint sides its views' edge fits found (ShadedCentre).
  std::vector<segment::FaintSideVote> faint_votes_;
  // Per camera: its last image's views as seen and their times (the rows' delays included).
  struct LastViews {
    std::vector<Eigen::Vector2d> pixels;
    std::vector<TimeNs> times;
  };
  std::vector<LastViews> last_views_;
  std::vector<std::vector<segment::Region>> regions_;   // per camera
  std::vector<segment::StreakSearch> streak_searches_;  // per camera
  std::vector<segment::StreakFinder> streak_finders_;   // per camera
  // Per camera: its last image's time and the shortest interval between its images seen (its
  // frame period; 0 until two images).
  std::vector<std::optional<TimeNs>> last_image_time_;
  std::vector<double> frame_period_s_;
  // Per camera: its colour tables found a region too large for the ball (split_merged).
  std::vector<char> ball_coloured_hall_;
  std::unique_ptr<CameraPool> pool_;
  TrackerOptions tracker_options_;  // the filter's, without restarts when tracks are confirmed
  BallTracker tracker_;
  TrackInitiator initiator_;
  std::optional<TimeNs> last_taken_t_;  // the last time-stamp whose measurement the filter took
  struct WaitingView {
    TimeNs t = 0;
    int camera = 0;
    Eigen::Vector2d pixel;  // the view, at the set's time
    Eigen::Vector3d ray;    // world frame, unit
    int detection = 0;      // index into that time-stamp's detections
  };
  std::vector<WaitingView> waiting_;  // lone views whose rows wait for the smoother, oldest first
  std::deque<TimeNs> fixes_;          // the time-stamps of the hold whose two views the track took
  std::deque<TimeNs> taken_;          // the time-stamps of the hold whose measurement it took
  // The time-stamps within RowHoldSeconds whose rows the track made measured (from its tracklet
  // on): a track that ended because it did not fall takes them back.
  std::deque<TimeNs> track_rows_;
  int taken_back_ = 0;
  // The time-stamps since the track's last measurement whose states are its predictions: dropped
  // (Revision::drop) when the track ends or is replaced without another measurement.
  std::vector<TimeNs> coasted_;
  // The sets of the hold: their views (as in FrameSetResult::detections) and whether their row
  // was a measurement, for BackFill and FillGaps.
  struct PastSet {
    TimeNs t = 0;
    std::vector<Detection> detections;
    bool measured = false;
    Vector6d state = Vector6d::Zero();  // of a measured row: the filter's position and velocity
  };
  std::deque<PastSet> past_;
  std::function<TimeNs()> clock_;

  // Whether the set has a row made after its own time-stamp: one the track took since (a lone
  // view placed, an earlier back-fill: Taken), not a lone view still waiting for its depth
  // (PlaceLoneViews), or a revision in `result` (this time-stamp's).
  bool RowMadeSince(const PastSet& set, const FrameSetResult& result) const;
  // The set's views on `flight` (ViewsOnFlight) as a row of r: two or more, their point; one,
  // placed on its ray where the flight crosses it, if `covariance` (of the flight's position)
  // knows that depth (PlaceOnRay). False for none, or views that do not meet.
  bool RowOnFlight(const PastSet& set, const Vector6d& flight, const Eigen::Matrix3d& covariance,
                   Revision* r) const;
  // The short flight between two contacts (contact_max_m) over the same free sets as Bridge's.
  bool BetweenContacts(const SmoothedState& first_step, TimeNs flight_t0, FrameSetResult* result);
  // The newest set before flight_t0 (within the hold) if it is a measured row and every set
  // between it and the flight is unmeasured and free: that row, and the sets between, newest
  // first. Null when not so.
  const PastSet* FreeSetsBefore(TimeNs flight_t0, const FrameSetResult& result,
                                std::vector<const PastSet*>* between) const;
  // After a hit one camera may lose the ball for a few sets (against a shirt of its colour):
  // where the measured row before the new flight lies on it (a flight of constant acceleration
  // within a ball's through that row and the flight's first 0.1 s), the sets between take their
  // views on that bridge, a single view placed where the bridge crosses its ray. False (nothing
  // done) where it does not hold.
  bool Bridge(std::span<const FilterStep> steps, std::span<const SmoothedState> smoothed,
              std::size_t first, TimeNs flight_t0, FrameSetResult* result);
  // The indices of the set's views the track took (a measured row's) that lie within
  // backfill_px of `point` in their images.
  std::vector<int> TakenViewsOn(const PastSet& set, const Eigen::Vector3d& point) const;
  // Per camera, the set's view nearest the flight's point within backfill_px; not still or cut
  // views, nor fragments (a view below min_size_ratio of the ball's size there: a highlight, the
  // lit cap of a shaded ball, whose centre is off the ball's). Each view's index joins
  // r->accepted, its centre moved back from shade (ShadedCentre at the point's width) joins
  // *observations and its (camera, index) views->members.
  void ViewsOnFlight(const PastSet& set, const Eigen::Vector3d& point, Revision* r,
                     std::vector<Observation>* observations, Hypothesis* views) const;
  // r as a measured row of its time-stamp (its state from its measurement); a lone view waiting
  // at that time-stamp no longer waits.
  void PushRevision(Revision r, FrameSetResult* result);
};

}  // namespace p4::track
