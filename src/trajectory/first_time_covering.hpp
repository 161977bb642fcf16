#pragma once
// The first time at which a motion law s(t) (non-decreasing) has covered a distance: bisection on
// its own sample() (the S-curve's; PathProfile::time_at narrows to one phase first).
namespace kontur::trajectory {

/// The first time [s] in [0, profile.duration()] at which profile.sample(t).s >= s_mm [mm];
/// bounded, stops when the interval cannot shrink.
template <class Profile>
[[nodiscard]] double first_time_covering(const Profile& profile, double s_mm) noexcept {
  double lo = 0.0, hi = profile.duration();
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    if (profile.sample(mid).s < s_mm)
      lo = mid;
    else
      hi = mid;
  }
  return hi;
}

}  // namespace kontur::trajectory
