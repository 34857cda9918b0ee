// oblique check: the bundled scenes' verdicts, a held-out set of scenes against independent
// geometry and the exact oblique matrix, and clear errors for broken scene files.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "oblique/oracle/problem.h"
#include "oblique/scene/check.h"
#include "oblique/scene/scene.h"

namespace oblique::scene {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

SceneCheck check_text(const std::string& text) {
  const ParsedScene parsed = parse_scene(text);
  if (!parsed.scene) ADD_FAILURE() << parsed.error;
  return parsed.scene ? check_scene(*parsed.scene) : SceneCheck{};
}

/// "render" or the first words of the skip reason, per surface.
std::vector<std::string> actions(const SceneCheck& check) {
  std::vector<std::string> out;
  for (const SurfaceCheck& s : check.surfaces) {
    if (s.render) {
      out.push_back("render");
    } else if (s.reason.find("camera is behind") != std::string::npos) {
      out.push_back("skip: camera behind");
    } else if (s.reason.find("kept side") != std::string::npos) {
      out.push_back("skip: camera on the kept side");
    } else if (s.reason.find("outside the main view volume") != std::string::npos) {
      out.push_back("skip: outside");
    } else {
      out.push_back("skip: " + s.reason);
    }
  }
  return out;
}

/// Every rendered pass: every property that applies holds, and the third row is within the
/// checker's bound of the exact rational answer for that camera and plane.
void expect_exact(const Scene& scene, const SceneCheck& check) {
  for (const SurfaceCheck& s : check.surfaces) {
    if (!s.render) continue;
    EXPECT_TRUE(s.passes()) << s.name;
    const oracle::Problem<double> problem(scene.camera.projection, s.plane_in_camera,
                                          scene.convention);
    ASSERT_EQ(problem.exact_status(), Status::ok) << s.name;
    EXPECT_TRUE(problem.compare_row3(*s.projection).within) << s.name;
    for (int i : {0, 1, 3})
      EXPECT_EQ(s.projection->row(i), scene.camera.projection.row(i)) << s.name;
    ASSERT_TRUE(s.depth) << s.name;
    EXPECT_GT(s.depth->fraction, 0) << s.name;
    EXPECT_LE(s.depth->fraction, 1 + 1e-12) << s.name;
  }
}

/// The virtual view of a mirror, built independently: gluLookAt of the reflected eye, target and
/// up, with its x axis negated (a reflection turns the right-handed camera frame left-handed).
void expect_mirrored_view(const Scene& scene, const SurfaceCheck& s, const Surface& surface) {
  const Vector3 n = surface.normal.normalized();
  auto reflect_point = [&](const Vector3& p) { return p - 2 * n.dot(p - surface.point) * n; };
  const Vector3 up = scene.camera.up - 2 * n.dot(scene.camera.up) * n;
  const auto mirrored =
      look_at(reflect_point(scene.camera.eye), reflect_point(scene.camera.target), up);
  ASSERT_TRUE(mirrored);
  Matrix4<double> expected = *mirrored;
  expected.row(0) *= -1;
  EXPECT_TRUE(s.view.isApprox(expected, 1e-12)) << s.name << "\n" << s.view << "\n" << expected;
  const double det = s.view.block<3, 3>(0, 0).determinant();
  EXPECT_NEAR(det, -1, 1e-12);
}

struct Bundled {
  const char* file;
  std::vector<std::string> actions;
};

TEST(Scenes, bundledExamplesGiveTheirVerdicts) {
  const Bundled bundled[] = {
      {"lake.json", {"render", "render"}},
      {"wall_mirror_reversed_z.json", {"render"}},
      {"map_orthographic.json", {"render", "render"}},
      {"mirror_behind_camera.json", {"skip: outside", "skip: camera behind"}},
      {"mirror_off_screen.json", {"skip: outside", "render"}},
      {"vulkan_reversed_z.json", {"render"}},
  };
  for (const Bundled& b : bundled) {
    const ParsedScene parsed =
        parse_scene(read_file(std::string(OBLIQUE_SCENES_DIR) + "/" + b.file));
    ASSERT_TRUE(parsed.scene) << b.file << ": " << parsed.error;
    const SceneCheck check = check_scene(*parsed.scene);
    EXPECT_EQ(actions(check), b.actions) << b.file;
    EXPECT_TRUE(check.passes()) << b.file;
    expect_exact(*parsed.scene, check);
    for (std::size_t i = 0; i < check.surfaces.size(); ++i) {
      if (parsed.scene->surfaces[i].kind == SurfaceKind::mirror)
        expect_mirrored_view(*parsed.scene, check.surfaces[i], parsed.scene->surfaces[i]);
    }
  }
}

// mirror_flip: the same lake, its reflection pass built three ways. In the view (the default) the
// pass camera is improper and the projection the camera's; with the flip in the projection the
// camera is proper (diag(-1, 1, 1, 1) V R) and M11 negated, and the image the same (P' V' = P V
// R); in the texture, the same proper camera with the projection as it is. The oblique matrix of
// each holds every property; a flip that contradicts a declared mirror_design is refused.
TEST(EngineScenes, mirrorPassesAreBuiltAsTheSceneSays) {
  const std::string lake = read_file(std::string(OBLIQUE_SCENES_DIR) + "/lake.json");
  auto with_flip = [&lake](const std::string& extra) {
    std::string text = lake;
    text.replace(text.find("\"convention\""), 0, extra + ", ");
    return text;
  };
  std::map<std::string, SurfaceCheck> reflection;
  for (const std::string flip : {"view", "projection_x", "texture"}) {
    const ParsedScene parsed = parse_scene(with_flip("\"mirror_flip\": \"" + flip + "\""));
    ASSERT_TRUE(parsed.scene) << parsed.error;
    const SceneCheck check = check_scene(*parsed.scene);
    ASSERT_FALSE(check.surfaces.empty());
    EXPECT_TRUE(check.passes()) << flip;
    EXPECT_TRUE(check.surfaces[0].render) << flip;
    reflection[flip] = check.surfaces[0];
    EXPECT_EQ(parsed.scene->mirror_design, flip == "view"
                                               ? oblique::oracle::MirrorDesign::reflected_view
                                               : oblique::oracle::MirrorDesign::proper_camera);
  }
  const SurfaceCheck& in_view = reflection["view"];
  const SurfaceCheck& in_projection = reflection["projection_x"];
  const SurfaceCheck& in_texture = reflection["texture"];
  EXPECT_LT((in_view.view.topLeftCorner<3, 3>().determinant()), 0);
  EXPECT_GT((in_projection.view.topLeftCorner<3, 3>().determinant()), 0);
  EXPECT_GT(in_view.camera_projection(0, 0), 0);
  EXPECT_LT(in_projection.camera_projection(0, 0), 0);
  EXPECT_GT(in_texture.camera_projection(0, 0), 0);
  EXPECT_TRUE((in_projection.camera_projection * in_projection.view)
                  .isApprox(in_view.camera_projection * in_view.view, 1e-12));
  EXPECT_TRUE(in_texture.view.isApprox(in_projection.view, 1e-12));
  // proper_camera alone flips in the projection; contradicting declarations are refused.
  const ParsedScene proper = parse_scene(with_flip("\"mirror_design\": \"proper_camera\""));
  ASSERT_TRUE(proper.scene) << proper.error;
  EXPECT_EQ(proper.scene->mirror_flip, oblique::scene::MirrorFlip::projection_x);
  const ParsedScene contradicting =
      parse_scene(with_flip("\"mirror_design\": \"reflected_view\", \"mirror_flip\": \"texture\""));
  EXPECT_FALSE(contradicting.scene);
  EXPECT_NE(contradicting.error.find("mirror_flip"), std::string::npos) << contradicting.error;
  const ParsedScene unknown = parse_scene(with_flip("\"mirror_flip\": \"projection_y\""));
  EXPECT_FALSE(unknown.scene);
  EXPECT_NE(unknown.error.find("unknown mirror flip"), std::string::npos) << unknown.error;
}

/// A scene with one camera and the given surfaces (JSON fragments).
std::string scene_json(const std::string& convention, const std::string& projection,
                       const std::string& eye, const std::string& target,
                       const std::vector<std::string>& surfaces) {
  std::string out = "{\"name\": \"held out\", \"convention\": \"" + convention +
                    "\", \"camera\": {\"projection\": " + projection +
                    ", \"view\": {\"eye\": " + eye + ", \"target\": " + target +
                    ", \"up\": [0, 1, 0]}}, \"surfaces\": [";
  for (std::size_t i = 0; i < surfaces.size(); ++i) out += (i ? ", " : "") + surfaces[i];
  return out + "]}";
}

std::string surface(const std::string& kind, const std::string& normal, const std::string& point) {
  return "{\"name\": \"" + kind + " " + normal + "\", \"kind\": \"" + kind +
         "\", \"plane\": {\"normal\": " + normal + ", \"point\": " + point + "}}";
}

const std::string kPerspective =
    R"({"type": "perspective", "fovy_deg": 50, "aspect": 1.5, "near": 0.2, "far": 300})";

struct HeldOut {
  const char* what;
  std::string json;
  std::vector<std::string> actions;
};

TEST(Scenes, heldOutScenesGetTheRightDecisionsAndExactMatrices) {
  const std::string water_up = surface("mirror", "[0, 1, 0]", "[0, 0, 0]");
  const std::string water_down = surface("clip", "[0, -1, 0]", "[0, 0, 0]");
  const HeldOut cases[] = {
      {"water seen from above, every convention",
       scene_json("gl", kPerspective, "[3, 5, 12]", "[0, 0, -30]", {water_up, water_down}),
       {"render", "render"}},
      {"water seen from above, [0, 1]",
       scene_json("zero_one", kPerspective, "[3, 5, 12]", "[0, 0, -30]", {water_up, water_down}),
       {"render", "render"}},
      {"water seen from below (a diver)",
       scene_json("gl", kPerspective, "[0, -3, 0]", "[0, 0, -30]", {water_up, water_down}),
       {"skip: camera behind", "skip: camera on the kept side"}},
      {"a mirror facing away from the camera",
       scene_json("gl", kPerspective, "[0, 1.5, 5]", "[0, 1.5, -10]",
                  {surface("mirror", "[0, 0, -1]", "[0, 1.5, 0]")}),
       {"skip: camera behind"}},
      {"a mirror behind the camera, facing it",
       scene_json("zero_one", kPerspective, "[0, 1.5, 5]", "[0, 1.5, -10]",
                  {surface("mirror", "[0, 0, -1]", "[0, 1.5, 9]")}),
       {"skip: outside"}},
      {"a mirror beyond the far plane",
       scene_json("gl", kPerspective, "[0, 1.5, 5]", "[0, 1.5, -10]",
                  {surface("mirror", "[0, 0, 1]", "[0, 1.5, -400]")}),
       {"skip: outside"}},
      {"a wall mirror ahead, infinite reversed Z",
       scene_json("reversed_z",
                  R"({"type": "infinite", "fovy_deg": 90, "aspect": 1.0, "near": 0.01})",
                  "[2, 1.8, 6]", "[-1, 1.2, -3]",
                  {surface("mirror", "[0.1, 0, 1]", "[0, 1, -4]"), water_up}),
       {"render", "render"}},
      {"orthographic [0, 1] map over the sea",
       scene_json(
           "zero_one",
           R"({"type": "orthographic", "left": -40, "right": 40, "bottom": -25, "top": 25, "near": 0.5, "far": 600})",
           "[10, 150, 90]", "[0, 0, 0]", {water_up, water_down}),
       {"render", "render"}},
      {"off-axis frustum, tilted mirror",
       scene_json(
           "gl",
           R"({"type": "frustum", "left": -0.05, "right": 0.15, "bottom": -0.06, "top": 0.09, "near": 0.1, "far": 80})",
           "[0, 2, 4]", "[1, 1, -6]", {surface("mirror", "[0.3, 0.2, 1]", "[0, 1, -5]")}),
       {"render"}},
  };
  for (const HeldOut& c : cases) {
    const ParsedScene parsed = parse_scene(c.json);
    ASSERT_TRUE(parsed.scene) << c.what << ": " << parsed.error;
    const SceneCheck all = check_scene(*parsed.scene);
    // max_depth 1: the passes seen in passes (infinite planes see each other) are listed, at the
    // depth limit; the main camera's passes, one per surface, in order.
    SceneCheck check = all;
    check.surfaces.clear();
    for (const SurfaceCheck& s : all.surfaces) {
      if (s.level == 1) {
        check.surfaces.push_back(s);
      } else {
        EXPECT_EQ(s.level, 2) << c.what;
        EXPECT_EQ(s.reason, "depth limit (max_depth 1)") << c.what << ": " << s.name;
      }
    }
    EXPECT_EQ(actions(check), c.actions) << c.what;
    expect_exact(*parsed.scene, check);
    for (std::size_t i = 0; i < check.surfaces.size(); ++i) {
      if (parsed.scene->surfaces[i].kind == SurfaceKind::mirror)
        expect_mirrored_view(*parsed.scene, check.surfaces[i], parsed.scene->surfaces[i]);
    }
  }
}

// A pass means judged (issue 44): what check judged of each consumer the scene names, summed
// over the rendered passes, of the implementation's answers (--impl) or the core's.
ConsumerResult consumer_result(SceneConsumer consumer, long judged, long left_out,
                               const std::string& note = "") {
  ConsumerResult r;
  r.consumer = consumer;
  r.judged = judged;
  if (left_out > 0) r.left_out_why["the stored depth's interval reaches w = 0"] = left_out;
  r.note = note;
  return r;
}

TEST(SceneConsumers, aNamedConsumerWithNothingJudgedSaysWhyAndWhatToChange) {
  Scene scene;
  scene.consumers = {SceneConsumer::reconstruction, SceneConsumer::culling,
                     SceneConsumer::pass_view};
  SceneCheck check;
  SurfaceCheck skipped;
  skipped.reason = "out of view";
  check.surfaces = {skipped};
  ConsumerCoverage none = consumer_coverage(scene, check, false);
  ASSERT_EQ(none.unjudged.size(), 3u);
  EXPECT_NE(none.unjudged[0].find("the scene names consumer reconstruction, and no answer of it "
                                  "was judged: no pass was rendered to ask it on"),
            std::string::npos)
      << none.unjudged[0];

  SurfaceCheck clip;
  clip.render = true;
  clip.consumers = {
      consumer_result(SceneConsumer::reconstruction, 64, 0),
      consumer_result(SceneConsumer::culling, 0, 5),
      consumer_result(SceneConsumer::pass_view, 0, 0, "a clip pass renders with the main view")};
  check.surfaces = {skipped, clip};
  const ConsumerCoverage some = consumer_coverage(scene, check, false);
  ASSERT_EQ(some.unjudged.size(), 2u);
  EXPECT_NE(some.unjudged[0].find("consumer culling, and no answer of it was judged: all 5 left "
                                  "out (why, over the run: the stored depth's interval reaches "
                                  "w = 0 5): ask in a wider precision"),
            std::string::npos)
      << some.unjudged[0];
  EXPECT_NE(some.unjudged[1].find("consumer pass_view, and no answer of it was judged: it applies "
                                  "to none of the 1 rendered passes (a clip pass renders with the "
                                  "main view 1): leave pass_view out of \"consumers\""),
            std::string::npos)
      << some.unjudged[1];
  EXPECT_TRUE(some.partly.empty());

  // With --impl, the implementation's answers are the verdict: the core's do not count.
  EXPECT_EQ(consumer_coverage(scene, check, true).unjudged.size(), 3u);
  clip.impl_consumers = clip.consumers;
  clip.impl_consumers[1] = consumer_result(SceneConsumer::culling, 3, 0);
  check.surfaces = {clip};
  scene.consumers = {SceneConsumer::reconstruction, SceneConsumer::culling};
  EXPECT_TRUE(consumer_coverage(scene, check, true).unjudged.empty());
  EXPECT_EQ(consumer_coverage(scene, check, false).unjudged.size(), 1u);
}

TEST(SceneConsumers, aNamedConsumerMostlyLeftOutIsNamedWithItsShare) {
  Scene scene;
  scene.consumers = {SceneConsumer::reconstruction, SceneConsumer::cascades};
  SceneCheck check;
  SurfaceCheck a, b;
  a.render = b.render = true;
  // reconstruction: 40 of 128 left out over two passes (31%, 20% at least: beyond chance);
  // cascades 1 of 2 (one is no pattern).
  a.consumers = {consumer_result(SceneConsumer::reconstruction, 44, 20),
                 consumer_result(SceneConsumer::cascades, 1, 1)};
  b.consumers = {consumer_result(SceneConsumer::reconstruction, 44, 20),
                 consumer_result(SceneConsumer::cascades, 1, 0)};
  check.surfaces = {a, b};
  EXPECT_EQ(consumer_coverage(scene, check, false).partly, "reconstruction 40 of 128");
  // 14 of 128 (10.9%) is within chance of a tenth (left_out_beyond()).
  a.consumers[0] = b.consumers[0] = consumer_result(SceneConsumer::reconstruction, 57, 7);
  check.surfaces = {a, b};
  EXPECT_EQ(consumer_coverage(scene, check, false).partly, "");
}

TEST(Scenes, infiniteEdgePropertyIsCheckedOnlyForInfiniteProjections) {
  auto names = [](const SceneCheck& check) {
    std::vector<std::string> out;
    for (const oracle::Finding& p : check.surfaces.at(0).properties)
      out.push_back(std::string(oracle::check_name(p.check)));
    return out;
  };
  const std::string mirror = surface("mirror", "[0, 1, 0]", "[0, 0, 0]");
  const auto finite =
      check_text(scene_json("gl", kPerspective, "[0, 3, 5]", "[0, 0, -20]", {mirror}));
  const auto infinite = check_text(
      scene_json("gl", R"({"type": "infinite", "fovy_deg": 60, "aspect": 1.5, "near": 0.1})",
                 "[0, 3, 5]", "[0, 0, -20]", {mirror}));
  const std::vector<std::string> finite_names = names(finite), infinite_names = names(infinite);
  EXPECT_EQ(std::count(finite_names.begin(), finite_names.end(), "infinite_edge_parallel"), 0);
  EXPECT_EQ(std::count(infinite_names.begin(), infinite_names.end(), "infinite_edge_parallel"), 1);
}

TEST(Scenes, jsonOutputHasTheDocumentedFields) {
  SceneCheck check = check_text(read_file(std::string(OBLIQUE_SCENES_DIR) + "/lake.json"));
  check.scene = "lake \"quoted\"\nand a newline";  // must come out as valid JSON
  const nlohmann::json j = nlohmann::json::parse(to_json(check));
  EXPECT_EQ(j.at("scene"), check.scene);
  const nlohmann::json& water = j.at("surfaces").at(0);
  EXPECT_EQ(water.at("name"), "water reflection");
  EXPECT_EQ(water.at("action"), "render");
  EXPECT_TRUE(water.at("reason").is_null());
  EXPECT_EQ(water.at("view").size(), 16u);
  EXPECT_EQ(water.at("projection").size(), 16u);
  EXPECT_EQ(water.at("method"), "closed_form");
  EXPECT_EQ(water.at("properties").at("near_is_clip_plane"), true);
  EXPECT_EQ(water.at("depth_bits_lost").get<double>(), check.surfaces[0].depth->bits_lost);
  for (int i = 0; i < 16; ++i)  // numbers round-trip
    EXPECT_EQ(water.at("projection").at(i).get<double>(),
              (*check.surfaces[0].projection)(i / 4, i % 4));
}

struct Broken {
  std::string text;
  std::string message;
};

TEST(Scenes, brokenFilesNameTheFieldOrThePosition) {
  const std::string camera =
      R"("camera": {"projection": {"type": "perspective", "fovy_deg": 60, "aspect": 1, "near": 0.1, "far": 10}, "view": {"eye": [0, 0, 0], "target": [0, 0, -1], "up": [0, 1, 0]}})";
  auto with = [&](const std::string& from, const std::string& to) {
    std::string body =
        "{\"name\": \"x\", \"convention\": \"gl\", " + camera + ", \"surfaces\": []}";
    const auto at = body.find(from);
    if (at == std::string::npos) ADD_FAILURE() << from;
    return body.replace(at, from.size(), to);
  };
  const Broken cases[] = {
      {"{\"name\": \"x\",\n \"convention\": \"gl\",,}", "line 2, column"},
      {"[1, 2]", "(top level): must be an object"},
      {R"({"name": "x", "convention": "gl", "surfaces": []})", "camera: missing"},
      {with("\"near\": 0.1", "\"near\": 0"), "camera.projection.near: must be > 0"},
      {with("\"near\": 0.1", "\"near\": -2"), "camera.projection.near: must be > 0"},
      {with("\"far\": 10", "\"far\": 0.1"), "camera.projection.far: must be > near"},
      {with("\"near\": 0.1", "\"near\": \"0.1\""),
       "camera.projection.near: must be a number, not a string"},
      {with("\"up\": [0, 1, 0]", "\"up\": [0, 0, 0]"),
       "camera.view.up: must not be the zero vector"},
      {with("\"target\": [0, 0, -1]", "\"target\": [0, 0, 0]"),
       "camera.view.target: must differ from eye"},
      {with("\"up\": [0, 1, 0]", "\"up\": [0, 0, 2]"), "camera.view.up: must not be parallel"},
      {with("\"eye\": [0, 0, 0]", "\"eye\": [0, 0]"),
       "camera.view.eye: must be an array of 3 numbers"},
      {with("\"gl\"", "\"vulkan\""), "convention: unknown convention"},
      {with("\"perspective\"", "\"fisheye\""), "camera.projection.type: unknown type"},
      {with("\"fovy_deg\": 60", "\"fovy_deg\": 180"),
       "camera.projection.fovy_deg: must be in (0, 180)"},
      {with("\"surfaces\": []", "\"surfaces\": [{\"name\": \"m\", \"kind\": \"door\"}]"),
       "surfaces[0].kind: unknown kind"},
      {with("\"surfaces\": []",
            "\"surfaces\": [{\"name\": \"m\", \"kind\": \"mirror\", \"plane\": {\"normal\": [0, 0, "
            "0], \"point\": [0, 0, 0]}}]"),
       "surfaces[0].plane.normal: must not be the zero vector"},
      {with("\"surfaces\": []", "\"surfaces\": [{\"name\": \"m\", \"kind\": \"clip\"}]"),
       "surfaces[0].plane: missing"},
      // Numbers beyond double's range, named by their field (nlohmann threw out_of_range.406).
      {"[1e999]", "(top level): must be an object"},
      {with("\"near\": 0.1", "\"near\": 1e999"), "camera.projection.near: out of the range"},
      {with("\"eye\": [0, 0, 0]", "\"eye\": [0, -" + std::string(400, '9') + ", 0]"),
       "camera.view.eye[1]: out of the range"},
      // Degenerate cameras: no finite view volume in double.
      {with("\"near\": 0.1, \"far\": 10", "\"near\": 1e-308, \"far\": 1e308"),
       "camera.projection: degenerate in double"},
      {with(
           R"("type": "perspective", "fovy_deg": 60, "aspect": 1, "near": 0.1, "far": 10)",
           R"("type": "orthographic", "left": -1e308, "right": 1e308, "bottom": -1e308, "top": 1e308, "near": -1e308, "far": 1e308)"),
       "camera.projection: degenerate in double"},
      {with("\"eye\": [0, 0, 0]", "\"eye\": [0, 0, 1.7e308]"), "camera"},
      {with("\"surfaces\": []",
            "\"surfaces\": [{\"name\": \"m\", \"kind\": \"mirror\", \"plane\": {\"normal\": [1, 1, "
            "1], \"point\": [1e308, 1e308, 1e308]}}]"),
       "surfaces[0].plane.point: out of range for this normal"},
      {std::string("{\"name\": \"x\"}") + std::string(1, '\0') + "garbage", "a NUL byte"},
  };
  for (const Broken& b : cases) {
    const ParsedScene parsed = parse_scene(b.text);
    EXPECT_FALSE(parsed.scene) << b.text;
    EXPECT_NE(parsed.error.find(b.message), std::string::npos)
        << "expected \"" << b.message << "\" in \"" << parsed.error << "\"";
  }
}

/// A scene with the camera's projection fields `projection` and the rest `rest` (after the camera).
std::string scene_with(const std::string& convention, const std::string& projection,
                       const std::string& rest = "\"surfaces\": []") {
  return "{\"name\": \"x\", \"convention\": \"" + convention +
         "\", \"camera\": {\"projection\": {" + projection +
         "}, \"view\": {\"eye\": [0, 0, 0], \"target\": [0, 0, -1], \"up\": [0, 1, 0]}}, " + rest +
         "}";
}

TEST(Scenes, unknownNamesSuggestTheClosestKnownOne) {
  const std::string camera =
      R"("type": "perspective", "fovy_deg": 60, "aspect": 1, "near": 0.1, "far": 10)";
  const Broken cases[] = {
      {scene_with("reversed-z", camera),
       "convention: unknown convention \"reversed-z\" (did you mean reversed_z?; known: gl"},
      {scene_with("gl",
                  R"("type": "perspectiv", "fovy_deg": 60, "aspect": 1, "near": 0.1, "far": 10)"),
       "camera.projection.type: unknown type \"perspectiv\" (did you mean perspective?"},
      {scene_with("gl", camera, R"("depth_buffer": "float", "surfaces": [])"),
       "depth_buffer: unknown depth buffer \"float\" (did you mean float32?"},
      {scene_with("gl", camera, R"("mirror_design": "reflected-view", "surfaces": [])"),
       "mirror_design: unknown mirror design \"reflected-view\" (did you mean reflected_view?"},
      {scene_with(
           "gl", camera,
           R"("surfaces": [{"name": "m", "kind": "miror", "plane": {"normal": [0, 0, 1], "point": [0, 0, -2]}}])"),
       "surfaces[0].kind: unknown kind \"miror\" (did you mean mirror?"},
      // Nothing close: the list alone.
      {scene_with("vulkan", camera),
       "convention: unknown convention \"vulkan\" (known: gl, zero_one, reversed_z)"},
  };
  for (const Broken& b : cases) {
    const ParsedScene parsed = parse_scene(b.text);
    EXPECT_FALSE(parsed.scene) << b.text;
    EXPECT_NE(parsed.error.find(b.message), std::string::npos)
        << "expected \"" << b.message << "\" in \"" << parsed.error << "\"";
  }
}

TEST(Scenes, aFieldOfViewInTheOtherUnitIsNamed) {
  auto parsed = [](const std::string& fovy) {
    return parse_scene(scene_with(
        "gl", fovy + R"(, "type": "perspective", "aspect": 1.6, "near": 0.1, "far": 10)"));
  };
  // 1.22 "degrees": accepted (a narrow lens is possible), with a warning that names radians.
  const ParsedScene radians_as_degrees = parsed(R"("fovy_deg": 1.22)");
  ASSERT_TRUE(radians_as_degrees.scene) << radians_as_degrees.error;
  ASSERT_EQ(radians_as_degrees.warnings.size(), 1u);
  EXPECT_NE(radians_as_degrees.warnings[0].find(
                "camera.projection.fovy_deg: 1.22 degrees is a very narrow view; if it is in "
                "radians (69.9 degrees), write \"fovy_rad\": 1.22"),
            std::string::npos)
      << radians_as_degrees.warnings[0];
  // Ordinary fields of view warn of nothing.
  for (const std::string fovy :
       {R"("fovy_deg": 70)", R"("fovy_deg": 3.5)", R"("fovy_rad": 1.22)"}) {
    const ParsedScene ordinary = parsed(fovy);
    ASSERT_TRUE(ordinary.scene) << fovy << ": " << ordinary.error;
    EXPECT_TRUE(ordinary.warnings.empty()) << fovy << ": " << ordinary.warnings[0];
  }
  // Degrees given as radians are beyond pi: refused, naming fovy_deg.
  const ParsedScene degrees_as_radians = parsed(R"("fovy_rad": 70)");
  EXPECT_FALSE(degrees_as_radians.scene);
  EXPECT_NE(degrees_as_radians.error.find(
                "camera.projection.fovy_rad: must be in (0, pi) radians; if 70 is in degrees, "
                "write \"fovy_deg\": 70"),
            std::string::npos)
      << degrees_as_radians.error;
}

TEST(Scenes, directionsAreJudgedByDirectionNotLength) {
  // An up vector of length 1e200 and a normal of length 1e-200 are as good as unit ones: the
  // scene checks exactly as with unit vectors (they were refused as parallel, or reflected NaN).
  const std::string lake = read_file(std::string(OBLIQUE_SCENES_DIR) + "/lake.json");
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = lake;
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  const ParsedScene unit = parse_scene(lake);
  ASSERT_TRUE(unit.scene) << unit.error;
  const std::string expected = to_json(check_scene(*unit.scene));
  for (const std::string& text : {replaced("\"up\": [0, 1, 0]", "\"up\": [0, 1e200, 0]"),
                                  replaced("\"normal\": [0, 1, 0]", "\"normal\": [0, 1e-200, 0]"),
                                  replaced("\"normal\": [0, 1, 0]", "\"normal\": [0, 1e300, 0]")}) {
    const ParsedScene parsed = parse_scene(text);
    ASSERT_TRUE(parsed.scene) << parsed.error;
    EXPECT_EQ(to_json(check_scene(*parsed.scene)), expected);
  }
}

TEST(Scenes, tableColumnIsCappedAndNamesAreEscaped) {
  const ParsedScene parsed = parse_scene(read_file(std::string(OBLIQUE_SCENES_DIR) + "/lake.json"));
  ASSERT_TRUE(parsed.scene) << parsed.error;
  Scene scene = *parsed.scene;
  const std::string long_name(10000, 'w');
  scene.surfaces[0].name = long_name;
  scene.surfaces[1].name = "evil\n\x1b[2Jname";
  const std::string text = to_text(check_scene(scene));
  // The long name stands on its own line; no row is padded to its length.
  std::istringstream lines(text);
  std::size_t longest = 0, rows_with_long_name = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line == long_name)
      ++rows_with_long_name;                        // the name on its own line, above its row
    else if (line.rfind(long_name + " (", 0) != 0)  // not the rendered pass's heading
      longest = std::max(longest, line.size());
  }
  EXPECT_GE(rows_with_long_name, 1u);
  EXPECT_LT(longest, 200u) << text.substr(0, 400);
  EXPECT_NE(text.find("evil\\n\\x1b[2Jname"), std::string::npos) << text;
  EXPECT_EQ(text.find('\x1b'), std::string::npos);
}

