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
// Walls are 0.2 m thick; doors 1.2 m. Routes run along corridor centrelines and into rooms
// through the doors, well clear of walls and furniture.
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

}  // namespace

std::vector<std::string> BuiltinWorldNames() { return {"office", "ambiguous"}; }

Result<World> MakeBuiltinWorld(const std::string& name, double resolution) {
  if (!(resolution > 0.0 && resolution <= 0.5)) {
    return InvalidInput("world resolution must be in (0, 0.5] m");
  }
  if (name == "office") {
    return MakeOffice(resolution);
  }
  if (name == "ambiguous") {
    return MakeAmbiguous(resolution);
  }
  return InvalidInput("unknown built-in world '" + name + "' (office, ambiguous)");
}

}  // namespace gridslam::simulation
