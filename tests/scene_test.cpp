// oblique check: the bundled scenes' verdicts, a held-out set of scenes against independent
// geometry and the exact oblique matrix, and clear errors for broken scene files.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "oblique/properties/properties.h"
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
    const properties::Problem<double> problem(scene.camera.projection, s.plane_in_camera,
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
    const SceneCheck check = check_scene(*parsed.scene);
    EXPECT_EQ(actions(check), c.actions) << c.what;
    expect_exact(*parsed.scene, check);
    for (std::size_t i = 0; i < check.surfaces.size(); ++i) {
      if (parsed.scene->surfaces[i].kind == SurfaceKind::mirror)
        expect_mirrored_view(*parsed.scene, check.surfaces[i], parsed.scene->surfaces[i]);
    }
  }
}

TEST(Scenes, infiniteEdgePropertyIsCheckedOnlyForInfiniteProjections) {
  auto names = [](const SceneCheck& check) {
    std::vector<std::string> out;
    for (const properties::Finding& p : check.surfaces.at(0).properties) out.push_back(p.kind);
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
      {with("\"surfaces\": []", "\"surfaces\": [{\"name\": \"m\", \"kind\": \"portal\"}]"),
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

#ifdef OBLIQUE_CLI
int run_check(const std::string& arguments) {
  const int raw =
      std::system((std::string(OBLIQUE_CLI) + " check " + arguments + " > /dev/null 2>&1").c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
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
#endif  // OBLIQUE_CLI

}  // namespace
}  // namespace oblique::scene
