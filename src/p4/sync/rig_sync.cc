#include "p4/sync/rig_sync.h"

#include "p4/core/error.h"

namespace p4::sync {

RigSyncResult SynchroniseRig(const Rig& rig,
                             const std::vector<std::vector<FrameCandidates>>& frames,
                             const RigSyncOptions& options) {
  if (static_cast<int>(frames.size()) != rig.size()) {
    throw Error("sync: frames of " + std::to_string(frames.size()) + " camera(s) for a rig of " +
                std::to_string(rig.size()));
  }
  RigSyncResult result;
  result.rig = rig;
  std::vector<std::vector<Track2d>> tracks(frames.size());
  for (std::size_t c = 0; c < frames.size(); ++c) {
    tracks[c] = LinkTracks(frames[c], options.tracks);
    // A point's own time: its row's delay after the top row's stamp.
    const CameraClock& clock = rig.cameras[c].clock;
    for (Track2d& track : tracks[c]) {
      for (TrackPoint& p : track.points) p.t += clock.RowDelay(p.pixel.y());
    }
    result.tracks.push_back(static_cast<int>(tracks[c].size()));
  }
  // The reference's tracks in the rig's time.
  const CameraClock& reference = rig.cameras[0].clock;
  std::vector<Track2d> world = tracks[0];
  for (Track2d& track : world) {
    for (TrackPoint& p : track.points) {
      p.t = reference.time_offset_s + reference.clock_rate * p.t;
    }
  }
  result.cameras.resize(frames.size());
  result.cameras[0].found = true;
  result.cameras[0].offset_s = reference.time_offset_s;
  result.cameras[0].rate = reference.clock_rate;
  result.rig.cameras[0].clock.has_offset = true;
  result.all_found = true;
  for (std::size_t c = 1; c < frames.size(); ++c) {
    OffsetResult& r = result.cameras[c];
    r = FindOffset(rig.cameras[0], world, rig.cameras[c], tracks[c], options.offsets);
    result.all_found = result.all_found && r.found;
    if (!r.found) continue;
    CameraClock& clock = result.rig.cameras[c].clock;
    clock.time_offset_s = r.offset_s;
    clock.clock_rate = r.rate;
    clock.has_offset = true;
  }
  return result;
}

}  // namespace p4::sync
