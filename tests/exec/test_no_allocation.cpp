// The control loop's calls allocate nothing: sampling a timed path and a schedule (both profiles)
// once their buffers exist.
#include <gtest/gtest.h>

#include "../support/allocation_counter.hpp"
#include "exec_fixtures.hpp"

namespace kaboum::exec {

TEST(NoAllocation, SamplingAPathAndAScheduleAllocatesNothing) {
  ExampleRun& run = bartender();
  ExecutionOptions options;
  options.sensing = [](const SensingQuery&) { return true; };
  for (const Profile profile : {Profile::RestToRest, Profile::Blended}) {
    options.trajectory.profile = profile;
    const ExecutionResult result = execute(run.world(), run.task(), run.plan(), options);
    const Schedule& schedule = result.schedule;
    ASSERT_GT(schedule.motions().size(), 10U);
    const TimedPath& path = schedule.motions()[1].path;
    std::vector<double> q(6), qd(6), qdd(6);
    const long allocations = test::allocationsDuring([&] {
      for (double t = 0; t <= schedule.duration(); t += 1e-3) {
        for (std::size_t r = 0; r < schedule.robotCount(); ++r) schedule.sample(t, r, q, qd, qdd);
        path.sample(t, q, qd, qdd);
      }
    });
    EXPECT_EQ(allocations, 0) << toString(profile);
  }
}

}  // namespace kaboum::exec
