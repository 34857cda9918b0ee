// The fuzz driver honours the contract (oblique/fuzzing.h): a family or a defect it does not claim
// is not given to the function, and under unit planes the plane reaches it with a unit normal.
#include "oblique/fuzzing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "oblique/oblique.h"

namespace oblique {
namespace {

// A fuzz input as the decoder reads it (fuzzing/driver.h): scalar (double), convention (gl),
// method, family byte; l, r, b, t, n, f as small dyadics ((selector - 101) / 8: -1, 1, -1, 1, 1,
// 10); then the plane C = (0, 0, -1, -2) by special-value index (0.0, 0.0, -1.0, -2.0): the plane
// z = -2 in front of the camera, keeping the far side.
std::vector<std::uint8_t> input(std::uint8_t family_byte) {
  return {1, 0, 0, family_byte, 93, 109, 93, 109, 109, 181, 0, 0, 3, 6};
}
constexpr std::uint8_t kFrustum = 0, kOrthographic = 2;

// Returns M unchanged: wrong for every plane that is not head-on at the near plane.
const auto leaves_m_unchanged = adapt<double>("leaves_m_unchanged", Layout::column_major,
                                              Convention::gl, [](double*, const double*) {});

TEST(FuzzDriverContract, aFamilyTheContractLeavesOutIsNotGivenToTheFunction) {
  Contract perspective_only;
  perspective_only.families = {generators::Family::perspective};
  const std::vector<std::uint8_t> box = input(kOrthographic), frustum = input(kFrustum);
  // Not given: no violation to find.
  EXPECT_EQ(fuzzing::test_one_input(box.data(), box.size(), leaves_m_unchanged, perspective_only),
            0);
  // Given (its family claimed): caught.
  EXPECT_DEATH(fuzzing::test_one_input(box.data(), box.size(), leaves_m_unchanged, Contract{}),
               "oblique property violated: .* by leaves_m_unchanged");
  EXPECT_DEATH(
      fuzzing::test_one_input(frustum.data(), frustum.size(), leaves_m_unchanged, perspective_only),
      "oblique property violated: .* by leaves_m_unchanged");
}

TEST(FuzzDriverContract, underUnitPlanesThePlaneArrivesWithAUnitNormal) {
  // Right only for a unit normal (as an engine that normalises nothing); the plane is C scaled
  // by 2: (0, 0, -2, -4), special values 6 (-2.0) and 31 (-4.0).
  const auto right_for_unit_planes =
      adapt<double>("right_for_unit_planes", Layout::column_major,
                    [](const Matrix4<double>& m, const Vector4<double>& c, Convention k) {
                      if (std::abs(c.head<3>().norm() - 1) > 1e-12)
                        return ObliqueResult<double>{Status::ok, {}, m};
                      return apply<double>(m, c, k);
                    });
  std::vector<std::uint8_t> scaled = input(kFrustum);
  scaled[12] = 6;
  scaled[13] = 31;
  Contract unit;
  unit.planes = Planes::unit;
  unit.conventions = {Convention::gl};
  EXPECT_EQ(fuzzing::test_one_input(scaled.data(), scaled.size(), right_for_unit_planes, unit), 0);
  Contract any;
  any.conventions = {Convention::gl};
  EXPECT_DEATH(fuzzing::test_one_input(scaled.data(), scaled.size(), right_for_unit_planes, any),
               "oblique property violated: .* by right_for_unit_planes");
}

TEST(FuzzDriverContract, aDefectTheContractLeavesOutIsNotGivenToTheFunction) {
  // Never refuses: wrong on every input without an answer. The plane (0, 0, -1, 2) has the camera
  // in front of it (C_w = 2: special value 4).
  const auto never_refuses =
      adapt<double>("never_refuses", Layout::column_major,
                    [](const Matrix4<double>& m, const Vector4<double>&, Convention) {
                      return ObliqueResult<double>{Status::ok, {}, m};
                    });
  std::vector<std::uint8_t> in_front = input(kFrustum);
  in_front[13] = 4;
  Contract no_camera_in_front;
  no_camera_in_front.conventions = {Convention::gl};
  no_camera_in_front.defects = {generators::Defect::misses_view_volume,
                                generators::Defect::singular, generators::Defect::near_singular,
                                generators::Defect::non_finite};
  EXPECT_EQ(
      fuzzing::test_one_input(in_front.data(), in_front.size(), never_refuses, no_camera_in_front),
      0);
  Contract every;
  every.conventions = {Convention::gl};
  EXPECT_DEATH(fuzzing::test_one_input(in_front.data(), in_front.size(), never_refuses, every),
               "oblique property violated: .* by never_refuses");
}

TEST(FuzzDriverContract, theConsumerDriverUsesOnlyTheContractsFamilies) {
  // A mirror view that is never right: caught on a round of a claimed family, not asked on one
  // of a family the contract leaves out.
  Consumers<double> wrong_mirror;
  wrong_mirror.name = "identity_mirror";
  wrong_mirror.mirror_view = [](const Matrix4<double>&, const Vector4<double>&) {
    return Matrix4<double>::Identity().eval();
  };
  Contract perspective_only;
  perspective_only.families = {generators::Family::perspective};
  const std::vector<std::uint8_t> box = input(kOrthographic);
  EXPECT_EQ(fuzzing::test_consumers(box.data(), box.size(), wrong_mirror, perspective_only), 0);
  EXPECT_DEATH(fuzzing::test_consumers(box.data(), box.size(), wrong_mirror, Contract{}),
               "identity_mirror");
}

}  // namespace
}  // namespace oblique
