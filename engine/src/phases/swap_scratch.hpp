// The swap rounds' per-candidate outcomes and buffers (swaps.cpp), kept from one iteration to the next:
// fresh arrays of this size would cost page faults every time.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "cudahull/parallel.hpp"
#include "phases/swaps.hpp"

namespace cudahull::phases {

// A swap tried without changing the mesh.
struct SwapTrial {
  enum Outcome : std::uint8_t { kNothing, kValid, kRejected };
  Outcome outcome = kNothing;
  SwapKind verdict = SwapKind::kRegular;  // a rejection's reason
  bool beneath_inside = false;            // a foldover's vertex beneath is proven inside the hull
  bool winner = false;                    // a valid swap that holds all its claims this round
  FaceId other_face = kNoFace;            // g, the face across the edge
  SwapRecord swap;
};

struct SwapScratch {
  // Per block of kNumberingBlock candidates: how many won, lost, were rejected, and won as regular swaps;
  // after number_outcomes(), the same counts before the block.
  struct BlockCount {
    std::size_t winners = 0, losers = 0, rejected = 0, regular = 0;
  };
  static constexpr std::size_t kNumberingBlock = 4096;

  std::vector<SwapTrial> trials;               // per candidate
  std::vector<std::pair<FaceId, int>> made;    // per winner: face and edge
  std::vector<std::pair<FaceId, int>> single;  // try_swap()'s batch of one (kept: no allocation a swap)
  std::vector<std::size_t> candidate_of;       // per winner: its candidate
  std::vector<std::size_t> rejected_at;        // per rejection: its candidate
  std::vector<std::size_t> wins_before;        // per rejection: the winners before it
  std::vector<std::size_t> recorded;           // the candidates of the recorded rejections
  std::vector<BlockCount> counts;
  BlockCount totals;  // the round's, from number_outcomes()
  // Claims, (round << 32 | candidate): per face id, and per hashed new edge (used through atomic_ref).
  std::unique_ptr<std::uint64_t[]> face_claims, edge_claims;
  std::size_t face_claim_count = 0, edge_claim_bits = 0;
  std::uint64_t claim_round = 0;

  // Grown tables are zeroed on all cores: a serial clear of 100 MB would cost more than a round.
  static void zero(std::uint64_t* table, std::size_t count) {
    parallel_chunks(count, hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
      std::fill(table + begin, table + end, std::uint64_t{0});
    });
  }
  void grow_claims(std::size_t faces, std::size_t edges) {
    if (faces > face_claim_count) {
      face_claim_count = std::max(faces, face_claim_count + face_claim_count / 2);
      face_claims.reset(new std::uint64_t[face_claim_count]);
      zero(face_claims.get(), face_claim_count);
    }
    std::size_t bits = 12;
    while ((std::size_t{1} << bits) < 2 * edges)
      ++bits;
    if (bits > edge_claim_bits) {
      edge_claims.reset(new std::uint64_t[std::size_t{1} << bits]);
      zero(edge_claims.get(), std::size_t{1} << bits);
      edge_claim_bits = bits;
    }
  }
  std::atomic_ref<std::uint64_t> face_claim(FaceId f) {
    return std::atomic_ref<std::uint64_t>(face_claims[f]);
  }
  std::atomic_ref<std::uint64_t> edge_claim(PointIndex a, PointIndex b) {
    const std::uint64_t key = static_cast<std::uint64_t>(std::min(a, b)) << 32 | std::max(a, b);
    return std::atomic_ref<std::uint64_t>(
        edge_claims[(key * 0x9E3779B97F4A7C15ull) >> (64 - edge_claim_bits)]);
  }

  // Counts the round's outcomes per block, turns `counts` into each block's offsets, and returns the totals.
  BlockCount number_outcomes(const std::vector<SwapCandidate>& candidates, unsigned workers) {
    const std::size_t count = candidates.size(), blocks = (count + kNumberingBlock - 1) / kNumberingBlock;
    counts.resize(blocks);
    parallel_chunks(
        blocks, workers,
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t b = begin; b < end; ++b) {
            BlockCount c;
            for (std::size_t k = b * kNumberingBlock; k < std::min(count, (b + 1) * kNumberingBlock); ++k) {
              const SwapTrial& t = trials[k];
              if (t.winner) {
                ++c.winners;
                c.regular += candidates[k].kind == SwapKind::kRegular;
              } else if (t.outcome == SwapTrial::kRejected) {
                ++c.rejected;
              } else if (t.outcome == SwapTrial::kValid) {
                ++c.losers;
              }
            }
            counts[b] = c;
          }
        },
        4);
    BlockCount total;
    for (BlockCount& c : counts) {
      const BlockCount here = c;
      c = total;
      total.winners += here.winners, total.losers += here.losers, total.rejected += here.rejected;
      total.regular += here.regular;
    }
    totals = total;
    return total;
  }

  // From the offsets: the winners (made, candidate_of), the rejections (rejected_at, wins_before) and the
  // losers, which go first into `next` (sized by the caller).
  void collect(const std::vector<SwapCandidate>& candidates, std::vector<SwapCandidate>& next,
               unsigned workers) {
    const std::size_t count = candidates.size();
    made.resize(totals.winners);
    candidate_of.resize(totals.winners);
    rejected_at.resize(totals.rejected);
    wins_before.resize(totals.rejected);
    parallel_chunks(
        counts.size(), workers,
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t b = begin; b < end; ++b) {
            BlockCount at = counts[b];
            for (std::size_t k = b * kNumberingBlock; k < std::min(count, (b + 1) * kNumberingBlock); ++k) {
              const SwapTrial& t = trials[k];
              if (t.winner) {
                candidate_of[at.winners] = k;
                made[at.winners++] = {candidates[k].edge.face, candidates[k].edge.index};
              } else if (t.outcome == SwapTrial::kRejected) {
                rejected_at[at.rejected] = k;
                wins_before[at.rejected++] = at.winners;
              } else if (t.outcome == SwapTrial::kValid) {
                next[at.losers++] = candidates[k];
              }
            }
          }
        },
        4);
  }
};

}  // namespace cudahull::phases
