// Peer of the "RRT* in 2D" benchmark (shared/BENCHMARKS.md): OMPL's
// og::RRTstar on the lab's 30-circle world, for exactly N iterations.
//
// Built and run by crates/labbench/benches/rrt_star.rs (native only):
//   g++ -O2 -std=c++17 -I/usr/include/ompl-1.5 -I/usr/include/eigen3 \
//       ompl_rrtstar.cpp -o ompl_rrtstar -lompl
//   ompl_rrtstar <radius|knearest> <iterations> <runs> [seed] < circles
//
// stdin: the circles, one "x y r" per line, written by the Rust bench from
// labbench::rrt_star::obstacles() (so the LCG is not re-implemented here).
//
// Setup: RealVectorStateSpace(2) on [0,100]^2; validity = inside the bounds
// and outside every circle (distance <= r is a hit, as in labcore); motion
// checks every 0.5 units (longest valid segment fraction 0.5 / diagonal);
// start (2,2); goal state (98,98) with threshold 1; path-length objective
// (cost threshold 0, so the planner never stops early); RRTstar with range 5,
// goal bias 0.05, radius mode (setKNearest(false)) or its default k-nearest
// mode. The termination condition counts iterations, so each run is exactly
// N iterations (checked: numIterations() is printed).
//
// Output: one line per run (a fresh planner each time):
//   run <i> iterations <n> seconds <s> it_per_s <rate> best <path length|nan>
// Timing covers planner->solve() only (setup() is done before).
// OMPL's RNG is seeded once per process (ompl::RNG::setSeed), so the sequence
// of runs is repeatable; each run's planner draws a different stream from it.

#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

struct Circle {
    double x, y, r2;
};

constexpr double kSide = 100.0;
constexpr double kStart[2] = {2.0, 2.0};
constexpr double kGoal[2] = {98.0, 98.0};
constexpr double kGoalRadius = 1.0;
constexpr double kEta = 5.0;
constexpr double kCheck = 0.5;
constexpr double kGoalBias = 0.05;

int usage() {
    std::fprintf(stderr, "usage: ompl_rrtstar <radius|knearest> <iterations> <runs> [seed] < circles\n");
    return 2;
}

}  // namespace

int main(int argc, char **argv) {
    if (argc < 4) return usage();
    const std::string mode = argv[1];
    if (mode != "radius" && mode != "knearest") return usage();
    const unsigned long iterations = std::strtoul(argv[2], nullptr, 10);
    const int runs = std::atoi(argv[3]);
    const unsigned long seed = argc > 4 ? std::strtoul(argv[4], nullptr, 10) : 1;
    if (iterations == 0 || runs <= 0) return usage();

    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(seed));

    std::vector<Circle> circles;
    double x, y, r;
    while (std::cin >> x >> y >> r) circles.push_back({x, y, r * r});
    if (circles.empty()) {
        std::fprintf(stderr, "ompl_rrtstar: no circles on stdin\n");
        return 2;
    }

    for (int run = 0; run < runs; ++run) {
        auto space = std::make_shared<ob::RealVectorStateSpace>(2);
        ob::RealVectorBounds bounds(2);
        bounds.setLow(0.0);
        bounds.setHigh(kSide);
        space->setBounds(bounds);
        // Checks every kCheck units: the fraction is of the space's maximum extent (the diagonal).
        space->setLongestValidSegmentFraction(kCheck / space->getMaximumExtent());

        auto si = std::make_shared<ob::SpaceInformation>(space);
        const ob::StateSpace *sp = space.get();
        si->setStateValidityChecker([&circles, sp](const ob::State *s) {
            if (!sp->satisfiesBounds(s)) return false;
            const double *v = s->as<ob::RealVectorStateSpace::StateType>()->values;
            for (const Circle &c : circles) {
                const double dx = v[0] - c.x, dy = v[1] - c.y;
                if (dx * dx + dy * dy <= c.r2) return false;
            }
            return true;
        });
        si->setup();

        auto pdef = std::make_shared<ob::ProblemDefinition>(si);
        ob::ScopedState<ob::RealVectorStateSpace> start(space), goal(space);
        start[0] = kStart[0];
        start[1] = kStart[1];
        goal[0] = kGoal[0];
        goal[1] = kGoal[1];
        pdef->addStartState(start);
        auto goalState = std::make_shared<ob::GoalState>(si);
        goalState->setState(goal);
        goalState->setThreshold(kGoalRadius);
        pdef->setGoal(goalState);
        auto obj = std::make_shared<ob::PathLengthOptimizationObjective>(si);
        obj->setCostThreshold(ob::Cost(0.0));  // never "good enough": run all N iterations
        pdef->setOptimizationObjective(obj);

        auto planner = std::make_shared<og::RRTstar>(si);
        planner->setRange(kEta);
        planner->setGoalBias(kGoalBias);
        planner->setKNearest(mode == "knearest");
        planner->setProblemDefinition(pdef);
        planner->setup();

        og::RRTstar *p = planner.get();
        ob::PlannerTerminationCondition ptc([p, iterations] { return p->numIterations() >= iterations; });
        const auto t0 = std::chrono::steady_clock::now();
        planner->solve(ptc);
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

        const double best = planner->bestCost().value();
        std::printf("run %d iterations %u seconds %.9f it_per_s %.3f best %.9f\n", run, planner->numIterations(), secs,
                    planner->numIterations() / secs, std::isfinite(best) ? best : NAN);
        std::fflush(stdout);
    }
    return 0;
}
