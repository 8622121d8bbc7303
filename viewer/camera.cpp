#include "camera.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>
#include <string>

namespace cudahull::viewer {

namespace {

constexpr float kDefaultYaw = 25.0f, kDefaultPitch = -20.0f;

float finite_number(const nlohmann::json& j, const char* key) {
  const auto& v = j.at(key);
  if (!v.is_number()) throw std::invalid_argument(std::string("camera: \"") + key + "\" must be a number");
  const float x = v.get<float>();
  if (!std::isfinite(x)) throw std::invalid_argument(std::string("camera: \"") + key + "\" must be finite");
  return x;
}

}  // namespace

void Camera::fit(const glm::vec3& lo, const glm::vec3& hi) {
  target_ = 0.5f * (lo + hi);
  radius_ = std::max(0.5f * glm::length(hi - lo), 1e-6f);
  // The bounding sphere just fits the vertical field of view, with a margin.
  distance_ = 1.15f * radius_ / std::sin(glm::radians(0.5f * fov_));
  yaw_ = kDefaultYaw;
  pitch_ = kDefaultPitch;
  home_target_ = target_;
  home_distance_ = distance_;
}

void Camera::frame(const glm::vec3& center, float radius) {
  target_ = center;
  distance_ = 1.15f * std::max(radius, 1e-6f) / std::sin(glm::radians(0.5f * fov_));
}

Camera Camera::home_view() const {
  Camera c = *this;
  c.target_ = home_target_;
  c.distance_ = home_distance_;
  c.yaw_ = kDefaultYaw;
  c.pitch_ = kDefaultPitch;
  c.fov_ = 40.0f;
  return c;
}

void Camera::orbit(float dx, float dy, float height) {
  const float degrees_per_pixel = 180.0f / std::max(height, 1.0f);
  yaw_ = std::remainder(yaw_ - dx * degrees_per_pixel, 360.0f);
  pitch_ = std::clamp(pitch_ - dy * degrees_per_pixel, -89.0f, 89.0f);
}

void Camera::pan(float dx, float dy, float height) {
  // The target moves with the cursor: a pixel is this much world at the target's depth.
  const float world_per_pixel =
      2.0f * distance_ * std::tan(glm::radians(0.5f * fov_)) / std::max(height, 1.0f);
  const glm::mat4 v = view();
  const glm::vec3 right(v[0][0], v[1][0], v[2][0]), up(v[0][1], v[1][1], v[2][1]);
  target_ += (-dx * right + dy * up) * world_per_pixel;
}

void Camera::zoom(float wheel_steps) {
  distance_ = std::clamp(distance_ * std::pow(0.85f, wheel_steps), radius_ * 1e-3f, radius_ * 1e3f);
}

glm::vec3 Camera::eye() const {
  const float yaw = glm::radians(yaw_), pitch = glm::radians(pitch_);
  const glm::vec3 forward(-std::sin(yaw) * std::cos(pitch), std::sin(pitch),
                          -std::cos(yaw) * std::cos(pitch));
  return target_ - distance_ * forward;
}

glm::mat4 Camera::view() const {
  return glm::lookAt(eye(), target_, glm::vec3(0.0f, 1.0f, 0.0f));
}

glm::mat4 Camera::projection(float aspect) const {
  const float far_plane = distance_ + 3.0f * radius_;
  const float near_plane = std::max(far_plane * 1e-4f, distance_ - 3.0f * radius_);
  return glm::perspective(glm::radians(fov_), std::max(aspect, 1e-3f), near_plane, far_plane);
}

nlohmann::json Camera::to_json() const {
  return {{"target", {target_.x, target_.y, target_.z}},
          {"yaw", yaw_},
          {"pitch", pitch_},
          {"distance", distance_},
          {"fov", fov_}};
}

void Camera::from_json(const nlohmann::json& j) {
  if (!j.is_object()) throw std::invalid_argument("camera: expected a JSON object");
  Camera c = *this;
  for (const auto& [key, value] : j.items()) {
    if (key == "target") {
      if (!value.is_array() || value.size() != 3)
        throw std::invalid_argument("camera: \"target\" must be an array of 3 numbers");
      for (int i = 0; i < 3; ++i) {
        if (!value[i].is_number() || !std::isfinite(value[i].get<float>()))
          throw std::invalid_argument("camera: \"target\" must be an array of 3 finite numbers");
        c.target_[i] = value[i].get<float>();
      }
    } else if (key == "yaw") {
      c.yaw_ = finite_number(j, "yaw");
    } else if (key == "pitch") {
      c.pitch_ = finite_number(j, "pitch");
      if (c.pitch_ < -89.0f || c.pitch_ > 89.0f)
        throw std::invalid_argument("camera: \"pitch\" must be in [-89, 89]");
    } else if (key == "distance") {
      c.distance_ = finite_number(j, "distance");
      if (c.distance_ <= 0) throw std::invalid_argument("camera: \"distance\" must be positive");
    } else if (key == "fov") {
      c.fov_ = finite_number(j, "fov");
      if (c.fov_ < 1.0f || c.fov_ > 170.0f)
        throw std::invalid_argument("camera: \"fov\" must be in [1, 170]");
    } else {
      throw std::invalid_argument("camera: unknown key \"" + key + "\" (target, yaw, pitch, distance, fov)");
    }
  }
  // A view pasted from another data set may be far away; keep the clip planes covering it.
  c.radius_ = std::max(c.radius_, 1e-6f);
  *this = c;
}

}  // namespace cudahull::viewer
