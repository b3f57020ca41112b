#include "p4/sim/match.h"

#include <cmath>
#include <random>

#include "p4/core/table.h"
#include "p4/sim/shot_solver.h"

namespace p4::sim {

bool MatchOptions::IsValid(std::string* error) const {
  const auto fail = [&](const std::string& what) {
    if (error) *error = what;
    return false;
  };
  if (points < 1) return fail("points must be >= 1");
  if (!game::MatchScore::IsValid(best_of, first_server, error)) return false;
  if (!(physics_dt > 0.0 && physics_dt <= 0.001)) return fail("physics_dt must be in (0, 1 ms]");
  if (!(min_speed > 0.0 && max_speed > min_speed)) return fail("need 0 < min_speed < max_speed");
  if (!(gap_s >= 0.0) || !(start_s >= 0.0)) return fail("start and gap must be >= 0");
  if (!(max_spin_rps >= 0.0)) return fail("max_spin_rps must be >= 0");
  if (!(continue_probability >= 0.0 && continue_probability < 1.0)) {
    return fail("continue_probability must be in [0, 1)");
  }
  return ball.IsValid(error);
}

namespace {

constexpr double kRevToRad = 2.0 * M_PI;
double Sign(char player) { return player == 'A' ? -1.0 : 1.0; }
char Other(char player) { return player == 'A' ? 'B' : 'A'; }

enum class Ending { kServeFault, kNet, kOut, kMissed, kDoubleBounce };

// What the receiver does after the ball bounced on their side: strike when it passes a plane
// behind the end line, or earlier, over the table, when it falls back to a chosen height.
struct HitRule {
  char player = 'A';
  double behind_m = 0.3;
  double low_z = 0.1;

  bool Hits(const BallState& s) const {
    const double depth = Sign(player) * s.position.x();  // > 0 on the player's half
    if (depth < 0.4) return false;
    return depth >= table::kHalfLength + behind_m ||
           (s.velocity.z() < 0.0 && s.position.z() < low_z);
  }
};

struct Run {
  std::vector<std::pair<double, BallState>> samples;
  std::vector<TruthEvent> events;  // bounce, net, floor, out (in time order)
  bool hit_reached = false;
  double end_t = 0.0;
  BallState end_state;
};

class Simulator {
 public:
  explicit Simulator(const MatchOptions& options)
      : options_(options),
        rng_(options.seed),
        result_{Trajectory{}, {}, game::MatchScore(options.best_of, options.first_server), 0, 0.0} {
  }

  MatchResult Play() {
    double t = options_.start_s;
    for (int point = 0; point < options_.points && !result_.score.match_over(); ++point) {
      t = PlayPoint(t) + options_.gap_s;
      ++result_.points_played;
    }
    result_.duration = t;
    std::stable_sort(result_.events.begin(), result_.events.end(),
                     [](const TruthEvent& a, const TruthEvent& b) { return a.t < b.t; });
    return std::move(result_);
  }

 private:
  double Uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  bool Chance(double p) { return Uniform(0.0, 1.0) < p; }

