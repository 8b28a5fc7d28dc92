#include "gridslam/grid/grid2d.hpp"
