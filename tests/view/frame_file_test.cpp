// Frame files: what was written comes back (held points to half a quantum, the rest exactly);
// every truncation, a flipped byte, a wrong magic or version is refused with the file's name and
// a byte offset; the page's bytes thin to the budget and keep every count.

#include "view/display_frame.hpp"
#include "view/frame_file.hpp"

#include "support/temp_dir.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>
#include <random>

namespace eco::view {
namespace {

FrameRecord sample_frame(std::size_t held, bool attributes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coordinate(-10.0f, 9.99f);
  FrameRecord r;
  r.frame = 42;
  r.world_T_sensor = Eigen::Translation3d(1234.5, -87.25, 3.0) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ());
  r.voxel_size = 0.5;
  for (std::size_t i = 0; i < held; ++i) {
    r.held.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng) / 4);
    r.age.push_back(std::uint16_t(i % 70000));
    if (attributes) {
      r.intensity.push_back(float(i) * 0.25f);
      r.id.push_back(std::uint32_t(4000000000u - i));
    }
  }
  r.dropped = {{10.5f, 0.0f, 1.0f}, {-10.25f, 3.0f, 0.5f}};
  r.cleared = {{2.0f, 2.0f, 0.0f}};
  r.voxels = {{2469, -175, 6}, {2449, -195, 5}, {2470, -174, 7}};
  return r;
}

TEST(FrameFile, ReadsBackWhatWasWritten) {
  test::TempDir dir;
  for (const bool attributes : {false, true}) {
    const FrameRecord r = sample_frame(5000, attributes);
    const std::string path = (dir / frame_file_name(r.frame)).string();
    write_frame_file(path, r);
    const FrameRecord back = read_frame_file(path);
    EXPECT_EQ(back.frame, 42u);
    EXPECT_TRUE(back.world_T_sensor.isApprox(r.world_T_sensor, 0.0));
    EXPECT_EQ(back.voxel_size, 0.5);
    ASSERT_EQ(back.held.size(), r.held.size());
    const double half_step = position_step(r.held) / 2;
    for (std::size_t i = 0; i < r.held.size(); ++i) {
      ASSERT_LE((back.held[i] - r.held[i]).cwiseAbs().maxCoeff(), half_step + 1e-6) << "point " << i;
    }
    EXPECT_EQ(back.age, r.age);
    EXPECT_EQ(back.intensity, r.intensity);
    EXPECT_EQ(back.id, r.id);
    EXPECT_EQ(back.dropped, r.dropped);
    EXPECT_EQ(back.cleared, r.cleared);
    EXPECT_EQ(back.voxels, r.voxels);
    EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
  }
  EXPECT_EQ(frame_file_name(7), "frame_000007.bin");
}

TEST(FrameFile, AnEmptyMapIsAFrame) {
  FrameRecord r;
  const FrameRecord back = decode_frame(encode_frame(r), "empty.bin");
  EXPECT_TRUE(back.held.empty());
  EXPECT_TRUE(back.voxels.empty());
}

TEST(FrameFile, RefusesEveryTruncationWithTheFileAndOffset) {
  const std::string bytes = encode_frame(sample_frame(40, true));
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    try {
      (void)decode_frame(bytes.substr(0, size), "frame_000042.bin");
      FAIL() << "a frame cut to " << size << " of " << bytes.size() << " bytes was read";
    } catch (const FrameFileError& e) {
      const std::string what = e.what();
      ASSERT_EQ(what.rfind("frame_000042.bin: byte ", 0), 0u) << what;
    }
  }
}

