// Shared helpers of the io tests: a scratch directory, data paths, error capture, mesh equality.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../support/test_support.hpp"
#include "kaboum/core/error.hpp"
#include "kaboum/geometry/triangle_mesh.hpp"
#include "kaboum/io/mesh_io.hpp"
#include "kaboum/testing/data_paths.hpp"

namespace kaboum::test {

using namespace kaboum::geometry;
using namespace kaboum::io;
using namespace kaboum::testing;

inline std::string meshData(const std::string& name) {
  return kaboum::testing::dataFile("meshes/" + name);
}

// The message readMesh(path) throws as InputError, or "" when it reads the mesh.
inline std::string readError(const std::string& path) {
  try {
    readMesh(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// readMesh(path) must fail with one line that starts with `where` (the file, with line:col where
// it applies) and contains `what`.
inline void expectReadError(const std::string& path, const std::string& where,
                            const std::string& what) {
  const std::string message = readError(path);
  EXPECT_EQ(message.rfind(where + ": ", 0), 0u) << message;
  EXPECT_NE(message.find(what), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

inline void expectSameMesh(const TriangleMesh& actual, const TriangleMesh& expected) {
  ASSERT_EQ(actual.vertices.size(), expected.vertices.size());
  ASSERT_EQ(actual.triangles.size(), expected.triangles.size());
  for (std::size_t i = 0; i < expected.vertices.size(); ++i) {
    ASSERT_EQ(actual.vertices[i], expected.vertices[i]) << "vertex " << i;
  }
  for (std::size_t t = 0; t < expected.triangles.size(); ++t) {
    ASSERT_EQ(actual.triangles[t], expected.triangles[t]) << "triangle " << t;
  }
}

}  // namespace kaboum::test