  // Simulates from `s` at t0. With a hit rule: until that player strikes after the ball bounced
  // on their side (or fails). Without: until the ball reached the floor and rolled a little.
  // `awaiting_bounce_on` is the half the ball must bounce on next (for "out").
  Run Simulate(BallState s, double t0, const HitRule* hit, char must_bounce_on, bool serve) {
    Run run;
    const BallParams& p = options_.ball;
    const double dt = options_.physics_dt;
    double t = t0;
    run.samples.emplace_back(t, s);
    bool bounced_on_receiver = false;
    bool awaiting = !serve;  // a serve first bounces on the server's own half
    bool own_bounce_done = !serve;
    int contacts = 0;
    double floor_t = -1.0;
    while (t < t0 + 3.0) {
      const BallState before = s;
      const ContactEvent contact = WorldStep(&s, t, dt, p);
      if (awaiting && contacts == 0 && before.position.z() >= p.radius &&
          s.position.z() < p.radius && contact.kind == Contact::kNone) {
        const double f = (before.position.z() - p.radius) / (before.position.z() - s.position.z());
        const Eigen::Vector3d at = before.position + f * (s.position - before.position);
        if (!table::OnSurface(at.x(), at.y())) {
          TruthEvent out;
          out.t = t + f * dt;
          out.type = "out";
          out.position = Eigen::Vector3d(at.x(), at.y(), 0.0);
          run.events.push_back(out);
          awaiting = false;
        }
      }
      if (contact.kind != Contact::kNone) {
        run.samples.emplace_back(contact.time, contact.before);
        run.samples.emplace_back(contact.time, contact.after);
        TruthEvent e;
        e.t = contact.time;
        ++contacts;
        if (contact.kind == Contact::kTable) {
          e.type = "bounce";
          e.side = table::SideOf(contact.point.x());
          e.position = Eigen::Vector3d(contact.point.x(), contact.point.y(), 0.0);
          if (!own_bounce_done) {
            own_bounce_done = true;
            awaiting = true;
            contacts = 0;  // the serve's own bounce does not end the "out" watch
          } else {
            awaiting = false;
          }
          if (e.side == must_bounce_on) bounced_on_receiver = true;
        } else if (contact.kind == Contact::kNet) {
          e.type = "net";
          e.position = contact.point;
          awaiting = false;
        } else {
          e.type = "floor";
          e.position = Eigen::Vector3d(contact.point.x(), contact.point.y(), table::kFloorZ);
          awaiting = false;
        }
        if (!(e.type == "floor" && floor_t >= 0.0)) run.events.push_back(e);
        if (e.type == "floor" && floor_t < 0.0) floor_t = contact.time;
      }
      t += dt;
      run.samples.emplace_back(t, s);
      if (hit && bounced_on_receiver && hit->Hits(s)) {
        run.hit_reached = true;
        break;
      }
      if (hit && (floor_t >= 0.0)) break;
      if (floor_t >= 0.0 && t > floor_t + 0.3) break;
    }
    run.end_t = t;
    run.end_state = s;
    return run;
  }

  BallState WithSpin(const BallState& at, const Eigen::Vector2d& target, double top_rps,
                     double side_rps) {
    BallState s = at;
    Eigen::Vector3d dir(target.x() - at.position.x(), target.y() - at.position.y(), 0.0);
    dir.normalize();
    const Eigen::Vector3d topspin_axis = Eigen::Vector3d::UnitZ().cross(dir);
    s.spin = kRevToRad * (top_rps * topspin_axis + side_rps * Eigen::Vector3d::UnitZ());
    return s;
  }

  bool SpeedOk(const Eigen::Vector3d& v, double min_speed) const {
    return v.norm() >= min_speed && v.norm() <= options_.max_speed;
  }

  // A serve from `at`; good or a long fault. Serves are drawn, not solved: a first bounce on
  // the own half and a flight time give a drag-free guess, spin bends it, and the physics
  // decides; a draw is kept when the ball did what the plan asked.
  std::optional<Run> TryServe(const BallState& at, char server, bool fault, const HitRule& hit) {
    const double s = Sign(server);
    const double max_serve_spin = std::min(80.0, options_.max_spin_rps);
    for (int attempt = 0; attempt < 200; ++attempt) {
      Eigen::Vector3d first(s * Uniform(0.3, 1.0), Uniform(-0.6, 0.6), options_.ball.radius);
      double top = Uniform(-max_serve_spin, 0.5 * max_serve_spin);
      if (fault) {  // long: deep on the own half, with topspin
        first.x() = s * Uniform(0.9, 1.3);
        top = Uniform(0.3, 1.0) * max_serve_spin;
      }
      BallState start = WithSpin(at, {-s, first.y()}, top, Uniform(-0.4, 0.4) * max_serve_spin);
      start.velocity =
          BallisticVelocity(at.position, first, Uniform(0.12, 0.4), options_.ball.gravity);
      if (start.velocity.norm() > options_.max_speed) continue;
      Run run = Simulate(start, at_time_, fault ? nullptr : &hit, Other(server), true);
      const auto& ev = run.events;
      if (fault) {
        if (ev.size() >= 2 && ev[0].type == "bounce" && ev[0].side == server &&
            ev[1].type == "out") {
          return run;
        }
      } else if (run.hit_reached && ev.size() == 2 && ev[0].type == "bounce" &&
                 ev[0].side == server && ev[1].type == "bounce" && ev[1].side == Other(server)) {
        return run;
      }
    }
    return std::nullopt;
  }

