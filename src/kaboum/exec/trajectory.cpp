#include "kaboum/exec/trajectory.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace kaboum::exec {

namespace {

// The rest-to-rest quintic s(τ) = 10τ³ − 15τ⁴ + 6τ⁵ peaks at s' = 15/8 (τ = 1/2) and
// |s''| = 10/√3 (τ = 1/2 ± √3/6).
constexpr double kPeakVelocity = 15.0 / 8.0;
const double kPeakAcceleration = 10.0 / std::sqrt(3.0);

constexpr std::size_t kCoefficients = 6;

// Polynomial Σ c[k] τ^k (k < n) and its value.
double evaluate(std::span<const double> c, double tau) {
  double value = 0;
  for (std::size_t k = c.size(); k-- > 0;) value = value * tau + c[k];
  return value;
}

// The largest |p(τ)| over τ in [0, 1] of a polynomial of degree ≤ 4 (coefficients `p`, derivative
// `dp`): the ends, a grid, and the roots of p' bracketed by the grid and refined by bisection.
double largestOnUnit(std::span<const double> p, std::span<const double> dp) {
  constexpr int kGrid = 64;
  double largest = std::max(std::abs(evaluate(p, 0)), std::abs(evaluate(p, 1)));
  double previous = evaluate(dp, 0);
  for (int i = 1; i <= kGrid; ++i) {
    const double right = static_cast<double>(i) / kGrid;
    const double slope = evaluate(dp, right);
    largest = std::max(largest, std::abs(evaluate(p, right)));
    if ((previous < 0) != (slope < 0)) {
      double lo = static_cast<double>(i - 1) / kGrid;
      double hi = right;
      const bool rising = previous < 0;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        ((evaluate(dp, mid) < 0) == rising ? lo : hi) = mid;
      }
      largest = std::max(largest, std::abs(evaluate(p, 0.5 * (lo + hi))));
    }
    previous = slope;
  }
  return largest;
}

// The quintic from p0 (velocity v0, acceleration 0) to p1 (velocity v1, acceleration 0) over T
// seconds, as coefficients in local time.
void quintic(double p0, double v0, double p1, double v1, double T, double* c) {
  const double h = p1 - p0;
  c[0] = p0;
  c[1] = v0;
  c[2] = 0;
  c[3] = (20 * h - (8 * v1 + 12 * v0) * T) / (2 * T * T * T);
  c[4] = (-30 * h + (14 * v1 + 16 * v0) * T) / (2 * T * T * T * T);
  c[5] = (12 * h - 6 * (v1 + v0) * T) / (2 * T * T * T * T * T);
}

}  // namespace

const char* toString(Profile profile) {
  return profile == Profile::RestToRest ? "rest-to-rest" : "blended";
}

Profile profileNamed(const std::string& name) {
  if (name == "rest-to-rest") return Profile::RestToRest;
  if (name == "blended") return Profile::Blended;
  throw std::invalid_argument("'" + name + "' is none of rest-to-rest, blended");
}

TimedPath::TimedPath(std::vector<std::vector<double>> waypoints, const JointLimits& limits,
                     Profile profile)
    : profile_(profile) {
  if (waypoints.empty()) throw std::invalid_argument("a path needs a waypoint");
  dof_ = waypoints.front().size();
  if (limits.velocity.size() != dof_ || limits.acceleration.size() != dof_) {
    throw std::invalid_argument("limits for another number of joints");
  }
  for (std::size_t j = 0; j < dof_; ++j) {
    if (!(limits.velocity[j] > 0) || !(limits.acceleration[j] > 0)) {
      throw std::invalid_argument("joint limits must be positive");
    }
  }
  for (std::vector<double>& waypoint : waypoints) {
    if (waypoint.size() != dof_) throw std::invalid_argument("waypoints of different sizes");
    if (waypoints_.empty() || waypoint != waypoints_.back())
      waypoints_.push_back(std::move(waypoint));
  }
  const std::size_t segments = waypoints_.size() - 1;
  // Rest-to-rest: the shortest duration within the limits; blended starts from the time at the
  // velocity limit and scales.
  for (std::size_t i = 0; i < segments; ++i) {
    double duration = 0;
    for (std::size_t j = 0; j < dof_; ++j) {
      const double distance = std::abs(waypoints_[i + 1][j] - waypoints_[i][j]);
      duration = profile == Profile::RestToRest
                     ? std::max({duration, kPeakVelocity * distance / limits.velocity[j],
                                 std::sqrt(kPeakAcceleration * distance / limits.acceleration[j])})
                     : std::max(duration, distance / limits.velocity[j]);
    }
    durations_.push_back(duration);
  }
  if (profile == Profile::Blended && segments > 0) {
    const auto fit = [&] {
      coefficients_.assign(segments * dof_ * kCoefficients, 0);
      for (std::size_t j = 0; j < dof_; ++j) {
        const auto slope = [&](std::size_t i) {
          return (waypoints_[i + 1][j] - waypoints_[i][j]) / durations_[i];
        };
        std::vector<double> via(segments + 1, 0.0);
        for (std::size_t i = 1; i < segments; ++i) {
          const double before = slope(i - 1);
          const double after = slope(i);
          if ((before > 0 && after > 0) || (before < 0 && after < 0))
            via[i] = 0.5 * (before + after);
        }
        for (std::size_t i = 0; i < segments; ++i) {
          quintic(waypoints_[i][j], via[i], waypoints_[i + 1][j], via[i + 1], durations_[i],
                  &coefficients_[(i * dof_ + j) * kCoefficients]);
        }
      }
    };
    // Per segment, the velocity and acceleration peaks relative to the limits: scaling a
    // segment's duration by k divides its velocities by about k and accelerations by k².
    std::vector<double> ratio(segments);
    const auto peaks = [&] {
      fit();
      for (std::size_t i = 0; i < segments; ++i) {
        const double T = durations_[i];
        double velocityRatio = 0;
        double accelerationRatio = 0;
        for (std::size_t j = 0; j < dof_; ++j) {
          const double* c = &coefficients_[(i * dof_ + j) * kCoefficients];
          // In τ = t / T: velocity T·q'(t), acceleration T²·q''(t) and their derivatives.
          std::array<double, 5> velocity{};
          std::array<double, 4> acceleration{};
          std::array<double, 3> jerk{};
          for (std::size_t k = 1; k < kCoefficients; ++k) {
            velocity[k - 1] = static_cast<double>(k) * c[k] * std::pow(T, static_cast<double>(k));
          }
          for (std::size_t k = 1; k < velocity.size(); ++k) {
            acceleration[k - 1] = static_cast<double>(k) * velocity[k];
          }
          for (std::size_t k = 1; k < acceleration.size(); ++k) {
            jerk[k - 1] = static_cast<double>(k) * acceleration[k];
          }
          velocityRatio = std::max(velocityRatio,
                                   largestOnUnit(velocity, acceleration) / T / limits.velocity[j]);
          accelerationRatio = std::max(accelerationRatio, largestOnUnit(acceleration, jerk) /
                                                              (T * T) / limits.acceleration[j]);
        }
        ratio[i] = std::max(velocityRatio, std::sqrt(accelerationRatio));
      }
    };
    // Each segment brought towards its own limit (the via velocities follow), then every duration
    // scaled by the largest remaining ratio, so that the limits hold exactly.
    constexpr int kRounds = 8;
    for (int round = 0; round < kRounds; ++round) {
      peaks();
      for (std::size_t i = 0; i < segments; ++i) durations_[i] *= std::sqrt(ratio[i]);
    }
    peaks();
    const double scale = *std::max_element(ratio.begin(), ratio.end());
    for (double& duration : durations_) duration *= scale;
    fit();
  }
  double start = 0;
  for (const double duration : durations_) {
    starts_.push_back(start);
    start += duration;
  }
  duration_ = start;
}

