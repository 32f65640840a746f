// The fk and ik verbs as users call them: output, JSON, exit codes, one-line errors.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Core>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "robots.hpp"

namespace kaboum::kinematics {

using namespace kaboum::testing;

namespace {

struct CliRun {
  int exitCode;
  std::string out;
  std::string err;
};

// Runs the kaboum CLI with `arguments` (already shell-quoted), capturing stdout and stderr.
CliRun kaboum(const std::string& arguments) {
  const std::string errFile =
      std::filesystem::temp_directory_path() / ("kaboum_cli_err_" + std::to_string(::getpid()));
  const std::string command = std::string("'") + KABOUM_CLI + "' " + arguments + " 2>" + errFile;
  CliRun run{-1, {}, {}};
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  std::array<char, 4096> buffer{};
  while (const std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe))
    run.out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(errFile);
  run.err.assign(std::istreambuf_iterator<char>(err), {});
  return run;
}

std::string quoted(const std::string& path) {
  return "'" + path + "'";
}

void expectOneLineError(const CliRun& run, const std::string& fragment) {
  EXPECT_EQ(run.exitCode, 2) << run.out << run.err;
  EXPECT_EQ(run.err.rfind("kaboum: error: ", 0), 0u) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_NE(run.err.find(fragment), std::string::npos) << run.err;
}

TEST(CliFk, PrintsTheToolPoseAndJson) {
  const CliRun text = kaboum("fk " + quoted(test::kComauRight) + " 0 0 0 0 0 0");
  ASSERT_EQ(text.exitCode, 0) << text.err;
  // Home pose: flange 0.45 + 0.59 + 0.64707 + 0.095 up, 0.13 back; identity rotation.
  std::istringstream lines(text.out);
  std::string tip, position, quaternion, name;
  std::getline(lines, tip);
  std::getline(lines, position);
  std::getline(lines, quaternion);
  EXPECT_EQ(tip, "tip frame8");
  double x = 0, y = 0, z = 0, w = 0;
  std::istringstream(position) >> name >> x >> y >> z;
  EXPECT_EQ(name, "position");
  EXPECT_TRUE(Eigen::Vector3d(x, y, z).isApprox(Eigen::Vector3d(0.02, 0, 1.78207), 1e-8))
      << position;
  std::istringstream(quaternion) >> name >> w >> x >> y >> z;
  EXPECT_EQ(name, "quaternion");
  EXPECT_NEAR(std::abs(w), 1.0, 1e-9) << quaternion;
  const CliRun json = kaboum("fk " + quoted(test::kComauRight) + " 0 -0.5 0.3 0 0 0 --json");
  ASSERT_EQ(json.exitCode, 0) << json.err;
  const auto parsed = nlohmann::json::parse(json.out);
  EXPECT_EQ(parsed["tip"], "frame8");
  EXPECT_EQ(parsed["position"].size(), 3u);
  EXPECT_EQ(parsed["quaternion_wxyz"].size(), 4u);
}

// fk then ik --all: the original joint values are among the closed-form solutions.
TEST(CliIk, RoundTripsTheKr5ThroughFk) {
  const std::string robot = quoted(test::kKr5);
  const auto pose =
      nlohmann::json::parse(kaboum("fk " + robot + " 0.1 -0.2 0.3 0.4 0.5 0.6 --json").out);
  std::string poseArgs;
  for (const auto& v : pose["position"]) poseArgs += " " + std::to_string(v.get<double>());
  for (const auto& v : pose["quaternion_wxyz"]) poseArgs += " " + std::to_string(v.get<double>());
  const CliRun run = kaboum("ik " + robot + " --pose" + poseArgs + " --all --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto result = nlohmann::json::parse(run.out);
  EXPECT_EQ(result["method"], "closed-form six-axis (A.3)");
  EXPECT_TRUE(result["reachable"]);
  const std::vector<double> original{0.1, -0.2, 0.3, 0.4, 0.5, 0.6};
  bool found = false;
  for (const auto& solution : result["solutions"]) {
    double difference = 0;
    for (std::size_t i = 0; i < 6; ++i)
      difference = std::max(difference, std::abs(solution[i].get<double>() - original[i]));
    found = found || difference < 1e-4;  // std::to_string keeps 6 decimals
  }
  EXPECT_TRUE(found) << run.out;
  const CliRun single = kaboum("ik " + robot + " --pose" + poseArgs);
  EXPECT_EQ(single.exitCode, 0);
  EXPECT_EQ(std::count(single.out.begin(), single.out.end(), '\n'), 1) << single.out;
}

TEST(CliIk, NumericForTheWamAndUnreachableIsExitCodeOne) {
  const CliRun wam =
      kaboum("ik " + quoted(test::kWam) + " --pose 0.5 0.3 0.6 1 0 0 0 --seed 3 --json");
  ASSERT_EQ(wam.exitCode, 0) << wam.err;
  EXPECT_EQ(nlohmann::json::parse(wam.out)["method"], "numeric (damped least squares)");
  const CliRun far = kaboum("ik " + quoted(test::kKr5) + " --pose 3 0 0 1 0 0 0");
  EXPECT_EQ(far.exitCode, 1);
  EXPECT_EQ(far.out, "unreachable\n");
  EXPECT_TRUE(far.err.empty()) << far.err;
}

TEST(CliErrors, BadInputIsOneLineAndExitCodeTwo) {
  const std::string kr5 = quoted(test::kKr5);
  expectOneLineError(kaboum("fk /nonexistent.urdf 0"), "/nonexistent.urdf: cannot open file");
  expectOneLineError(kaboum("fk " + kr5 + " 1 2"), "has 6 joints, got 2 values");
  expectOneLineError(kaboum("fk " + kr5 + " --tip nosuch 0 0 0 0 0 0"), "no link named 'nosuch'");
  expectOneLineError(kaboum("fk " + kr5 + " 0 0 zero 0 0 0"), "zero");
  expectOneLineError(kaboum("ik " + kr5 + " --pose 0 0 0 2 0 0 0"), "unit length");
  expectOneLineError(kaboum("ik " + kr5 + " --pose 1 2 3"), "--pose");
  expectOneLineError(kaboum("ik " + kr5), "--pose");
  const std::string broken = std::filesystem::temp_directory_path() / "kaboum_cli_broken.urdf";
  std::ofstream(broken) << "<robot name='x'><link name='a'>";
  expectOneLineError(kaboum("ik '" + broken + "' --pose 0 0 0 1 0 0 0"), "invalid URDF");
}

}  // namespace
}  // namespace kaboum::kinematics