TEST(Scenes, unreadableAndSpecialFilesAreRefused) {
  const std::pair<std::string, std::string> cases[] = {
      {"/dev/zero", "larger than"},
      {::testing::TempDir(), "is a directory"},
      {std::string(OBLIQUE_SCENES_DIR) + "/no-such-scene.json", "cannot open"},
  };
  for (const auto& [path, expected] : cases) {
    const ParsedScene parsed = read_scene_file(path);
    EXPECT_FALSE(parsed.scene) << path;
    EXPECT_NE(parsed.error.find(expected), std::string::npos) << path << ": " << parsed.error;
  }
  EXPECT_TRUE(read_scene_file(std::string(OBLIQUE_SCENES_DIR) + "/lake.json").scene);
}

// ---- Engine scenes: cameras as engines hold them, bounded surfaces, portals, recursion ----

/// The passes' names and "render" / the first words of their reasons.
std::vector<std::pair<std::string, std::string>> named_actions(const SceneCheck& check) {
  std::vector<std::pair<std::string, std::string>> out;
  const std::vector<std::string> a = actions(check);
  for (std::size_t i = 0; i < a.size(); ++i) {
    std::string action = a[i];
    if (action.find("depth limit") != std::string::npos) action = "skip: depth limit";
    if (action.find("not visible through its parent") != std::string::npos)
      action = "skip: not visible through its parent";
    out.emplace_back(check.surfaces[i].name, action);
  }
  return out;
}

