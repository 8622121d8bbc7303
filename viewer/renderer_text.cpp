// The renderer's words on the picture: ids, sequence numbers and the legend in the font (text.hpp), or,
// without a font, the sequence numbers as seven-segment line digits.
#include <glad/gl.h>

#include <algorithm>
#include <cstdint>
#include <glm/gtc/type_ptr.hpp>
#include <memory>
#include <string>
#include <vector>

#include "gl_helpers.hpp"
#include "renderer.hpp"
#include "text.hpp"

namespace cudahull::viewer {

namespace {
// Seven-segment digits: segments a (top) b c d (bottom) e f g (middle), as in a pocket calculator.
constexpr std::uint8_t kDigitSegments[10] = {0x3f, 0x06, 0x5b, 0x4f, 0x66, 0x6d, 0x7d, 0x07, 0x7f, 0x6f};
// Each segment in a 1 x 2 cell, (x0, y0, x1, y1), y up.
constexpr float kSegmentEnds[7][4] = {{0, 2, 1, 2}, {1, 2, 1, 1}, {1, 1, 1, 0}, {0, 0, 1, 0},
                                      {0, 0, 0, 1}, {0, 1, 0, 2}, {0, 1, 1, 1}};
}  // namespace

// Ids and sequence numbers in the font (text.hpp), centred on their points; those whose outward direction
// faces away from the eye are behind the hull and left out.  The legend in the view's bottom left corner.
void Renderer::draw_text(const ViewParams& view, const glm::mat4& view_proj) const {
  if (text_->pixel_height() != kTextPixels * view.pixel_scale)
    text_ = std::make_unique<TextRenderer>(kTextPixels * view.pixel_scale);
  text_->clear();
  const glm::vec3 eye = glm::vec3(glm::inverse(view.view)[3]);
  auto place = [&](const TextLabel& label) {
    const glm::vec3 p(label.x, label.y, label.z), outward(label.nx, label.ny, label.nz);
    const glm::vec4 clip = view_proj * glm::vec4(p, 1.0f);
    if (clip.w <= 0) return;
    // Silhouette faces and vertices, seen nearly edge-on, keep their labels.
    const float facing = glm::dot(outward, eye - p);
    if (facing < -0.2f * glm::length(outward) * glm::length(eye - p)) return;
    const float px = (clip.x / clip.w * 0.5f + 0.5f) * view.width + label.dx * view.pixel_scale,
                py = (0.5f - clip.y / clip.w * 0.5f) * view.height + label.dy * view.pixel_scale;
    if (px < 0 || py < 0 || px > view.width || py > view.height) return;
    text_->add_label(px, py, label.text, label.rgba);
  };
  for (const TextLabel& label : text_labels_)
    place(label);
  for (const OverlayLabel& label : labels_)
    // Below right of their edge or vertex, where the ids (above right) are not.
    place({label.x, label.y, label.z, 0, 0, 0, label.rgba, std::to_string(label.number), 9, 10});
  if (!legend_.empty()) {
    const float pad = 8 * view.pixel_scale, swatch = 12 * view.pixel_scale, line = text_->line_height();
    float widest = 0;
    for (const LegendRow& row : legend_)
      widest = std::max(widest, text_->width(row.text) + (row.heading ? 0 : swatch + pad));
    const float box_w = widest + 2 * pad, box_h = legend_.size() * line + 2 * pad;
    const float left = pad, top = view.height - pad - box_h;
    text_->add_rect(left, top, left + box_w, top + box_h, pack_rgba(0.05f, 0.05f, 0.06f, 0.82f));
    float y = top + pad;
    for (const LegendRow& row : legend_) {
      const float baseline = y + 0.5f * line + 0.35f * text_->ascent();
      if (row.heading) {
        text_->add_text(left + pad, baseline, row.text, pack_rgba(0.65f, 0.65f, 0.7f, 1.0f));
      } else {
        const float sy = y + 0.5f * (line - swatch);
        text_->add_rect(left + pad, sy, left + pad + swatch, sy + swatch,
                        pack_rgba(row.color.r, row.color.g, row.color.b, 1.0f));
        text_->add_text(left + 2 * pad + swatch, baseline, row.text, pack_rgba(0.92f, 0.92f, 0.92f, 1.0f));
      }
      y += line;
    }
  }
  text_->draw(view.width, view.height);
}

void Renderer::draw_labels(const ViewParams& view, const glm::mat4& view_proj) const {
  std::vector<OverlayVertex> lines;
  const float unit = 5.0f * view.pixel_scale;  // a digit is 5 x 10 pixels at scale 1
  for (const OverlayLabel& label : labels_) {
    const glm::vec4 clip = view_proj * glm::vec4(label.x, label.y, label.z, 1.0f);
    if (clip.w <= 0) continue;
    // Pixel coordinates of the anchor, then the digits to its upper right.
    float x = (clip.x / clip.w * 0.5f + 0.5f) * view.width + 3 * view.pixel_scale;
    const float y = (clip.y / clip.w * 0.5f + 0.5f) * view.height + 3 * view.pixel_scale;
    for (char ch : std::to_string(label.number)) {
      const std::uint8_t mask = kDigitSegments[ch - '0'];
      for (int seg = 0; seg < 7; ++seg) {
        if (!(mask & (1u << seg))) continue;
        const float* e = kSegmentEnds[seg];
        for (int end = 0; end < 2; ++end) {
          const float px = x + e[2 * end] * unit, py = y + e[2 * end + 1] * unit;
          lines.push_back({2 * px / view.width - 1, 2 * py / view.height - 1, 0.0f, label.rgba});
        }
      }
      x += 1.75f * unit;
    }
  }
  if (lines.empty()) return;
  ensure_capacity(label_buffer_, label_capacity_, lines.size() * sizeof(OverlayVertex));
  glNamedBufferSubData(label_buffer_, 0, static_cast<GLsizeiptr>(lines.size() * sizeof(OverlayVertex)),
                       lines.data());
  const glm::mat4 identity(1.0f);
  glUniformMatrix4fv(loc(overlay_program_, "u_view_proj"), 1, GL_FALSE, glm::value_ptr(identity));
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(label_vao_);
  glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(lines.size()));
  glEnable(GL_DEPTH_TEST);
}

}  // namespace cudahull::viewer