std::size_t TimedPath::segmentAt(double t, double& local) const {
  const auto after = std::upper_bound(starts_.begin(), starts_.end(), t);
  const std::size_t segment =
      after == starts_.begin() ? 0 : static_cast<std::size_t>(after - starts_.begin()) - 1;
  local = std::clamp(t - starts_[segment], 0.0, durations_[segment]);
  return segment;
}

void TimedPath::sample(double t, std::span<double> q, std::span<double> qd,
                       std::span<double> qdd) const {
  if (durations_.empty()) {
    std::copy(waypoints_.front().begin(), waypoints_.front().end(), q.begin());
    std::fill(qd.begin(), qd.end(), 0.0);
    std::fill(qdd.begin(), qdd.end(), 0.0);
    return;
  }
  double local = 0;
  const std::size_t i = segmentAt(std::clamp(t, 0.0, duration_), local);
  const double T = durations_[i];
  if (profile_ == Profile::RestToRest) {
    const double tau = local / T;
    const double tau2 = tau * tau;
    const double s = tau2 * tau * (10 + tau * (-15 + 6 * tau));
    const double sd = tau2 * (30 + tau * (-60 + 30 * tau)) / T;
    const double sdd = tau * (60 + tau * (-180 + 120 * tau)) / (T * T);
    for (std::size_t j = 0; j < dof_; ++j) {
      const double delta = waypoints_[i + 1][j] - waypoints_[i][j];
      q[j] = waypoints_[i][j] + s * delta;
      qd[j] = sd * delta;
      qdd[j] = sdd * delta;
    }
    return;
  }
  for (std::size_t j = 0; j < dof_; ++j) {
    const double* c = &coefficients_[(i * dof_ + j) * kCoefficients];
    const double x = local;
    q[j] = c[0] + x * (c[1] + x * (c[2] + x * (c[3] + x * (c[4] + x * c[5]))));
    qd[j] = c[1] + x * (2 * c[2] + x * (3 * c[3] + x * (4 * c[4] + x * 5 * c[5])));
    qdd[j] = 2 * c[2] + x * (6 * c[3] + x * (12 * c[4] + x * 20 * c[5]));
  }
}

double distanceToPath(std::span<const double> q,
                      const std::vector<std::vector<double>>& waypoints) {
  double nearest = INFINITY;
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    const std::vector<double>& a = waypoints[i];
    const std::vector<double>& b = waypoints[std::min(i + 1, waypoints.size() - 1)];
    double along = 0;
    double length = 0;
    for (std::size_t j = 0; j < q.size(); ++j) {
      along += (q[j] - a[j]) * (b[j] - a[j]);
      length += (b[j] - a[j]) * (b[j] - a[j]);
    }
    const double s = length > 0 ? std::clamp(along / length, 0.0, 1.0) : 0.0;
    double squared = 0;
    for (std::size_t j = 0; j < q.size(); ++j) {
      const double d = q[j] - (a[j] + s * (b[j] - a[j]));
      squared += d * d;
    }
    nearest = std::min(nearest, std::sqrt(squared));
  }
  return nearest;
}

double pathDeviation(const TimedPath& path, double step) {
  std::vector<double> q(path.dof()), qd(path.dof()), qdd(path.dof());
  double largest = 0;
  const auto steps = static_cast<std::size_t>(std::floor(path.duration() / step));
  for (std::size_t k = 0; k <= steps + 1; ++k) {
    path.sample(std::min(static_cast<double>(k) * step, path.duration()), q, qd, qdd);
    largest = std::max(largest, distanceToPath(q, path.waypoints()));
  }
  return largest;
}

}  // namespace kaboum::exec
