// The camera (libigl's ViewerCore, in GLM): an orbit around a target point with pan and zoom, fit to the
// data, reset to the fitted view, and copy/paste as JSON (polyscope's "camera views as JSON").
//
// Y is up.  Angles are in degrees; yaw 0 and pitch 0 look along -Z.  The JSON form is
//   {"target": [x, y, z], "yaw": deg, "pitch": deg, "distance": d, "fov": deg}
// and from_json() accepts any subset of those keys (the rest keep their values), rejecting wrong types and
// out-of-range values with std::invalid_argument.
#pragma once

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace cudahull::viewer {

class Camera {
 public:
  // Frames the box [lo, hi] and remembers that view for reset().
  void fit(const glm::vec3& lo, const glm::vec3& hi);
  void reset() { *this = home_view(); }
  // Looks at a sphere of `radius` around `center` (the debugger's "frame this case"), keeping the angles.
  void frame(const glm::vec3& center, float radius);

  // Mouse motion in logical pixels over a viewport `height` logical pixels tall.
  void orbit(float dx, float dy, float height);
  void pan(float dx, float dy, float height);
  void zoom(float wheel_steps);  // positive: closer

  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;
  glm::vec3 eye() const;

  nlohmann::json to_json() const;
  void from_json(const nlohmann::json& j);

  float yaw() const { return yaw_; }
  float pitch() const { return pitch_; }
  float distance() const { return distance_; }
  glm::vec3 target() const { return target_; }

 private:
  Camera home_view() const;

  glm::vec3 target_{0.0f};
  float yaw_ = 25.0f, pitch_ = -20.0f;
  float distance_ = 3.0f;
  float fov_ = 40.0f;
  float radius_ = 1.0f;  // of the data, for the clip planes
  glm::vec3 home_target_{0.0f};
  float home_distance_ = 3.0f;
};

}  // namespace cudahull::viewer
