#include "viz/pictures.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "navigation/internal/test_worlds.h"

namespace fognav::viz {
namespace {

using navigation::Move;
using navigation::PlanResult;
using navigation::PlanStatus;
using navigation::Posture;
using navigation::internal::CorridorWithTable;
using navigation::internal::FillBox;
using navigation::internal::FlatFog;
using perception::CellType;
using perception::Fog;
using perception::Pose2;
using perception::Rgb;
using perception::RgbImage;

bool Same(const Rgb& a, const Rgb& b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

TEST(FogPicture, OneHeightIsOneGreyInEveryPicture) {
  // two maps whose heights span different ranges: the 10 cm cell is the same grey in both
  Fog low = FlatFog(20, 20, 0.04, CellType::kFloor, 0.0f);
  FillBox(&low, 0.0, 0.0, 0.2, 0.2, CellType::kFloor, 0.1f);
  Fog high = FlatFog(20, 20, 0.04, CellType::kFloor, 0.5f);
  FillBox(&high, 0.0, 0.0, 0.2, 0.2, CellType::kFloor, 0.1f);
  const Pose2 away{0.6, 0.6, 0.0};
  const RgbImage a = DrawFog(low, away, 4), b = DrawFog(high, away, 4);
  const Eigen::Vector2i p = CellPixel(low.window, 4, 1, 1);
  EXPECT_TRUE(Same(a.at(p.x(), p.y()), b.at(p.x(), p.y())));
  // and darker than the floor at 0 m, lighter than the floor at 0.5 m
  const Eigen::Vector2i q = CellPixel(low.window, 4, 10, 10);
  EXPECT_GT(a.at(q.x(), q.y()).r, a.at(p.x(), p.y()).r);
  EXPECT_LT(b.at(q.x(), q.y()).r, b.at(p.x(), p.y()).r);
}

TEST(FogPicture, ACellWithoutFloorHasItsOwnMark) {
  Fog fog = FlatFog(30, 10, 0.04);
  FillBox(&fog, 0.0, 0.0, 0.4, 0.4, CellType::kBorder, 0.05f);
  FillBox(&fog, 0.4, 0.0, 0.8, 0.4, CellType::kBorder, -std::numeric_limits<float>::infinity());
  FillBox(&fog, 0.8, 0.0, 1.2, 0.4, CellType::kObstacle, 0.3f);
  const RgbImage picture = DrawFog(fog, {5.0, 5.0, 0.0}, 6);
  // cell corners (off the diagonals of crosses and hatches)
  auto corner = [&](int ix) { return picture.at(ix * 6 + 1, 10 * 6 - 6 * 4 + 4); };
  const Rgb border = corner(3), no_floor = corner(13), obstacle = corner(23);
  EXPECT_FALSE(Same(border, no_floor));
  EXPECT_FALSE(Same(obstacle, no_floor));
  EXPECT_GT(no_floor.b, no_floor.g);  // lavender, not brown or black
  EXPECT_GT(border.r, border.b);
}

TEST(FogPicture, HasALegendAndAMetreScaleUnderTheMap) {
  const Fog fog = FlatFog(100, 100, 0.04);
  const RgbImage picture = DrawFog(fog, {2.0, 2.0, 0.0}, 6);
  ASSERT_GT(picture.height, 600 + 30);
  ASSERT_GE(picture.width, 600);
  // the legend holds dark text and the metre bar: 150 px of a black row for 1 m at 6 px per 4 cm
  int longest = 0;
  for (int v = 600; v < picture.height; ++v) {
    int run = 0;
    for (int u = 0; u < picture.width; ++u) {
      const Rgb& c = picture.at(u, v);
      run = (c.r < 60 && c.g < 60 && c.b < 60) ? run + 1 : 0;
      longest = std::max(longest, run);
    }
  }
  EXPECT_NEAR(longest, 150, 3);
}

TEST(FogErrorsPicture, ColoursCellsByHowTheyCompareWithTheTruth) {
  // the truth: a floor with a block; the map holds the block's middle as floor (unsafe) and a
  // floor cell far from it as obstacle (wrong class)
  Fog truth = FlatFog(20, 20, 0.04);
  FillBox(&truth, 0.2, 0.2, 0.4, 0.4, CellType::kObstacle, 0.3f);
  Fog map = truth;
  FillBox(&map, 0.28, 0.28, 0.32, 0.32, CellType::kFloor, 0.0f);
  FillBox(&map, 0.64, 0.64, 0.68, 0.68, CellType::kObstacle, 0.3f);
  const RgbImage img = DrawFogErrors(map, truth, perception::FogParams{}, {0.1, 0.7, 0.0}, 6);

  // a cell's colour one pixel in from its corner (the unsafe cell's cross runs corner to corner)
  auto colour = [&](int ix, int iy) {
    const Eigen::Vector2i c = CellPixel(truth.window, 6, ix, iy);
    return img.at(c.x() - 2, c.y() - 1);
  };
  EXPECT_TRUE(Same(colour(7, 7), Rgb{230, 0, 0}));     // unsafe: red
  EXPECT_TRUE(Same(colour(16, 16), Rgb{40, 90, 200}));  // wrong class: blue
  EXPECT_TRUE(Same(colour(15, 3), Rgb{215, 215, 215}));  // right: light grey
  // the legend below the map
  EXPECT_GT(img.height, 20 * 6 + 2 * 22);
}

TEST(PathPicture, DrawsThePathOverTheMap) {
  const Fog fog = CorridorWithTable();
  const Eigen::Vector2d goal(2.70, 1.22);
  const Pose2 start{0.50, 1.22, 0.0};
  const PlanResult r = Plan(fog, start, goal, navigation::PlannerParams());
  ASSERT_EQ(r.status, PlanStatus::kOk);
  const int px = 4;
  const RgbImage map = DrawFog(fog, start, px);
  const RgbImage picture = DrawPlanPicture(fog, start, r, goal, px);
  ASSERT_EQ(picture.width, map.width);
  ASSERT_GT(picture.height, map.height);  // the moves' row of the legend
  // a walked cell of the path turns blue, a crawled one red
  const Eigen::Vector2i walk_px = CellPixel(fog.window, px, 16, 30);  // 0.66 m, the table at 1.4
  EXPECT_GT(picture.at(walk_px.x(), walk_px.y()).b, 150);
  EXPECT_LT(picture.at(walk_px.x(), walk_px.y()).r, 120);
  const Eigen::Vector2i crawl_px = CellPixel(fog.window, px, 42, 30);
  EXPECT_GT(picture.at(crawl_px.x(), crawl_px.y()).r, 180);
  EXPECT_LT(picture.at(crawl_px.x(), crawl_px.y()).g, 100);
  // far from the path, and right of the map, nothing changed
  const Eigen::Vector2i far_px = CellPixel(fog.window, px, 10, 20);
  EXPECT_TRUE(Same(picture.at(far_px.x(), far_px.y()), map.at(far_px.x(), far_px.y())));
  for (int v = 0; v < 60 * px; ++v) {
    for (int u = 80 * px; u < picture.width; ++u) {
      ASSERT_TRUE(Same(picture.at(u, v), map.at(u, v)));
    }
  }
}

TEST(PathPicture, DrawsTheGoalAndClipsPosesOutsideTheMap) {
  const Fog fog = FlatFog(50, 50, 0.04);
  PlanResult r;
  r.status = PlanStatus::kOk;
  r.path = {{{0.5, 1.02, 0.0}, Move::kNone, Posture::kUpright},
            {{5.0, 1.02, 0.0}, Move::kWalk, Posture::kUpright}};
  RgbImage picture(50 * 3 + 7, 50 * 3 + 5);  // 7 px right of the map, 5 below
  DrawPath(r, fog.window, 3, &picture);
  DrawGoal({5.0, 1.0}, fog.window, 3, &picture);
  for (int v = 0; v < picture.height; ++v) {
    for (int u = 0; u < picture.width; ++u) {
      if (u >= 150 || v >= 150) {
        ASSERT_EQ(picture.at(u, v).b, 0);
      }
    }
  }
  const Eigen::Vector2i on_line = CellPixel(fog.window, 3, 40, 25);
  EXPECT_GT(picture.at(on_line.x(), on_line.y()).b, 100);
}

TEST(MissionMap, ColoursTheTrueWayByMoveAndDashesTheBelieved) {
  const Fog fog = FlatFog(100, 50, 0.04);  // 4 m x 2 m
  PlanResult optimal;
  optimal.status = PlanStatus::kOk;
  optimal.path = {{{0.5, 1.5, 0.0}, Move::kNone, Posture::kUpright},
                  {{3.5, 1.5, 0.0}, Move::kWalk, Posture::kUpright}};
  // the true way walks along y = 1, then crawls; the believed one drifts to y = 0.6
  std::vector<TrackPoint> track;
  for (int i = 1; i <= 30; ++i) {
    const double x = 0.5 + 0.1 * i;
    track.push_back({{x, 1.0, 0.0}, {x, 1.0 - 0.4 * i / 30.0, 0.0}, i <= 15 ? "walk" : "crawl"});
  }
  const int px = 6;
  const RgbImage picture = DrawMissionMap(fog, optimal, {0.5, 1.0, 0.0}, {3.6, 1.0}, track, px);
  auto at = [&](double x, double y) -> const Rgb& {  // the pixel of a point
    return picture.at(int(std::lround((x / 0.04 - fog.window.origin_ix) * px)),
                      int(std::lround((50 - (y / 0.04 - fog.window.origin_iy)) * px)));
  };
  const Rgb walk = MoveColour(Move::kWalk), crawl = MoveColour(Move::kCrawl);
  EXPECT_TRUE(Same(at(1.2, 1.0), walk));
  EXPECT_TRUE(Same(at(2.8, 1.0), crawl));
  const Rgb optimal_px = at(2.0, 1.5);
  EXPECT_GT(optimal_px.g, optimal_px.r + 40);  // green
  // the believed way: dark pixels along its line, light ones between the dashes
  int dark = 0, light = 0;
  for (int i = 0; i < 120; ++i) {
    const double x = 1.0 + 0.02 * i;
    const double y = 1.0 - 0.4 * (x - 0.5) / 3.0;
    const Rgb& c = at(x, y);
    dark += c.r < 90;
    light += c.r > 200;
  }
  EXPECT_GT(dark, 20);
  EXPECT_GT(light, 20);
  EXPECT_GT(picture.height, 50 * px + 3 * 20);  // four legend rows
}

TEST(GridSideViews, HaveAxesAroundTheViews) {
  perception::MapParams params;
  perception::MapState state;
  perception::MapInput in;
  in.p_GC = Eigen::Vector3d(0.0, 0.0, 0.5);
  // a post at x = 1, 0.3 m high
  for (double z = 0.0; z <= 0.3; z += 0.01) {
    in.points.push_back({Eigen::Vector3f(1.0f, 0.0f, float(z))});
  }
  perception::UpdateMaps(params, in, &state);
  const RgbImage picture = DrawGridSideViews(state, params.grid.p_occ, 6);
  EXPECT_GT(picture.width, state.window.size_x * 6);  // the z axis's labels on the left
  int dark_column = -1;  // first column inside the x-z view (rows 22-117) with an occupied cell
  for (int u = 47; u < 46 + 600 && dark_column < 0; ++u) {
    for (int v = 22; v < 118; ++v) {
      const Rgb& c = picture.at(u, v);
      if (c.r < 170 && c.r == c.g && c.g == c.b) {
        dark_column = u;
        break;
      }
    }
  }
  ASSERT_GE(dark_column, 0);
  // 1 m from the window's left edge (x = -2 m): 75 cells of 6 px right of the axis
  EXPECT_NEAR(dark_column, 46 + (1.0 + 2.0) / 0.04 * 6, 8);
}

TEST(FramePictures, ColourNearDisparitiesRedAndFarBlue) {
  perception::Image<float> disparity(4, 1, std::numeric_limits<float>::quiet_NaN());
  disparity.at(1, 0) = 1.0f;
  disparity.at(2, 0) = 10.0f;
  const RgbImage picture = DrawDisparity(disparity);
  ASSERT_EQ(picture.width, 4);
  EXPECT_TRUE(Same(picture.at(0, 0), Rgb{0, 0, 0}));
  EXPECT_GT(picture.at(1, 0).b, picture.at(1, 0).r);
  EXPECT_GT(picture.at(2, 0).r, picture.at(2, 0).b);
}

TEST(FramePictures, DrawSegmentsBordersBlackAndUnlabelledWhite) {
  perception::PlaneSet set;
  set.labels = perception::LabelImage(5, 5, -1);
  for (int v = 1; v < 5; ++v) {
    for (int u = 1; u < 5; ++u) set.labels.at(u, v) = 0;
  }
  const RgbImage picture = DrawSegments(set);
  EXPECT_TRUE(Same(picture.at(0, 0), Rgb{255, 255, 255}));
  EXPECT_TRUE(Same(picture.at(1, 1), Rgb{0, 0, 0}));
  const Rgb inside = picture.at(2, 2);
  EXPECT_FALSE(Same(inside, Rgb{0, 0, 0}));
  EXPECT_FALSE(Same(inside, Rgb{255, 255, 255}));
}

}  // namespace
}  // namespace fognav::viz
