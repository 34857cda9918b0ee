#include "oblique/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <stdexcept>

#include "oblique/projection.h"
#include "oblique/protocol/json.h"
#include "oblique/protocol/names.h"
#include "oblique/protocol/protocol.h"
#include "reading.h"

namespace oblique::scene {

using namespace reading;  // NOLINT: the reader's parts (reading.h)

Vector4<double> Surface::plane() const {
  return Vector4<double>(normal.x(), normal.y(), normal.z(), -normal.dot(point));
}

std::optional<Matrix4<double>> look_at(const Vector3& eye, const Vector3& target,
                                       const Vector3& up) {
  const Vector3 forward = target - eye;
  const Vector3 f = unit_direction(forward).normalized();
  const Vector3 up_unit = unit_direction(up).normalized();
  if (!(f.norm() > 0) || !(up_unit.norm() > 0)) return std::nullopt;
  const Vector3 side = f.cross(up_unit);
  if (!(side.norm() > 1e-12)) return std::nullopt;  // up parallel to the view direction
  const Vector3 s = side.normalized();
  const Vector3 u = s.cross(f);
  Matrix4<double> v = Matrix4<double>::Identity();
  v.block<1, 3>(0, 0) = s.transpose();
  v.block<1, 3>(1, 0) = u.transpose();
  v.block<1, 3>(2, 0) = -f.transpose();
  v(0, 3) = -s.dot(eye);
  v(1, 3) = -u.dot(eye);
  v(2, 3) = f.dot(eye);
  return v;
}

ParsedScene read_scene_file(const std::string& path) {
  const Expected<std::string> text = protocol::read_text_file(path, kMaxSceneBytes);
  if (!text) {
    ParsedScene out;
    out.error = text.error() + ": not a scene file";
    return out;
  }
  return parse_scene(*text);
}

ParsedScene parse_scene(std::string_view text_in) {
  ParsedScene out;
  // Every value counts, and a vertex is 4 (its array and 3 numbers): room for kMaxSceneNumbers.
  const Expected<json> parsed = protocol::parse_json(
      text_in, protocol::JsonLimits{2 * kMaxSceneNumbers, 32, kMaxSceneNumbers});
  if (!parsed) {
    const bool limit = parsed.error().rfind("more than", 0) == 0;
    out.error = (limit ? "not a scene: " : "not valid JSON: ") + parsed.error();
    return out;
  }
  const json& root = *parsed;
  try {
    Scene scene;
    if (!root.is_object())
      fail("(top level)", std::string("must be an object, not ") + type_of(root));
    only_keys(root, "",
              {"name", "convention", "depth_buffer", "camera", "surfaces", "max_depth", "viewport",
               "consumers", "mirror_design", "mirror_flip"});
    scene.name = text(root, "", "name");
    const std::string convention = text(root, "", "convention");
    const auto c = parse_convention(convention);
    if (!c) fail_unknown("convention", "convention", convention, names_in(convention_names));
    scene.convention = *c;
    // A reversed-Z buffer is a float buffer (that is what reversing is for); else 24-bit fixed.
    scene.depth_buffer =
        scene.convention == Convention::reversed_z ? DepthBuffer::float32 : DepthBuffer::fixed24;
    if (has(root, "depth_buffer")) {
      const std::string buffer = text(root, "", "depth_buffer");
      const std::optional<DepthBuffer> parsed = parse_depth_buffer(buffer);
      if (!parsed)
        fail_unknown("depth_buffer", "depth buffer", buffer, names_in(depth_buffer_names));
      scene.depth_buffer = *parsed;
    }
    if (has(root, "max_depth"))
      scene.max_depth = integer(root.at("max_depth"), "max_depth", 1, kMaxDepth);
    if (has(root, "viewport")) {
      const json& v = root.at("viewport");
      if (!v.is_array() || v.size() != 2)
        fail("viewport", "must be [width, height] in pixels, not " + type_of(v));
      scene.viewport = std::array<int, 2>{integer(v[0], "viewport[0]", 1, 1 << 16),
                                          integer(v[1], "viewport[1]", 1, 1 << 16)};
    }
    if (has(root, "consumers")) {
      const json& list = root.at("consumers");
      if (!list.is_array()) fail("consumers", "must be an array of names, not " + type_of(list));
      for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string where = "consumers[" + std::to_string(i) + "]";
        if (!list[i].is_string()) fail(where, "must be a name, not " + type_of(list[i]));
        const std::string name = list[i].text;
        const auto consumer = parse_scene_consumer(name);
        if (!consumer) {
          std::vector<std::string> known;
          for (const SceneConsumer c : all_scene_consumers)
            known.emplace_back(scene_consumer_name(c));
          fail_unknown(where, "consumer", name, known);
        }
        if (std::find(scene.consumers.begin(), scene.consumers.end(), *consumer) ==
            scene.consumers.end())
          scene.consumers.push_back(*consumer);
      }
    }
    if (has(root, "mirror_design")) {
      const std::string design = text(root, "", "mirror_design");
      const auto parsed_design = oracle::parse_mirror_design(design);
      if (!parsed_design)
        fail_unknown("mirror_design", "mirror design", design,
                     names_in(oracle::mirror_design_names));
      scene.mirror_design = *parsed_design;
    }
    if (has(root, "mirror_flip")) {
      const std::string flip = text(root, "", "mirror_flip");
      const auto parsed_flip = parse_mirror_flip(flip);
      if (!parsed_flip)
        fail_unknown("mirror_flip", "mirror flip", flip, names_in(mirror_flip_names));
      scene.mirror_flip = *parsed_flip;
      const oracle::MirrorDesign implied = *parsed_flip == MirrorFlip::view
                                               ? oracle::MirrorDesign::reflected_view
                                               : oracle::MirrorDesign::proper_camera;
      if (has(root, "mirror_design") && scene.mirror_design != implied)
        fail("mirror_flip", "\"" + flip + "\" builds a " +
                                std::string(oracle::mirror_design_name(implied)) +
                                " mirror pass, but mirror_design says " +
                                std::string(oracle::mirror_design_name(scene.mirror_design)) +
                                ": give one of them, or both alike");
      scene.mirror_design = implied;
    } else if (scene.mirror_design == oracle::MirrorDesign::proper_camera) {
      scene.mirror_flip = MirrorFlip::projection_x;  // a proper camera's flip: the projection's
    }
    scene.camera = read_camera(root, scene.convention, out.warnings);
    const json& surfaces = member(root, "", "surfaces");
    if (!surfaces.is_array())
      fail("surfaces", std::string("must be an array, not ") + type_of(surfaces));
    for (std::size_t i = 0; i < surfaces.size(); ++i)
      scene.surfaces.push_back(read_surface(surfaces[i], "surfaces[" + std::to_string(i) + "]"));
    out.scene = std::move(scene);
  } catch (const FieldError& e) {
    out.error = e.what();
  }
  return out;
}

}  // namespace oblique::scene
