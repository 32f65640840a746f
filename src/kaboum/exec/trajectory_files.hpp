// The files of an execution (docs/execution.md): per robot its sampled trajectory as JSON and CSV
// (time, q, qd, qdd per joint); the execution record — actions, timed motions (waypoints, segment
// durations and profile: what a viewer needs to replay them exactly), gripper events, sensing
// outcomes, the branch taken and every branch's time; and the same as a stream of JSON lines.
#pragma once

#include <iosfwd>
#include <nlohmann/json.hpp>

#include "kaboum/exec/executor.hpp"

namespace kaboum::exec {

// {"format": "kaboum-trajectory", "version": 1, "robot", "joints", "profile", "rate", "duration",
// "limits", "time", "q", "qd", "qdd"}.
nlohmann::json robotTrajectoryJson(const world::World& world, const Schedule& schedule,
                                   const RobotSamples& samples, double rate);

// A header line "time,q.<joint>…,qd.<joint>…,qdd.<joint>…" and one line per sample.
void writeRobotTrajectoryCsv(std::ostream& out, const world::World& world,
                             const RobotSamples& samples);

// {"format": "kaboum-execution", "version": 1, …}: the whole run.
nlohmann::json executionJson(const world::World& world, const ExecutionResult& result, double rate);

// The run as JSON lines in time order: "action", "sense", "grasp" and "release" records, one
// "sample" per control tick with every robot's q, qd, qdd, and an "end" record.
void writeExecutionStream(std::ostream& out, const world::World& world,
                          const ExecutionResult& result, double rate);

}  // namespace kaboum::exec