Scene bundled_scene(const std::string& file) {
  const ParsedScene parsed = read_scene_file(std::string(OBLIQUE_SCENES_DIR) + "/" + file);
  if (!parsed.scene) ADD_FAILURE() << file << ": " << parsed.error;
  return parsed.scene ? *parsed.scene : Scene{};
}

Vector3 reflect(const Surface& s, const Vector3& p) {
  const Vector3 n = s.normal.normalized();
  return p - 2 * n.dot(p - s.point) * n;
}

/// Where a pass camera is in the world: its view's inverse applied to the origin.
Vector3 pass_eye(const SurfaceCheck& s) {
  return (s.view.inverse() * Vector4<double>(0, 0, 0, 1)).head<3>();
}

using Actions = std::vector<std::pair<std::string, std::string>>;

TEST(EngineScenes, hallOfMirrorsRecursesToItsDepthWithReflectedEyes) {
  const Scene scene = bundled_scene("hall_of_mirrors.json");
  const SceneCheck check = check_scene(scene);
  const Actions expected = {
      {"north mirror", "render"},
      {"north mirror > south mirror", "render"},
      {"north mirror > south mirror > north mirror", "render"},
      {"north mirror > south mirror > north mirror > south mirror", "skip: depth limit"},
      {"south mirror", "skip: outside"}};
  EXPECT_EQ(named_actions(check), expected);
  EXPECT_TRUE(check.passes());
  expect_exact(scene, check);
  // Each pass's eye is the main eye reflected through each mirror of its path, outermost first;
  // each reflection flips handedness.
  for (const SurfaceCheck& s : check.surfaces) {
    if (!s.render) continue;
    Vector3 eye = scene.camera.eye;
    for (const std::size_t k : s.path) eye = reflect(scene.surfaces[k], eye);
    EXPECT_TRUE(pass_eye(s).isApprox(eye, 1e-12)) << s.name << ": " << pass_eye(s).transpose();
    EXPECT_NEAR((s.view.block<3, 3>(0, 0).determinant()), s.path.size() % 2 ? -1 : 1, 1e-12);
    ASSERT_TRUE(s.scissor) << s.name;
    EXPECT_TRUE(s.scissor->pixels) << s.name;
  }
  // A mirror seen in a mirror is smaller: each scissor lies within its parent's.
  for (std::size_t i = 1; i < 3; ++i) {
    const Scissor& inner = *check.surfaces[i].scissor;
    const Scissor& outer = *check.surfaces[i - 1].scissor;
    EXPECT_GE(inner.x0, outer.x0);
    EXPECT_LE(inner.x1, outer.x1);
    EXPECT_GE(inner.y0, outer.y0);
    EXPECT_LE(inner.y1, outer.y1);
    EXPECT_LT(inner.ndc_area, outer.ndc_area);
  }
}