TEST(FrameFile, RefusesDamage) {
  const std::string good = encode_frame(sample_frame(40, false));
  const auto refusal = [](const std::string& bytes) {
    try {
      (void)decode_frame(bytes, "f.bin");
    } catch (const FrameFileError& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  std::string flipped = good;
  flipped[good.size() / 2] = char(flipped[good.size() / 2] ^ 0x10);  // inside the held points
  EXPECT_NE(refusal(flipped).find("checksum mismatch"), std::string::npos) << refusal(flipped);
  std::string magic = good;
  magic[0] = 'X';
  EXPECT_NE(refusal(magic).find("f.bin: byte 0: not a frame file"), std::string::npos) << refusal(magic);
  std::string version = good;
  version[8] = 9;
  EXPECT_NE(refusal(version).find("f.bin: byte 8: version 9"), std::string::npos) << refusal(version);
  EXPECT_NE(refusal(good + "xxxx").find("bytes after the frame's last part"), std::string::npos);
  std::string step = good;  // a quantum that would overflow a float
  const double huge_step = 1e300;
  std::memcpy(step.data() + 8 + 4 + 4 + 4 + 96, &huge_step, 8);
  EXPECT_NE(refusal(step).find("f.bin: byte 116: quantum 1e+300 m is not in (0, 100]"), std::string::npos) << refusal(step);
  std::string counts = good;  // a held count far beyond the file
  const std::uint32_t huge = 1u << 30;
  std::memcpy(counts.data() + 8 + 4 + 4 + 4 + 96 + 16, &huge, 4);
  EXPECT_NE(refusal(counts).find("held points: the file ends inside"), std::string::npos) << refusal(counts);
}

TEST(FrameFile, MissingFileIsNamed) {
  try {
    (void)read_frame_file("/nonexistent/frame_000001.bin");
    FAIL();
  } catch (const FrameFileError& e) {
    EXPECT_STREQ(e.what(), "frame_000001.bin: cannot be opened");
  }
}

TEST(FrameFile, RefusesWhatItCannotWrite) {
  FrameRecord r = sample_frame(3, false);
  r.age.pop_back();
  EXPECT_THROW((void)encode_frame(r), std::invalid_argument);
  r = sample_frame(3, false);
  r.voxels.push_back({2469 + 40000, 0, 0});  // 40,000 voxels from the sensor's: beyond int16
  EXPECT_THROW((void)encode_frame(r), std::invalid_argument);
}

/// The page's bytes: header, then the arrays display_bytes() documents.
struct Display {
  nlohmann::json header;
  std::vector<std::int16_t> xyz;
  std::vector<std::uint16_t> age;
  std::size_t bytes_after = 0;
};
Display parse_display(const std::string& bytes) {
  Display d;
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data(), 4);
  EXPECT_EQ(length % 4, 0u);
  d.header = nlohmann::json::parse(bytes.substr(4, length));
  const std::size_t n = d.header["drawn"];
  std::size_t at = 4 + length;
  d.xyz.resize(3 * n);
  std::memcpy(d.xyz.data(), bytes.data() + at, 6 * n);
  at += 6 * n;
  d.age.resize(n);
  std::memcpy(d.age.data(), bytes.data() + at, 2 * n);
  at += 2 * n;
  d.bytes_after = bytes.size() - at;
  return d;
}

TEST(DisplayFrame, ThinsToTheBudgetByAStride) {
  EXPECT_EQ(thinning_stride(10, 0), 1u);
  EXPECT_EQ(thinning_stride(10, 10), 1u);
  EXPECT_EQ(thinning_stride(11, 10), 2u);
  EXPECT_EQ(thinning_stride(1000000, 150000), 7u);
  const FrameRecord r = sample_frame(1000, true);
  for (const std::size_t budget : {std::size_t(0), std::size_t(1000), std::size_t(300), std::size_t(1)}) {
    const Display d = parse_display(display_bytes(r, budget));
    const std::size_t stride = thinning_stride(1000, budget);
    const std::size_t drawn = (1000 + stride - 1) / stride;
    EXPECT_EQ(d.header["held"], 1000);
    EXPECT_EQ(d.header["stride"], stride);
    ASSERT_EQ(d.header["drawn"], drawn);
    EXPECT_EQ(d.header["dropped"], 2);
    EXPECT_EQ(d.header["cleared"], 1);
    EXPECT_EQ(d.header["voxels"], 3);
    const double step = d.header["step"];
    for (std::size_t k = 0; k < drawn; ++k) {  // the k-th drawn point is held point k * stride
      for (int axis = 0; axis < 3; ++axis) {
        ASSERT_NEAR(d.xyz[3 * k + axis] * step, r.held[k * stride][axis], step / 2 + 1e-6);
      }
      ASSERT_EQ(d.age[k], r.age[k * stride]);
    }
    // intensities and ids (4 + 4 B a drawn point), then dropped, cleared (thinned alike) and voxels
    const std::size_t voxels_drawn = d.header["voxels_drawn"];
    EXPECT_EQ(d.header["dropped_drawn"], stride == 1 ? 2 : 1);
    EXPECT_EQ(d.header["cleared_drawn"], 1);
    EXPECT_EQ(voxels_drawn, budget == 1 ? 1 : 3);
    EXPECT_EQ(d.bytes_after, 8 * drawn + 12 * (std::size_t(d.header["dropped_drawn"]) + 1 + voxels_drawn));
  }
}

TEST(DisplayFrame, LeavesOutTheVoxelMapWhenAsked) {
  const FrameRecord r = decode_frame(encode_frame(sample_frame(10, false)), "f.bin");
  const Display d = parse_display(display_bytes(r, 100, false));
  EXPECT_EQ(d.header["voxels"], 3);
  EXPECT_EQ(d.header["voxels_drawn"], 0);
  EXPECT_EQ(d.header["step"], r.step);  // the file's own step: its int16 values sent unchanged
  EXPECT_EQ(d.bytes_after, 12u * (2 + 1));
}

TEST(DisplayFrame, SendsNoAttributesItDoesNotHave) {
  const Display d = parse_display(display_bytes(sample_frame(10, false), 100));
  EXPECT_FALSE(d.header["has_intensity"]);
  EXPECT_FALSE(d.header["has_ids"]);
  EXPECT_EQ(d.bytes_after, 12u * (2 + 1 + 3));
}

}  // namespace
}  // namespace eco::view
