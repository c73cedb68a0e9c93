// The behaviour's transitions on small hand-made FOGs: each test puts the state where a
// transition starts and checks the decision and the state after it. No rendering.
#include "scenarios/behaviour.h"

#include <gtest/gtest.h>

#include "navigation/internal/test_worlds.h"

namespace fognav::scenarios {
namespace {

namespace nav = navigation;
using nav::internal::FillBox;
using nav::internal::FlatFog;
using perception::CellType;
using perception::Fog;
using perception::Pose2;

constexpr double kRes = 0.04;

// A 3 m x 2 m window of floor whose cell (0, 0) starts at the grid origin.
Fog OpenFloor() { return FlatFog(75, 50, kRes); }

// The open floor with a wall (0.5 m, obstacle) across it at x in [1.4, 1.6).
Fog WallAcross() {
  Fog fog = OpenFloor();
  FillBox(&fog, 1.4, 0.0, 1.6, 2.0, CellType::kObstacle, 0.5f);
  return fog;
}

// The robot boxed in by walls 0.5 m around (0.3 .. 0.9) x (0.7 .. 1.3).
Fog Boxed() {
  Fog fog = OpenFloor();
  FillBox(&fog, 0.2, 0.6, 1.0, 0.7, CellType::kObstacle, 0.5f);
  FillBox(&fog, 0.2, 1.3, 1.0, 1.4, CellType::kObstacle, 0.5f);
  FillBox(&fog, 0.2, 0.6, 0.3, 1.4, CellType::kObstacle, 0.5f);
  FillBox(&fog, 0.9, 0.6, 1.0, 1.4, CellType::kObstacle, 0.5f);
  return fog;
}

const Pose2 kStart{0.5, 1.0, 0.0};
const perception::MapState kNoMaps;  // no obstacle ranges: nothing to inspect

Behaviour MakeBehaviour(const Eigen::Vector2d& goal, const Pose2& start = kStart,
                        nav::PlannerParams planner = {}) {
  planner.goal_tolerance = 0.1;
  return Behaviour({goal, 0.2}, planner, ExecutionLimits{}, start);
}

double Distance(const Eigen::Vector2d& a, const Pose2& b) { return std::hypot(a.x() - b.x, a.y() - b.y); }

TEST(Behaviour, FollowsAPlanToTheGoalOneCommandAtATime) {
  Behaviour b = MakeBehaviour({2.5, 1.0});
  const Decision d = b.Decide(OpenFloor(), kNoMaps, kStart, nav::Posture::kUpright);
  EXPECT_EQ(d.action, Action::kFollow);
  EXPECT_STREQ(d.name, "follow");
  EXPECT_STREQ(d.found, "goal");
  ASSERT_TRUE(d.plan.reaches_goal);
  EXPECT_EQ(d.run.move, nav::Move::kWalk);
  // the run is cut to one walk command (ExecutionLimits::walk) but reaches it
  const Pose2& end = d.plan.path[size_t(d.run.last)].pose_G;
  const double run = std::hypot(end.x - kStart.x, end.y - kStart.y);
  EXPECT_GE(run, ExecutionLimits{}.walk - 1e-9);
  EXPECT_LT(run, ExecutionLimits{}.walk + 2 * kRes);
  EXPECT_EQ(b.mode(), Mode::kFollow);
}

TEST(Behaviour, KeepsToTheLastPlanWhereItGotToTheRunsEnd) {
  Behaviour b = MakeBehaviour({2.5, 1.0});
  const Decision first = b.Decide(OpenFloor(), kNoMaps, kStart, nav::Posture::kUpright);
  const size_t reached = size_t(first.run.last);
  b.Moved(first.plan, reached);
  EXPECT_FALSE(b.state().just_looked);
  const Pose2 there = first.plan.path[reached].pose_G;
  const Decision next = b.Decide(OpenFloor(), kNoMaps, there, nav::Posture::kUpright);
  ASSERT_EQ(next.action, Action::kFollow);
  // the rest of the first plan, pose for pose
  ASSERT_EQ(next.plan.path.size(), first.plan.path.size() - reached);
  for (size_t k = 1; k < next.plan.path.size(); ++k) {
    EXPECT_NEAR(next.plan.path[k].pose_G.x, first.plan.path[reached + k].pose_G.x, 1e-9);
    EXPECT_NEAR(next.plan.path[k].pose_G.y, first.plan.path[reached + k].pose_G.y, 1e-9);
  }
}

TEST(Behaviour, WithoutAWayItFirstLooksAroundOnceItHasMoved) {
  Behaviour b = MakeBehaviour({2.5, 1.0});
  b.mutable_state().just_looked = false;
  b.mutable_state().peek_at = Eigen::Vector2d(1.0, 1.0);
  const Decision d = b.Decide(Boxed(), kNoMaps, {0.6, 1.0, 0.0}, nav::Posture::kUpright);
  EXPECT_EQ(d.action, Action::kLookAround);
  EXPECT_STREQ(d.name, "look_around");
  // a pending peek is looked at after the sweep, once
  ASSERT_TRUE(d.peek_at);
  EXPECT_FALSE(b.state().peek_at);
  EXPECT_TRUE(b.state().just_looked);
}

TEST(Behaviour, WithoutAWayToTheGoalItGoesNearerAndLooksAgain) {
  Behaviour b = MakeBehaviour({2.5, 1.0});
  const Decision d = b.Decide(WallAcross(), kNoMaps, kStart, nav::Posture::kUpright);
  EXPECT_NE(std::string(d.found), "goal");
  EXPECT_EQ(d.action, Action::kFollow);
  EXPECT_STREQ(d.name, "toward_goal");
  ASSERT_GE(d.plan.path.size(), 2u);
  const Pose2& end = d.plan.path.back().pose_G;
  EXPECT_LT(Distance({2.5, 1.0}, end), Distance({2.5, 1.0}, kStart) - 0.5);
  EXPECT_LT(end.x, 1.4);  // the wall's near face
}

TEST(Behaviour, BoxedInItGoesNearerLooksAroundLooksAfreshBacksOffAndThenGivesUp) {
  const Eigen::Vector2d goal(2.5, 1.0);
  Behaviour b = MakeBehaviour(goal, {0.4, 1.0, 0.0});
  const Decision toward = b.Decide(Boxed(), kNoMaps, {0.4, 1.0, 0.0}, nav::Posture::kUpright);
  ASSERT_EQ(toward.action, Action::kFollow);
  EXPECT_STREQ(toward.name, "toward_goal");
  // there, as near as the box allows: it looks around once it has moved
  const Pose2 end = toward.plan.path.back().pose_G;
  b.Moved(toward.plan, toward.plan.path.size() - 1);
  const Decision look = b.Decide(Boxed(), kNoMaps, end, nav::Posture::kUpright);
  EXPECT_EQ(look.action, Action::kLookAround);
  EXPECT_STREQ(look.name, "look_around");
  // still no way nearer: the grid's evidence is weakened and it looks afresh
  const Decision fresh = b.Decide(Boxed(), kNoMaps, end, nav::Posture::kUpright);
  EXPECT_EQ(fresh.action, Action::kFreshLook);
  EXPECT_STREQ(fresh.name, "fresh_look");
  ASSERT_TRUE(b.state().fresh_at);
  EXPECT_TRUE(b.state().just_looked);
  // the same place again: no second fresh look; walled in within the window, nothing to
  // explore or inspect: it backs off from the goal's side to look again from there
  const Decision back = b.Decide(Boxed(), kNoMaps, end, nav::Posture::kUpright);
  ASSERT_EQ(back.action, Action::kFollow);
  EXPECT_STREQ(back.name, "back_off");
  EXPECT_EQ(b.mode(), Mode::kGoLook);
  ASSERT_TRUE(back.target);
  EXPECT_NEAR((*back.target - Eigen::Vector2d(end.x, end.y)).norm(), ExecutionLimits{}.back_off,
              1e-9);
  EXPECT_LT(back.target->x(), end.x);  // away from the goal
  // with its explorations spent, nothing is left
  b.mutable_state().explore.reset();
  b.mutable_state().explorations = ExecutionLimits{}.max_explorations;
  const Decision then = b.Decide(Boxed(), kNoMaps, end, nav::Posture::kUpright);
  EXPECT_EQ(then.action, Action::kGiveUp);
  EXPECT_STREQ(then.name, "give_up");
  EXPECT_EQ(then.failure_detail, nav::NoPathReasonName(then.plan.reason));
}

TEST(Behaviour, ExploresPastTheWindowsEdgeWhereTheGoalsRegionMeetsIt) {
  // the wall leaves a way round beyond the window's top edge (y = 2.0) only: the goal's region
  // meets the edge, the robot's too
  Fog fog = OpenFloor();
  FillBox(&fog, 1.4, 0.0, 1.6, 2.0, CellType::kObstacle, 0.5f);
  Behaviour b = MakeBehaviour({2.5, 1.0});
  b.mutable_state().fresh_at = Pose2{1.2, 1.0, 0.0};  // looked afresh here already
  const Decision d = b.Decide(fog, kNoMaps, {1.2, 1.0, 0.0}, nav::Posture::kUpright);
  ASSERT_EQ(d.action, Action::kFollow) << d.name;
  EXPECT_STREQ(d.name, "explore_edge");
  ASSERT_TRUE(d.target);
  EXPECT_EQ(b.mode(), Mode::kExplore);
  EXPECT_EQ(b.state().explorations, 1);
  // beyond the window's edge, explore_beyond past where the way meets it
  const Eigen::Vector2d end(d.plan.path.back().pose_G.x, d.plan.path.back().pose_G.y);
  EXPECT_NEAR((*d.target - end).norm(), ExecutionLimits{}.explore_beyond, 1e-9);
}

// obstacle evidence of `fog` as seen from `range` metres
perception::MapState SeenFrom(const Fog& fog, float range) {
  perception::MapState maps;
  maps.obstacle_range.assign(fog.type.size(), 0.0f);
  for (size_t i = 0; i < fog.type.size(); ++i) {
    if (fog.type[i] == CellType::kObstacle) maps.obstacle_range[i] = range;
  }
  return maps;
}

TEST(Behaviour, ObstacleEvidenceSeenOnlyFromAfarIsInspectedFromNearby) {
  const Fog fog = WallAcross();
  // it has been at the wall's face before, and looked afresh here
  auto at_the_wall_before = [](Behaviour* b) {
    b->mutable_state().fresh_at = kStart;
    b->mutable_state().explorations = 1;
    b->mutable_state().nearest_to_goal = 1.2;
  };
  Behaviour b = MakeBehaviour({2.5, 1.0});
  at_the_wall_before(&b);
  const Decision d = b.Decide(fog, SeenFrom(fog, 3.0f), kStart, nav::Posture::kUpright);
  ASSERT_EQ(d.action, Action::kFollow) << d.name;
  EXPECT_STREQ(d.name, "inspect");
  EXPECT_EQ(b.mode(), Mode::kGoLook);
  ASSERT_TRUE(d.target);
  // from before the wall, on the way the wall would leave if it were not there
  EXPECT_LT(d.target->x(), 1.4);
  EXPECT_GT(d.target->x(), 1.0);
  EXPECT_NEAR(d.target->y(), 1.0, 0.2);
  // the same wall seen from nearby is not inspected: the robot explores past the window's edge
  Behaviour near = MakeBehaviour({2.5, 1.0});
  at_the_wall_before(&near);
  EXPECT_STREQ(near.Decide(fog, SeenFrom(fog, 1.0f), kStart, nav::Posture::kUpright).name,
               "explore_edge");
}

TEST(Behaviour, AGapOnlyABlindSideStepPassesIsPeekedInto) {
  // a wall along x with a 0.28 m gap at x in [1.28, 1.56), narrower than the shoulders of a
  // broad robot, the floor beyond it unseen: only a side-step into unseen cells goes through
  nav::PlannerParams broad;
  broad.shoulder_width = 0.30;
  Fog fog = OpenFloor();
  FillBox(&fog, 0.0, 1.2, 1.28, 1.3, CellType::kObstacle, 0.5f);
  FillBox(&fog, 1.56, 1.2, 3.0, 1.3, CellType::kObstacle, 0.5f);
  FillBox(&fog, 0.0, 1.3, 3.0, 2.0, CellType::kUnknown, -std::numeric_limits<float>::infinity());
  // walls down the window's sides: no way round beyond its edge nearby
  FillBox(&fog, 0.0, 0.0, 0.1, 1.3, CellType::kObstacle, 0.5f);
  FillBox(&fog, 2.9, 0.0, 3.0, 1.3, CellType::kObstacle, 0.5f);
  // it has been beside the gap before, and looked afresh here
  const Pose2 at{0.6, 1.0, 0.0};
  Behaviour b = MakeBehaviour({1.44, 1.8}, at, broad);
  b.mutable_state().fresh_at = at;
  b.mutable_state().explorations = 1;
  b.mutable_state().nearest_to_goal = 0.7;
  const Decision d = b.Decide(fog, kNoMaps, at, nav::Posture::kUpright);
  ASSERT_EQ(d.action, Action::kFollow) << d.name;
  EXPECT_STREQ(d.name, "peek");
  ASSERT_TRUE(b.state().peek_at);
  // from beside the gap, at the floor beyond the wall
  ASSERT_TRUE(d.target);
  EXPECT_NEAR(d.target->x(), 1.44, 0.05);
  EXPECT_LT(d.target->y(), 1.2);
  EXPECT_GT(b.state().peek_at->y(), 1.3);
}

TEST(Behaviour, AnExplorationGoesOnWhileItGetsNearerAndEndsWhereNoWayDoes) {
  Fog fog = OpenFloor();
  FillBox(&fog, 1.4, 0.0, 1.6, 2.0, CellType::kObstacle, 0.5f);
  Behaviour b = MakeBehaviour({2.5, 1.0});
  MissionState& s = b.mutable_state();
  s.explore = MissionState::Exploration{{1.0, 1.0}, 0.2, false, 0.5, 0};
  s.explorations = 1;
  const Decision on = b.Decide(fog, kNoMaps, {0.5, 1.0, 0.0}, nav::Posture::kUpright);
  ASSERT_EQ(on.action, Action::kFollow);
  EXPECT_STREQ(on.name, "explore");
  EXPECT_EQ(*on.target, Eigen::Vector2d(1.0, 1.0));
  // at the wall with the target behind it: the exploration ends and the next cycle plans afresh
  b.mutable_state().explore->target = Eigen::Vector2d(2.0, 1.0);
  b.mutable_state().explore->best = 1.0;
  const Decision ends = b.Decide(fog, kNoMaps, {1.3, 1.0, 0.0}, nav::Posture::kUpright);
  EXPECT_EQ(ends.action, Action::kReplan);
  EXPECT_STREQ(ends.name, "explore_ends");
  EXPECT_FALSE(b.state().explore);
  EXPECT_EQ(b.mode(), Mode::kFollow);
}

TEST(Behaviour, ComeToLookItLooksAroundAndAtThePeeksFloor) {
  Behaviour b = MakeBehaviour({2.5, 1.0});
  MissionState& s = b.mutable_state();
  s.explore = MissionState::Exploration{{0.52, 1.0}, 0.05, true, 0.3, 0};
  s.peek_at = Eigen::Vector2d(1.0, 1.3);
  s.just_looked = false;
  const Decision d = b.Decide(OpenFloor(), kNoMaps, kStart, nav::Posture::kUpright);
  EXPECT_EQ(d.action, Action::kLookAround);
  EXPECT_STREQ(d.name, "look_on_arrival");
  ASSERT_TRUE(d.peek_at);
  EXPECT_EQ(*d.peek_at, Eigen::Vector2d(1.0, 1.3));
  EXPECT_FALSE(b.state().explore);
  EXPECT_FALSE(b.state().peek_at);
}

TEST(Behaviour, AStalledExplorationEndsAndAPlanToTheGoalIsFollowed) {
  Behaviour b = MakeBehaviour({2.5, 1.0});
  MissionState& s = b.mutable_state();
  s.explore = MissionState::Exploration{{2.0, 0.2}, 0.2, true, 1.0, ExecutionLimits{}.explore_patience};
  const Decision d = b.Decide(OpenFloor(), kNoMaps, kStart, nav::Posture::kUpright);
  EXPECT_EQ(d.action, Action::kFollow);
  EXPECT_STREQ(d.name, "follow");
  EXPECT_FALSE(d.target);
  EXPECT_FALSE(b.state().explore);
}

TEST(Behaviour, ComingBackToOnePoseAgainAndAgainCallsForALook) {
  Behaviour b = MakeBehaviour({2.5, 1.0});
  MissionState& s = b.mutable_state();
  s.just_looked = false;
  s.nearest_to_goal = Distance({2.5, 1.0}, kStart);
  const int before = ExecutionLimits{}.circling_arrivals - 1;
  for (int i = 0; i < before; ++i) {
    s.arrivals.push_back({kStart, s.nearest_to_goal});
    s.arrivals.push_back({Pose2{0.8, 1.0, 0.0}, s.nearest_to_goal});
  }
  const Decision d = b.Decide(OpenFloor(), kNoMaps, kStart, nav::Posture::kUpright);
  EXPECT_EQ(d.action, Action::kLookAround);
  EXPECT_STREQ(d.name, "circling_look");
  EXPECT_TRUE(b.state().arrivals.empty());
}

TEST(Behaviour, GoingBackAndForthTwiceGivesUp) {
  Behaviour b = MakeBehaviour({2.5, 1.0});
  MissionState& s = b.mutable_state();
  s.thrashes = 1;
  s.nearest_to_goal = Distance({2.5, 1.0}, kStart);
  for (int i = 0; i + 1 < ExecutionLimits{}.thrash_cycles; ++i) {
    s.recent.push_back({Eigen::Vector2d(kStart.x, kStart.y), s.nearest_to_goal});
  }
  const Decision d = b.Decide(WallAcross(), kNoMaps, kStart, nav::Posture::kUpright);
  EXPECT_EQ(d.action, Action::kGiveUp);
  EXPECT_EQ(d.failure_detail, "no_progress");
  EXPECT_EQ(b.state().thrashes, 2);
}

TEST(Behaviour, OnceItWentBackAndForthAPlanShortOfTheGoalMustLeadNearerThanEver) {
  Behaviour b = MakeBehaviour({2.5, 1.0});
  MissionState& s = b.mutable_state();
  s.thrashes = 1;
  s.fresh_at = kStart;
  s.explorations = ExecutionLimits{}.max_explorations;  // nothing left to explore
  s.nearest_to_goal = 1.1;  // it had been at the wall's face before
  const Decision d = b.Decide(WallAcross(), kNoMaps, kStart, nav::Posture::kUpright);
  EXPECT_EQ(d.action, Action::kGiveUp);
  // without the earlier visit the same map gives a way nearer
  Behaviour fresh = MakeBehaviour({2.5, 1.0});
  EXPECT_EQ(fresh.Decide(WallAcross(), kNoMaps, kStart, nav::Posture::kUpright).action,
            Action::kFollow);
}

TEST(Behaviour, AnExplorationBudgetSpentLeavesNothingButGivingUp) {
  Fog fog = OpenFloor();
  FillBox(&fog, 1.4, 0.0, 1.6, 2.0, CellType::kObstacle, 0.5f);
  Behaviour b = MakeBehaviour({2.5, 1.0});
  b.mutable_state().fresh_at = Pose2{1.2, 1.0, 0.0};
  b.mutable_state().explorations = ExecutionLimits{}.max_explorations;
  const Decision d = b.Decide(fog, kNoMaps, {1.2, 1.0, 0.0}, nav::Posture::kUpright);
  EXPECT_EQ(d.action, Action::kGiveUp);
}

TEST(Behaviour, GettingUpUnderUnseenHeadroomLastsUntilItStands) {
  Behaviour b = MakeBehaviour({2.5, 1.0});
  b.mutable_state().getting_up_unseen = true;
  EXPECT_FALSE(b.planner().get_up_under_seen_headroom);
  b.Decide(OpenFloor(), kNoMaps, kStart, nav::Posture::kCrawling);
  EXPECT_TRUE(b.state().getting_up_unseen);
  b.Decide(OpenFloor(), kNoMaps, kStart, nav::Posture::kUpright);
  EXPECT_FALSE(b.state().getting_up_unseen);
  EXPECT_EQ(b.planner().get_up_under_seen_headroom, nav::PlannerParams{}.get_up_under_seen_headroom);
}

TEST(Behaviour, LookingAroundByItselfIsRemembered) {
  Behaviour b = MakeBehaviour({2.5, 1.0});
  b.Moved(nav::PlanResult{}, 0);
  EXPECT_FALSE(b.state().just_looked);
  b.LookedAround({1.0, 1.5, 0.3});
  EXPECT_TRUE(b.state().just_looked);
  EXPECT_DOUBLE_EQ(b.state().looked_at.x, 1.0);
}

}  // namespace
}  // namespace fognav::scenarios
