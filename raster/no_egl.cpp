// A build without EGL and OpenGL: every way in to the rasterizer says what to install.
#include "oblique/raster/case_scene.h"
#include "oblique/raster/raster.h"

namespace oblique::raster {

namespace {
constexpr const char* kNoEgl =
    "no EGL: this oblique was built without EGL and OpenGL; install libegl-dev libgl-dev "
    "libopengl-dev libegl-mesa0 libgl1-mesa-dri (bash scripts/setup.sh) and build again";
}  // namespace

NoShaderCache::NoShaderCache() : ours_(false) {}
NoShaderCache::~NoShaderCache() = default;

struct GlContext::State {};
GlContext::GlContext(std::unique_ptr<State> state) : state_(std::move(state)) {}
GlContext::~GlContext() = default;
Expected<std::unique_ptr<GlContext>> GlContext::open(Device) {
  return Expected<std::unique_ptr<GlContext>>::failure(kNoEgl);
}
bool GlContext::make_current(std::string* error) {
  if (error) *error = kNoEgl;
  return false;
}
const std::string& GlContext::renderer() const {
  static const std::string none;
  return none;
}
Device GlContext::device() const {
  return Device::software;
}

struct Rasterizer::State {
  Options options;
  std::string renderer;
};

Rasterizer::Rasterizer(std::unique_ptr<State> state) : state_(std::move(state)) {}
Rasterizer::~Rasterizer() = default;
const std::string& Rasterizer::renderer() const {
  return state_->renderer;
}
const Options& Rasterizer::options() const {
  return state_->options;
}

Expected<Readback> Rasterizer::render(const Frame&, const Eigen::Matrix4d&, Convention,
                                      DepthBuffer) {
  return Expected<Readback>::failure("no EGL in this build");
}

Expected<AxisDepth> Rasterizer::axis_depth(const Eigen::Matrix4d&, const Eigen::Vector4d&,
                                           const Eigen::Matrix4d&, Convention, DepthBuffer) {
  return Expected<AxisDepth>::failure("no EGL in this build");
}

Expected<std::vector<std::optional<double>>> Rasterizer::stored_depths(
    const Eigen::Matrix4d&, const std::vector<Eigen::Vector4d>&, Convention, DepthBuffer) {
  return Expected<std::vector<std::optional<double>>>::failure("no EGL in this build");
}

Result Rasterizer::check(const Eigen::Matrix4d&, const Eigen::Vector4d&, const Eigen::Matrix4d&,
                         Convention, DepthBuffer, std::uint64_t, int) {
  Result r;
  r.why = "no EGL in this build";
  return r;
}

Expected<Readback> Rasterizer::render(const PreparedCheck& p, double*) {
  return Expected<Readback>::failure(p.why.empty() ? "no EGL in this build" : p.why);
}

Result Rasterizer::check(const PreparedCheck&) {
  Result r;
  r.why = "no EGL in this build";
  return r;
}

Expected<std::shared_ptr<Rasterizer>> Rasterizer::open(const Options&) {
  return Expected<std::shared_ptr<Rasterizer>>::failure(kNoEgl);
}

Expected<unsigned> link_program(const char*, const char*) {
  return Expected<unsigned>::failure(kNoEgl);
}

float set_engine_depth(Convention convention) {
  return convention == Convention::reversed_z ? 0.0f : 1.0f;
}

std::string gl_error_after(const char*) {
  return kNoEgl;
}

Expected<Render> draw_mesh(GlContext&, const Mesh&, const Eigen::Matrix4d&, Convention, DepthBuffer,
                           int) {
  return Expected<Render>::failure(kNoEgl);
}

Expected<CaseRenders> render_case(const Eigen::Matrix4d&, const Eigen::Vector4d&,
                                  const Eigen::Matrix4d&, const Eigen::Matrix4d&, Convention,
                                  const std::vector<Eigen::Vector4d>&, int) {
  return Expected<CaseRenders>::failure(kNoEgl);
}

}  // namespace oblique::raster
