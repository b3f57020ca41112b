#include "p4/io/flight_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "p4/core/error.h"
#include "p4/core/table.h"

namespace p4 {
namespace {

namespace fs = std::filesystem;

const fs::path kFlights = fs::path(P4_SHARED_DATA) / "trajectories" / "tt3d";

TEST(Tt3dFlight, ConvertsTheFrameAndFindsTheBounce) {
  const RealFlight flight = ReadTt3dFlight((kFlights / "001.csv").string(), 0.2);
  // First row: Timestamp 12.056, X -0.0541, Y 1.4726, Z 0.3444  =>  x = Y, y = -X, z = Z.
  const auto first = flight.trajectory.At(0.2);
  ASSERT_TRUE(first.has_value());
  EXPECT_NEAR(first->position.x(), 1.4725837748244797, 1e-12);
  EXPECT_NEAR(first->position.y(), 0.054095524796083, 1e-12);
  EXPECT_NEAR(first->position.z(), 0.3443900000588409, 1e-12);
  EXPECT_LT(first->velocity.x(), -5.0);  // flying towards A
  ASSERT_EQ(flight.bounces.size(), 1u);
  EXPECT_EQ(flight.bounces[0].side, 'A');
  EXPECT_FALSE(flight.trajectory.At(0.1).has_value());
}

TEST(Tt3dFlight, EveryRecordedFlightHasABounceOnTheTable) {
  int flights = 0;
  for (const auto& entry : fs::directory_iterator(kFlights)) {
    const RealFlight flight = ReadTt3dFlight(entry.path().string(), 0.0);
    ASSERT_GE(flight.bounces.size(), 1u) << entry.path();
    for (const auto& b : flight.bounces) {
      EXPECT_TRUE(table::OnSurface(b.position->x(), b.position->y())) << entry.path();
    }
    ++flights;
  }
  EXPECT_EQ(flights, 139);
}

TEST(Tt3dFlight, BadFilesAreNamed) {
  const std::string path = (fs::temp_directory_path() / "p4_bad_flight.csv").string();
  std::ofstream(path) << "Timestamp,X,Y,Z\n1.0,0,0,0\n1.1,0,zero,0\n";
  try {
    ReadTt3dFlight(path, 0.0);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ReadTt3dFlight("/nonexistent.csv", 0.0), Error);
  fs::remove(path);
}

}  // namespace
}  // namespace p4
