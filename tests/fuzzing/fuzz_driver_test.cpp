// The fuzz driver honours the contract (oblique/fuzzing.h): a family or a defect it does not claim
// is not given to the function, and under unit planes the plane reaches it with a unit normal.
// Built inputs (oblique/fuzzing/driver.h's decode()) are the case builder's: of the contract's
// families, conventions, places and defects, and they reach the judgement.
#include "oblique/fuzzing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "oblique/fuzzing/driver.h"

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
  perspective_only.families = {cases::Family::perspective};
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
  no_camera_in_front.defects = {cases::Defect::misses_view_volume, cases::Defect::singular,
                                cases::Defect::near_singular, cases::Defect::non_finite};
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
  perspective_only.families = {cases::Family::perspective};
  const std::vector<std::uint8_t> box = input(kOrthographic);
  EXPECT_EQ(fuzzing::test_consumers(box.data(), box.size(), wrong_mirror, perspective_only), 0);
  EXPECT_DEATH(fuzzing::test_consumers(box.data(), box.size(), wrong_mirror, Contract{}),
               "identity_mirror");
}

// A built input: scalar byte `scalar`, a family byte in the built window, the rest random picks.
std::vector<std::uint8_t> built_input(std::mt19937& random, std::uint8_t scalar) {
  std::vector<std::uint8_t> in(96);
  for (auto& b : in) b = static_cast<std::uint8_t>(random());
  in[0] = scalar;
  in[3] = static_cast<std::uint8_t>(fuzzing::kBuiltLow +
                                    random() % (fuzzing::kBuiltHigh - fuzzing::kBuiltLow));
  return in;
}

template <class E>
bool listed(const std::vector<E>& list, E value) {
  return std::find(list.begin(), list.end(), value) != list.end();
}

TEST(FuzzDriverBuilder, builtCasesAreOfTheContractsFamiliesConventionsPlacesAndDefects) {
  using cases::Family;
  using cases::Place;
  Contract given;
  given.families = {Family::orthographic, Family::x_flipped};
  given.conventions = {Convention::reversed_z};
  given.places = {Place::near_eye, Place::typical};
  given.defects = {cases::Defect::singular};
  const Contract contract =
      resolved(given, cases::every_convention(), cases::StatusContract::exact, false);
  std::mt19937 random(4501);
  std::set<Family> families;
  std::set<Place> places;
  int spoiled = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::vector<std::uint8_t> bytes = built_input(random, static_cast<std::uint8_t>(i % 3));
    const fuzzing::FuzzCase c = fuzzing::decode(bytes.data(), bytes.size(), contract);
    ASSERT_EQ(c.family, fuzzing::kBuilt);
    const cases::Case<long double>& in = c.input;
    ASSERT_TRUE(listed(given.families, in.family)) << cases::family_name(in.family);
    ASSERT_TRUE(listed(given.places, in.place)) << cases::place_name(in.place);
    ASSERT_EQ(in.convention, Convention::reversed_z);
    families.insert(in.family);
    places.insert(in.place);
    if (in.defect) {
      ASSERT_EQ(*in.defect, cases::Defect::singular);
      ++spoiled;
      continue;
    }
    // What the numbers are, not only what the case says: a box keeps w = 1; a mirror camera has
    // M11 < 0; a plane at near_eye passes within 2^-8 |N| of the eye (rounded to T: 2^-7).
    if (in.family == Family::orthographic) {
      EXPECT_EQ(in.matrix.row(3), (Vector4<long double>(0, 0, 0, 1).transpose()));
    } else {
      EXPECT_LT(in.matrix(0, 0), 0);
    }
    if (in.place == Place::near_eye) {
      EXPECT_LE(std::abs(in.plane.w()), std::ldexp(1.0L, -7) * in.plane.head<3>().norm());
    }
  }
  EXPECT_EQ(families.size(), 2u);
  EXPECT_EQ(places.size(), 2u);
  EXPECT_GT(spoiled, 3000 / 10);  // one in five
  EXPECT_LT(spoiled, 3000 * 3 / 10);
}

TEST(FuzzDriverBuilder, builtCasesDrawEveryFamilyPlaceConventionAndDefect) {
  std::mt19937 random(4502);
  std::set<cases::Family> families;
  std::set<cases::Place> places;
  std::set<Convention> conventions;
  std::set<cases::Defect> defects;
  for (int i = 0; i < 4000; ++i) {
    const std::vector<std::uint8_t> bytes = built_input(random, static_cast<std::uint8_t>(i % 3));
    const fuzzing::FuzzCase c = fuzzing::decode(bytes.data(), bytes.size());
    families.insert(c.input.family);
    places.insert(c.input.place);
    conventions.insert(c.input.convention);
    if (c.input.defect) defects.insert(*c.input.defect);
  }
  EXPECT_EQ(families.size(), std::size(cases::all_families));
  EXPECT_EQ(places.size(), std::size(cases::all_places));
  EXPECT_EQ(conventions.size(), std::size(all_conventions));
  EXPECT_EQ(defects.size(), std::size(cases::all_defects));
}

// What reached the function of the next test, and how many of its answers were judged.
std::vector<Matrix4<double>> given_matrices;

TEST(FuzzDriverBuilder, underANarrowContractBuiltInputsReachTheFunctionAndAreJudged) {
  // The core, recording what it is given.
  const auto recording_core =
      adapt<double>("recording_core", Layout::column_major,
                    [](const Matrix4<double>& m, const Vector4<double>& c, Convention k) {
                      given_matrices.push_back(m);
                      return apply<double>(m, c, k);
                    });
  Contract boxes;
  boxes.families = {cases::Family::orthographic};
  // Defects that spoil the plane only, so every matrix given is still a box.
  boxes.defects = {cases::Defect::camera_in_front, cases::Defect::misses_view_volume};
  std::mt19937 random(4503);
  given_matrices.clear();
  const long judged_before = fuzzing::counts().judged();
  constexpr int kInputs = 400;
  for (int i = 0; i < kInputs; ++i) {
    const std::vector<std::uint8_t> bytes = built_input(random, 1);  // double
    ASSERT_EQ(fuzzing::test_one_input(bytes.data(), bytes.size(), recording_core, boxes), 0);
  }
  // Every built input is a box: most reach the function and are judged (some have no answer
  // that is decidable in double, or are spoiled into one a function is not asked).
  const long judged = fuzzing::counts().judged() - judged_before;
  EXPECT_GT(judged, kInputs / 2);
  EXPECT_EQ(static_cast<long>(given_matrices.size()), judged);
  for (const Matrix4<double>& m : given_matrices)
    ASSERT_EQ(m.row(3), (Vector4<double>(0, 0, 0, 1).transpose()));
  // Decoded-number inputs of other shapes are left out, not given.
  given_matrices.clear();
  for (int i = 0; i < kInputs; ++i) {
    std::vector<std::uint8_t> bytes = built_input(random, 1);
    bytes[3] = 0;  // a frustum
    ASSERT_EQ(fuzzing::test_one_input(bytes.data(), bytes.size(), recording_core, boxes), 0);
  }
  EXPECT_TRUE(given_matrices.empty());
}

}  // namespace
}  // namespace oblique
