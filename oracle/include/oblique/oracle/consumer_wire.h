// A consumer function's request line and its answer's numbers (protocol/consumer_messages.h): what
// a round's asks send a program, and how the numbers it answers become the function's result.
// Shared by the rounds' asks (consumers.h) and a program's Consumers
// (oblique/client/consumer_program.h).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "oblique/oracle/consumers.h"
#include "oblique/protocol/consumer_messages.h"

namespace oblique::oracle::wire {

/// How many numbers a kind's answer holds, and in groups of how many (count 0: any multiple).
inline std::pair<std::size_t, std::size_t> answer_shape(protocol::ConsumerKind kind) {
  using protocol::ConsumerKind;
  switch (kind) {
    case ConsumerKind::view_position:
    case ConsumerKind::world_position: return {3, 3};
    case ConsumerKind::linear_depth: return {1, 1};
    case ConsumerKind::culling_planes: return {24, 4};
    case ConsumerKind::camera_plane: return {4, 4};
    case ConsumerKind::mirror_view:
    case ConsumerKind::portal_view: return {16, 16};
    case ConsumerKind::corners: return {0, 3};
  }
  return {0, 1};
}

template <class T>
protocol::ConsumerRequest depth_request(protocol::ConsumerKind kind, const DepthSample<T>& s) {
  protocol::ConsumerRequest r(kind);
  r.numbers("projection", s.projection)
      .numbers("original", s.original)
      .text("convention", convention_name(s.convention))
      .text("buffer", std::string(depth_buffer_name(s.buffer)))
      .numbers("ndc", Eigen::Matrix<T, 1, 2>(s.ndc_x, s.ndc_y))
      .number("depth", s.depth)
      .number("stored", static_cast<double>(s.stored));
  if (kind == protocol::ConsumerKind::world_position) r.numbers("view", s.view);
  return r;
}

template <class T>
protocol::ConsumerRequest culling_request(const Matrix4<T>& oblique, Convention convention) {
  protocol::ConsumerRequest r(protocol::ConsumerKind::culling_planes);
  r.numbers("projection", oblique).text("convention", convention_name(convention));
  return r;
}

template <class T>
protocol::ConsumerRequest corners_request(const Matrix4<T>& oblique, const Matrix4<T>& original,
                                          Convention convention) {
  protocol::ConsumerRequest r(protocol::ConsumerKind::corners);
  r.numbers("projection", oblique)
      .numbers("original", original)
      .text("convention", convention_name(convention));
  return r;
}

/// camera_plane and mirror_view: a view and a world plane.
template <class T>
protocol::ConsumerRequest view_and_plane_request(protocol::ConsumerKind kind,
                                                 const Matrix4<T>& view, const Vector4<T>& plane) {
  protocol::ConsumerRequest r(kind);
  r.numbers("view", view).numbers("plane", plane);
  return r;
}

template <class T>
protocol::ConsumerRequest portal_request(const Matrix4<T>& view, const Matrix4<T>& frame,
                                         const Matrix4<T>& linked) {
  protocol::ConsumerRequest r(protocol::ConsumerKind::portal_view);
  r.numbers("view", view).numbers("frame", frame).numbers("linked", linked);
  return r;
}

template <class T>
Vector3<T> vector3(const std::vector<T>& v, std::size_t at = 0) {
  return Vector3<T>(v[at], v[at + 1], v[at + 2]);
}

template <class T>
Vector4<T> vector4(const std::vector<T>& v, std::size_t at = 0) {
  return Vector4<T>(v[at], v[at + 1], v[at + 2], v[at + 3]);
}

/// Row-major, as requests and answers hold matrices.
template <class T>
Matrix4<T> matrix4(const std::vector<T>& v) {
  Matrix4<T> m;
  for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = v[static_cast<std::size_t>(i)];
  return m;
}

/// Left, right, bottom, top, near, far.
template <class T>
FrustumPlanes<T> planes(const std::vector<T>& v) {
  FrustumPlanes<T> p;
  p.left = vector4(v, 0);
  p.right = vector4(v, 4);
  p.bottom = vector4(v, 8);
  p.top = vector4(v, 12);
  p.near_plane = vector4(v, 16);
  p.far_plane = vector4(v, 20);
  return p;
}

template <class T>
std::vector<Vector3<T>> points(const std::vector<T>& v) {
  std::vector<Vector3<T>> out;
  for (std::size_t i = 0; i + 2 < v.size(); i += 3) out.push_back(vector3(v, i));
  return out;
}

/// The inverse of the above: a function's result as its answer's numbers.
template <class T, int R, int C>
std::vector<T> numbers_of(const Eigen::Matrix<T, R, C>& m) {
  std::vector<T> out;
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j) out.push_back(m(i, j));
  return out;
}
template <class T>
std::vector<T> numbers_of(const FrustumPlanes<T>& p) {
  std::vector<T> out;
  for (const Vector4<T>* x : {&p.left, &p.right, &p.bottom, &p.top, &p.near_plane, &p.far_plane})
    for (int i = 0; i < 4; ++i) out.push_back((*x)(i));
  return out;
}
template <class T>
std::vector<T> numbers_of(const std::vector<Vector3<T>>& points) {
  std::vector<T> out;
  for (const Vector3<T>& p : points)
    for (int i = 0; i < 3; ++i) out.push_back(p(i));
  return out;
}

}  // namespace oblique::oracle::wire