TEST(EngineScenes, heldOutHallsChangeTheirVerdictsWithDepthAndPosition) {
  std::string text = R"({"name": "hall", "convention": "zero_one", "max_depth": MAXD,
    "camera": {"projection": {"type": "perspective", "fovy_deg": 70, "aspect": 1, "near": 0.1, "far": 50},
               "view": {"eye": EYE, "target": TARGET, "up": [0, 1, 0]}},
    "surfaces": [
      {"name": "a", "kind": "mirror", "rectangle": {"center": [0, 1, -3], "normal": [0, 0, 1], "up": [0, 1, 0], "size": [3, 2]}},
      {"name": "b", "kind": "mirror", "rectangle": {"center": [0, 1, 3], "normal": [0, 0, -1], "up": [0, 1, 0], "size": [3, 2]}}]})";
  auto variant = [&](const std::string& depth, const std::string& eye,
                     const std::string& target = "[0, 1, -3]") {
    std::string t = text;
    t.replace(t.find("MAXD"), 4, depth);
    t.replace(t.find("EYE"), 3, eye);
    t.replace(t.find("TARGET"), 6, target);
    const ParsedScene parsed = parse_scene(t);
    EXPECT_TRUE(parsed.scene) << parsed.error;
    return parsed.scene ? check_scene(*parsed.scene) : SceneCheck{};
  };
  EXPECT_EQ(named_actions(variant("1", "[0, 1, 0]")),
            (Actions{{"a", "render"}, {"a > b", "skip: depth limit"}, {"b", "skip: outside"}}));
  const SceneCheck deep = variant("5", "[0.2, 1.1, 0]");
  ASSERT_EQ(deep.surfaces.size(), 7u);  // a, a>b, ..., five rendered, the sixth at the limit, b
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(deep.surfaces[static_cast<std::size_t>(i)].render) << i;
  EXPECT_EQ(deep.surfaces[5].reason, "depth limit (max_depth 5)");
  // Beside the mirrors (x = 10), looking away along +x: neither is seen, nothing renders.
  const SceneCheck aside = variant("3", "[10, 1, 0]", "[20, 1, 0]");
  EXPECT_EQ(named_actions(aside), (Actions{{"a", "skip: outside"}, {"b", "skip: outside"}}));
  for (const SurfaceCheck& s : aside.surfaces) EXPECT_FALSE(s.render) << s.name;
}

