#include "statistics/learning_curve.hpp"

#include <boost/math/distributions/students_t.hpp>
#include <cmath>

#include "statistics/statistics_proportion.hpp"

namespace palprig::stats {

std::vector<LearningPoint> proportion_curve(const std::vector<std::pair<std::int64_t, std::int64_t>>& k_of_n,
                                            double confidence) {
  std::vector<LearningPoint> curve;
  for (std::size_t i = 0; i < k_of_n.size(); ++i) {
    LearningPoint p;
    p.session = static_cast<int>(i + 1);
    const auto [k, n] = k_of_n[i];
    p.n = n;
    if (n > 0) {
      const WilsonInterval w = wilson_interval(k, n, confidence);
      p.defined = true;
      p.value = w.p;
      p.lower = w.lower;
      p.upper = w.upper;
    }
    curve.push_back(p);
  }
  return curve;
}

std::vector<LearningPoint> mean_curve(const std::vector<std::vector<double>>& values, double confidence) {
  std::vector<LearningPoint> curve;
  for (std::size_t i = 0; i < values.size(); ++i) {
    LearningPoint p;
    p.session = static_cast<int>(i + 1);
    const auto& v = values[i];
    p.n = static_cast<std::int64_t>(v.size());
    if (!v.empty()) {
      double sum = 0;
      for (double x : v) sum += x;
      const double mean = sum / static_cast<double>(v.size());
      p.defined = true;
      p.value = p.lower = p.upper = mean;
      if (v.size() > 1) {
        double ss = 0;
        for (double x : v) ss += (x - mean) * (x - mean);
        const double sd = std::sqrt(ss / static_cast<double>(v.size() - 1));
        const boost::math::students_t_distribution<double> t(static_cast<double>(v.size() - 1));
        const double half =
            boost::math::quantile(t, 1.0 - (1.0 - confidence) / 2.0) * sd / std::sqrt(static_cast<double>(v.size()));
        p.lower = mean - half;
        p.upper = mean + half;
      }
    }
    curve.push_back(p);
  }
  return curve;
}

std::optional<int> first_run_meeting(const std::vector<LearningPoint>& curve, double benchmark, Better better,
                                     int consecutive) {
  int run = 0;
  for (const LearningPoint& p : curve) {
    const bool met = p.defined && (better == Better::higher ? p.value >= benchmark : p.value <= benchmark);
    run = met ? run + 1 : 0;
    if (run >= consecutive && consecutive > 0) return p.session - consecutive + 1;
  }
  return std::nullopt;
}

}  // namespace palprig::stats
