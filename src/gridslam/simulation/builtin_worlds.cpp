// The built-in worlds, drawn in code from rectangles (metres, origin at the lower-left corner):
//   office    50 x 50 m: a ring corridor and a central cross (2.4 m wide) around four blocks of
//             offices, a lab, a pillared hall, a kitchen, a storage room with shelves, a
//             conference room and a lecture room; niches in the outer walls. Its tour drives
//             the outer ring, then a second loop through the hall, the middle corridor and the
//             lab, and visits three rooms: several large loops and many revisits.
//   ambiguous 62 x 30 m: a 60 m corridor without a single feature, and two rows of eight
//             identical rooms (same door, same furniture) off two parallel corridors: perceptual
//             aliasing everywhere, and the featureless corridor is longer than the laser range.
//             Its tour drives the featureless corridor, visits four of the identical rooms and
//             drives the middle corridor twice in the same direction.
//   campus    250 x 170 m: open ground with six blocks of buildings between 10 m roads, trees
//             and posts along the roads, niches in the fence. Its 1.72 km tour drives the whole
//             ring (784 m) before closing it, then two loops of 310 m and 466 m through the middle;
//             every revisit comes after at least 300 m of travel.
//   corridors 72 x 72 m: a square ring of 2.4 m corridors with 60 m sides (like the ACES
//             building) between outer and inner offices and a solid core; each side has doors
//             along one 20 m stretch only, so 30-40 m of every side is blank wall. Its tour
//             drives the ring twice anticlockwise, visiting four rooms.
//   courts    260 x 130 m: a 236 x 106 m ring of 2.4 m corridors around two courtyards, split by
//             a middle corridor (like MIT's Killian Court building), lined on both sides with
//             rooms of pseudo-random width and depth, most with a door, some with a cabinet
//             (`simulation.layout` chooses the draw; 1 by default).
//             Its 1.81 km tour drives the whole ring (690 m) before closing it, up the middle
//             corridor and all the way back: every corridor is met again from its other end,
//             where a stretch of doors can look like itself turned by pi.
// Walls are 0.2 m thick; doors 1.2 m. Routes run along corridor centrelines and into rooms
// through the doors, well clear of walls and furniture.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <utility>

#include "gridslam/simulation/world.hpp"

namespace gridslam::simulation {
namespace {

using V2 = Eigen::Vector2d;

constexpr double kWall = 0.2;
constexpr double kDoor = 1.2;

enum class Side { kSouth, kNorth, kWest, kEast };

/// A rectangular room with a door in its `door` wall, drawn in room coordinates: u runs along
/// the door wall (from its lower/left end), v from the door wall into the room.
class Room {
 public:
  Room(WorldBuilder& b, double x0, double y0, double x1, double y1, Side door)
      : b_(b), x0_(x0), y0_(y0), x1_(x1), y1_(y1), door_(door) {
    b_.Carve(x0, y0, x1, y1);
  }
  [[nodiscard]] double Width() const {
    return door_ == Side::kSouth || door_ == Side::kNorth ? x1_ - x0_ : y1_ - y0_;
  }
  [[nodiscard]] double Depth() const {
    return door_ == Side::kSouth || door_ == Side::kNorth ? y1_ - y0_ : x1_ - x0_;
  }
  /// A door centred at u through the door wall.
  Room& Door(double u, double width = kDoor) {
    Set(u - 0.5 * width, -kWall - 0.05, u + 0.5 * width, 0.05, false);
    return *this;
  }
  /// Furniture in room coordinates.
  Room& Fill(double u0, double v0, double u1, double v1) {
    Set(u0, v0, u1, v1, true);
    return *this;
  }
  /// A desk against the back wall away from the door at u, and a cabinet on the door's side.
  Room& Furnish(double door_u, int variant) {
    const double length = 1.2 + 0.3 * (variant % 4);
    const double cabinet = 0.8 + 0.4 * (variant % 3);
    if (door_u < 0.5 * Width()) {
      Fill(Width() - length, Depth() - 0.7, Width(), Depth());
      Fill(0.0, 1.5, 0.45, 1.5 + cabinet);
    } else {
      Fill(0.0, Depth() - 0.7, length, Depth());
      Fill(Width() - 0.45, 1.5, Width(), 1.5 + cabinet);
    }
    return *this;
  }

