// `grip params`: a vehicle's complete parameters as a file that reads back to itself, and a bad
// file refused with its place on stderr.

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "grip_command.hpp"

namespace {

using grip::testing::CommandRun;
using grip::testing::run_grip;

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(ParamsCommand, WhatItPrintsForARobotReadsBackToTheSameText) {
  // GIVEN the car's parameters as `grip params` prints them
  const CommandRun car = run_grip("params --robot car", "2>/dev/null");
  ASSERT_EQ(car.status, 0) << car.output;
  EXPECT_NE(car.output.find("  model: car"), std::string::npos) << car.output;
  const std::string path = write_file("grip-params-car.yaml", car.output);

  // WHEN that output is the parameter file THEN it prints the same, with or without --robot
  const CommandRun again = run_grip("params --params " + path, "2>/dev/null");
  EXPECT_EQ(again.status, 0);
  EXPECT_EQ(again.output, car.output);
  const CommandRun both = run_grip("params --robot car --params " + path, "2>/dev/null");
  EXPECT_EQ(both.status, 0);
  EXPECT_EQ(both.output, car.output);
  std::remove(path.c_str());
}

TEST(ParamsCommand, WithoutOptionsItPrintsTheVelocityControlledRobot) {
  const CommandRun r = run_grip("params", "2>/dev/null");
  ASSERT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("  model: dd-vel"), std::string::npos) << r.output;
}

TEST(ParamsCommand, ABadFileExitsWithTwoAndItsPlaceOnStderr) {
  const std::string path =
      write_file("grip-params-bad.yaml", "vehicle:\n  model: car\n  max_steer_rad: 2.0\n");
  const CommandRun r = run_grip("params --params " + path, "2>&1 >/dev/null");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find(path + ":3:18: vehicle.max_steer_rad must be"), std::string::npos)
      << r.output;
  std::remove(path.c_str());
}

TEST(ParamsCommand, ARobotOtherThanTheFilesModelExitsWithTwo) {
  const std::string path = write_file("grip-params-dd.yaml", "vehicle:\n  model: dd-vel\n");
  const CommandRun r = run_grip("params --robot car --params " + path, "2>&1 >/dev/null");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--robot car contradicts " + path), std::string::npos) << r.output;
  std::remove(path.c_str());
}

TEST(ParamsCommand, AnUnknownRobotExitsWithTwo) {
  const CommandRun r = run_grip("params --robot tank", "2>&1 >/dev/null");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("unknown robot 'tank'"), std::string::npos) << r.output;
}

}  // namespace
