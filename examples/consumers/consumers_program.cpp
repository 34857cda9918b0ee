// The code around the matrix (consumers.h) as a program that `oblique verify --consumers` and
// `oblique check --impl` drive: one JSON request per line on standard input, one answer line each
// on standard output, flushed (the request kinds: docs/verify.md). Right by default; `--wrong
// NAME` answers one kind with one of the mistakes of consumers.h, `--float` computes in float.
// A request without a kind (the oblique matrix itself, as `oblique check --impl` sends first) is
// answered by the core, so that only the consumers are this program's own.
//
//   consumers_program [--float] [--wrong NAME]
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include <oblique/oblique.h>

#include "consumers.h"

namespace {

using engine_consumers::Convention;
using engine_consumers::Matrix4;
using engine_consumers::Vector3;
using engine_consumers::Vector4;
using nlohmann::json;

/// A request's number: a JSON number or one of the protocol's strings ("nan", "inf", hex).
double number(const json& v) {
  if (v.is_number()) return v.get<double>();
  return std::strtod(v.get<std::string>().c_str(), nullptr);
}

template <class T, int R, int C>
Eigen::Matrix<T, R, C> numbers(const json& v) {
  Eigen::Matrix<T, R, C> m;
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j) m(i, j) = static_cast<T>(number(v.at(std::size_t(i * C + j))));
  return m;
}

Convention convention(const json& request) {
  const std::string name = request.value("convention", std::string("gl"));
  return name == "zero_one"     ? Convention::zero_one
         : name == "reversed_z" ? Convention::reversed_z
                                : Convention::gl;
}

template <class T>
std::string text(T x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", sizeof(T) == sizeof(float) ? 9 : 17,
                static_cast<double>(x));
  return buffer;
}

/// "[a, b, ...]" of a matrix, row by row.
template <class T, int R, int C>
std::string list(const Eigen::Matrix<T, R, C>& m) {
  std::string out = "[";
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j) out += (i || j ? ", " : "") + text(m(i, j));
  return out + "]";
}

