#include "gridslam/keymap/key_map.hpp"

#include "gridslam/grid/log_odds.hpp"

namespace gridslam::keymap {

OccupancyImage ToOccupancyImage(const Grid2D<float>& log_odds, double occupied_probability,
                                double free_probability) {
  const auto occupied = static_cast<float>(ProbabilityToLogOdds(occupied_probability));
  const auto free = static_cast<float>(ProbabilityToLogOdds(free_probability));
  OccupancyImage image(log_odds.Limits(), kUnknownCell);
  for (std::size_t k = 0; k < log_odds.size(); ++k) {
    const float l = log_odds.data()[k];
    image.data()[k] = l > occupied ? kOccupiedCell : (l < free ? kFreeCell : kUnknownCell);
  }
  return image;
}

Grid2D<std::uint8_t> ObstacleMask(const Grid2D<float>& log_odds, double occupied_probability) {
  const auto occupied = static_cast<float>(ProbabilityToLogOdds(occupied_probability));
  Grid2D<std::uint8_t> mask(log_odds.Limits(), 0);
  for (std::size_t k = 0; k < log_odds.size(); ++k) {
    mask.data()[k] = log_odds.data()[k] > occupied ? 1 : 0;
  }
  return mask;
}

}  // namespace gridslam::keymap