  // A rally shot of `ending` kind (nullopt = a good shot the opponent returns).
  std::optional<Run> TryShot(const BallState& at, char hitter, std::optional<Ending> ending,
                             const HitRule& hit) {
    const double s = -Sign(hitter);  // towards the opponent's half
    for (int attempt = 0; attempt < 40; ++attempt) {
      RallyGoal goal;
      goal.landing = {s * Uniform(0.35, 1.25), Uniform(-0.65, 0.65)};
      goal.net_z = table::kNetHeight + options_.ball.radius + Uniform(0.03, 0.35);
      double top = Chance(0.75) ? Uniform(0.0, options_.max_spin_rps) : -Uniform(0.0, 60.0);
      double min_speed = options_.min_speed;
      if (ending == Ending::kOut) {
        if (Chance(0.6)) {
          goal.landing.x() = s * (table::kHalfLength + Uniform(0.05, 0.5));
        } else {
          goal.landing.y() = (Chance(0.5) ? 1.0 : -1.0) * (table::kHalfWidth + Uniform(0.05, 0.35));
        }
      } else if (ending == Ending::kNet) {
        goal.net_z = Uniform(0.03, 0.12);
      } else if (ending == Ending::kDoubleBounce) {
        goal.landing.x() = s * Uniform(0.15, 0.4);
        goal.net_z = table::kNetHeight + options_.ball.radius + Uniform(0.02, 0.1);
        top = -Uniform(10.0, 50.0);
        min_speed = 2.0;
      }
      const BallState spun =
          WithSpin(at, goal.landing, top, Uniform(-0.2, 0.2) * options_.max_spin_rps);
      const auto v = SolveRallyShot(spun, goal, options_.ball);
      if (!v || !SpeedOk(*v, min_speed)) continue;
      BallState start = spun;
      start.velocity = *v;
      const bool returned = !ending.has_value();
      Run run = Simulate(start, at_time_, returned ? &hit : nullptr, Other(hitter), false);
      const auto& ev = run.events;
      const char opp = Other(hitter);
      const auto is = [&](std::size_t i, const char* type, char side = 0) {
        return i < ev.size() && ev[i].type == type && (side == 0 || ev[i].side == side);
      };
      bool ok = false;
      if (returned) {
        ok = run.hit_reached && ev.size() == 1 && is(0, "bounce", opp);
      } else if (*ending == Ending::kOut) {
        ok = is(0, "out");
      } else if (*ending == Ending::kNet) {
        ok = is(0, "net") && ev.size() >= 2 && (is(1, "floor") || is(1, "bounce", hitter));
      } else if (*ending == Ending::kMissed) {
        ok = is(0, "bounce", opp) && is(1, "floor");
      } else if (*ending == Ending::kDoubleBounce) {
        ok = is(0, "bounce", opp) && is(1, "bounce", opp);
      }
      if (ok) return run;
    }
    return std::nullopt;
  }

  void Commit(const Run& run, double until) {
    for (const auto& [t, state] : run.samples) {
      if (t > until) break;
      result_.trajectory.Append(t, state);
    }
    for (const TruthEvent& e : run.events) {
      if (e.t <= until) result_.events.push_back(e);
    }
  }

  void Struck(const char* type, char player, double t, const BallState& s) {
    TruthEvent e;
    e.t = t;
    e.type = type;
    e.player = player;
    e.position = s.position;
    result_.events.push_back(e);
  }

  Ending DrawEnding() {
    const double u = Uniform(0.0, 1.0);
    if (u < 0.08) return Ending::kServeFault;
    if (u < 0.28) return Ending::kNet;
    if (u < 0.58) return Ending::kOut;
    if (u < 0.85) return Ending::kMissed;
    return Ending::kDoubleBounce;
  }

  HitRule DrawHit(char player) { return {player, Uniform(0.05, 0.6), Uniform(0.05, 0.3)}; }