TEST(EngineScenes, portalPassLooksOutOfTheLinkedPortal) {
  const Scene scene = bundled_scene("portal_pair.json");
  const SceneCheck check = check_scene(scene);
  const Actions expected = {{"blue portal", "render"},
                            {"blue portal > orange portal", "skip: camera behind"},
                            {"blue portal > wall mirror", "render"},
                            {"blue portal > wall mirror > orange portal", "skip: depth limit"},
                            {"orange portal", "skip: outside"},
                            {"wall mirror", "skip: camera behind"}};
  EXPECT_EQ(named_actions(check), expected);
  expect_exact(scene, check);
  // By hand: the eye is 6 in front of blue (0.1 above its center); through the portal it is 6
  // behind orange (whose front faces -x), 0.1 above its center, and looks along orange's normal.
  const SurfaceCheck& blue = check.surfaces[0];
  EXPECT_TRUE(pass_eye(blue).isApprox(Vector3(26, 1.6, 0), 1e-12)) << pass_eye(blue).transpose();
  const Vector3 forward = -blue.view.block<1, 3>(2, 0).transpose();
  EXPECT_TRUE(forward.isApprox(Vector3(-1, 0, 0), 1e-12)) << forward.transpose();
  EXPECT_NEAR((blue.view.block<3, 3>(0, 0).determinant()), 1, 1e-12);  // a portal keeps handedness
  // Its oblique near plane is orange's plane: a point on orange's face is on the near plane.
  const Vector4<double> on_orange(20, 2, 0.5, 1);
  const Vector4<double> clip = *blue.projection * blue.view * on_orange;
  EXPECT_NEAR(clip.z() / clip.w(), 0, 1e-12);  // zero_one: the near plane at z = 0
}

TEST(EngineScenes, boundedSurfacesAreDecidedByThePolygonNotThePlane) {
  const Scene scene = bundled_scene("mirror_off_screen.json");
  const SceneCheck check = check_scene(scene);
  EXPECT_EQ(named_actions(check),
            (Actions{{"far side mirror", "skip: outside"}, {"vanity mirror", "render"}}));
  // The same mirror as an infinite plane: its plane enters the view volume far away, so render.
  Scene unbounded = scene;
  unbounded.surfaces[0].polygon.clear();
  EXPECT_TRUE(check_scene(unbounded).surfaces[0].render);
  // The vanity mirror's scissor by hand: x = +-0.5, y = 1..2 at distance 10 from the eye (y 1.6).
  const Scissor& s = *check.surfaces[1].scissor;
  const double f = 1 / std::tan(30 * 3.14159265358979323846 / 180), aspect = 1.78;
  EXPECT_NEAR(s.x0, -0.5 * f / aspect / 10, 1e-12);
  EXPECT_NEAR(s.x1, 0.5 * f / aspect / 10, 1e-12);
  EXPECT_NEAR(s.y0, -0.6 * f / 10, 1e-12);
  EXPECT_NEAR(s.y1, 0.4 * f / 10, 1e-12);
  ASSERT_TRUE(s.pixels && s.covered_pixels);
  const auto px = [](double ndc, double size) { return (ndc + 1) / 2 * size; };
  EXPECT_EQ((*s.pixels)[0], static_cast<int>(std::floor(px(s.x0, 1920))));
  EXPECT_EQ((*s.pixels)[1], static_cast<int>(std::floor(px(s.y0, 1080))));
  EXPECT_EQ((*s.pixels)[0] + (*s.pixels)[2], static_cast<int>(std::ceil(px(s.x1, 1920))));
  EXPECT_EQ((*s.pixels)[1] + (*s.pixels)[3], static_cast<int>(std::ceil(px(s.y1, 1080))));
  EXPECT_NEAR(*s.covered_pixels,
              (px(s.x1, 1920) - px(s.x0, 1920)) * (px(s.y1, 1080) - px(s.y0, 1080)), 1e-6);
}

TEST(EngineScenes, polygonPartlyOnScreenIsClippedToTheScreen) {
  const Scene scene = bundled_scene("mirror_off_screen.json");
  // A wide quad across the whole view at distance 10: clipped to the screen's edges.
  const std::vector<Vector3> wide = {
      {-100, -50, -10}, {100, -50, -10}, {100, 50, -10}, {-100, 50, -10}};
  const auto s = clip_polygon(wide, scene.camera.view, scene.camera.projection, scene.convention,
                              std::nullopt, std::array<int, 2>{100, 50});
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->x0, -1, 1e-15);  // the clipped vertex lies on x = -w, within rounding
  EXPECT_NEAR(s->x1, 1, 1e-15);
  EXPECT_NEAR(s->ndc_area, 4, 1e-9);
  EXPECT_EQ(*s->pixels, (std::array<int, 4>{0, 0, 100, 50}));
  // Behind the camera, or beyond the far plane: nothing left.
  const std::vector<Vector3> behind = {{-1, 0, 5}, {1, 0, 5}, {1, 2, 5}, {-1, 2, 5}};
  EXPECT_FALSE(clip_polygon(behind, scene.camera.view, scene.camera.projection, scene.convention,
                            std::nullopt, std::nullopt));
  const std::vector<Vector3> beyond = {
      {-1, 0, -2000}, {1, 0, -2000}, {1, 2, -2000}, {-1, 2, -2000}};
  EXPECT_FALSE(clip_polygon(beyond, scene.camera.view, scene.camera.projection, scene.convention,
                            std::nullopt, std::nullopt));
}

TEST(EngineScenes, vulkanCameraIsYFlippedReversedZWithAFloatBuffer) {
  const Scene scene = bundled_scene("vulkan_reversed_z.json");
  EXPECT_EQ(scene.depth_buffer, DepthBuffer::float32);
  EXPECT_EQ(scene.camera.type, ProjectionType::infinite);
  EXPECT_LT(scene.camera.projection(1, 1), 0);  // y flipped
  const SceneCheck check = check_scene(scene);
  EXPECT_EQ(named_actions(check), (Actions{{"puddle", "render"}}));
  expect_exact(scene, check);
  expect_mirrored_view(scene, check.surfaces[0], scene.surfaces[0]);
  // The quaternion is a rotation of -15 degrees about x: the camera looks down by 15 degrees.
  const Vector3 forward = -scene.camera.view.block<1, 3>(2, 0).transpose();
  const double a = 15 * 3.14159265358979323846 / 180;
  EXPECT_TRUE(forward.isApprox(Vector3(0, -std::sin(a), -std::cos(a)), 1e-12));
  // y-flipped: the puddle (below the eye) is in the upper half of NDC.
  EXPECT_GT(check.surfaces[0].scissor->y1, 0);
}

/// Bits lost in a float32 buffer, by a second route: floats in [0, x) counted by binades (frexp).
double floats_below(double x) {
  const float f = static_cast<float>(x);
  if (f <= 0) return 0;
  int e = 0;
  const double m = std::frexp(static_cast<double>(f), &e);       // f = m 2^e, m in [0.5, 1)
  if (e < -125) return std::ldexp(static_cast<double>(f), 149);  // subnormal: in steps of 2^-149
  return std::ldexp(1.0, 23) * (e + 125) + (2 * m - 1) * std::ldexp(1.0, 23) + std::ldexp(1.0, 23);
}

