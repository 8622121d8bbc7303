// A slot of the batch kernel's team on the host (tests of issue 27): the arrays a team's slot has on the
// device, filled with stale data as a slot that served other clouds holds, and a cloud's run through
// batch_hull() or small_hull() on HostTeam, the host twin of the device's teams.
#pragma once

#include <array>
#include <vector>

#include "cudahull/resident/small_hull.hpp"
#include "cudahull/types.hpp"

namespace cudahull::testing {

template <class Point>
struct HostBatchSlot {
  std::vector<resident::u32> fv, fn, fv_spare, fn_spare, replaced_by, revisit, flags, face_rank, win_mask,
      word_rank, list, point_words, words, used{0, 0};
  std::vector<resident::u64> extreme, claim;
  std::vector<resident::Entry> entries;
  std::vector<resident::Candidate> cands;
  resident::RoundsState st{};
  std::vector<Point> coordinates;
  resident::BatchSlot slot{};
  // Room for a hull of `vertices` vertices, as batch_hull()'s slots have it, or small_hull()'s (`small`).
  HostBatchSlot(resident::u32 vertices, std::size_t points, bool small = false) {
    const resident::BatchRoom room =
        small ? resident::small_hull_room(vertices) : resident::batch_room(vertices);
    for (auto* b : {&fv, &fn, &fv_spare, &fn_spare})
      b->assign(3 * room.faces, 0xdeadbeefu);  // stale data, as a slot reused on the device holds
    for (auto* b : {&replaced_by, &revisit, &flags, &face_rank})
      b->assign(room.faces + 1, 0xdeadbeefu);
    win_mask.assign(room.faces / 32 + 1, 0);
    word_rank.assign(room.faces / 32 + 1, 0);
    extreme.assign(room.faces, ~0ull);
    claim.assign(room.faces, ~0ull);
    entries.resize(room.entries);
    list.resize(room.work);
    cands.resize(room.work);
    point_words.assign(6 * points, 0xdeadbeefu);
    words.resize(7 * std::size_t{vertices} + 16);
    coordinates.resize(vertices);
    slot = resident::BatchSlot{fv.data(),
                               fn.data(),
                               fv_spare.data(),
                               fn_spare.data(),
                               replaced_by.data(),
                               revisit.data(),
                               flags.data(),
                               face_rank.data(),
                               win_mask.data(),
                               word_rank.data(),
                               extreme.data(),
                               claim.data(),
                               entries.data(),
                               list.data(),
                               cands.data(),
                               &st,
                               room};
  }
  // The cloud's hull by batch_hull(), or by small_hull() (`small`), on `team`.
  template <class Team = resident::HostTeam>
  resident::BatchResult run(const std::vector<Point>& points, bool small = false, const Team& team = {}) {
    const std::size_t n = points.size();
    resident::u32* w = point_words.data();
    const resident::BatchCloud<Point> cloud{
        points.data(), static_cast<resident::u32>(n), w, w + n, w + 2 * n, w + 3 * n, w + 4 * n, w + 5 * n};
    used = {0, 0};
    const resident::BatchOutput<Point> out{words.data(), coordinates.data(), used.data(),
                                           static_cast<resident::u32>(words.size()),
                                           static_cast<resident::u32>(coordinates.size())};
    resident::BatchResult result{};
    if (small)
      resident::small_hull(team, slot, cloud, out, &result);
    else
      resident::batch_hull(team, slot, cloud, out, &result);
    return result;
  }
};

// A cloud's faces on its own indices, from a done run's output (`slot.words`: corners into the vertex list,
// then the list).
template <class Point>
std::vector<std::array<PointIndex, 3>> host_batch_faces(const HostBatchSlot<Point>& slot,
                                                        const resident::BatchResult& result) {
  const resident::u32* words = slot.words.data() + result.word_at;
  const resident::u32* ids = words + 3 * result.faces;
  std::vector<std::array<PointIndex, 3>> faces;
  for (resident::u32 f = 0; f < result.faces; ++f)
    faces.push_back({static_cast<PointIndex>(ids[words[3 * f]]),
                     static_cast<PointIndex>(ids[words[3 * f + 1]]),
                     static_cast<PointIndex>(ids[words[3 * f + 2]])});
  return faces;
}

}  // namespace cudahull::testing
