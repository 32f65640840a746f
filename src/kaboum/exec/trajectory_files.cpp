#include "kaboum/exec/trajectory_files.hpp"

#include <fmt/format.h>

#include <ostream>

#include "kaboum/io/json_kinematics.hpp"

namespace kaboum::exec {

using json = nlohmann::json;

namespace {

std::vector<std::string> jointNames(const world::World& world, std::size_t robot) {
  std::vector<std::string> names;
  for (const world::JointSpec& joint : world.description().robots[robot].joints) {
    names.push_back(joint.name);
  }
  return names;
}

// The rows of a samples × dof block as a list of lists.
json rows(const std::vector<double>& values, std::size_t dof) {
  json out = json::array();
  for (std::size_t at = 0; at < values.size(); at += dof) {
    out.push_back(std::vector<double>(values.begin() + static_cast<std::ptrdiff_t>(at),
                                      values.begin() + static_cast<std::ptrdiff_t>(at + dof)));
  }
  return out;
}

json eventJson(const world::World& world, const GripperEvent& event) {
  const world::RobotSpec& robot = world.description().robots[event.robot];
  json out = {{"type", tamp::toString(event.kind)},
              {"time", event.time},
              {"node", event.node},
              {"robot", robot.name},
              {"tool", robot.tools[event.tool].name},
              {"object", world.scene().name(event.object)}};
  if (event.kind == tamp::GeometricStep::Kind::Grasp) {
    out["link"] = robot.tools[event.tool].link;
    out["object_in_link"] = io::toJson(event.pose);
  } else {
    out["object_pose"] = io::toJson(event.pose);
  }
  return out;
}

json logJson(const world::World& world, const ExecutionResult& result, const LogRecord& record) {
  if (record.kind == LogRecord::Kind::Gripper) {
    return eventJson(world, result.schedule.events()[record.index]);
  }
  if (record.kind == LogRecord::Kind::Sensing) {
    const SensingOutcome& outcome = result.sensed[record.index];
    return {{"type", "sense"},
            {"time", outcome.time},
            {"node", outcome.node},
            {"test", outcome.test},
            {"value", outcome.value}};
  }
  const TimedAction& action = result.schedule.actions()[record.index];
  return {{"type", "action"},
          {"time", action.start},
          {"node", action.node},
          {"action", action.name},
          {"end", action.end}};
}

json branchJson(const BranchTiming& branch) {
  return {{"outcomes", branch.outcomes}, {"actions", branch.actions}, {"seconds", branch.seconds}};
}

json endJson(const ExecutionResult& result) {
  json outcomes = json::array();
  for (const SensingOutcome& sensed : result.sensed) {
    outcomes.push_back(sensed.test + (sensed.value ? " true" : " false"));
  }
  json actions = json::array();
  for (const TimedAction& action : result.schedule.actions()) actions.push_back(action.name);
  return {{"reached_goal", result.reachedGoal},
          {"stop_reason", result.stopReason},
          {"branch", {{"outcomes", outcomes}, {"actions", actions}}},
          {"seconds", result.schedule.duration()}};
}

}  // namespace

json robotTrajectoryJson(const world::World& world, const Schedule& schedule,
                         const RobotSamples& samples, double rate) {
  return {{"format", "kaboum-trajectory"},
          {"version", 1},
          {"robot", world.description().robots[samples.robot].name},
          {"joints", jointNames(world, samples.robot)},
          {"profile", toString(schedule.profile())},
          {"rate", rate},
          {"duration", schedule.duration()},
          {"time", samples.times},
          {"q", rows(samples.positions, samples.dof)},
          {"qd", rows(samples.velocities, samples.dof)},
          {"qdd", rows(samples.accelerations, samples.dof)}};
}

void writeRobotTrajectoryCsv(std::ostream& out, const world::World& world,
                             const RobotSamples& samples) {
  const std::vector<std::string> joints = jointNames(world, samples.robot);
  out << "time";
  for (const char* prefix : {"q", "qd", "qdd"}) {
    for (const std::string& joint : joints) out << ',' << prefix << '.' << joint;
  }
  out << '\n';
  fmt::memory_buffer line;
  for (std::size_t k = 0; k < samples.times.size(); ++k) {
    line.clear();
    fmt::format_to(std::back_inserter(line), "{}", samples.times[k]);
    for (const std::vector<double>* values :
         {&samples.positions, &samples.velocities, &samples.accelerations}) {
      for (std::size_t j = 0; j < samples.dof; ++j) {
        fmt::format_to(std::back_inserter(line), ",{}", (*values)[k * samples.dof + j]);
      }
    }
    line.push_back('\n');
    out.write(line.data(), static_cast<std::streamsize>(line.size()));
  }
}

json executionJson(const world::World& world, const ExecutionResult& result, double rate) {
  const Schedule& schedule = result.schedule;
  json robots = json::array();
  for (std::size_t r = 0; r < schedule.robotCount(); ++r) {
    robots.push_back(
        {{"name", world.description().robots[r].name}, {"joints", jointNames(world, r)}});
  }
  json actions = json::array();
  for (const TimedAction& action : schedule.actions()) {
    actions.push_back({{"node", action.node},
                       {"action", action.name},
                       {"start", action.start},
                       {"end", action.end}});
  }
  json motions = json::array();
  for (const TimedMotion& motion : schedule.motions()) {
    motions.push_back({{"node", motion.node},
                       {"step", motion.step + 1},
                       {"kind", tamp::toString(motion.kind)},
                       {"robot", world.description().robots[motion.robot].name},
                       {"start", motion.start},
                       {"duration", motion.path.duration()},
                       {"waypoints", motion.path.waypoints()},
                       {"segment_durations", motion.path.durations()},
                       {"path_deviation", pathDeviation(motion.path, 1 / rate)}});
  }
  json events = json::array();
  for (const GripperEvent& event : schedule.events()) events.push_back(eventJson(world, event));
  json sensed = json::array();
  for (const SensingOutcome& outcome : result.sensed) {
    sensed.push_back({{"node", outcome.node},
                      {"test", outcome.test},
                      {"value", outcome.value},
                      {"time", outcome.time}});
  }
  json branches = json::array();
  for (const BranchTiming& branch : result.branches) branches.push_back(branchJson(branch));
  json out = {{"format", "kaboum-execution"},
              {"version", 1},
              {"profile", toString(schedule.profile())},
              {"rate", rate},
              {"robots", robots},
              {"actions", actions},
              {"motions", motions},
              {"events", events},
              {"sensed", sensed},
              {"branches", branches}};
  out.update(endJson(result));
  return out;
}

void writeExecutionStream(std::ostream& out, const world::World& world,
                          const ExecutionResult& result, double rate) {
  const Schedule& schedule = result.schedule;
  std::vector<std::pair<double, json>> records;
  for (const LogRecord& record : executionLog(result)) {
    records.emplace_back(record.time, logJson(world, result, record));
  }
  std::vector<std::vector<double>> q(schedule.robotCount()), qd(q.size()), qdd(q.size());
  for (std::size_t r = 0; r < q.size(); ++r) {
    q[r].resize(schedule.dof(r));
    qd[r].resize(schedule.dof(r));
    qdd[r].resize(schedule.dof(r));
  }
  std::vector<std::string> names;  // as JSON strings
  for (const world::RobotSpec& robot : world.description().robots) {
    names.push_back(json(robot.name).dump());
  }
  std::size_t next = 0;
  fmt::memory_buffer line;
  for (const double t : sampleTimes(schedule.duration(), rate)) {
    for (; next < records.size() && records[next].first <= t; ++next) {
      out << records[next].second.dump() << '\n';
    }
    line.clear();
    fmt::format_to(std::back_inserter(line), R"({{"type":"sample","time":{},"robots":{{)", t);
    for (std::size_t r = 0; r < q.size(); ++r) {
      schedule.sample(t, r, q[r], qd[r], qdd[r]);
      fmt::format_to(std::back_inserter(line), R"({}{}:{{"q":[{}],"qd":[{}],"qdd":[{}]}})",
                     r == 0 ? "" : ",", names[r], fmt::join(q[r], ","), fmt::join(qd[r], ","),
                     fmt::join(qdd[r], ","));
    }
    line.append(std::string_view("}}\n"));
    out.write(line.data(), static_cast<std::streamsize>(line.size()));
  }
  for (; next < records.size(); ++next) out << records[next].second.dump() << '\n';
  json end = endJson(result);
  end["type"] = "end";
  json branches = json::array();
  for (const BranchTiming& branch : result.branches) branches.push_back(branchJson(branch));
  end["branches"] = branches;
  out << end.dump() << '\n';
}

}  // namespace kaboum::exec
