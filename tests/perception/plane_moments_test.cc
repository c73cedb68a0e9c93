// Plane fitting from moments (paper eq. 3-10) and line extraction along one scan line (eq. 11).
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "perception/internal/line_extraction.h"
#include "perception/internal/plane_moments.h"

namespace fognav::perception::internal {
namespace {

// Points on the plane n . p = d (n unit) around the point c, spread over +-half metres, with
// Gaussian noise of sigma metres along n.
std::vector<Eigen::Vector3d> PlanePoints(const Eigen::Vector3d& n, double d, double half,
                                         double sigma, int count, unsigned seed) {
  const Eigen::Vector3d u = n.unitOrthogonal(), w = n.cross(u);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-half, half);
  std::normal_distribution<double> normal(0, 1);
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < count; ++i)
    pts.push_back(d * n + uni(rng) * u + uni(rng) * w + sigma * normal(rng) * n);
  return pts;
}

Moments Sum(const std::vector<Eigen::Vector3d>& pts) {
  Moments m;
  for (const auto& p : pts) m.Add(p);
  return m;
}

TEST(PlaneMoments, FitsExactPlaneWithNormalTowardsTheCamera) {
  // a floor 0.55 m below a camera pitched down: n away from the camera is (0, 0.9, 0.44)
  const Eigen::Vector3d n_away = Eigen::Vector3d(0, 0.9, 0.44).normalized();
  const auto pts = PlanePoints(n_away, 1.2, 0.5, 0.0, 200, 1);

  const PlaneFit fit = FitPlane(Sum(pts));

  ASSERT_TRUE(fit.ok);
  EXPECT_LT((fit.n + n_away).norm(), 1e-9);  // eq. (6), flipped towards the camera
  EXPECT_NEAR(fit.dist, -1.2, 1e-9);
  EXPECT_NEAR(Rms(Sum(pts), fit.n, fit.dist), 0.0, 1e-6);
}

TEST(PlaneMoments, RmsFromMomentsEqualsDirectRms) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.3, -1).normalized();
  const auto pts = PlanePoints(-n, 2.0, 0.4, 0.01, 500, 2);
  const Moments m = Sum(pts);
  const PlaneFit fit = FitPlane(m);
  ASSERT_TRUE(fit.ok);

  // eq. (8) point by point against eq. (9) from the moments, for the fit and a shifted plane
  for (double shift : {0.0, 0.05}) {
    double sum = 0;
    for (const auto& p : pts) sum += std::pow(p.dot(fit.n) - (fit.dist + shift), 2);
    EXPECT_NEAR(Rms(m, fit.n, fit.dist + shift), std::sqrt(sum / pts.size()), 1e-9);
  }
  // the fit's rms resembles the noise, and r_sigma (eq. 10) against it is about 1
  EXPECT_NEAR(Rms(m, fit.n, fit.dist), 0.01, 0.0015);
  EXPECT_NEAR(RSigma(m, fit.n, fit.dist, 0.01), 1.0, 0.15);
}

TEST(PlaneMoments, AddAndSubtractInConstantTime) {
  const auto a = PlanePoints(Eigen::Vector3d(0, 0, 1), 1.0, 0.3, 0.002, 100, 3);
  const auto b = PlanePoints(Eigen::Vector3d(0, 0, 1), 1.0, 0.3, 0.002, 50, 4);
  Moments ab = Sum(a);
  ab.Add(Sum(b));  // eq. (7)
  std::vector<Eigen::Vector3d> all = a;
  all.insert(all.end(), b.begin(), b.end());
  const Moments direct = Sum(all);
  EXPECT_EQ(ab.n, 150);
  EXPECT_LT((ab.A - direct.A).norm(), 1e-9);
  EXPECT_LT((ab.b - direct.b).norm(), 1e-9);

  ab.Subtract(Sum(b));
  ab.Subtract(a[0]);
  Moments rest = Sum(std::vector<Eigen::Vector3d>(a.begin() + 1, a.end()));
  EXPECT_EQ(ab.n, 99);
  EXPECT_LT((ab.A - rest.A).norm(), 1e-9);
}

TEST(PlaneMoments, RejectsDegenerateSets) {
  Moments m;
  EXPECT_FALSE(FitPlane(m).ok);
  for (int i = 0; i < 10; ++i) m.Add(Eigen::Vector3d(0.1 * i, 0, 1));  // collinear
  EXPECT_FALSE(FitPlane(m).ok);
}

TEST(MaxConsecutiveSameSide, CountsTheLongestRun) {
  const std::vector<double> r = {0.1, -0.2, 0.3, 0.1, 0.2, 0.0, 0.4, 0.1, -0.1};
  EXPECT_EQ(MaxConsecutiveSameSide(r.data(), int(r.size()), 0.01), 3);
  EXPECT_EQ(MaxConsecutiveSameSide(r.data(), 0, 0.01), 0);
  // residuals within the tolerance are on the line and break runs
  EXPECT_EQ(MaxConsecutiveSameSide(r.data(), int(r.size()), 0.15), 1);
}

