// The prior search of loop closure (loop_closure/prior_search.hpp, docs/alignment.md "Prior
// search"): branch and bound against the exhaustive lattice it replaces, for the windows a
// loop's uncertainty distance gives (Arg: translation half-window [dm]; the rotation window
// grows with it as PriorSearchOptions::WindowTheta does at the same uncertainty distance).
// Two 12 m key maps of the synthetic corridor world, 2.5 m apart; the prediction is 0.7 of the
// window off in x and y and 0.6 of the rotation window off in yaw. Also the refinement on the
// distance field that follows an alignment.
#include <benchmark/benchmark.h>

#include "gridslam/loop_closure/grid_refinement.hpp"
#include "gridslam/loop_closure/prior_search.hpp"
#include "gridslam/matching/internal/synthetic.hpp"

namespace gridslam::loop_closure {
namespace {

namespace synthetic = matching::internal;

const Pose2 kTwa(0.0, 0.5, 0.0);
const Pose2 kTwb(2.5, 0.2, 0.2);

struct Fixture {
  Fixture()
      : a(synthetic::MakeKeyMap(synthetic::CorridorWorld(), kTwa)),
        b(synthetic::MakeKeyMap(synthetic::CorridorWorld(), kTwb)) {}
  synthetic::SyntheticKeyMap a;
  synthetic::SyntheticKeyMap b;
};

const Fixture& Get() {
  static const Fixture fixture;
  return fixture;
}

template <bool kExhaustive>
void BM_SearchAroundPrior(benchmark::State& state) {
  const Fixture& f = Get();
  const PriorSearchOptions options;
  const double window_xy = 0.1 * static_cast<double>(state.range(0));
  const double u = window_xy / options.window_per_m;  // the uncertainty distance it stands for
  const double window_theta = options.WindowTheta(u);
  const Pose2 T_a_b = Between(kTwa, kTwb);
  const Pose2 prior = Pose2(0.7 * window_xy, -0.7 * window_xy, 0.6 * window_theta) * T_a_b;
  PriorSearchResult result;
  for (auto _ : state) {
    result = kExhaustive ? SearchAroundPriorExhaustive(f.b.obstacles, f.a.distance, prior,
                                                       window_xy, window_theta, options)
                         : SearchAroundPrior(f.b.obstacles, f.a.distance, prior, window_xy,
                                             window_theta, options);
    benchmark::DoNotOptimize(result);
  }
  state.counters["poses"] = static_cast<double>(result.poses);
  state.counters["scored"] = static_cast<double>(result.scored);
  state.counters["ok"] = result.ok ? 1.0 : 0.0;
  state.counters["error_m"] = (result.T_a_b.translation() - T_a_b.translation()).norm();
}
BENCHMARK_TEMPLATE(BM_SearchAroundPrior, false)
    ->Arg(10)
    ->Arg(30)
    ->Arg(60)
    ->Arg(100)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_SearchAroundPrior, true)
    ->Arg(10)
    ->Arg(30)
    ->Arg(60)
    ->Arg(100)
    ->Unit(benchmark::kMillisecond);

// The Gauss-Newton refinement that follows an alignment (loop_closure/grid_refinement.hpp): b's
// obstacle points on a's distance field, from a start 0.1 m and 0.02 rad off the truth.
void BM_RefineOnDistanceField(benchmark::State& state) {
  const Fixture& f = Get();
  const RefinementOptions options;
  const Pose2 T_a_b = Between(kTwa, kTwb);
  const Pose2 start = Pose2(0.07, -0.07, 0.02) * T_a_b;
  RefinementResult result;
  for (auto _ : state) {
    result = RefineOnDistanceField(f.b.obstacles, f.a.distance, start, options);
    benchmark::DoNotOptimize(result);
  }
  state.counters["ok"] = result.ok ? 1.0 : 0.0;
  state.counters["points"] = result.points;
  state.counters["iterations"] = result.iterations;
  state.counters["error_m"] = (result.T_a_b.translation() - T_a_b.translation()).norm();
}
BENCHMARK(BM_RefineOnDistanceField)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace gridslam::loop_closure