 private:
  void Set(double u0, double v0, double u1, double v1, bool fill) {
    double ax = 0.0;
    double ay = 0.0;
    double bx = 0.0;
    double by = 0.0;
    switch (door_) {
      case Side::kSouth:
        ax = x0_ + u0, bx = x0_ + u1, ay = y0_ + v0, by = y0_ + v1;
        break;
      case Side::kNorth:
        ax = x0_ + u0, bx = x0_ + u1, ay = y1_ - v1, by = y1_ - v0;
        break;
      case Side::kWest:
        ax = x0_ + v0, bx = x0_ + v1, ay = y0_ + u0, by = y0_ + u1;
        break;
      case Side::kEast:
        ax = x1_ - v1, bx = x1_ - v0, ay = y0_ + u0, by = y0_ + u1;
        break;
    }
    if (fill) {
      b_.Fill(ax, ay, bx, by);
    } else {
      b_.Carve(ax, ay, bx, by);
    }
  }
  WorldBuilder& b_;
  double x0_, y0_, x1_, y1_;
  Side door_;
};

/// Appends a visit to a room: from `corridor` (on the door's axis, on the corridor centreline,
/// `wall_offset` from the room's wall face) in along `in`, around a `depth` x `side` rectangle
/// (side along `lateral`) and back out to `corridor`.
void AppendRoomVisit(std::vector<V2>& route, const V2& corridor, const V2& in, const V2& lateral,
                     double wall_offset, double depth, double side) {
  const V2 face = corridor + in * wall_offset;
  route.push_back(corridor);
  route.push_back(face + in * 1.0);
  route.push_back(face + in * depth);
  route.push_back(face + in * depth + lateral * side);
  route.push_back(face + in * 2.0 + lateral * side);
  route.push_back(face + in * 2.0);
  route.push_back(corridor);
}

World MakeOffice(double resolution) {
  WorldBuilder b(50.0, 50.0, resolution);
  // Ring corridor and central cross; centrelines y = 2.2, 25, 47.8 and x = 2.2, 25, 47.8.
  b.Carve(1.0, 1.0, 49.0, 3.4).Carve(1.0, 46.6, 49.0, 49.0);
  b.Carve(1.0, 1.0, 3.4, 49.0).Carve(46.6, 1.0, 49.0, 49.0);
  b.Carve(1.0, 23.8, 49.0, 26.2).Carve(23.8, 1.0, 26.2, 49.0);
  // Niches in the outer walls, irregularly spaced.
  const std::pair<double, double> south[] = {{6.0, 1.0}, {17.0, 1.6}, {31.0, 0.8}, {40.0, 1.2}};
  const std::pair<double, double> north[] = {{9.0, 1.4}, {20.0, 0.8}, {34.0, 1.2}, {43.0, 1.0}};
  const std::pair<double, double> west[] = {{7.0, 1.2}, {18.0, 0.8}, {32.0, 1.6}, {41.0, 1.0}};
  const std::pair<double, double> east[] = {{5.0, 0.8}, {19.0, 1.4}, {30.0, 1.0}, {38.0, 1.2}};
  for (int k = 0; k < 4; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    b.Carve(south[ku].first, 0.4, south[ku].first + south[ku].second, 1.0);
    b.Carve(north[ku].first, 49.0, north[ku].first + north[ku].second, 49.6);
    b.Carve(0.4, west[ku].first, 1.0, west[ku].first + west[ku].second);
    b.Carve(49.0, east[ku].first, 49.6, east[ku].first + east[ku].second);
  }

  // South-west block: two rows of five offices around a lab.
  for (int k = 0; k < 5; ++k) {
    const double x0 = 3.6 + 4.04 * k;
    Room(b, x0, 3.6, x0 + 3.84, 8.6, Side::kSouth).Door(1.2).Furnish(1.2, k);
    Room(b, x0, 18.6, x0 + 3.84, 23.6, Side::kNorth).Door(2.6).Furnish(2.6, k + 1);
  }
  Room lab(b, 3.6, 8.8, 23.6, 18.4, Side::kWest);
  lab.Door(4.8, 1.6);
  b.Carve(23.55, 12.8, 23.85, 14.4);  // East door of the lab.
  b.Fill(6.0, 10.4, 10.0, 11.8).Fill(13.0, 10.4, 17.0, 11.8).Fill(6.0, 15.4, 9.0, 16.8);
  b.Fill(12.0, 15.6, 18.5, 16.6).Fill(20.5, 10.0, 21.0, 10.5).Fill(20.5, 16.8, 23.6, 18.4);

  // South-east block: a hall with pillars, shelves and a partition; four wide openings.
  b.Carve(26.4, 3.6, 46.4, 23.6);
  b.Carve(26.15, 12.6, 26.45, 14.6).Carve(46.35, 12.6, 46.65, 14.6);
  b.Carve(35.4, 3.35, 37.4, 3.65).Carve(38.0, 23.55, 40.0, 23.85);
  for (const double x : {31.0, 36.4, 41.8}) {
    for (const double y : {8.6, 18.6}) {
      b.Fill(x - 0.25, y - 0.25, x + 0.25, y + 0.25);
    }
  }
  b.Fill(27.0, 20.8, 29.6, 23.6).Fill(43.0, 4.2, 45.8, 5.0);
  b.Fill(33.0, 16.0, 33.2, 21.0).Fill(33.0, 20.8, 36.0, 21.0);

  // North-west block: offices along the middle corridor, kitchen, storage, conference room.
  const double office_y[][2] = {{26.4, 30.4}, {30.6, 35.6}, {35.8, 40.2}, {40.4, 46.4}};
  for (int k = 0; k < 4; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    const double u = 0.5 * (office_y[ku][1] - office_y[ku][0]);
    Room(b, 18.6, office_y[ku][0], 23.6, office_y[ku][1], Side::kEast).Door(u).Furnish(u, k + 2);
  }
  Room(b, 3.6, 26.4, 10.8, 34.0, Side::kWest)
      .Door(3.6)
      .Fill(4.4, 0.0, 7.2, 0.7)
      .Fill(6.5, 0.7, 7.2, 3.6)
      .Fill(1.8, 4.6, 3.3, 6.1);
  Room storage(b, 11.0, 26.4, 18.4, 34.0, Side::kSouth);
  storage.Door(3.6);
  for (const double v : {2.2, 4.6, 6.6}) {
    storage.Fill(0.6, v, 6.8, v + 0.4);
  }
  Room(b, 3.6, 34.2, 18.4, 46.4, Side::kNorth)
      .Door(7.4)
      .Fill(3.4, 5.4, 11.4, 8.4)
      .Fill(0.0, 10.0, 0.5, 12.2)
      .Fill(13.0, 0.0, 14.8, 0.6);

  // North-east block: offices along the north and east corridors, a lecture room.
  const double north_x[][2] = {{26.4, 30.6}, {30.8, 34.0}, {34.2, 39.6}, {39.8, 46.4}};
  for (int k = 0; k < 4; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    const double u = k == 3 ? 4.2 : 1.6;
    Room(b, north_x[ku][0], 41.4, north_x[ku][1], 46.4, Side::kNorth).Door(u).Furnish(u, k);
  }
  const double east_y[][2] = {{26.4, 31.0}, {31.2, 35.0}, {35.2, 41.2}};
  for (int k = 0; k < 3; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    const double u = k == 1 ? 1.8 : 2.8;
    Room(b, 41.4, east_y[ku][0], 46.4, east_y[ku][1], Side::kEast).Door(u).Furnish(u, k + 3);
  }
  Room lecture(b, 26.4, 26.4, 41.2, 41.2, Side::kWest);
  lecture.Door(6.6);
  b.Carve(34.0, 26.15, 35.2, 26.45);  // South door of the lecture room.
  for (const double y : {29.0, 31.4, 35.0, 37.4}) {
    b.Fill(29.0, y, 39.0, y + 0.6);
  }
  b.Fill(33.0, 39.6, 35.0, 40.2);

  // The tour. Loop A: the outer ring, with visits to an office, an east office and the
  // conference room. Loop B: the middle corridor's south half, the hall, the east corridor, the
  // whole middle corridor west, the lab, back to the start.
  std::vector<V2> route = {{8.0, 2.2}};
  AppendRoomVisit(route, {12.88, 2.2}, {0, 1}, {1, 0}, 1.4, 3.4, 1.6);
  route.insert(route.end(), {{25.0, 2.2}, {47.8, 2.2}});
  AppendRoomVisit(route, {47.8, 33.0}, {-1, 0}, {0, 1}, 1.4, 3.0, 1.4);
  route.push_back({47.8, 47.8});
  AppendRoomVisit(route, {11.0, 47.8}, {0, -1}, {1, 0}, 1.4, 3.4, 3.0);
  route.insert(route.end(), {{2.2, 47.8},
                             {2.2, 2.2},
                             {25.0, 2.2},
                             {25.0, 13.6},
                             {47.8, 13.6},
                             {47.8, 25.0},
                             {2.2, 25.0},
                             {2.2, 13.6},
                             {25.0, 13.6},
                             {25.0, 2.2},
                             {8.0, 2.2}});
  return b.Build("office", std::move(route));
}

World MakeAmbiguous(double resolution) {
  constexpr int kRooms = 8;
  WorldBuilder b(62.0, 30.0, resolution);
  // Ring corridor (centrelines y = 2.2, 27.8; x = 2.2, 59.8) and a middle corridor (y = 15).
  b.Carve(1.0, 1.0, 61.0, 3.4).Carve(1.0, 26.6, 61.0, 29.0);
  b.Carve(1.0, 1.0, 3.4, 29.0).Carve(58.6, 1.0, 61.0, 29.0);
  b.Carve(3.4, 13.8, 58.6, 16.2);
  // Two rows of identical rooms; both open northwards, so the south corridor has no feature.
  const double width = (58.4 - 3.6 - (kRooms - 1) * kWall) / kRooms;
  for (int k = 0; k < kRooms; ++k) {
    const double x0 = 3.6 + k * (width + kWall);
    for (const double y0 : {3.6, 16.4}) {
      Room(b, x0, y0, x0 + width, y0 + 10.0, Side::kNorth)
          .Door(1.5)
          .Fill(4.5, 6.0, 6.0, 7.5)
          .Fill(0.0, 9.4, 2.5, 10.0)
          .Fill(width - 0.5, 1.0, width, 3.0);
    }
  }
  auto door_x = [&](int k) { return 3.6 + k * (width + kWall) + 1.5; };
  std::vector<V2> route = {{2.2, 8.0}, {2.2, 2.2}, {59.8, 2.2}, {59.8, 15.0}};
  AppendRoomVisit(route, {door_x(5), 15.0}, {0, -1}, {1, 0}, 1.4, 4.0, 2.0);
  AppendRoomVisit(route, {door_x(2), 15.0}, {0, -1}, {1, 0}, 1.4, 4.0, 2.0);
  route.insert(route.end(), {{2.2, 15.0}, {2.2, 27.8}});
  AppendRoomVisit(route, {door_x(1), 27.8}, {0, -1}, {1, 0}, 1.4, 4.0, 2.0);
  AppendRoomVisit(route, {door_x(6), 27.8}, {0, -1}, {1, 0}, 1.4, 4.0, 2.0);
  // Down the east corridor and along the middle corridor again, the same way: past the same
  // identical doors, back to the start, facing the way the tour began.
  route.insert(route.end(), {{59.8, 27.8}, {59.8, 15.0}, {2.2, 15.0}, {2.2, 8.0}});
  return b.Build("ambiguous", std::move(route));
}

/// A small deterministic generator for the layout of the large worlds (independent of the
/// simulation seed: a world is the same for every run).
class Layout {
 public:
  explicit Layout(std::uint32_t state) : state_(state) {}
  /// Uniform in [lo, hi).
  double Uniform(double lo, double hi) {
    state_ = state_ * 1664525U + 1013904223U;  // Numerical Recipes LCG
    return lo + (hi - lo) * static_cast<double>(state_ >> 8) / static_cast<double>(1U << 24);
  }