TEST(LongestSameSideRun, StopsOnceARunReachesTheLimit) {
  // sides + - + + + 0 + + -: runs 1, 1, 3, 0, 2, 1
  const std::vector<double> r = {0.1, -0.2, 0.3, 0.1, 0.2, 0.0, 0.4, 0.1, -0.1};
  int read = 0;
  auto residual = [&](int i) {
    ++read;
    return r[size_t(i)];
  };
  EXPECT_EQ(LongestSameSideRun(int(r.size()), residual, 0.01, 2), 2);
  EXPECT_EQ(read, 4);  // the run of three reaches two at index 3
  read = 0;
  EXPECT_EQ(LongestSameSideRun(int(r.size()), residual, 0.01, 100), 3);
  EXPECT_EQ(read, int(r.size()));
  // a run that starts after a zero counts from its own start
  const std::vector<double> z = {0.0, 0.0, 0.5, 0.5};
  EXPECT_EQ(LongestSameSideRun(int(z.size()), [&](int i) { return z[size_t(i)]; }, 0.01, 100), 2);
}

// One scan line (row 0) of a point image: points at depths z(u) along the optical axis.
PointImage Row(const std::vector<double>& z) {
  PointImage img(int(z.size()), 1);
  const double f = 200, cx = 0.5 * (z.size() - 1);
  for (size_t u = 0; u < z.size(); ++u)
    img.at(int(u), 0) = Eigen::Vector3f(float((u - cx) / f * z[u]), 0.f, float(z[u]));
  return img;
}

// Depths of 80 pixels (f = 200) seeing a corner of two walls in the scan line's plane:
// z = 1 + slope |x|, so z = 1 / (1 - slope |t|) along the ray x = t z.
std::vector<double> Corner(double slope) {
  std::vector<double> z;
  for (int u = 0; u < 80; ++u) z.push_back(1.0 / (1.0 - slope * std::abs((u - 39.5) / 200)));
  return z;
}

TEST(LineExtraction, RdSplitCutsACornerAndKeepsNoisyLinesWhole) {
  const std::vector<double> z = Corner(0.8);
  LineSet ls;
  ScanlineScratch scratch;
  SegmentParams p;
  ExtractLines(Row(z), p, &ls, &scratch);
  ASSERT_EQ(ls.lines.size(), 2u);
  EXPECT_NEAR(ls.lines[0].e, 39, 1);
  EXPECT_EQ(ls.lines[0].b, 0);
  EXPECT_EQ(ls.lines[1].e, 79);
  EXPECT_EQ(ls.lines[0].m.n + ls.lines[1].m.n, 80);

  // a straight line with 1 cm noise stays one line: its sides alternate at random
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0, 0.01);
  std::vector<double> noisy(80);
  for (double& d : noisy) d = 2.0 + normal(rng);
  ExtractLines(Row(noisy), p, &ls, &scratch);
  ASSERT_EQ(ls.lines.size(), 1u);
  EXPECT_EQ(ls.lines[0].m.n, 80);
  EXPECT_NEAR(ls.lines[0].sigma, 0.01, 0.003);  // eq. (11) sigma: the line's fitting error
}

TEST(LineExtraction, ClassicSplitUsesTheChordThreshold) {
  const std::vector<double> z = Corner(0.8);
  LineSet ls;
  ScanlineScratch scratch;
  SegmentParams p;
  p.method = LineMethod::kSplit;
  p.d_cord = 0.5;  // a coarse threshold keeps the corner
  ExtractLines(Row(z), p, &ls, &scratch);
  EXPECT_EQ(ls.lines.size(), 1u);
  p.d_cord = 0.01;
  ExtractLines(Row(z), p, &ls, &scratch);
  EXPECT_EQ(ls.lines.size(), 2u);
}

TEST(LineExtraction, CutsAtHolesAndDepthJumps) {
  std::vector<double> z(60, 1.0);
  for (int u = 30; u < 60; ++u) z[size_t(u)] = 2.0;  // occlusion boundary
  PointImage img = Row(z);
  for (int u = 10; u < 13; ++u) img.at(u, 0) = Eigen::Vector3f::Constant(NAN);  // 3-pixel hole
  LineSet ls;
  ScanlineScratch scratch;
  ExtractLines(img, SegmentParams(), &ls, &scratch);
  ASSERT_EQ(ls.lines.size(), 3u);
  EXPECT_EQ(ls.lines[0].e, 9);
  EXPECT_EQ(ls.lines[1].b, 13);
  EXPECT_EQ(ls.lines[1].e, 29);
  EXPECT_EQ(ls.lines[2].b, 30);
  EXPECT_EQ(ls.valid[11], 0);
}

}  // namespace
}  // namespace fognav::perception::internal
