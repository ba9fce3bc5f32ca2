#include "hirsute/core/time_left.h"

#include <algorithm>

namespace hirsute {

void TimeLeft::add(double seconds, double share) {
  share = std::clamp(share, 0.0, 1.0);
  if (share <= share_) return;  // no move: the last estimate counts down
  const double countedDown = estimate_ >= 0 ? std::max(0.0, estimate_ - (seconds - movedAt_)) : -1;
  share_ = share;
  movedAt_ = seconds;
  if (share < kEnoughShare || seconds <= 0) return;
  // At the mean rate so far (share / seconds), what is left takes this long.
  const double atMeanRate = seconds * (1 - share) / share;
  estimate_ = countedDown >= 0 ? (atMeanRate + countedDown) / 2 : atMeanRate;
}

std::optional<double> TimeLeft::secondsLeft(double seconds) const {
  if (estimate_ < 0 || share_ >= 1) return std::nullopt;
  return std::max(0.0, estimate_ - std::max(0.0, seconds - movedAt_));
}

}  // namespace hirsute
