#include "gridslam/pipeline/slam_options.hpp"
