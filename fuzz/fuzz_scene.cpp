// libFuzzer target: the scene reader and checker of `oblique check`. The bytes are a scene file.
// A scene is either refused with a message, or read and checked: every surface gets a decision
// with a reason when skipped, every rendered pass a finite projection, and the table and JSON
// outputs are written (the JSON must parse back) without a crash.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "oblique/report/views.h"
#include "oblique/scene/check.h"
#include "oblique/scene/scene.h"

namespace {

[[noreturn]] void fail(const char* what, const std::string& detail) {
  std::fprintf(stderr, "scene contract violated: %s\n%s\n", what, detail.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace oblique::scene;
  using oblique::report::Segment;
  using oblique::report::volume_edges;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const ParsedScene parsed = parse_scene(text);
  if (!parsed.scene) {
    if (parsed.error.empty()) fail("a refused scene without a message", std::string(text));
    return 0;
  }
  const Scene& scene = *parsed.scene;
  if (!scene.camera.projection.allFinite() || !scene.camera.view.allFinite())
    fail("an accepted camera with a non-finite matrix", std::string(text));
  const SceneCheck check = check_scene(scene);
  std::size_t first_level = 0;
  for (const SurfaceCheck& s : check.surfaces) first_level += s.level == 1 ? 1 : 0;
  if (!check.truncated && check.unlisted == 0 && first_level != scene.surfaces.size())
    fail("a surface without a decision", std::string(text));
  // At most kMaxPasses visible passes, and out-of-view surfaces listed while the list had room.
  if (check.surfaces.size() > 2 * kMaxPasses)
    fail("more passes than kMaxPasses", std::string(text));
  for (const SurfaceCheck& s : check.surfaces) {
    if (!s.render && s.reason.empty()) fail("a skipped surface without a reason", s.name);
    if (s.level > scene.max_depth + 1) fail("a pass beyond the depth limit", s.name);
    if (s.render && (!s.projection || !s.projection->allFinite()))
      fail("a rendered pass without a finite projection", s.name);
    if (s.render && s.level > scene.max_depth) fail("a pass rendered beyond max_depth", s.name);
    if (s.scissor &&
        !(s.scissor->x0 >= -1 && s.scissor->x0 <= s.scissor->x1 && s.scissor->x1 <= 1 &&
          s.scissor->y0 >= -1 && s.scissor->y0 <= s.scissor->y1 && s.scissor->y1 <= 1))
      fail("a scissor outside the screen", s.name);
    // The picture's geometry: finite segments (or none).
    if (s.render) {
      for (const Segment& seg : volume_edges(s.view, *s.projection, scene.convention, 100)) {
        if (!seg.a.allFinite() || !seg.b.allFinite()) fail("a non-finite picture edge", s.name);
      }
    }
  }
  const std::string json_text = to_json(check);
  if (!nlohmann::json::accept(json_text)) fail("--json output that is not JSON", json_text);
  const std::string table = to_text(check);
  for (const char ch : table) {
    if (ch != '\n' && static_cast<unsigned char>(ch) < 0x20)
      fail("a control character in the table", table);
  }
  return 0;
}
