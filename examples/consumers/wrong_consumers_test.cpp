// Each wrong function of consumers.h, alone, under the contract of the engine it comes from;
// CTest runs one test at a time and expects it caught by its property
// (expect_consumer_caught.cmake).
#include <oblique/testing.h>

#include "consumers.h"

namespace {

using oblique::Consumers;
using oblique::Contract;
using oblique::Convention;

template <class F>
Consumers<float> only(const char* name, F set) {
  Consumers<float> c;
  c.name = name;
  set(c);
  return c;
}

Contract perspective_in(Convention convention) {
  Contract c;
  c.families = {oblique::cases::Family::perspective};
  c.conventions = {convention};
  return c;
}

}  // namespace

OBLIQUE_CONSUMERS_TEST(WrongConsumers, reconstructsWithOriginal,
                       only("reconstructs_with_original",
                            [](auto& c) {
                              c.view_position = engine_consumers::reconstructs_with_original<float>;
                            }),
                       Contract{})
OBLIQUE_CONSUMERS_TEST(WrongConsumers, worldWithOriginal,
                       only("world_with_original",
                            [](auto& c) {
                              c.world_position = engine_consumers::world_with_original<float>;
                            }),
                       Contract{})
OBLIQUE_CONSUMERS_TEST(WrongConsumers, linearisesWithNearFar,
                       only("linearises_with_near_far",
                            [](auto& c) {
                              c.linear_depth = engine_consumers::linearises_with_near_far<float>;
                            }),
                       perspective_in(Convention::zero_one))
OBLIQUE_CONSUMERS_TEST(WrongConsumers, glPlanesOnAnyMatrix,
                       only("gl_planes_on_any_matrix",
                            [](auto& c) {
                              c.culling_planes = engine_consumers::gl_planes_on_any_matrix<float>;
                            }),
                       perspective_in(Convention::zero_one))
OBLIQUE_CONSUMERS_TEST(WrongConsumers, planesOfTranspose,
                       only("planes_of_transpose",
                            [](auto& c) {
                              c.culling_planes = engine_consumers::planes_of_transpose<float>;
                            }),
                       Contract{})
OBLIQUE_CONSUMERS_TEST(WrongConsumers, planeWithoutTranslation,
                       only("plane_without_translation",
                            [](auto& c) {
                              c.camera_plane = engine_consumers::plane_without_translation<float>;
                            }),
                       Contract{})
OBLIQUE_CONSUMERS_TEST(WrongConsumers, planeFlippedForMirrors,
                       only("plane_flipped_for_mirrors",
                            [](auto& c) {
                              c.camera_plane = engine_consumers::plane_flipped_for_mirrors<float>;
                            }),
                       Contract{})
OBLIQUE_CONSUMERS_TEST(WrongConsumers, mirrorByReflectedLookAt,
                       only("mirror_by_reflected_look_at",
                            [](auto& c) {
                              c.mirror_view = engine_consumers::mirror_by_reflected_look_at<float>;
                            }),
                       Contract{})
OBLIQUE_CONSUMERS_TEST(WrongConsumers, portalWithoutTurn,
                       only("portal_without_turn",
                            [](auto& c) {
                              c.portal_view = engine_consumers::portal_without_turn<float>;
                            }),
                       Contract{})
OBLIQUE_CONSUMERS_TEST(WrongConsumers, cornersOfObliqueMatrix,
                       only("corners_of_oblique_matrix",
                            [](auto& c) {
                              c.corners = engine_consumers::corners_of_oblique_matrix<float>;
                            }),
                       Contract{})
