// Branched execution of committed plan files (thesis §6.1.3): pick and place timed and sampled on
// one clock with its gripper events; the Bartender's plan executed in each of its hidden states,
// every branch's time; sensing sources (hidden states, a terminal, a callback) and their errors;
// each action's geometric precondition re-checked against observed object poses; the stream and
// the files.
#include <gtest/gtest.h>

#include <sstream>

#include "exec_fixtures.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/exec/trajectory_files.hpp"

namespace kaboum::exec {

namespace {

// The hidden state of file `name` in tests/exec/data (or written as `text`) as a sensing source.
SensingSource hidden(ExampleRun& run, const std::string& file, const std::string& text) {
  const std::vector<symbolic::HiddenState> states =
      symbolic::parseHidden(text, file, run.problem());
  return hiddenStateSource(run.task(), run.task().hiddenWorld(states.front(), file));
}

SensingSource hiddenFile(ExampleRun& run, const std::string& name) {
  const std::string file = execData(name);
  return hidden(run, file, test::slurp(file));
}

std::vector<std::string> actionNames(const ExecutionResult& result) {
  std::vector<std::string> names;
  for (const TimedAction& action : result.schedule.actions()) names.push_back(action.name);
  return names;
}

// The pose of the Bartender's release at `shared` (where robot1 puts o1 down).
Pose sharedPlacement(const ExampleRun& run) {
  for (const auto& node : run.plan().geometry) {
    for (const tamp::ActionGeometry& effect : node) {
      if (effect.procedure != "putDown" || effect.arguments.back() != "shared") continue;
      for (const tamp::GeometricStep& step : effect.steps) {
        if (step.kind == tamp::GeometricStep::Kind::Release) return step.pose;
      }
    }
  }
  ADD_FAILURE() << "no release at shared";
  return Pose::Identity();
}

}  // namespace

TEST(Execute, PickAndPlaceRunsBothActionsOnOneClockWithItsGripperEvents) {
  ExampleRun& run = pickAndPlace();
  const ExecutionResult result = execute(run.world(), run.task(), run.plan(), {});
  ASSERT_TRUE(result.reachedGoal) << result.stopReason;
  EXPECT_EQ(actionNames(result),
            (std::vector<std::string>{"(pickup kr5 block left)", "(putdown kr5 block right)"}));
  const Schedule& schedule = result.schedule;
  ASSERT_EQ(schedule.motions().size(), 6U);
  ASSERT_EQ(schedule.events().size(), 2U);
  EXPECT_EQ(schedule.events()[0].kind, tamp::GeometricStep::Kind::Grasp);
  EXPECT_EQ(schedule.events()[1].kind, tamp::GeometricStep::Kind::Release);
  // Motions follow each other without a gap; the actions partition the time.
  double end = 0;
  for (const TimedMotion& motion : schedule.motions()) {
    EXPECT_DOUBLE_EQ(motion.start, end);
    end = motion.start + motion.path.duration();
  }
  EXPECT_DOUBLE_EQ(end, schedule.duration());
  EXPECT_DOUBLE_EQ(schedule.actions()[1].start, schedule.actions()[0].end);
  // Sampled at 1 kHz: every sample on the path of the motion running then, at rest at the grasp.
  const RobotSamples samples = sampleRobot(schedule, 0, 1000);
  EXPECT_EQ(samples.times.size(),
            static_cast<std::size_t>(std::floor(schedule.duration() * 1000)) + 2);
  for (std::size_t k = 0; k < samples.times.size(); ++k) {
    const double t = samples.times[k];
    const auto running = std::find_if(
        schedule.motions().begin(), schedule.motions().end(),
        [&](const TimedMotion& m) { return t >= m.start && t <= m.start + m.path.duration(); });
    ASSERT_NE(running, schedule.motions().end());
    const std::span<const double> q(&samples.positions[k * samples.dof], samples.dof);
    ASSERT_LE(distanceToPath(q, running->path.waypoints()), 1e-9) << "t = " << t;
  }
  std::vector<double> q(6), qd(6), qdd(6);
  schedule.sample(schedule.events()[0].time, 0, q, qd, qdd);
  for (const double v : qd) EXPECT_EQ(v, 0);
  // One leaf, timed as executed.
  ASSERT_EQ(result.branches.size(), 1U);
  EXPECT_NEAR(result.branches[0].seconds, schedule.duration(), 1e-9);
  EXPECT_TRUE(result.branches[0].outcomes.empty());
}

TEST(Execute, BartenderFollowsTheBranchOfEachHiddenState) {
  ExampleRun& run = bartender();
  ExecutionOptions options;
  options.sensing = hiddenFile(run, "bartender-1-empty.hidden.pddl");
  const ExecutionResult empty = execute(run.world(), run.task(), run.plan(), options);
  ASSERT_TRUE(empty.reachedGoal);
  EXPECT_EQ(
      actionNames(empty),
      (std::vector<std::string>{"(senseifempty o1)", "(pickup robot1 o1 left)",
                                "(putdown robot1 o1 shared)", "(retract robot1)",
                                "(pickup robot2 o1 shared)", "(putdown robot2 o1 dishwasher)"}));
  ASSERT_EQ(empty.sensed.size(), 1U);
  EXPECT_EQ(empty.sensed[0].test, "(isemptybottle o1)");
  EXPECT_TRUE(empty.sensed[0].value);
  // Both arms move, one after the other: the bottle passes from robot1 to robot2.
  std::set<std::size_t> moving;
  for (const TimedMotion& motion : empty.schedule.motions()) moving.insert(motion.robot);
  EXPECT_EQ(moving.size(), 2U);
  ASSERT_EQ(empty.schedule.events().size(), 4U);
  EXPECT_EQ(empty.schedule.events()[2].robot, 1U);

  options.sensing = hiddenFile(run, "bartender-1-full.hidden.pddl");
  const ExecutionResult full = execute(run.world(), run.task(), run.plan(), options);
  ASSERT_TRUE(full.reachedGoal);
  EXPECT_EQ(actionNames(full), (std::vector<std::string>{"(senseifempty o1)"}));
  EXPECT_FALSE(full.sensed[0].value);
  EXPECT_EQ(full.schedule.duration(), 0);

  // Every branch of the plan, timed as its execution is.
  ASSERT_EQ(empty.branches.size(), 2U);
  EXPECT_EQ(empty.branches[0].outcomes, (std::vector<std::string>{"(isemptybottle o1) true"}));
  EXPECT_NEAR(empty.branches[0].seconds, empty.schedule.duration(), 1e-9);
  EXPECT_EQ(empty.branches[1].outcomes, (std::vector<std::string>{"(isemptybottle o1) false"}));
  EXPECT_EQ(empty.branches[1].actions, actionNames(full));
}

TEST(Execute, ACallbackDecidesTheBranch) {
  ExampleRun& run = bartender();
  std::vector<std::string> asked;
  ExecutionOptions options;
  options.sensing = [&](const SensingQuery& query) {
    asked.push_back(query.test);
    return false;
  };
  const ExecutionResult result = execute(run.world(), run.task(), run.plan(), options);
  EXPECT_TRUE(result.reachedGoal);
  EXPECT_EQ(asked, (std::vector<std::string>{"(isemptybottle o1)"}));
  EXPECT_EQ(result.schedule.actions().size(), 1U);
}

TEST(Execute, SensingSourcesRejectWhatThePlanDoesNotAdmit) {
  ExampleRun& run = bartender();
  // A branch with no source.
  EXPECT_THROW(execute(run.world(), run.task(), run.plan(), {}), InputError);
  // A hidden state the initial knowledge does not admit: o1 starts at left.
  try {
    hidden(run, "h.pddl", "(define (problem h) (:hidden (isatlocation o1 dishwasher)))");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("h.pddl:1:"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("not one of the initial worlds"), std::string::npos);
  }
  // An unknown fact.
  EXPECT_THROW(hidden(run, "h.pddl", "(define (problem h) (:hidden (isbroken o1)))"), InputError);
  // A terminal's answers: yes, no, anything else, nothing.
  for (const auto& [answer, value] :
       std::vector<std::pair<std::string, bool>>{{"y\n", true}, {" No \n", false}}) {
    std::istringstream in(answer);
    std::ostringstream out;
    ExecutionOptions options;
    options.sensing = promptSource(in, out);
    const ExecutionResult result = execute(run.world(), run.task(), run.plan(), options);
    EXPECT_EQ(result.sensed.at(0).value, value);
    EXPECT_EQ(out.str(), "(isemptybottle o1)? [y/n] ");
  }
  for (const std::string answer : {"maybe\n", ""}) {
    std::istringstream in(answer);
    std::ostringstream out;
    ExecutionOptions options;
    options.sensing = promptSource(in, out);
    EXPECT_THROW(execute(run.world(), run.task(), run.plan(), options), InputError) << answer;
  }
}

TEST(Execute, ObservedObjectsReCheckEachActionsGeometricPrecondition) {
  ExampleRun& run = pickAndPlace();
  const std::size_t block = run.world().find("block")->index;
  const Pose start = tamp::objectPose(run.world(), run.world().initialState(), block);
  WorldObservation observed;
  observed.objects[block] = start;
  ExecutionOptions options;
  options.observed = &observed;
  ExecutionResult result = execute(run.world(), run.task(), run.plan(), options);
  EXPECT_TRUE(result.reachedGoal) << result.stopReason;
  // The block 10 cm away from where the plan grasps it.
  observed.objects[block].translation().y() += 0.1;
  result = execute(run.world(), run.task(), run.plan(), options);
  EXPECT_FALSE(result.reachedGoal);
  EXPECT_EQ(result.schedule.actions().size(), 0U);
  EXPECT_EQ(result.stopReason,
            "nodes[2] (pickup kr5 block left): step 3 (grasp): object 'block' is 0.100 m and 0.0° "
            "from where robot 'kr5' grasps it");
}

TEST(Execute, AnObjectInTheWayStopsTheActionWhoseMotionItBlocks) {
  ExampleRun& run = bartender();
  // Observing nothing new: every action's precondition holds as the planner certified it.
  WorldObservation observed;
  ExecutionOptions options;
  options.sensing = hiddenFile(run, "bartender-1-empty.hidden.pddl");
  options.observed = &observed;
  EXPECT_TRUE(execute(run.world(), run.task(), run.plan(), options).reachedGoal);
  // Bottle o2 stands where robot1 is to put o1 down.
  observed.objects[run.world().find("o2")->index] = sharedPlacement(run);
  const ExecutionResult result = execute(run.world(), run.task(), run.plan(), options);
  EXPECT_FALSE(result.reachedGoal);
  EXPECT_EQ(actionNames(result),
            (std::vector<std::string>{"(senseifempty o1)", "(pickup robot1 o1 left)"}));
  EXPECT_NE(result.stopReason.find("(putdown robot1 o1 shared): step"), std::string::npos)
      << result.stopReason;
  EXPECT_NE(result.stopReason.find("'o2'"), std::string::npos) << result.stopReason;
}

TEST(Execute, WorldStateFilesAreReadOrRejectedNamingTheKey) {
  const world::World& world = pickAndPlace().world();
  const nlohmann::json good = nlohmann::json::parse(
      R"({"objects": {"block": {"position": [0.4, 0.2, -0.07], "quaternion_wxyz": [1, 0, 0, 0]}}})");
  const WorldObservation observed = readWorldObservation(good, "state.json", world);
  ASSERT_EQ(observed.objects.size(), 1U);
  EXPECT_NEAR(observed.objects.begin()->second.translation().x(), 0.4, 1e-12);
  const auto error = [&](const std::string& text) {
    try {
      readWorldObservation(nlohmann::json::parse(text), "state.json", world);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error(R"({"objects": {"cup": {}}})"),
            "state.json: objects.cup: no object 'cup' in the scene");
  EXPECT_EQ(error(R"({"objects": {"table": {}}})"),
            "state.json: objects.table: object 'table' is not movable");
  EXPECT_EQ(error(R"({"objects": {"block": {"position": [0, 0]}}})"),
            "state.json: objects.block.position: expected 3 numbers");
  EXPECT_EQ(error(R"({"objects": {}, "robots": {}})"),
            "state.json: robots: unknown key (known: objects)");
  EXPECT_EQ(error(R"([])"), "state.json: objects: expected an object of object name → pose");
}

TEST(Execute, TheStreamHasTheLogInOrderOneSamplePerTickAndAnEnd) {
  ExampleRun& run = bartender();
  ExecutionOptions options;
  options.sensing = hiddenFile(run, "bartender-1-empty.hidden.pddl");
  const ExecutionResult result = execute(run.world(), run.task(), run.plan(), options);
  std::ostringstream out;
  writeExecutionStream(out, run.world(), result, 100);
  std::istringstream lines(out.str());
  std::vector<nlohmann::json> records;
  for (std::string line; std::getline(lines, line);) records.push_back(nlohmann::json::parse(line));
  std::size_t samples = 0;
  std::vector<std::string> kinds;
  double time = 0;
  for (const nlohmann::json& record : records) {
    const std::string type = record["type"];
    if (type == "end") continue;
    EXPECT_GE(record["time"].get<double>(), time) << record.dump();
    time = record["time"];
    if (type == "sample") {
      ++samples;
      EXPECT_EQ(record["robots"]["robot2"]["q"].size(), 6U);
    } else {
      kinds.push_back(type);
    }
  }
  EXPECT_EQ(samples, sampleTimes(result.schedule.duration(), 100).size());
  EXPECT_EQ(kinds,
            (std::vector<std::string>{"action", "sense", "action", "grasp", "action", "release",
                                      "action", "action", "grasp", "action", "release"}));
  EXPECT_EQ(records.back()["type"], "end");
  EXPECT_EQ(records.back()["reached_goal"], true);
  EXPECT_EQ(records.back()["branches"].size(), 2U);
  // The execution record: what a viewer needs to replay each motion exactly.
  const nlohmann::json record = executionJson(run.world(), result, 100);
  EXPECT_EQ(record["format"], "kaboum-execution");
  EXPECT_EQ(record["motions"].size(), result.schedule.motions().size());
  EXPECT_EQ(record["motions"][0]["segment_durations"].size() + 1,
            record["motions"][0]["waypoints"].size());
}

}  // namespace kaboum::exec
