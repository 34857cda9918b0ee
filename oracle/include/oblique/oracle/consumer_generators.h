// RapidCheck generators of the inputs the code around the matrix gets (consumer_cases.h, picked
// by RapidCheck so that failures shrink).
#pragma once

#include <rapidcheck.h>

#include "oblique/cases/generators.h"
#include "oblique/oracle/consumer_cases.h"

namespace oblique::generators {

template <class T>
rc::Gen<Vector4<T>> kept_point(const Matrix4<T>& m, const Vector4<T>& c, Convention convention) {
  return rc::gen::exec([=] { return consumer_cases::kept_point<T>(m, c, convention, rc_pick); });
}

template <class T>
rc::Gen<Matrix4<T>> rigid_view() {
  return rc::gen::exec([] { return consumer_cases::rigid_view<T>(rc_pick); });
}

template <class T>
rc::Gen<Vector4<T>> world_plane() {
  return rc::gen::exec([] { return consumer_cases::world_plane<T>(rc_pick); });
}

template <class T>
rc::Gen<Matrix4<T>> portal_frame() {
  return rc::gen::exec([] { return consumer_cases::portal_frame<T>(rc_pick); });
}

template <class T>
rc::Gen<consumer_cases::PassPlaneCase<T>> pass_plane_case() {
  return rc::gen::exec([] { return consumer_cases::pass_plane_case<T>(rc_pick); });
}

}  // namespace oblique::generators
