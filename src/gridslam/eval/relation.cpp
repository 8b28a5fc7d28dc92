#include "gridslam/eval/relation.hpp"