 private:
  std::uint32_t state_;
};

World MakeCampus(double resolution) {
  // 250 x 170 m inside a 1 m fence. Roads 10 m wide: a ring (centrelines y = 7, 163; x = 7,
  // 243), a middle road (y = 85) and two cross roads (x = 88, 166) between six blocks of
  // buildings. Everything but the buildings, trees and the fence is open ground.
  constexpr double kW = 250.0;
  constexpr double kH = 170.0;
  WorldBuilder b(kW, kH, resolution);
  b.Carve(1.0, 1.0, kW - 1.0, kH - 1.0);
  Layout layout(2026U);
  // Niches and buttresses along the fence, irregularly spaced, so the ring road's outer side is
  // not one featureless wall.
  for (double u = 4.0; u < kW - 6.0; u += layout.Uniform(8.0, 22.0)) {
    const double w = layout.Uniform(0.6, 2.0);
    b.Carve(u, 0.4, u + w, 1.0);
    b.Fill(u + layout.Uniform(4.0, 7.0), 1.0, u + layout.Uniform(7.5, 8.5), 1.5);
  }
  for (double u = 4.0; u < kW - 6.0; u += layout.Uniform(8.0, 22.0)) {
    b.Carve(u, kH - 1.0, u + layout.Uniform(0.6, 2.0), kH - 0.4);
  }
  for (double u = 4.0; u < kH - 6.0; u += layout.Uniform(8.0, 22.0)) {
    b.Carve(0.4, u, 1.0, u + layout.Uniform(0.6, 2.0));
    b.Carve(kW - 1.0, u, kW - 0.4, u + layout.Uniform(0.6, 2.0));
  }
  // Six blocks between the roads; each holds two to four buildings with irregular setbacks,
  // some L-shaped, with open lawns between them.
  const double xs[][2] = {{12.0, 83.0}, {93.0, 161.0}, {171.0, 238.0}};
  const double ys[][2] = {{12.0, 80.0}, {90.0, 158.0}};
  for (const auto& bx : xs) {
    for (const auto& by : ys) {
      const double mx = layout.Uniform(0.35, 0.65) * (bx[1] - bx[0]) + bx[0];
      const double my = layout.Uniform(0.35, 0.65) * (by[1] - by[0]) + by[0];
      const double lots[][4] = {{bx[0], by[0], mx, my},
                                {mx, by[0], bx[1], my},
                                {bx[0], my, mx, by[1]},
                                {mx, my, bx[1], by[1]}};
      for (const auto& lot : lots) {
        if (layout.Uniform(0.0, 1.0) < 0.2) {
          continue;  // a lawn
        }
        const double x0 = lot[0] + layout.Uniform(1.0, 6.0);
        const double y0 = lot[1] + layout.Uniform(1.0, 6.0);
        const double x1 = lot[2] - layout.Uniform(1.0, 6.0);
        const double y1 = lot[3] - layout.Uniform(1.0, 6.0);
        if (x1 - x0 < 6.0 || y1 - y0 < 6.0) {
          continue;
        }
        if (layout.Uniform(0.0, 1.0) < 0.5) {
          // L-shape: two wings.
          const double cx = x0 + layout.Uniform(0.3, 0.5) * (x1 - x0);
          const double cy = y0 + layout.Uniform(0.3, 0.5) * (y1 - y0);
          b.Fill(x0, y0, cx, y1).Fill(x0, y0, x1, cy);
        } else {
          b.Fill(x0, y0, x1, y1);
          // A recessed entrance.
          const double e = x0 + layout.Uniform(0.2, 0.7) * (x1 - x0);
          b.Carve(e, y0, e + 2.0, y0 + 1.0);
        }
      }
    }
  }
  // Trees (0.6 m) and posts (0.2 m) along both sides of every road, 3.8 m off its centreline,
  // none within 9 m of a crossing.
  const double road_y[] = {7.0, 85.0, 163.0};
  const double road_x[] = {7.0, 88.0, 166.0, 243.0};
  const auto near_crossing = [](double u, const double* centres, int n) {
    for (int k = 0; k < n; ++k) {
      if (std::abs(u - centres[k]) < 9.0) {
        return true;
      }
    }
    return false;
  };
  for (const double y : road_y) {
    for (const double side : {-3.8, 3.8}) {
      for (double x = 3.0; x < kW - 3.0; x += layout.Uniform(6.0, 16.0)) {
        if (near_crossing(x, road_x, 4)) {
          continue;
        }
        const double r = layout.Uniform(0.0, 1.0) < 0.7 ? 0.3 : 0.1;
        b.Fill(x - r, y + side - r, x + r, y + side + r);
      }
    }
  }
  for (const double x : road_x) {
    for (const double side : {-3.8, 3.8}) {
      for (double y = 3.0; y < kH - 3.0; y += layout.Uniform(6.0, 16.0)) {
        if (near_crossing(y, road_y, 3)) {
          continue;
        }
        const double r = layout.Uniform(0.0, 1.0) < 0.7 ? 0.3 : 0.1;
        b.Fill(x + side - r, y - r, x + side + r, y + r);
      }
    }
  }
  // The tour (1.72 km): loop A, the whole ring (784 m), closed only where it began; then up the
  // west cross road, east along the middle road, round the north-east block (a 310 m loop) and
  // the middle block (466 m) back to the west cross road, north to the ring and round the west
  // side to the start. Every revisit comes after at least 300 m of travel.
  std::vector<V2> route = {
      {20.0, 7.0},  {243.0, 7.0},  {243.0, 163.0}, {7.0, 163.0},   {7.0, 7.0},     {20.0, 7.0},
      {88.0, 7.0},  {88.0, 85.0},  {166.0, 85.0},  {166.0, 163.0}, {243.0, 163.0}, {243.0, 85.0},
      {88.0, 85.0}, {88.0, 163.0}, {7.0, 163.0},   {7.0, 7.0},     {20.0, 7.0}};
  return b.Build("campus", std::move(route));
}

World MakeCorridors(double resolution) {
  // 72 x 72 m: a square ring corridor 2.4 m wide (centrelines x, y = 6 and 66; 60 m sides) like
  // the ACES building, offices on both sides of it and a solid core. On each side only one
  // stretch of about 20 m has doors; the rest of the side is blank wall, so for 30-40 m the
  // corridor is featureless (a 10 m lidar sees two parallel walls and nothing else there).
  constexpr double kS = 72.0;
  WorldBuilder b(kS, kS, resolution);
  b.Carve(4.8, 4.8, 67.2, 7.2).Carve(4.8, 64.8, 67.2, 67.2);
  b.Carve(4.8, 4.8, 7.2, 67.2).Carve(64.8, 4.8, 67.2, 67.2);
  const double widths[] = {4.0, 3.2, 5.6, 4.0, 6.4, 3.2, 4.8};
  // Door zones along each side, in the side's own coordinate u in [7.4, 64.6].
  const double zone[][2] = {{12.0, 32.0}, {40.0, 60.0}, {20.0, 40.0}, {34.0, 54.0}};
  // Per side (south, east, north, west), the room visits the tour can make: inner and outer
  // rooms with a door, at least 4 m wide.
  struct Visit {
    V2 corridor;  // on the corridor centreline, on the door's axis
    V2 in;
    V2 lateral;
    double depth = 0.0;
  };
  std::vector<Visit> inner_visits[4];
  std::vector<Visit> outer_visits[4];
  int variant = 0;
  for (int sidx = 0; sidx < 4; ++sidx) {
    const auto s = static_cast<std::size_t>(sidx);
    double u = 7.4;
    for (int k = 0; u < 64.0; ++k) {
      const double w = std::min(widths[static_cast<std::size_t>((k + sidx) % 7)], 64.6 - u);
      if (w < 2.5) {
        break;
      }
      const bool door = u + 0.5 * w > zone[s][0] && u + 0.5 * w < zone[s][1];
      const double du = 1.0 + 0.2 * ((k + sidx) % 3);
      const double outer_door = u + du;  // along the side's axis
      const double inner_door = u + w - du;
      // Outer room (3.6 m deep) and inner room (6 m deep) on either side of the corridor; the
      // outer room's door lies near its low-u end, the inner room's near its high-u end.
      std::optional<Room> outer;
      std::optional<Room> inner;
      Visit o;
      Visit i;
      o.depth = 2.2;
      i.depth = 3.6;
      switch (sidx) {
        case 0:  // south: u along +x, centreline y = 6
          outer.emplace(b, u, 1.0, u + w, 4.6, Side::kNorth);
          inner.emplace(b, u, 7.4, u + w, 13.4, Side::kSouth);
          o = {{outer_door, 6.0}, {0, -1}, {1, 0}, o.depth};
          i = {{inner_door, 6.0}, {0, 1}, {-1, 0}, i.depth};
          break;
        case 1:  // east: u along +y, centreline x = 66
          outer.emplace(b, 67.4, u, 71.0, u + w, Side::kWest);
          inner.emplace(b, 58.6, u, 64.6, u + w, Side::kEast);
          o = {{66.0, outer_door}, {1, 0}, {0, 1}, o.depth};
          i = {{66.0, inner_door}, {-1, 0}, {0, -1}, i.depth};
          break;
        case 2:  // north: u along +x, centreline y = 66
          outer.emplace(b, u, 67.4, u + w, 71.0, Side::kSouth);
          inner.emplace(b, u, 58.6, u + w, 64.6, Side::kNorth);
          o = {{outer_door, 66.0}, {0, 1}, {1, 0}, o.depth};
          i = {{inner_door, 66.0}, {0, -1}, {-1, 0}, i.depth};
          break;
        default:  // west: u along +y, centreline x = 6
          outer.emplace(b, 1.0, u, 4.6, u + w, Side::kEast);
          inner.emplace(b, 7.4, u, 13.4, u + w, Side::kWest);
          o = {{6.0, outer_door}, {-1, 0}, {0, 1}, o.depth};
          i = {{6.0, inner_door}, {1, 0}, {0, -1}, i.depth};
          break;
      }
      if (door) {
        outer->Door(du).Furnish(du, variant++);
        inner->Door(w - du).Furnish(w - du, variant++);
        if (w >= 4.0) {
          outer_visits[s].push_back(o);
          inner_visits[s].push_back(i);
        }
      }
      u += w + kWall;
    }
  }
  const auto visit = [](std::vector<V2>& route, const Visit& v) {
    AppendRoomVisit(route, v.corridor, v.in, v.lateral, 1.4, v.depth, 1.4);
  };
  // The core between the inner rooms stays solid. The tour: two laps anticlockwise (so the
  // second lap revisits the first in the same direction, as relations need), the first visiting
  // an inner room on the south side and an outer room on the east side, the second an outer
  // room on the north side and an inner room on the west side: 2 x 240 m of ring, four rooms.
  std::vector<V2> route = {{9.0, 6.0}};
  visit(route, inner_visits[0].front());
  route.push_back({66.0, 6.0});
  visit(route, outer_visits[1].back());
  route.insert(route.end(), {{66.0, 66.0}, {6.0, 66.0}, {6.0, 6.0}, {66.0, 6.0}, {66.0, 66.0}});
  visit(route, outer_visits[2].back());
  route.push_back({6.0, 66.0});
  visit(route, inner_visits[3].back());
  route.insert(route.end(), {{6.0, 6.0}, {9.0, 6.0}});
  return b.Build("corridors", std::move(route));
}

/// Uniform numbers from std::minstd_rand, whose sequence the standard fixes (the distributions
/// of <random> are not portable): the same world on every platform.
class UniformSource {
 public:
  explicit UniformSource(std::uint32_t seed) : engine_(seed) {}
  double operator()(double lo, double hi) {
    const double unit = static_cast<double>(engine_() - std::minstd_rand::min()) /
                        static_cast<double>(std::minstd_rand::max() - std::minstd_rand::min());
    return lo + (hi - lo) * unit;
  }

