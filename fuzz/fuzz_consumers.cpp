// libFuzzer target: the core's references for the code around the matrix (depth reconstruction,
// culling planes, the pass camera and its plane, the kept region's vertices), computed in the
// scalar type the input's first byte picks, judged by the consumer properties through the fuzz
// driver (oblique::fuzzing::test_consumers). A finding is a reference that breaks its property or
// a bound too tight for careful arithmetic: either is a bug of ours.
#include <vector>

#include "oblique/depth_reconstruction.h"
#include "oblique/frustum_planes.h"
#include "oblique/fuzzing.h"
#include "oblique/kept_region.h"
#include "oblique/pass_camera.h"

namespace {

template <class T>
oblique::Consumers<T> references() {
  oblique::Consumers<T> c;
  c.name = "core_references";
  c.view_position = [](const oblique::properties::DepthSample<T>& s) {
    return oblique::view_position(s.projection, s.ndc_x, s.ndc_y, s.depth, s.convention);
  };
  c.linear_depth = [](const oblique::properties::DepthSample<T>& s) {
    return oblique::linear_depth(s.projection, s.ndc_x, s.ndc_y, s.depth, s.convention,
                                 oblique::view_axis_sign(s.original, s.convention));
  };
  c.culling_planes = [](const oblique::Matrix4<T>& m, oblique::Convention k) {
    return oblique::frustum_planes(m, k);
  };
  c.camera_plane = [](const oblique::Matrix4<T>& view, const oblique::Vector4<T>& plane) {
    return oblique::plane_in_camera(view, plane);
  };
  c.mirror_view = [](const oblique::Matrix4<T>& view, const oblique::Vector4<T>& plane) {
    return oblique::mirror_view(view, plane);
  };
  c.portal_view = [](const oblique::Matrix4<T>& view, const oblique::Matrix4<T>& frame,
                     const oblique::Matrix4<T>& linked) {
    return oblique::portal_view(view, frame, linked);
  };
  c.corners = [](const oblique::Matrix4<T>& m, const oblique::Matrix4<T>& original,
                 oblique::Convention k) {
    std::vector<oblique::Vector3<T>> out;
    for (const auto& v : oblique::kept_region_vertices(original, oblique::near_plane(m, k), k))
      out.push_back(v.template head<3>());
    return out;
  };
  return c;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto f = references<float>();
  static const auto d = references<double>();
  static const auto ld = references<long double>();
  switch (size ? data[0] % 3 : 1) {
    case 0: return oblique::fuzzing::test_consumers(data, size, f);
    case 1: return oblique::fuzzing::test_consumers(data, size, d);
    default: return oblique::fuzzing::test_consumers(data, size, ld);
  }
}