TEST(EngineScenes, depthBitsAreCountedInTheDeclaredBuffer) {
  Scene scene = bundled_scene("wall_mirror_reversed_z.json");
  EXPECT_EQ(scene.depth_buffer, DepthBuffer::float32);  // reversed Z: a float buffer
  const SceneCheck as_float = check_scene(scene);
  scene.depth_buffer = DepthBuffer::fixed24;
  const SceneCheck as_fixed = check_scene(scene);
  const DepthPrecision& f = *as_float.surfaces[0].depth;
  const DepthPrecision& x = *as_fixed.surfaces[0].depth;
  EXPECT_EQ(f.fraction, x.fraction);
  EXPECT_DOUBLE_EQ(x.bits_lost, -std::log2(x.fraction));
  // Reversed Z [0, 1]: near at 1; the axis spans window depths [far_depth, 1].
  const double expected =
      std::log2(floats_below(1) / (floats_below(1) - floats_below(f.far_depth)));
  EXPECT_NEAR(f.bits_lost, expected, 1e-9) << f.far_depth;
  EXPECT_GT(f.bits_lost, x.bits_lost);  // the tilted far plane takes the dense floats near 0
}

TEST(EngineScenes, cameraFormsAgree) {
  // One camera written five ways: eye/target/up, a row- and a column-major view matrix,
  // position + quaternion, and fovy in radians.
  const std::string head = R"({"name": "forms", "convention": "gl", "camera": {"projection": )";
  const std::string deg =
      R"({"type": "perspective", "fovy_deg": 90, "aspect": 1, "near": 0.5, "far": 100})";
  const std::string rad =
      R"({"type": "perspective", "fovy_rad": 1.5707963267948966, "aspect": 1, "near": 0.5, "far": 100})";
  const std::string tail =
      R"(}, "surfaces": [{"name": "m", "kind": "mirror", "rectangle": {"center": [-5, 2, 3], "normal": [1, 0, 0.2], "up": [0, 1, 0], "size": [2, 2]}}]})";
  // Eye (1, 2, 3) looking along -x: the camera's x axis is world -z (a yaw of +90 degrees).
  const std::string look = R"("view": {"eye": [1, 2, 3], "target": [0, 2, 3], "up": [0, 1, 0]})";
  const std::string rows =
      R"("view": {"layout": "row_major", "matrix": [0, 0, -1, 3,  0, 1, 0, -2,  1, 0, 0, -1,  0, 0, 0, 1]})";
  const std::string columns =
      R"("view": {"layout": "column_major", "matrix": [0, 0, 1, 0,  0, 1, 0, 0,  -1, 0, 0, 0,  3, -2, -1, 1]})";
  // A row-vector engine's view (DirectXMath): the transpose, by rows: column_major's numbers.
  const std::string row_vectors =
      R"("view": {"layout": "row_vectors", "matrix": [0, 0, 1, 0,  0, 1, 0, 0,  -1, 0, 0, 0,  3, -2, -1, 1]})";
  const std::string quaternion =
      R"("view": {"position": [1, 2, 3], "quaternion_xyzw": [0, 0.7071067811865476, 0, 0.7071067811865476]})";
  std::vector<SceneCheck> checks;
  for (const auto& [projection, view] : {std::pair{deg, look},
                                         {deg, rows},
                                         {deg, columns},
                                         {deg, row_vectors},
                                         {deg, quaternion},
                                         {rad, look}}) {
    const ParsedScene parsed = parse_scene(head + projection + ", " + view + tail);
    ASSERT_TRUE(parsed.scene) << view << ": " << parsed.error;
    checks.push_back(check_scene(*parsed.scene));
    ASSERT_EQ(checks.back().surfaces.size(), 1u);
    EXPECT_TRUE(checks.back().surfaces[0].render) << view;
  }
  for (const SceneCheck& c : checks) {
    EXPECT_TRUE(c.surfaces[0].view.isApprox(checks[0].surfaces[0].view, 1e-12));
    EXPECT_TRUE(c.surfaces[0].projection->isApprox(*checks[0].surfaces[0].projection, 1e-12));
  }
  // y_flip negates clip y, nothing else; infinite_far is the infinite projection.
  const ParsedScene flipped = parse_scene(
      head +
      R"({"type": "perspective", "fovy_deg": 90, "aspect": 1, "near": 0.5, "far": 100, "y_flip": true}, )" +
      look + tail);
  ASSERT_TRUE(flipped.scene) << flipped.error;
  const ParsedScene plain = parse_scene(head + deg + ", " + look + tail);
  Matrix4<double> expected = plain.scene->camera.projection;
  expected.row(1) *= -1;
  EXPECT_EQ(flipped.scene->camera.projection, expected);
  const ParsedScene endless = parse_scene(
      head +
      R"({"type": "perspective", "fovy_deg": 90, "aspect": 1, "near": 0.5, "infinite_far": true}, )" +
      look + tail);
  const ParsedScene infinite = parse_scene(
      head + R"({"type": "infinite", "fovy_deg": 90, "aspect": 1, "near": 0.5}, )" + look + tail);
  ASSERT_TRUE(endless.scene && infinite.scene) << endless.error << infinite.error;
  EXPECT_EQ(endless.scene->camera.projection, infinite.scene->camera.projection);
}

TEST(EngineScenes, unknownKeysAndBadShapesAreRefusedWithTheirPath) {
  const std::string base = read_file(std::string(OBLIQUE_SCENES_DIR) + "/portal_pair.json");
  auto with = [&](const std::string& from, const std::string& to) {
    std::string body = base;
    const auto at = body.find(from);
    if (at == std::string::npos) ADD_FAILURE() << from;
    return at == std::string::npos ? body : body.replace(at, from.size(), to);
  };
  const Broken cases[] = {
      {with("\"fovy_rad\"", "\"fovy\""), "camera.projection.fovy: unknown key"},
      {with("\"near\": 0.1,", "\"near\": 0.1, \"y_flip\": 1,"),
       "camera.projection.y_flip: must be true or false"},
      {with("\"up\": [0, 1, 0]}", "\"up\": [0, 1, 0], \"y_flip\": true}"),
       "camera.view.y_flip: unknown key"},
      {with("\"max_depth\": 2", "\"max_depth\": 2, \"maxdepth\": 3"), "maxdepth: unknown key"},
      {with("\"max_depth\": 2", "\"max_depth\": 0"), "max_depth: must be an integer in [1, 8]"},
      {with("\"max_depth\": 2", "\"max_depth\": 2.5"), "max_depth: must be an integer"},
      {with("[1280, 720]", "[1280]"), "viewport: must be [width, height]"},
      {with("[1280, 720]", "[0, 720]"), "viewport[0]: must be an integer in [1, 65536]"},
      {with("\"fovy_rad\": 1.0471975511965976", "\"fovy_rad\": 60"),
       "camera.projection.fovy_rad: must be in (0, pi) radians"},
      {with("\"fovy_rad\": 1.0471975511965976", "\"fovy_rad\": 1, \"fovy_deg\": 60"),
       "camera.projection.fovy_rad: give fovy_deg or fovy_rad, not both"},
      {with("\"size\": [2, 3]},\n     \"linked\"",
            "\"size\": [2, 3], \"colour\": 1},\n     \"linked\""),
       "surfaces[0].rectangle.colour: unknown key"},
      {with("\"linked\": {\"center\": [20, 1.5, 0]", "\"link\": {\"center\": [20, 1.5, 0]"),
       "surfaces[0].link: unknown key"},
      {with("\"size\": [2, 3]},\n     \"linked\": {\"center\": [20, 1.5, 0], \"normal\": [-1, 0, "
            "0], \"up\": [0, 1, 0]}},",
            "\"size\": [2, 3]}},"),
       "surfaces[0].linked: missing"},
      {with("\"size\": [3, 3]}}", "\"size\": [3, 3]}, \"linked\": {}}"),
       "surfaces[2].linked: only a portal"},
      {with("\"up\": [0, 1, 0], \"size\": [3, 3]", "\"up\": [1, 0, 0], \"size\": [3, 3]"),
       "surfaces[2].rectangle.up: must not be the zero vector nor parallel to the normal"},
      {with("\"size\": [3, 3]", "\"size\": [3, -1]"),
       "surfaces[2].rectangle.size: width and height"},
      {with("\"rectangle\": {\"center\": [10, 1.5, 0], \"normal\": [1, 0, 0], \"up\": [0, 1, 0], "
            "\"size\": [3, 3]}",
            "\"polygon\": {\"vertices\": [[10, 0, 0], [10, 0, 1], [10, 1, 1], [10.5, 1, 0]]}"),
       "surfaces[2].polygon.vertices[0]: not in the plane of the others (not planar)"},
      {with("\"rectangle\": {\"center\": [10, 1.5, 0], \"normal\": [1, 0, 0], \"up\": [0, 1, 0], "
            "\"size\": [3, 3]}",
            "\"polygon\": {\"vertices\": [[0, 0, 0], [1, 1, 1], [2, 2, 2]]}"),
       "surfaces[2].polygon.vertices: degenerate: the vertices are collinear"},
      {with("\"rectangle\": {\"center\": [10, 1.5, 0], \"normal\": [1, 0, 0], \"up\": [0, 1, 0], "
            "\"size\": [3, 3]}",
            "\"rectangle\": {\"center\": [10, 1.5, 0], \"normal\": [1, 0, 0], \"up\": [0, 1, 0], "
            "\"size\": [3, 3]}, \"plane\": {}"),
       "surfaces[2].plane: give exactly one of plane, polygon or rectangle"},
      {with("\"kind\": \"portal\",\n     \"rectangle\": {\"center\": [0, 1.5, -4], \"normal\": [0, "
            "0, 1], \"up\": [0, 1, 0], \"size\": [2, 3]}",
            "\"kind\": \"portal\",\n     \"polygon\": {\"vertices\": [[0, 0, -4], [1, 0, -4], [1, "
            "1, -4]]}"),
       "surfaces[0].rectangle: a portal is a rectangle"},
      {with("\"view\": {\"eye\": [0, 1.6, 2], \"target\": [0, 1.6, -4], \"up\": [0, 1, 0]}",
            "\"view\": {\"matrix\": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}"),
       "camera.view.layout: missing"},
      {with("\"view\": {\"eye\": [0, 1.6, 2], \"target\": [0, 1.6, -4], \"up\": [0, 1, 0]}",
            "\"view\": {\"layout\": \"row_major\", \"matrix\": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, "
            "0, 0, 0, 1, 1]}"),
       "camera.view.matrix: must be affine"},
      {with("\"view\": {\"eye\": [0, 1.6, 2], \"target\": [0, 1.6, -4], \"up\": [0, 1, 0]}",
            "\"view\": {\"layout\": \"rows\", \"matrix\": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, "
            "0, 0, 1]}"),
       "camera.view.layout: unknown layout"},
      {with("\"view\": {\"eye\": [0, 1.6, 2], \"target\": [0, 1.6, -4], \"up\": [0, 1, 0]}",
            "\"view\": {\"position\": [0, 1.6, 2], \"quaternion_xyzw\": [0, 0, 0, 0]}"),
       "camera.view.quaternion_xyzw: must not be zero"},
      {with("\"convention\": \"zero_one\"",
            "\"convention\": \"zero_one\", \"depth_buffer\": \"float16\""),
       "depth_buffer: unknown depth buffer"},
  };
  for (const Broken& c : cases) {
    const ParsedScene parsed = parse_scene(c.text);
    EXPECT_FALSE(parsed.scene) << c.message;
    EXPECT_NE(parsed.error.find(c.message), std::string::npos)
        << "expected: " << c.message << "\n     got: " << parsed.error;
  }
}

