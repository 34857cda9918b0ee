// oblique::adapt: every function shape it takes gives the same Answer as the core, in both
// layouts and scalar types, with the status contract its return type implies.
#include "oblique/oracle/adapter.h"

#include <gtest/gtest.h>

#include "oblique/oblique.h"
#include "oblique/projection.h"

namespace oblique {
namespace {

using cases::StatusContract;

template <class T>
Matrix4<T> frustum_matrix() {
  return frustum<T>(T(-1), T(2), T(-0.5), T(1.5), T(1), T(100), Convention::gl);
}
template <class T>
Vector4<T> plane_in_view() {
  return Vector4<T>(T(0.25), T(0.5), T(-1), T(-3));
}

// The core through each shape, in `layout`'s order.
template <class T>
Status core_in_place(T* m, const T* c, Layout layout) {
  const Matrix4<T> in = adapting::load(m, layout);
  const auto r = apply<T>(in, Vector4<T>(c[0], c[1], c[2], c[3]), Convention::gl);
  if (r.ok()) adapting::store(r.projection, layout, m);
  return r.status;
}

template <class T>
void expect_same_as_core(const oracle::Implementation<T>& impl, bool refusal_too = true) {
  const Matrix4<T> m = frustum_matrix<T>();
  const auto core = apply<T>(m, plane_in_view<T>(), Convention::gl);
  ASSERT_TRUE(core.ok());
  const Answer<T> got = impl.run(m, plane_in_view<T>(), Convention::gl);
  EXPECT_EQ(got.status, Status::ok);
  EXPECT_EQ(got.projection, core.projection) << impl.name;
  if (refusal_too) {
    const Vector4<T> in_front(T(0), T(0), T(-1), T(2));
    EXPECT_NE(impl.run(m, in_front, Convention::gl).status, Status::ok) << impl.name;
  }
}

TEST(Adapt, inPlaceColumnMajorFloatWithoutStatuses) {
  const auto impl = adapt<float>(
      "void_column_major", Layout::column_major, Convention::gl,
      [](float* m, const float* c) { core_in_place<float>(m, c, Layout::column_major); });
  EXPECT_EQ(impl.status_contract(), StatusContract::answers_only);
  EXPECT_EQ(impl.conventions, std::vector<Convention>{Convention::gl});
  expect_same_as_core(impl, /*refusal_too=*/false);
}

TEST(Adapt, inPlaceRowMajorDoubleWithABool) {
  const auto impl = adapt<double>(
      "bool_row_major", Layout::row_major, Convention::gl, [](double* m, const double* c) {
        return core_in_place<double>(m, c, Layout::row_major) == Status::ok;
      });
  EXPECT_EQ(impl.status_contract(), StatusContract::any_refusal);
  expect_same_as_core(impl);
}

TEST(Adapt, outOfPlaceWithStatuses) {
  const auto impl = adapt<double>("status_out_of_place", Layout::column_major, Convention::gl,
                                  [](const double* m, const double* c, double* out) {
                                    double copy[16];
                                    for (int i = 0; i < 16; ++i) copy[i] = m[i];
                                    const Status s =
                                        core_in_place<double>(copy, c, Layout::column_major);
                                    for (int i = 0; i < 16; ++i) out[i] = copy[i];
                                    return s;
                                  });
  EXPECT_EQ(impl.status_contract(), StatusContract::exact);
  expect_same_as_core(impl);
}

TEST(Adapt, matrixShapedFunctions) {
  const auto impl =
      adapt<float>("matrices", Layout::row_major,
                   [](const Matrix4<float>& m, const Vector4<float>& c, Convention convention) {
                     return apply<float>(m, c, convention);
                   });
  EXPECT_EQ(impl.status_contract(), StatusContract::exact);
  EXPECT_EQ(impl.conventions.size(), std::size(all_conventions));  // it takes the convention
  expect_same_as_core(impl);
}

// A row-vector engine (v R, R = M^T, DirectXMath): its matrix by rows, its oblique row R's third
// column. Declared Layout::row_vectors it is the core; declared row_major (the natural guess) it
// is handed M for R and answers something else.
TEST(Adapt, rowVectorEnginesAreHandedTheTranspose) {
  auto row_vector_engine = [](float* r, const float* c) {
    Matrix4<float> rows;  // R, as the engine holds it
    for (int i = 0; i < 16; ++i) rows(i / 4, i % 4) = r[i];
    const auto answer = apply<float>(Matrix4<float>(rows.transpose()),
                                     Vector4<float>(c[0], c[1], c[2], c[3]), Convention::zero_one);
    if (!answer.ok()) return false;
    const Matrix4<float> out = answer.projection.transpose();
    for (int i = 0; i < 16; ++i) r[i] = out(i / 4, i % 4);
    return true;
  };
  const auto declared =
      adapt<float>("d3d", Layout::row_vectors, Convention::zero_one, row_vector_engine);
  const Matrix4<float> m = frustum<float>(-1, 2, -0.5f, 1.5f, 1, 100, Convention::zero_one);
  const auto core = apply<float>(m, plane_in_view<float>(), Convention::zero_one);
  ASSERT_TRUE(core.ok());
  const Answer<float> got = declared.run(m, plane_in_view<float>(), Convention::zero_one);
  EXPECT_EQ(got.status, Status::ok);
  EXPECT_EQ(got.projection, core.projection);
  const auto misdeclared =
      adapt<float>("d3d", Layout::row_major, Convention::zero_one, row_vector_engine);
  const Answer<float> wrong = misdeclared.run(m, plane_in_view<float>(), Convention::zero_one);
  EXPECT_FALSE(wrong.status == Status::ok && wrong.projection == core.projection);
  // A function of matrices written for row vectors is handed R = M^T, its answer transposed back.
  const auto matrices =
      adapt<float>("d3d_matrices", Layout::row_vectors,
                   [](const Matrix4<float>& r, const Vector4<float>& c, Convention convention) {
                     auto a = apply<float>(Matrix4<float>(r.transpose()), c, convention);
                     a.projection.transposeInPlace();
                     return a;
                   });
  const Answer<float> by_matrices = matrices.run(m, plane_in_view<float>(), Convention::zero_one);
  EXPECT_EQ(by_matrices.projection, core.projection);
}

TEST(Adapt, layoutsStoreTheTransposeOfEachOther) {
  const Matrix4<double> m = frustum_matrix<double>();
  double row[16], column[16];
  adapting::store(m, Layout::row_major, row);
  adapting::store(m, Layout::column_major, column);
  EXPECT_EQ(row[2], m(0, 2));     // m[4 * row + column]
  EXPECT_EQ(column[8], m(0, 2));  // m[4 * column + row], OpenGL's order
  EXPECT_EQ(adapting::load(row, Layout::row_major), m);
  EXPECT_EQ(adapting::load(column, Layout::column_major), m);
}

TEST(Adapt, perspectiveShapeOnlyAcceptsThatShape) {
  const auto impl = adapt<double>(
      "closed", Layout::row_major, Convention::gl, [](double*, const double*) {},
      perspective_shape_only<double>);
  EXPECT_TRUE(impl.accepts(Convention::gl, frustum_matrix<double>()));
  EXPECT_FALSE(
      impl.accepts(Convention::gl, orthographic<double>(-1, 1, -1, 1, 1, 10, Convention::gl)));
}

}  // namespace
}  // namespace oblique
