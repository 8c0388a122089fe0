// Checkpoint files verify themselves: every truncation and a flipped byte are detected,
// an intact file reads back bit for bit. Stored points are found again by position.
#include "io/CheckpointFile.h"
#include "mesh/PointLookup.h"
#include "mpi_main.h"
#include <cmath>
#include <filesystem>

using namespace cellphase;
namespace
{
CheckpointData sample()
{
  CheckpointData d;
  d.set("time", 0.1 + 0.2); // not exactly representable: must come back bit for bit
  d.arrays["field.phi.values"] = {1.0, -1.0, std::nextafter(0.5, 1.0), 1e-300};
  d.texts["scene"] = "domain:\n  lower: [0, 0]\n";
  d.texts["empty"] = "";
  return d;
}
} // namespace

TEST(CheckpointFile, RoundTripIsExact)
{
  const auto back = decode(encode(sample()));
  EXPECT_EQ(back.scalar("time"), 0.1 + 0.2);
  EXPECT_EQ(back.array("field.phi.values"), sample().arrays["field.phi.values"]);
  EXPECT_EQ(back.text("scene"), sample().texts["scene"]);
  EXPECT_EQ(back.text("empty"), "");
  EXPECT_THROW(back.array("missing"), CheckpointError);
}

TEST(CheckpointFile, EveryTruncationIsDetected)
{
  const std::string bytes = encode(sample());
  for (std::size_t n = 0; n < bytes.size(); ++n)
    EXPECT_THROW(decode(bytes.substr(0, n)), CheckpointError) << "cut at " << n;
}

TEST(CheckpointFile, FlippedByteIsDetected)
{
  const std::string bytes = encode(sample());
  for (std::size_t i = 0; i < bytes.size(); i += 7)
  {
    std::string damaged = bytes;
    damaged[i] ^= 0x10;
    EXPECT_THROW(decode(damaged), CheckpointError) << "byte " << i;
  }
}

TEST(CheckpointFile, AtomicWriteLeavesNoTemporary)
{
  const std::string path = testing::TempDir() + "/cellphase-test.cpk";
  write_file_atomically(path, encode(sample()));
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  EXPECT_EQ(decode(read_file(path)).scalar("time"), 0.1 + 0.2);
  std::filesystem::remove(path);
  EXPECT_THROW(read_file(path), CheckpointError);
}

TEST(PointLookup, FindsPointsDespiteRoundOffOnly)
{
  // A lattice of spacing 1e-3, as P2 nodes of a fine mesh, with a point on a bin boundary.
  std::vector<double> pts;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      pts.insert(pts.end(), {i * 1e-3, j * 1e-3, 0.0});
  PointLookup lookup(pts, 1e-11);
  for (std::size_t k = 0; k < pts.size() / 3; ++k)
  {
    double p[3] = {pts[3 * k] * (1 + 1e-15), pts[3 * k + 1] - 1e-16, 0.0};
    EXPECT_EQ(lookup.find(p), std::int64_t(k));
  }
  double off[3] = {5e-4, 0, 0}; // between two nodes
  EXPECT_EQ(lookup.find(off), -1);
}