/// A value of a bundled scene, by the path the scene reader names it with
/// ("camera.view.eye[1]", "surfaces[0].plane"; the root is "(top level)").
struct Located {
  std::string path;
  nlohmann::json::json_pointer pointer;
};

void every_value(const nlohmann::json& v, const std::string& path,
                 const nlohmann::json::json_pointer& pointer, std::vector<Located>& out) {
  out.push_back({path.empty() ? "(top level)" : path, pointer});
  if (v.is_object()) {
    for (const auto& item : v.items())
      every_value(item.value(), path.empty() ? item.key() : path + "." + item.key(),
                  pointer / item.key(), out);
  } else if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i)
      every_value(v[i], path + "[" + std::to_string(i) + "]", pointer / i, out);
  }
}

/// JSON's six kinds of value (numbers are one kind).
int kind_of(const nlohmann::json& v) {
  if (v.is_null()) return 0;
  if (v.is_boolean()) return 1;
  if (v.is_number()) return 2;
  if (v.is_string()) return 3;
  if (v.is_array()) return 4;
  return 5;
}

/// One value of each kind, in kind_of()'s order.
std::vector<nlohmann::json> one_of_each_kind() {
  return {nullptr, true, 1, "x", nlohmann::json::array({1}), nlohmann::json::object()};
}

/// Every bundled scene with one value replaced by a value of another kind: the scene's path,
/// the path of the value, the kind it got, and the text.
struct Mistyped {
  std::string scene, path, replaced_by, text;
};

std::vector<Mistyped> every_mistyped_bundled_scene() {
  std::vector<Mistyped> out;
  for (const auto& entry : std::filesystem::directory_iterator(OBLIQUE_SCENES_DIR)) {
    if (entry.path().extension() != ".json") continue;
    const nlohmann::json scene = nlohmann::json::parse(read_file(entry.path().string()));
    std::vector<Located> values;
    every_value(scene, "", nlohmann::json::json_pointer(), values);
    for (const Located& at : values) {
      for (const nlohmann::json& wrong : one_of_each_kind()) {
        if (kind_of(wrong) == kind_of(scene.at(at.pointer))) continue;
        nlohmann::json broken = scene;
        broken.at(at.pointer) = wrong;
        out.push_back({entry.path().string(), at.path, wrong.dump(), broken.dump()});
      }
    }
  }
  return out;
}

// Every value of every bundled scene, replaced by a value of each other kind (array for object,
// string for number, null, ...): refused with a message that starts with that value's path.
TEST(Scenes, aValueOfTheWrongKindAnywhereIsRefusedWithItsPath) {
  const std::vector<Mistyped> cases = every_mistyped_bundled_scene();
  EXPECT_GT(cases.size(), 2000u);  // 8 scenes, hundreds of values each
  for (const Mistyped& c : cases) {
    const ParsedScene parsed = parse_scene(c.text);
    EXPECT_FALSE(parsed.scene) << c.scene << ": " << c.path << " = " << c.replaced_by;
    EXPECT_EQ(parsed.error.rfind(c.path + ": ", 0), 0u)
        << c.scene << ": " << c.path << " = " << c.replaced_by << "\n  got: " << parsed.error;
  }
  // fuzz_scene's find (an uncaught nlohmann::invalid_iterator from the key check).
  const ParsedScene found =
      parse_scene(R"({"name": "x", "convention": "gl", "camera": [1], "surfaces": []})");
  EXPECT_EQ(found.error, "camera: must be an object, not an array of 1");
}

