// The diagnosis (diagnosis.h) names each catalogued mistake as itself and as no other, every pair
// of mistakes as the pair and triples as the three, a right formula along a losing route as that
// route, and nothing for a correct answer with noise or for a mistake the model does not know.
#include <gtest/gtest.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <string>

#include "oblique/cases/generators.h"
#include "oblique/mistakes/answer_geometry.h"
#include "oblique/mistakes/diagnosis.h"
#include "oblique/mistakes/mistakes.h"
#include "oblique/mistakes/numerical_routes.h"
#include "oblique/oblique.h"
#include "oblique/oracle/checker.h"
#include "oblique/oracle/filtered.h"

namespace {

using namespace oblique;
using namespace oblique::oracle;
using namespace oblique::mistakes;

template <class T>
Observation<T> observe(const Implementation<T>& impl, const Matrix4<T>& m, const Vector4<T>& c,
                       Convention convention) {
  const Answer<T> outcome = impl.run(m, c, convention);
  Checks checks;
  checks.statuses = StatusContract::any_refusal;
  Observation<T> o{m, c, convention, outcome.status, outcome.projection, false, std::nullopt};
  o.wrong = judge(FilteredProblem<T>(m, c, convention), outcome, checks).violation() != nullptr;
  return o;
}

/// The first generated case (valid, or with one defect) `impl` answers wrongly, diagnosed with
/// `impl` asked again; ran == false when none of `cases` showed a wrong answer.
template <class T>
Diagnosis first_finding_diagnosed(const Implementation<T>& impl, int cases = 4000) {
  const auto valid = cases::valid_case<T>();
  const auto invalid = cases::invalid_case<T>();
  rc::Random random(26001);
  for (int i = 0; i < cases; ++i) {
    const cases::Case<T> c = i % 4 == 3 ? invalid(random.split(), i % 101).value()
                                        : valid(random.split(), i % 101).value();
    if (!all_finite(c.matrix) || !all_finite(c.plane)) continue;
    Observation<T> o = observe(impl, c.matrix, c.plane, c.convention);
    if (!o.wrong) continue;
    o.family = c.family;
    const Probe<T> probe = [&impl](const Matrix4<T>& m, const Vector4<T>& p, Convention k,
                                   cases::Family) {
      return std::optional<Observation<T>>(observe(impl, m, p, k));
    };
    return diagnose<T>({o}, probe);
  }
  return Diagnosis{};
}

template <class T>
class Diagnose : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(Diagnose, Scalars);

TYPED_TEST(Diagnose, everyMistakeIsItselfAndNoOther) {
  using T = TypeParam;
  for (Mistake m : all_mistakes) {
    const std::string name(mistake_entry(m).name);
    const Diagnosis d = first_finding_diagnosed(mistaken_implementation<T>({m}));
    EXPECT_TRUE(d.ran) << name << ": no wrong answer found";
    EXPECT_EQ(d.causes, std::vector<std::vector<Mistake>>{{m}})
        << name << ": " << likely_cause_line(d);
    EXPECT_GT(d.wrong_where_it_differs, 0) << name;
  }
}

/// How many of `causes`, each made in one program, are diagnosed as exactly that cause (in any
/// order) and nothing else; a failure names each of the others.
template <class T>
int named_as_themselves(const std::vector<std::vector<Mistake>>& causes) {
  int named = 0;
  for (const auto& cause : causes) {
    const Diagnosis d = first_finding_diagnosed(mistaken_implementation<T>(cause));
    if (!d.ran) {
      ADD_FAILURE() << cause_name(cause) << ": no wrong answer found";
      continue;
    }
    auto sorted = [](std::vector<Mistake> v) {
      std::sort(v.begin(), v.end());
      return v;
    };
    if (d.causes.size() == 1 && sorted(d.causes[0]) == sorted(cause))
      ++named;
    else
      ADD_FAILURE() << cause_name(cause) << ": " << likely_cause_line(d);
  }
  return named;
}

// Every two mistakes the diagnosis tries together, made in one program, are named as the pair.
TYPED_TEST(Diagnose, everyPairIsThePair) {
  const auto pairs = causes_tried(2);
  EXPECT_EQ(named_as_themselves<TypeParam>(pairs), static_cast<int>(pairs.size()));
}

// Three faults in one program, as ported engine code has them, are named as the three: the
// bundled ones (tests/end_to_end runs them through verify too) and every 40th triple tried.
TYPED_TEST(Diagnose, threeMistakesTogetherAreTheThree) {
  std::vector<std::vector<Mistake>> triples = {
      // Direct3D's factor in OpenGL portal code that reads the corner from C, symmetric frustum
      {Mistake::camera_space_signs, Mistake::drops_off_axis, Mistake::zero_one_factor_on_gl},
      // a Vulkan port: the fast path's y sign, no corner guard, sgn as x / |x|
      {Mistake::ignores_m22_sign, Mistake::no_corner_guard, Mistake::sign_by_division},
      // Listing 5.1 and Eq. 7 as printed, on every matrix, without the camera guard
      {Mistake::far_face_fixed, Mistake::perspective_rows, Mistake::no_camera_guard},
      // OpenGL's factor on [0, 1], the corner fixed at (1, 1), head-on planes skipped
      {Mistake::skips_head_on, Mistake::gl_factor_on_zero_one, Mistake::fixed_corner_signs},
  };
  const auto tried = causes_tried(3);
  for (std::size_t i = 0; i < tried.size(); i += 40) triples.push_back(tried[i]);
  EXPECT_EQ(named_as_themselves<TypeParam>(triples), static_cast<int>(triples.size()));
}

// Three mistakes made on a route through OpenGL's range and back (a [0, 1] engine that keeps one
// OpenGL code path): four choices, named as the four; the route alone is right.
TYPED_TEST(Diagnose, threeMistakesOnARouteAreTheFour) {
  using T = TypeParam;
  const std::vector<Mistake> four = {Mistake::camera_space_signs, Mistake::drops_off_axis,
                                     Mistake::zero_one_factor_on_gl, Mistake::through_gl};
  EXPECT_EQ(named_as_themselves<T>({four}), 1);
  EXPECT_FALSE(first_finding_diagnosed(mistaken_implementation<T>({Mistake::through_gl})).ran);
  // Every 40th cause of four choices tried (each a route with three mistakes) is among those
  // named, and each named is of four choices. More than one where the route makes them one
  // program on every matrix: on a route through OpenGL's range M34 < 0 always, so a closed form
  // that drops M14, M24 reads C'_z = C_w / M34 > 0 and takes the far face, as far_face_fixed does
  // (drops_shift + divides_by_m43 + zero_one_factor_on_gl + through_gl is far_face_fixed + ...).
  const auto tried = causes_tried(4);
  ASSERT_FALSE(tried.empty());
  auto sorted = [](std::vector<Mistake> v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  for (std::size_t i = 0; i < tried.size(); i += 40) {
    const Diagnosis d = first_finding_diagnosed(mistaken_implementation<T>(tried[i]));
    ASSERT_TRUE(d.ran) << cause_name(tried[i]);
    bool found = false;
    for (const auto& cause : d.causes) {
      EXPECT_EQ(cause.size(), 4u) << cause_name(tried[i]) << ": " << likely_cause_line(d);
      found = found || sorted(cause) == sorted(tried[i]);
    }
    EXPECT_TRUE(found) << cause_name(tried[i]) << ": " << likely_cause_line(d);
  }
}

// Code right on the symmetric frustum and wrong where clip y is flipped (it takes another path
// for M22 < 0, and that path puts Q'_z on the near face): no one mistake reproduces every answer,
// and each family's answers are diagnosed alone.
TYPED_TEST(Diagnose, aProgramRightOnSomeFamiliesIsNamedPerFamily) {
  using T = TypeParam;
  const Implementation<T> wrong_face = mistaken_implementation<T>({Mistake::wrong_face});
  Implementation<T> impl;
  impl.name = "wrong_face_where_y_is_flipped";
  impl.accepts = [](Convention, const Matrix4<T>&) { return true; };
  impl.run = [wrong_face](const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
    if (m(1, 1) < 0) return wrong_face.run(m, c, convention);
    const ObliqueResult<T> r = apply<T>(m, c, convention);
    return Answer<T>{r.status, r.projection};
  };
  const Diagnosis d = first_finding_diagnosed(impl);
  ASSERT_TRUE(d.ran);
  EXPECT_TRUE(d.causes.empty()) << likely_cause_line(d);
  ASSERT_FALSE(d.families.empty()) << likely_cause_line(d);
  bool perspective_right = false, y_flipped_named = false;
  for (const FamilyDiagnosis& f : d.families) {
    if (f.family == cases::Family::perspective) perspective_right = f.wrong == 0;
    // The panel's y-flipped cases cannot tell wrong_face from far_face_fixed (in gl both put
    // Q'_z at 1 there); the family's causes must hold wrong_face, and only single mistakes.
    if (f.family == cases::Family::y_flipped) {
      y_flipped_named = f.wrong > 0 && !f.causes.empty();
      for (const auto& cause : f.causes) y_flipped_named = y_flipped_named && cause.size() == 1;
      y_flipped_named =
          y_flipped_named && std::find(f.causes.begin(), f.causes.end(),
                                       std::vector<Mistake>{Mistake::wrong_face}) != f.causes.end();
    }
  }
  EXPECT_TRUE(perspective_right) << likely_cause_line(d);
  EXPECT_TRUE(y_flipped_named) << likely_cause_line(d);
  const std::string line = likely_cause_line(d);
  EXPECT_NE(line.find("; on y_flipped: "), std::string::npos) << line;
  EXPECT_NE(line.find("right on perspective"), std::string::npos) << line;
  const std::string md = likely_cause_markdown(d);
  EXPECT_NE(md.find("| y_flipped | clip y flipped (M22 < 0, Vulkan) |"), std::string::npos) << md;
}

// A correct answer one ulp off in row 3, even if a checker took it for wrong, is no mistake.
TYPED_TEST(Diagnose, aCorrectAnswerWithNoiseIsNeverDiagnosed) {
  using T = TypeParam;
  const auto valid = cases::valid_case<T>();
  rc::Random random(26002);
  int diagnosed = 0;
  for (int i = 0; i < 300; ++i) {
    const cases::Case<T> c = valid(random.split(), i % 101).value();
    const ObliqueResult<T> r = apply<T>(c.matrix, c.plane, c.convention);
    Observation<T> o{c.matrix, c.plane, c.convention, r.status, r.projection, true, c.family};
    if (r.status == Status::ok) {
      for (int j = 0; j < 4; ++j)
        o.projection(2, j) = std::nextafter(o.projection(2, j), j % 2 ? T(1e30) : T(-1e30));
    }
    const Diagnosis d = diagnose<T>({o});
    if (!d.causes.empty() || d.numerical) {
      ++diagnosed;
      ADD_FAILURE() << likely_cause_line(d) << "\n"
                    << likely_cause_markdown(d) << "\nM =\n"
                    << c.matrix << "\nC = " << c.plane.transpose() << " "
                    << convention_name(c.convention) << " " << status_code(r.status);
    }
  }
  EXPECT_EQ(diagnosed, 0);
}

// The right formula along a route that loses bits in T, written here apart from the diagnosis's
// own model: reversed Z through the core's [0, 1] answer on the converted matrix (row 3
// M_4 - M_3 rounded in T), and the far corner unprojected to a point (Eigen's LU) with
// a = k (M_4 . Q) / (C . Q). Each is named as its numerical route, no formula mistake.
TYPED_TEST(Diagnose, aRightFormulaAlongALosingRouteIsNamedNumerical) {
  using T = TypeParam;
  Implementation<T> through_zero_one;
  through_zero_one.name = "reversed_z_through_zero_one";
  through_zero_one.accepts = [](Convention, const Matrix4<T>&) { return true; };
  through_zero_one.run = [](const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
    if (convention != Convention::reversed_z) {
      const ObliqueResult<T> r = apply<T>(m, c, convention);
      return Answer<T>{r.status, r.projection};
    }
    Matrix4<T> zero_one = m;
    zero_one.row(2) = m.row(3) - m.row(2);
    const ObliqueResult<T> r = apply<T>(zero_one, c, Convention::zero_one);
    Answer<T> out{r.status, m};
    if (r.status == Status::ok) out.projection.row(2) = m.row(3) - r.projection.row(2);
    return out;
  };
  Implementation<T> as_point;
  as_point.name = "far_corner_as_point";
  as_point.accepts = [](Convention, const Matrix4<T>&) { return true; };
  as_point.run = [](const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
    const ObliqueResult<T> r = apply<T>(m, c, convention);
    Answer<T> out{r.status, r.projection};
    if (r.status != Status::ok) return out;
    const Vector4<T> c_clip = m.transpose().fullPivLu().solve(c);
    const DepthRange range = clip_depth_range(convention);
    auto sgn = [](T v) { return T(v > 0) - T(v < 0); };
    const T z = c_clip(2) > 0   ? T(range.z_high)
                : c_clip(2) < 0 ? T(range.z_low)
                                : T(range.z_low + range.z_high) / 2;
    const Vector4<T> q = m.fullPivLu().solve(Vector4<T>(sgn(c_clip(0)), sgn(c_clip(1)), z, 1));
    const Vector4<T> point = q / q(3);
    const T a = T(range.z_high - range.z_low) * m.row(3).dot(point) / c.dot(point);
    const RowCombination near = near_rows(convention);
    out.projection.row(2) = T(near.m3) * (a * c.transpose() - T(near.m4) * m.row(3));
    return out;
  };
  for (const auto& [impl, route] :
       {std::pair{through_zero_one, NumericalRoute::reversed_z_through_zero_one},
        std::pair{as_point, NumericalRoute::far_corner_as_point}}) {
    const Diagnosis d = first_finding_diagnosed(impl);
    ASSERT_TRUE(d.ran) << impl.name << ": no wrong answer found";
    EXPECT_TRUE(d.causes.empty()) << impl.name << ": " << likely_cause_line(d);
    ASSERT_TRUE(d.numerical.has_value()) << impl.name << ": " << likely_cause_line(d);
    EXPECT_EQ(d.numerical->route, route) << likely_cause_line(d);
    EXPECT_EQ(d.numerical->precision, std::numeric_limits<T>::digits);
    if (route == NumericalRoute::far_corner_as_point) {
      EXPECT_TRUE(d.numerical->non_finite) << likely_cause_line(d);
    } else {
      EXPECT_GT(d.numerical->bits_lost, 0) << likely_cause_line(d);
      EXPECT_GT(d.numerical->relative_error, 0) << likely_cause_line(d);
    }
    const std::string line = likely_cause_line(d);
    EXPECT_EQ(line.rfind("likely cause: numerical: " + impl.name + " (", 0), 0u) << line;
    EXPECT_NE(likely_cause_markdown(d).find("Rewrite: "), std::string::npos);
  }
}

// A row-vector engine (v R, R = M^T) declared as column vectors: handed M for R, it modifies
// M^T and its answer is read back transposed. Named as the layout, not as a formula mistake.
TYPED_TEST(Diagnose, aRowVectorFunctionDeclaredAsColumnVectorsIsTheTransposedLayout) {
  using T = TypeParam;
  Implementation<T> impl;
  impl.name = "row_vectors_as_columns";
  impl.accepts = [](Convention, const Matrix4<T>&) { return true; };
  impl.reports_statuses = true;
  impl.run = [](const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
    const ObliqueResult<T> r = apply<T>(Matrix4<T>(m.transpose()), c, convention);
    return Answer<T>{r.status, Matrix4<T>(r.projection.transpose())};
  };
  const Diagnosis d = first_finding_diagnosed(impl);
  ASSERT_TRUE(d.ran);
  EXPECT_TRUE(d.causes.empty()) << likely_cause_line(d);
  EXPECT_TRUE(d.transposed_layout) << likely_cause_line(d);
  EXPECT_EQ(likely_cause_line(d).rfind("likely cause: transposed_layout (", 0), 0u)
      << likely_cause_line(d);
  EXPECT_NE(likely_cause_markdown(d).find("Layout::row_vectors"), std::string::npos);
}

// A closed form written for a row-vector engine's matrix, declared as column vectors: handed M
// for R it runs Listing 5.1 on numbers that are not a perspective matrix, and writes its row 3
// into M's third column. No formula reproduces the answers; where they are written is the layout.
TYPED_TEST(Diagnose, aClosedFormWritingColumnThreeIsTheTransposedLayout) {
  using T = TypeParam;
  Implementation<T> impl;
  impl.name = "listing_on_the_transpose";
  impl.accepts = [](Convention, const Matrix4<T>& m) { return has_perspective_shape(m); };
  impl.run = [](const Matrix4<T>& m, const Vector4<T>& c, Convention) {
    Matrix4<T> r = m.transpose();
    const T sx = c(0) > 0 ? T(1) : (c(0) < 0 ? T(-1) : T(0));
    const T sy = c(1) > 0 ? T(1) : (c(1) < 0 ? T(-1) : T(0));
    const Vector4<T> q((sx + r(0, 2)) / r(0, 0), (sy + r(1, 2)) / r(1, 1), T(-1),
                       (T(1) + r(2, 2)) / r(2, 3));
    const T a = T(2) / c.dot(q);
    r.row(2) = a * c.transpose();
    r(2, 2) += T(1);
    return Answer<T>{Status::ok, Matrix4<T>(r.transpose())};
  };
  const Diagnosis d = first_finding_diagnosed(impl);
  ASSERT_TRUE(d.ran);
  EXPECT_TRUE(d.causes.empty()) << likely_cause_line(d);
  EXPECT_TRUE(d.transposed_layout) << likely_cause_line(d);
}

/// The right answer with C's multiple in row 3 made 1.5 times the right one (a = 3 / (C . Q) on
/// gl): a wrong scale no catalogued mistake gives.
template <class T>
Answer<T> three_halves_scale(const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
  const ObliqueResult<T> r = apply<T>(m, c, convention);
  Answer<T> out{r.status, r.projection};
  if (r.status == Status::ok) {
    const RowCombination near = near_rows(convention);
    const Vector4<T> m4 = m.row(3).transpose();
    const Vector4<T> ac = (T(near.m3) * r.projection.row(2).transpose() + T(near.m4) * m4);
    out.projection.row(2) = (T(near.m3) * (T(1.5) * ac - T(near.m4) * m4)).transpose();
  }
  return out;
}

// a = 3 / (C . Q): a wrong scale no catalogued mistake gives.
TYPED_TEST(Diagnose, anUnlistedMistakeIsNoKnownMistake) {
  using T = TypeParam;
  Implementation<T> impl;
  impl.name = "three_halves_scale";
  impl.accepts = [](Convention, const Matrix4<T>&) { return true; };
  impl.run = three_halves_scale<T>;
  const Diagnosis d = first_finding_diagnosed(impl);
  ASSERT_TRUE(d.ran);
  EXPECT_TRUE(d.causes.empty()) << likely_cause_line(d);
  EXPECT_FALSE(d.numerical.has_value()) << likely_cause_line(d);
  EXPECT_EQ(likely_cause_line(d), "likely cause: no known mistake reproduces these answers");
  // Described instead, in geometry: row 3 is 1.5 times C's right multiple with M_4's right one,
  // so the near plane is still C and the far plane falls short of Q, clipping the volume.
  ASSERT_TRUE(d.geometry.has_value());
  const AnswerGeometry& g = *d.geometry;
  EXPECT_TRUE(g.side_rows_kept);
  EXPECT_TRUE(g.in_span) << g.rest_share;
  EXPECT_TRUE(g.beta_right) << g.beta << " against " << g.right_beta;
  EXPECT_NEAR(g.alpha_ratio, 1.5, 1e-3);
  EXPECT_TRUE(g.near_is_c);
  EXPECT_FALSE(g.far_through_q);
  EXPECT_TRUE(g.clips);
  const std::string md = likely_cause_markdown(d);
  EXPECT_NE(md.find("C's multiple is 1.5 times the right one, M_4's is right."), std::string::npos)
      << md;
  EXPECT_NE(md.find("The near plane is C, its kept side the right one."), std::string::npos) << md;
  EXPECT_NE(md.find("is clipped: the far plane cuts away the point"), std::string::npos) << md;
}

// The same unlisted scale on y-flipped matrices only: the answers part by family, and the family
// no cause explains says what its answers show.
TYPED_TEST(Diagnose, aFamilyNoCauseExplainsSaysWhatItsAnswersShow) {
  using T = TypeParam;
  Implementation<T> impl;
  impl.name = "three_halves_scale_where_y_is_flipped";
  impl.accepts = [](Convention, const Matrix4<T>&) { return true; };
  impl.run = [](const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
    if (m(1, 1) < 0 && m(0, 0) > 0) return three_halves_scale<T>(m, c, convention);
    const ObliqueResult<T> r = apply<T>(m, c, convention);
    return Answer<T>{r.status, r.projection};
  };
  const Diagnosis d = first_finding_diagnosed(impl);
  ASSERT_TRUE(d.ran);
  EXPECT_TRUE(d.causes.empty()) << likely_cause_line(d);
  ASSERT_FALSE(d.families.empty()) << likely_cause_line(d);
  bool said = false;
  for (const FamilyDiagnosis& f : d.families) {
    if (f.family != cases::Family::y_flipped) continue;
    EXPECT_TRUE(f.causes.empty()) << likely_cause_line(d);
    ASSERT_TRUE(f.geometry.has_value()) << likely_cause_line(d);
    EXPECT_NEAR(f.geometry->alpha_ratio, 1.5, 1e-3);
    said = true;
  }
  EXPECT_TRUE(said) << likely_cause_line(d);
  EXPECT_NE(likely_cause_line(d).find(
                "on y_flipped: no known mistake (C's multiple 1.5 times the right one, the far "
                "plane misses Q, the view volume clipped)"),
            std::string::npos)
      << likely_cause_line(d);
}

// The geometry of answers that are not the right one in other ways: the near plane negated (the
// wrong side kept), a side row changed, and row 3 off the span of C and M_4.
TEST(AnswerGeometry, namesWhatEachWrongAnswerChanges) {
  const Convention k = Convention::gl;
  Matrix4<double> m;
  m << 1.5, 0, 0, 0, 0, 2, 0, 0, 0, 0, -1.2, -2.2, 0, 0, -1, 0;
  const Vector4<double> c(0.3, 0.2, -1, -2);
  const ObliqueResult<double> r = apply<double>(m, c, k);
  ASSERT_EQ(r.status, Status::ok);
  const AnswerGeometry right = answer_geometry(m, c, k, r.projection);
  ASSERT_TRUE(right.described);
  EXPECT_TRUE(right.side_rows_kept && right.in_span && right.beta_right && right.near_is_c &&
              right.far_through_q && !right.clips);
  EXPECT_NEAR(right.alpha_ratio, 1, 1e-12);
  EXPECT_NEAR(right.q_depth, 1, 1e-12);

  // The [0, 1] factor with the gl form (docs/mistakes.md's worked example): row 3 = C / (C . Q) -
  // M_4. The near plane is still C; the far plane lies beyond Q, which lands at depth 0.
  Matrix4<double> half = r.projection;
  half.row(2) = 0.5 * (r.projection.row(2) + m.row(3)) - m.row(3);
  const AnswerGeometry zero_one_factor = answer_geometry(m, c, k, half);
  EXPECT_TRUE(zero_one_factor.in_span && zero_one_factor.beta_right);
  EXPECT_NEAR(zero_one_factor.alpha_ratio, 0.5, 1e-12);
  EXPECT_TRUE(zero_one_factor.near_is_c);
  EXPECT_FALSE(zero_one_factor.far_through_q);
  EXPECT_NEAR(zero_one_factor.q_depth, 0, 1e-12);
  EXPECT_FALSE(zero_one_factor.clips);

  Matrix4<double> negated = r.projection;  // near' = -(M'_3 + M_4): the wrong side
  negated.row(2) = -r.projection.row(2) - 2 * m.row(3);
  const AnswerGeometry wrong_side = answer_geometry(m, c, k, negated);
  EXPECT_FALSE(wrong_side.near_is_c);
  EXPECT_TRUE(wrong_side.near_wrong_side);

  Matrix4<double> side = r.projection;
  side(0, 0) = 1.25;
  const AnswerGeometry moved = answer_geometry(m, c, k, side);
  EXPECT_FALSE(moved.side_rows_kept);
  EXPECT_EQ(moved.changed_row, 1);
  EXPECT_EQ(moved.changed_column, 1);

  Matrix4<double> tilted = r.projection;
  tilted(2, 0) += 0.5;
  const AnswerGeometry off = answer_geometry(m, c, k, tilted);
  EXPECT_FALSE(off.in_span);
  EXPECT_GT(off.rest_share, 0.01);
  EXPECT_FALSE(off.near_is_c);
  EXPECT_NE(answer_geometry_markdown(off).find("+ a rest"), std::string::npos);
}

TEST(Mistakes, everyEntryHasOneNameReadBackToItself) {
  for (Mistake m : all_mistakes) {
    const MistakeEntry& e = mistake_entry(m);
    EXPECT_EQ(e.mistake, m);
    EXPECT_EQ(parse_mistake(e.name), m) << e.name;
    EXPECT_FALSE(e.title.empty() || e.explanation.empty() || e.fix.empty() || e.shows.empty());
  }
  EXPECT_FALSE(parse_mistake("no_such_mistake"));
}

}  // namespace
