// The time a stage of a long run has left, estimated from how fast it has gone so far, for the
// progress line (progress.h): "about 1:10 left".
//
// The estimate is the stage's mean rate (the share done over the seconds it took), taken again
// each time the share moves and averaged with what the last estimate has counted down to since.
// Between two moves it counts down: work that lands in bursts (frames rendered a few at a time,
// the passes of the path tracer) does not make it climb while the next burst is under way, and
// one burst faster or slower than the rest moves it only half way. Nothing is estimated before
// kEnoughShare of the stage is done.
#pragma once

#include <optional>

namespace hirsute {

class TimeLeft {
 public:
  // The share of a stage done before an estimate is given.
  static constexpr double kEnoughShare = 0.05;

  // `share` (0 to 1) of the stage done `seconds` after it began.
  void add(double seconds, double share);
  // The seconds left at `seconds` after the stage began; none before enough is known, or once
  // it is done.
  std::optional<double> secondsLeft(double seconds) const;

 private:
  double share_ = 0;      // at the last move
  double movedAt_ = 0;    // seconds into the stage of the last move
  double estimate_ = -1;  // seconds left at the last move; < 0: none yet
};

}  // namespace hirsute