#ifdef OBLIQUE_CLI
/// `oblique check ARGUMENTS`: its exit status (-1 when it did not exit, e.g. an abort) and what
/// it wrote to standard output and error.
int run_check_capturing(const std::string& arguments, std::string& output) {
  output.clear();
  FILE* pipe = popen((std::string(OBLIQUE_CLI) + " check " + arguments + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    output.append(buffer, n);
  const int raw = pclose(pipe);
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

// The same through the command: exit 2 (never an abort) with the file and the value's path.
// Every value of every bundled scene, each with one wrong kind (taking turns), and the 60-byte
// scene fuzz_scene found aborting `oblique check` (exit 134).
TEST(Scenes, cliRefusesAValueOfTheWrongKindAnywhereWithItsPath) {
  const std::string file = ::testing::TempDir() + "oblique_mistyped_scene.json";
  std::string output;
  std::ofstream(file) << R"({"name": "x", "convention": "gl", "camera": [1], "surfaces": []})";
  EXPECT_EQ(run_check_capturing(file, output), 2) << output;
  EXPECT_NE(output.find(file + ": camera: must be an object, not an array"), std::string::npos)
      << output;
  std::string previous;
  std::size_t values = 0, position = 0;
  for (const Mistyped& c : every_mistyped_bundled_scene()) {
    // One of the five wrong kinds per value here, the next one for the next value.
    if (c.scene + c.path != previous) ++values, position = 0;
    previous = c.scene + c.path;
    if (position++ != values % 5) continue;
    std::ofstream(file, std::ios::trunc) << c.text;
    EXPECT_EQ(run_check_capturing(file, output), 2)
        << c.scene << ": " << c.path << " = " << c.replaced_by << "\n"
        << output;
    EXPECT_NE(output.find(file + ": " + c.path + ": "), std::string::npos)
        << c.scene << ": " << c.path << " = " << c.replaced_by << "\n"
        << output;
  }
}

int run_check(const std::string& arguments) {
  const int raw =
      std::system((std::string(OBLIQUE_CLI) + " check " + arguments + " > /dev/null 2>&1").c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

TEST(Scenes, cliPrintsTheWarningsAndStillChecks) {
  const std::string file = ::testing::TempDir() + "oblique_fovy_radians.json";
  std::ofstream(file) << scene_with(
      "gl", R"("type": "perspective", "fovy_deg": 1.22, "aspect": 1.6, "near": 0.1, "far": 10)",
      R"("surfaces": [{"name": "m", "kind": "mirror", "plane": {"normal": [0, 0, 1], "point": [0, 0, -2]}}])");
  std::string output;
  EXPECT_EQ(run_check_capturing(file, output), 0) << output;
  EXPECT_NE(output.find(file + ": warning: camera.projection.fovy_deg: 1.22 degrees"),
            std::string::npos)
      << output;
}

// --html replaces a file of its name, never a device or a folder (it once replaced /dev/full).
TEST(Scenes, cliHtmlWritesOnlyAFile) {
  const std::string dir = OBLIQUE_SCENES_DIR;
  std::string output;
  EXPECT_EQ(run_check_capturing(dir + "/lake.json --html /dev/null", output), 2) << output;
  EXPECT_NE(output.find("names something other than a file"), std::string::npos) << output;
  EXPECT_TRUE(std::filesystem::exists("/dev/null") &&
              !std::filesystem::is_regular_file("/dev/null"));
  const std::string folder = ::testing::TempDir() + "oblique_html_folder";
  std::filesystem::create_directories(folder);
  EXPECT_EQ(run_check_capturing(dir + "/lake.json --html " + folder, output), 2) << output;
  EXPECT_TRUE(std::filesystem::is_directory(folder));
  // A name ending in a slash names a folder: refused before anything is made (it once left an
  // empty folder x.html/ behind).
  const std::string slashed = ::testing::TempDir() + "oblique_never_made.html/";
  std::filesystem::remove_all(slashed);
  EXPECT_EQ(run_check_capturing(dir + "/lake.json --html " + slashed, output), 2) << output;
  EXPECT_NE(output.find("it names a folder, not a file"), std::string::npos) << output;
  EXPECT_FALSE(std::filesystem::exists(slashed));
  const std::string page = ::testing::TempDir() + "oblique_page.html";
  std::ofstream(page) << "an earlier page\n";
  EXPECT_EQ(run_check_capturing(dir + "/lake.json --html " + page, output), 0) << output;
  EXPECT_NE(read_file(page).find("<canvas"), std::string::npos);
}

TEST(Scenes, cliExitStatus) {
  const std::string dir = OBLIQUE_SCENES_DIR;
  EXPECT_EQ(run_check(dir + "/lake.json"), 0);
  EXPECT_EQ(run_check("--json " + dir + "/mirror_behind_camera.json"), 0);
  EXPECT_EQ(run_check(dir + "/no-such-scene.json"), 2);
  const std::string broken = ::testing::TempDir() + "oblique_broken_scene.json";
  std::ofstream(broken) << "{\"name\": \"broken\", \"convention\": \"gl\"";
  EXPECT_EQ(run_check(broken), 2);
  // Numbers out of range, special files, a full disk: exit 2, never an abort.
  std::ofstream(broken, std::ios::trunc) << "[1e999]";
  EXPECT_EQ(run_check(broken), 2);
  EXPECT_EQ(run_check("/dev/zero"), 2);
  EXPECT_EQ(run_check(dir), 2);
  const int full = std::system(
      (std::string(OBLIQUE_CLI) + " check " + dir + "/lake.json > /dev/full 2>/dev/null").c_str());
  EXPECT_EQ(WIFEXITED(full) ? WEXITSTATUS(full) : -1, 2);
}

TEST(Scenes, cliImplJudgesTheUsersMatricesOnEveryPass) {
  const std::string dir = OBLIQUE_SCENES_DIR;
  // Our own `oblique apply` answers every pass correctly.
  EXPECT_EQ(
      run_check(dir + "/hall_of_mirrors.json --impl '" + std::string(OBLIQUE_CLI) + " apply'"), 0);
  // An implementation that answers the unchanged identity: the report names pass and property.
  const std::string out = ::testing::TempDir() + "oblique_check_impl.txt";
  const std::string identity = ::testing::TempDir() + "oblique_identity_impl.sh";
  std::ofstream(identity) << "while read line; do echo '{\"status\": \"ok\", \"projection\": "
                             "[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}'; done\n";
  const int raw =
      std::system((std::string(OBLIQUE_CLI) + " check " + dir +
                   "/hall_of_mirrors.json --impl 'sh " + identity + "' > " + out + " 2>&1")
                      .c_str());
  EXPECT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 1);
  const std::string text = read_file(out);
  EXPECT_NE(text.find("north mirror > south mirror: FAIL"), std::string::npos) << text;
  EXPECT_NE(text.find("FAIL near_is_clip_plane"), std::string::npos) << text;
  // One that answers nothing, or cannot be started: exit 2.
  EXPECT_EQ(run_check(dir + "/hall_of_mirrors.json --timeout 2 --impl 'cat > /dev/null'"), 2);
  EXPECT_EQ(run_check(dir + "/hall_of_mirrors.json --impl 'exit 3'"), 2);
  // One that answers each request twice: its lines are out of step with the requests, a protocol
  // error (exit 2), never a property judged against another request's plane (it was exit 1).
  const std::string twice = ::testing::TempDir() + "oblique_answers_twice.sh";
  std::ofstream(twice) << "while read -r line; do echo \"$line\" | " << OBLIQUE_CLI
                       << " apply; echo '{\"status\": \"invalid_input\"}'; done\n";
  std::string output;
  EXPECT_EQ(run_check_capturing(dir + "/hall_of_mirrors.json --impl 'sh " + twice + "'", output), 2)
      << output;
  EXPECT_NE(output.find("lines beyond one answer per request"), std::string::npos) << output;
  // An endless line, as the answer to the first request: said as such. (It waits for the request:
  // written before it, it is output nobody asked for, which check says otherwise.)
  EXPECT_EQ(
      run_check_capturing(
          dir + "/lake.json --timeout 2 --impl 'read -r line; head -c 3000000 /dev/zero'", output),
      2)
      << output;
  EXPECT_NE(output.find("an answer line longer than 1 MiB"), std::string::npos) << output;
}

TEST(Scenes, cliPlotWritesTwoViewsOrSaysWhyNot) {
  const std::string dir = OBLIQUE_SCENES_DIR;
  const std::string plot = ::testing::TempDir() + "oblique_check_plot";
  std::filesystem::remove_all(plot);
  EXPECT_EQ(run_check(dir + "/hall_of_mirrors.json --plot " + plot), 0);
  for (const char* file : {"top.png", "side.png", "scene.dat", "top.gp", "side.gp"})
    EXPECT_GT(std::filesystem::file_size(plot + "/" + file), 0u) << file;
  // A directory that cannot be made (under a regular file): exit 2, with a message.
  EXPECT_EQ(run_check(dir + "/lake.json --plot " + dir + "/lake.json/pictures"), 2);
  // A relative folder, as scripts/demo.sh gives it (gnuplot runs in the folder itself: the
  // scripts name their files relative to it).
  const std::string cwd = ::testing::TempDir(), relative = "oblique_check_plot_relative";
  std::filesystem::remove_all(cwd + relative);
  const int raw = std::system(("cd '" + cwd + "' && " + std::string(OBLIQUE_CLI) + " check " + dir +
                               "/lake.json --plot " + relative + " > /dev/null 2>&1")
                                  .c_str());
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << raw;
  for (const char* file : {"top.png", "side.png"})
    EXPECT_TRUE(std::filesystem::exists(cwd + relative + "/" + file)) << file;
}

// The picture explains the pass: the view across the water comes first, its camera and the
// mirrored one are labelled, the mirrored camera's volume is drawn with and without the oblique
// near plane, and the frame reaches where the view axis meets the water (z = -20), not the
// 500 m far plane, nor only the 10 m around the eye.
TEST(Scenes, cliPlotShowsTheCameraTheMirroredCameraAndTheObliqueVolume) {
  const std::string dir = OBLIQUE_SCENES_DIR;
  const std::string plot = ::testing::TempDir() + "oblique_check_plot_lake";
  std::filesystem::remove_all(plot);
  std::string output;
  ASSERT_EQ(run_check_capturing(dir + "/lake.json --plot " + plot, output), 0) << output;
  EXPECT_NE(output.find("picture: " + plot + "/side.png (across water reflection)"),
            std::string::npos)
      << output;
  // And the scene in 3D, one page beside the pictures.
  EXPECT_NE(output.find("page: " + plot + "/scene.html (in 3D)"), std::string::npos) << output;
  EXPECT_NE(read_file(plot + "/scene.html").find("<canvas"), std::string::npos);
  const std::string side = read_file(plot + "/side.gp");
  for (const char* expected : {"title 'water reflection (pass)'",
                               "title 'water reflection: without the oblique near plane'"})
    EXPECT_NE(side.find(expected), std::string::npos) << expected << "\n" << side;
  // The eye (0, 2, 10) and the mirrored one (0, -2, 10), at (z, y) in the side view.
  const auto label_at = [&](const std::string& text, double z, double y) {
    const std::string start = "set label '" + text + "' at ";
    const auto at = side.find(start);
    ASSERT_NE(at, std::string::npos) << text << "\n" << side;
    double got_z = 0, got_y = 0;
    ASSERT_EQ(std::sscanf(side.c_str() + at + start.size(), "%lf,%lf", &got_z, &got_y), 2);
    EXPECT_NEAR(got_z, z, 1e-9) << text;
    EXPECT_NEAR(got_y, y, 1e-9) << text;
  };
  label_at("camera", 10, 2);
  label_at("virtual camera (water reflection)", 10, -2);
  const auto range = [&](const std::string& axis) {
    const auto at = side.find("set " + axis + "range [");
    EXPECT_NE(at, std::string::npos) << side;
    double lo = 0, hi = 0;
    std::sscanf(side.c_str() + at + 12, "%lf:%lf", &lo, &hi);
    return std::pair{lo, hi};
  };
  const auto [z_lo, z_hi] = range("x");  // the side view's x axis is world z
  EXPECT_LT(z_lo, -20);
  EXPECT_GT(z_lo, -40);
  EXPECT_GT(z_hi, 10);
  EXPECT_LT(z_hi, 20);
}
#endif  // OBLIQUE_CLI

}  // namespace
}  // namespace oblique::scene