  // Plays one point from its toss at t; returns the time the ball leaves the scene.
  double PlayPoint(double t) {
    const char server = result_.score.Server();
    Ending ending = DrawEnding();
    int good_returns = 0;
    while (Chance(options_.continue_probability) && good_returns < 12) ++good_returns;

    // The toss: from the open palm behind the end line, at least 16 cm up (ITTF 2.6.2).
    BallState ball;
    ball.position = {Sign(server) * (table::kHalfLength + Uniform(0.1, 0.3)), Uniform(-0.5, 0.5),
                     Uniform(0.0, 0.15)};
    ball.velocity = {0.0, 0.0, Uniform(2.2, 2.8)};
    const double contact_z = ball.position.z() + Uniform(0.05, 0.25);
    {
      Run toss;
      double tt = t;
      toss.samples.emplace_back(tt, ball);
      while (!(ball.velocity.z() < 0.0 && ball.position.z() <= contact_z)) {
        WorldStep(&ball, tt, options_.physics_dt, options_.ball);
        tt += options_.physics_dt;
        toss.samples.emplace_back(tt, ball);
      }
      Commit(toss, tt);
      t = tt;
    }
    at_time_ = t;
    Struck("serve", server, t, ball);

    char hitter = server;
    char winner = 0;
    std::string reason;
    double decided = t;
    Run last;
    // The serve.
    HitRule hit = DrawHit(Other(server));
    std::optional<Run> run = TryServe(ball, server, ending == Ending::kServeFault, hit);
    if (!run && ending != Ending::kServeFault) {
      ending = Ending::kServeFault;  // no good serve found: the server faults
      run = TryServe(ball, server, true, hit);
    }
    if (!run) {  // cannot happen in practice; keep the rules consistent anyway
      winner = Other(server);
      reason = "serve fault";
      last.end_t = t + 0.5;
    } else if (ending == Ending::kServeFault) {
      last = *run;
      winner = Other(server);
      reason = "serve fault";
      decided = last.events[1].t;
    } else {
      // Good serve and rally.
      last = *run;
      for (int shot = 1;; ++shot) {
        Commit(last, last.end_t);
        hitter = Other(hitter);
        at_time_ = last.end_t;
        BallState at = last.end_state;
        Struck("hit", hitter, at_time_, at);
        std::optional<Ending> kind;
        if (shot > good_returns) kind = ending;
        hit = DrawHit(Other(hitter));
        std::optional<Run> next = TryShot(at, hitter, kind, hit);
        if (!next) {  // no such shot from here: end the rally with another kind
          kind = kind == Ending::kOut ? Ending::kMissed : Ending::kOut;
          next = TryShot(at, hitter, kind, hit);
        }
        if (!next) {  // cannot happen in practice; keep the rules consistent anyway
          winner = Other(hitter);
          reason = "out";
          last = Run{};
          last.end_t = at_time_ + 0.5;
          decided = at_time_;
          break;
        }
        last = *next;
        if (!kind) continue;  // a good shot: the opponent strikes next
        const auto& ev = last.events;
        switch (*kind) {
          case Ending::kOut:
            winner = Other(hitter), reason = "out", decided = ev[0].t;
            break;
          case Ending::kNet:
            winner = Other(hitter), reason = "net", decided = ev[1].t;
            break;
          case Ending::kMissed:
            winner = hitter, reason = "no return", decided = ev[1].t;
            break;
          case Ending::kDoubleBounce:
            winner = hitter, reason = "double bounce", decided = ev[1].t;
            break;
          case Ending::kServeFault:
            break;
        }
        break;
      }
    }
    // The ball stays in the scene a little after the point is decided (at most 0.5 s).
    const double leave = std::min(last.end_t, decided + 0.5);
    Commit(last, leave);
    result_.trajectory.EndSegment();

    const game::PointOutcome outcome = result_.score.AwardPoint(winner);
    for (TruthEvent& e : game::PointEvents(decided, winner, reason, outcome)) {
      result_.events.push_back(std::move(e));
    }
    return std::max(leave, decided);
  }

  MatchOptions options_;
  std::mt19937_64 rng_;
  MatchResult result_;
  double at_time_ = 0.0;
};

}  // namespace

MatchResult SimulateMatch(const MatchOptions& options) { return Simulator(options).Play(); }

}  // namespace p4::sim
