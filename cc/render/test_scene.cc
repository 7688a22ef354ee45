#include "cc/render/test_scene.h"

#include "cc/kdtree/test_scenes.h"

namespace kdtree {
namespace testing {

TriangleSoup SphereOnGround(float scale) {
  TriangleSoup soup = BumpySphere(3, 5);
  const float g = -1.2f, e = 4.0f;
  soup.Add({-e, g, -e}, {-e, g, e}, {e, g, e});
  soup.Add({-e, g, -e}, {e, g, e}, {e, g, -e});
  for (Vec3& v : soup.v) v = v * scale;
  return soup;
}

View SphereView(int width, int height, float scale, bool with_light) {
  View view;
  view.camera.position = Vec3(0.3f, 1.5f, 5.0f) * scale;
  view.camera.look_at = Vec3(0.0f, -0.4f, 0.0f) * scale;
  view.camera.up = Vec3(0, 1, 0);
  view.camera.fov_deg = 45.0f;
  view.width = width;
  view.height = height;
  if (with_light) view.lights.push_back(PointLight{Vec3(-3.0f, 5.0f, 2.0f) * scale});
  return view;
}

}  // namespace testing
}  // namespace kdtree