 private:
  std::minstd_rand engine_;
};

/// Rooms along one side of a straight corridor: from u0 to u1 along the corridor (x for a
/// horizontal one, y for a vertical one), behind its wall face at `face` (the other coordinate),
/// reaching away from the corridor in direction `out` (+1 or -1). Widths 3-9 m, depths 3-7 m;
/// three in four have a door, one in two a 0.8 x 0.6 m cabinet.
void RoomsAlong(WorldBuilder& b, UniformSource& uniform, bool horizontal, double u0, double u1,
                double face, double out) {
  const auto rect = [&](double ua, double va, double ub, double vb, bool fill) {
    const double lo_u = std::min(ua, ub);
    const double hi_u = std::max(ua, ub);
    const double lo_v = std::min(va, vb);
    const double hi_v = std::max(va, vb);
    if (horizontal) {
      fill ? b.Fill(lo_u, lo_v, hi_u, hi_v) : b.Carve(lo_u, lo_v, hi_u, hi_v);
    } else {
      fill ? b.Fill(lo_v, lo_u, hi_v, hi_u) : b.Carve(lo_v, lo_u, hi_v, hi_u);
    }
  };
  double u = u0 + 1.0;
  while (u < u1 - 4.0) {
    const double w = std::min(uniform(3.0, 9.0), u1 - u - 0.5);
    if (w < 2.5) {
      break;
    }
    const double depth = uniform(3.0, 7.0);
    const double v0 = face + out * kWall;
    rect(u, v0, u + w, v0 + out * depth, false);
    if (uniform(0.0, 1.0) < 0.75) {
      const double door = u + uniform(0.3, w - kDoor - 0.3);
      rect(door, face - out * 0.05, door + kDoor, v0 + out * 0.05, false);
    }
    if (uniform(0.0, 1.0) < 0.5) {
      const double cu = u + uniform(0.5, w - 1.5);
      const double cv = v0 + out * uniform(1.0, depth - 1.0);
      rect(cu, cv, cu + 0.8, cv + out * 0.6, true);
    }
    u += w + kWall;
  }
}

World MakeCourts(double resolution, int layout) {
  // Corridor centrelines: south y = 12, north y = 118, west x = 12, east x = 248, middle x = 130.
  WorldBuilder b(260.0, 130.0, resolution);
  const auto corridors = [&b] {
    b.Carve(10.8, 10.8, 249.2, 13.2).Carve(10.8, 116.8, 249.2, 119.2);
    b.Carve(10.8, 10.8, 13.2, 119.2).Carve(246.8, 10.8, 249.2, 119.2);
    b.Carve(128.8, 10.8, 131.2, 119.2);
  };
  corridors();
  UniformSource uniform(static_cast<std::uint32_t>(layout));
  // Outer rooms along the whole of each side; courtyard rooms keep 7.3 m clear of the corners,
  // where the rooms of the crossing corridor reach.
  RoomsAlong(b, uniform, true, 13.2, 246.8, 10.8, -1.0);   // south, outer
  RoomsAlong(b, uniform, true, 13.2, 246.8, 119.2, 1.0);   // north, outer
  RoomsAlong(b, uniform, false, 13.2, 116.8, 10.8, -1.0);  // west, outer
  RoomsAlong(b, uniform, false, 13.2, 116.8, 249.2, 1.0);  // east, outer
  for (const auto& [u0, u1] : {std::pair{20.5, 121.5}, std::pair{138.5, 239.5}}) {
    RoomsAlong(b, uniform, true, u0, u1, 13.2, 1.0);    // south, courtyard side
    RoomsAlong(b, uniform, true, u0, u1, 116.8, -1.0);  // north, courtyard side
  }
  RoomsAlong(b, uniform, false, 20.5, 109.5, 13.2, 1.0);    // west, courtyard side
  RoomsAlong(b, uniform, false, 20.5, 109.5, 246.8, -1.0);  // east, courtyard side
  RoomsAlong(b, uniform, false, 20.5, 109.5, 128.8, -1.0);  // middle, west side
  RoomsAlong(b, uniform, false, 20.5, 109.5, 131.2, 1.0);   // middle, east side
  corridors();                                              // no cabinet may reach into a corridor
  // The ring anticlockwise and up the middle corridor, then the same way back: every corridor
  // is met again from its other end.
  std::vector<V2> route = {{12.0, 12.0}, {248.0, 12.0}, {248.0, 118.0}, {12.0, 118.0},
                           {12.0, 12.0}, {130.0, 12.0}, {130.0, 118.0}, {130.0, 12.0},
                           {12.0, 12.0}, {12.0, 118.0}, {248.0, 118.0}, {248.0, 12.0},
                           {12.0, 12.0}};
  return b.Build("courts", std::move(route));
}

}  // namespace

std::vector<std::string> BuiltinWorldNames() {
  return {"office", "ambiguous", "campus", "corridors", "courts"};
}

Result<World> MakeBuiltinWorld(const std::string& name, double resolution, int layout) {
  if (!(resolution > 0.0 && resolution <= 0.5)) {
    return InvalidInput("world resolution must be in (0, 0.5] m");
  }
  if (layout < 1) {
    return InvalidInput("world layout must be 1 or more");
  }
  if (name == "office") {
    return MakeOffice(resolution);
  }
  if (name == "ambiguous") {
    return MakeAmbiguous(resolution);
  }
  if (name == "campus") {
    return MakeCampus(resolution);
  }
  if (name == "corridors") {
    return MakeCorridors(resolution);
  }
  if (name == "courts") {
    return MakeCourts(resolution, layout);
  }
  return InvalidInput("unknown built-in world '" + name +
                      "' (office, ambiguous, campus, corridors, courts)");
}

}  // namespace gridslam::simulation
