// Bad robot descriptions: every class gives an InputError naming the file and the element.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "kaboum/core/error.hpp"
#include "kaboum/io/urdf_loader.hpp"

// urdfdom 3.0.1 leaks the links of a cyclic joint graph when it rejects it (the links own each
// other through child_links); the "cycle.urdf" case below triggers that, so LeakSanitizer is
// told to ignore allocations made inside urdf::parseURDF.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:urdf::parseURDF\n";
}

namespace kaboum::kinematics {

using namespace kaboum::io;

namespace {

namespace fs = std::filesystem;

// Writes `text` to a file in a folder emptied when the process first writes to it (a process
// that reuses an earlier run's id must not find that run's files: the mesh lookup searches the
// folder and its ancestors) and returns its path.
std::string writeUrdf(const std::string& name, const std::string& text) {
  static const fs::path dir = [] {
    const fs::path fresh =
        fs::temp_directory_path() / ("kaboum_urdf_" + std::to_string(::getpid()));
    fs::remove_all(fresh);
    fs::create_directories(fresh);
    return fresh;
  }();
  const fs::path path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

// Expects loadUrdf(text) to throw an InputError whose message contains every fragment.
void expectError(const std::string& name, const std::string& text,
                 const std::vector<std::string>& fragments) {
  const std::string path = writeUrdf(name, text);
  try {
    loadUrdf(path);
    ADD_FAILURE() << name << " loaded without error";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const auto& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos) << message << " lacks " << fragment;
    }
  }
}

const std::string kTwoLinks = R"(<robot name="r"><link name="a"/><link name="b"/>)";

TEST(UrdfErrors, MissingFile) {
  EXPECT_THROW(loadUrdf("/nonexistent/robot.urdf"), InputError);
}

TEST(UrdfErrors, MalformedXml) {
  expectError("malformed.urdf", R"(<robot name="r"><link name="a">)", {"invalid URDF"});
  expectError("empty.urdf", "", {"invalid URDF"});
  expectError("notrobot.urdf", "<html/>", {"invalid URDF"});
}

TEST(UrdfErrors, UnknownAndFloatingJointTypes) {
  expectError(
      "screw.urdf",
      kTwoLinks +
          R"(<joint name="j" type="screw"><parent link="a"/><child link="b"/></joint></robot>)",
      {"invalid URDF", "j"});
  expectError(
      "floating.urdf",
      kTwoLinks +
          R"(<joint name="free" type="floating"><parent link="a"/><child link="b"/></joint></robot>)",
      {"joint 'free'", "floating"});
}

TEST(UrdfErrors, MissingLimitsAndZeroAxis) {
  expectError(
      "nolimit.urdf",
      kTwoLinks +
          R"(<joint name="elbow" type="revolute"><parent link="a"/><child link="b"/></joint></robot>)",
      {"elbow"});
  expectError(
      "zeroaxis.urdf",
      kTwoLinks + R"(<joint name="slide" type="prismatic"><parent link="a"/><child link="b"/>
                <axis xyz="0 0 0"/><limit lower="0" upper="1" effort="0" velocity="1"/></joint></robot>)",
      {"slide"});
}

TEST(UrdfErrors, KinematicLoops) {
  expectError("twoparents.urdf",
              R"(<robot name="r"><link name="a"/><link name="b"/><link name="c"/>
                 <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
                 <joint name="ac" type="fixed"><parent link="a"/><child link="c"/></joint>
                 <joint name="bc" type="fixed"><parent link="b"/><child link="c"/></joint></robot>)",
              {"'ac'", "'bc'", "'c'", "kinematic loop"});
  expectError("tworoots.urdf",
              R"(<robot name="r"><link name="a"/><link name="b"/><link name="c"/>
                 <joint name="ac" type="fixed"><parent link="a"/><child link="c"/></joint>
                 <joint name="bc" type="fixed"><parent link="b"/><child link="c"/></joint></robot>)",
              {"Two root links"});
  expectError(
      "cycle.urdf",
      kTwoLinks + R"(<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
                 <joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint></robot>)",
      {"invalid URDF"});
  expectError(
      "unknownlink.urdf",
      kTwoLinks +
          R"(<joint name="ax" type="fixed"><parent link="a"/><child link="x"/></joint></robot>)",
      {"ax"});
}

TEST(UrdfErrors, MissingMeshFiles) {
  const std::string mesh = R"(<robot name="r"><link name="hand"><collision><geometry>
      <mesh filename="FILE"/></geometry></collision></link></robot>)";
  const auto withMesh = [&](const std::string& file) {
    std::string text = mesh;
    text.replace(text.find("FILE"), 4, file);
    return text;
  };
  expectError("mesh.urdf", withMesh("meshes/hand.stl"),
              {"link 'hand'", "meshes/hand.stl", "not found"});
  expectError("package.urdf", withMesh("package://nowhere/hand.stl"),
              {"package://nowhere/hand.stl", "not found"});
  expectError("scheme.urdf", withMesh("http://example.com/hand.stl"), {"unsupported URI scheme"});
  // The same mesh present next to the URDF resolves.
  const std::string path = writeUrdf("present.urdf", withMesh("hand.stl"));
  std::ofstream(fs::path(path).parent_path() / "hand.stl") << "solid hand\nendsolid hand\n";
  const RobotModel robot = loadUrdf(path);
  EXPECT_EQ(robot.links()[0].collisions.at(0).meshPath,
            (fs::path(path).parent_path() / "hand.stl").string());
}

}  // namespace
}  // namespace kaboum::kinematics