template <class T>
std::string answer(const json& request, const std::string& wrong) {
  namespace ec = engine_consumers;
  if (!request.contains("kind")) {
    const oblique::ObliqueResult<T> r =
        oblique::apply<T>(numbers<T, 4, 4>(request.at("projection")),
                          numbers<T, 4, 1>(request.at("plane")), convention(request));
    if (r.status != oblique::Status::ok)
      return "{\"status\": \"" + std::string(oblique::status_code(r.status)) + "\"}";
    return "{\"status\": \"ok\", \"projection\": " + list(r.projection) + "}";
  }
  const std::string kind = request.at("kind").get<std::string>();
  if (kind == "view_position" || kind == "linear_depth" || kind == "world_position") {
    oblique::oracle::DepthSample<T> s;
    s.projection = numbers<T, 4, 4>(request.at("projection"));
    s.original = numbers<T, 4, 4>(request.at("original"));
    s.convention = convention(request);
    s.buffer = request.at("buffer") == "float32" ? oblique::DepthBuffer::float32
                                                 : oblique::DepthBuffer::fixed24;
    s.ndc_x = static_cast<T>(number(request.at("ndc").at(0)));
    s.ndc_y = static_cast<T>(number(request.at("ndc").at(1)));
    s.depth = static_cast<T>(number(request.at("depth")));
    s.stored = static_cast<std::uint32_t>(number(request.at("stored")));
    if (kind == "world_position") {
      s.view = numbers<T, 4, 4>(request.at("view"));
      return "{\"position\": " +
             list(wrong == "world_with_original" ? ec::world_with_original(s)
                                                 : ec::world_position(s)) +
             "}";
    }
    if (kind == "view_position")
      return "{\"position\": " +
             list(wrong == "reconstructs_with_original" ? ec::reconstructs_with_original(s)
                                                        : ec::view_position(s)) +
             "}";
    return "{\"depth\": " +
           text(wrong == "linearises_with_near_far" ? ec::linearises_with_near_far(s)
                                                    : ec::linear_depth(s)) +
           "}";
  }
  if (kind == "culling_planes") {
    const Matrix4<T> m = numbers<T, 4, 4>(request.at("projection"));
    const Convention c = convention(request);
    const oblique::FrustumPlanes<T> p =
        wrong == "gl_planes_on_any_matrix" ? ec::gl_planes_on_any_matrix(m, c)
        : wrong == "planes_of_transpose"   ? ec::planes_of_transpose(m, c)
                                           : ec::culling_planes(m, c);
    return "{\"planes\": [" + list(p.left) + ", " + list(p.right) + ", " + list(p.bottom) + ", " +
           list(p.top) + ", " + list(p.near_plane) + ", " + list(p.far_plane) + "]}";
  }
  if (kind == "camera_plane") {
    const Matrix4<T> view = numbers<T, 4, 4>(request.at("view"));
    const Vector4<T> plane = numbers<T, 4, 1>(request.at("plane"));
    return "{\"plane\": " +
           list(wrong == "plane_without_translation"   ? ec::plane_without_translation(view, plane)
                : wrong == "plane_flipped_for_mirrors" ? ec::plane_flipped_for_mirrors(view, plane)
                                                       : ec::camera_plane(view, plane)) +
           "}";
  }
  if (kind == "mirror_view") {
    const Matrix4<T> view = numbers<T, 4, 4>(request.at("view"));
    const Vector4<T> plane = numbers<T, 4, 1>(request.at("plane"));
    return "{\"view\": " +
           list(wrong == "mirror_by_reflected_look_at"
                    ? ec::mirror_by_reflected_look_at(view, plane)
                    : ec::mirror_view(view, plane)) +
           "}";
  }
  if (kind == "portal_view") {
    const Matrix4<T> view = numbers<T, 4, 4>(request.at("view"));
    const Matrix4<T> frame = numbers<T, 4, 4>(request.at("frame"));
    const Matrix4<T> linked = numbers<T, 4, 4>(request.at("linked"));
    return "{\"view\": " +
           list(wrong == "portal_without_turn" ? ec::portal_without_turn(view, frame, linked)
                                               : ec::portal_view(view, frame, linked)) +
           "}";
  }
  if (kind == "corners") {
    const Matrix4<T> m = numbers<T, 4, 4>(request.at("projection"));
    const Matrix4<T> original = numbers<T, 4, 4>(request.at("original"));
    const Convention c = convention(request);
    std::string out = "{\"corners\": [";
    bool first = true;
    for (const Vector3<T>& p : wrong == "corners_of_oblique_matrix"
                                   ? ec::corners_of_oblique_matrix(m, original, c)
                                   : ec::corners(m, original, c)) {
      out += (first ? "" : ", ") + list(p);
      first = false;
    }
    return out + "]}";
  }
  return "{\"error\": \"unknown kind\"}";
}

}  // namespace

int main(int argc, char** argv) {
  bool in_float = false;
  std::string wrong;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--float") {
      in_float = true;
    } else if (a == "--wrong" && i + 1 < argc) {
      wrong = argv[++i];
      static const char* const known[] = {
          "reconstructs_with_original",  "linearises_with_near_far",  "gl_planes_on_any_matrix",
          "planes_of_transpose",         "plane_without_translation", "plane_flipped_for_mirrors",
          "mirror_by_reflected_look_at", "portal_without_turn",       "corners_of_oblique_matrix",
          "world_with_original"};
      bool found = false;
      for (const char* k : known) found = found || wrong == k;
      if (!found) {
        std::cerr << "consumers_program: unknown mistake " << wrong << "\n";
        return 2;
      }
    } else {
      std::cerr << "usage: consumers_program [--float] [--wrong NAME]\n";
      return 2;
    }
  }
  std::string line;
  while (std::getline(std::cin, line)) {
    const json request = json::parse(line, nullptr, false);
    std::string out = "{\"error\": \"not a request\"}";
    if (!request.is_discarded()) {
      try {
        out = in_float ? answer<float>(request, wrong) : answer<double>(request, wrong);
      } catch (const json::exception& e) {
        out = "{\"error\": " + json(std::string(e.what())).dump() + "}";
      }
    }
    std::cout << out << std::endl;
  }
  return 0;
}
