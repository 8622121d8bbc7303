// The CUDA backend's prepared planes (routing.hpp) against face_verdict() and face_height() on the host.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "cudahull/predicates.hpp"
#include "cudahull/routing.hpp"
#include "support/exact_reference.hpp"

namespace cudahull {
namespace {

// ---------------------------------------------------------------------------------------------------------
// The CUDA backend's prepared planes (routing.hpp, face_verdict_prepared): the same verdict and exit edge as
// face_verdict() and the same height bits as face_height(), on faces and points made to be degenerate.

TEST(PreparedPlanes, SameVerdictAndHeightAsFaceVerdict) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1), param(-2, 2);
  std::uniform_int_distribution<int> scale(-30, 30), kind(0, 5), ulps(-2, 2), bits(1, 12);
  const float kPool[] = {0.f, 1.f, -1.f, 1e30f, -1e30f, 1e-30f, 3e38f, -3e38f, 1e-40f, 7e-45f};
  int verdicts[3] = {0, 0, 0};
  unsigned long long fallbacks = 0;  // orient3d calls made by face_verdict_prepared
  const int cases = 200000;
  for (int i = 0; i < cases; ++i) {
    const double sc = std::ldexp(1.0, scale(rng));
    auto rp = [&] { return std::array<double, 3>{unit(rng) * sc, unit(rng) * sc, unit(rng) * sc}; };
    auto to_float = [](const std::array<double, 3>& p) {
      return Point3{float(p[0]), float(p[1]), float(p[2])};
    };
    FaceGeometry face{};
    Vec3d c;
    Point3 x;
    const int k = kind(rng);
    if (k == 5) {  // extreme magnitudes, mixed
      std::uniform_int_distribution<std::size_t> pick(0, std::size(kPool) - 1);
      auto p = [&] { return Point3{kPool[pick(rng)], kPool[pick(rng)], kPool[pick(rng)]}; };
      face.v[0] = p(), face.v[1] = p(), face.v[2] = p();
      const Point3 q = p();
      c = {(double(face.v[0].x) + face.v[1].x + face.v[2].x + q.x) / 4,
           (double(face.v[0].y) + face.v[1].y + face.v[2].y + q.y) / 4,
           (double(face.v[0].z) + face.v[1].z + face.v[2].z + q.z) / 4};
      x = p();
    } else {
      std::array<double, 3> v[3] = {rp(), rp(), rp()};
      if (k == 4) {  // few significant bits: exact coplanarities everywhere
        const int nb = bits(rng);
        for (auto& p : v)
          for (double& t : p)
            t = std::ldexp(std::round(std::ldexp(t / sc, nb)), -nb) * sc;
      }
      for (int j = 0; j < 3; ++j)
        face.v[j] = to_float(v[j]);
      const std::array<double, 3> q = rp();
      c = {(double(face.v[0].x) + face.v[1].x + face.v[2].x + float(q[0])) / 4,
           (double(face.v[0].y) + face.v[1].y + face.v[2].y + float(q[1])) / 4,
           (double(face.v[0].z) + face.v[1].z + face.v[2].z + float(q[2])) / 4};
      std::array<double, 3> target{};
      const double s = param(rng), t = param(rng);
      double inside[3] = {std::fabs(unit(rng)), std::fabs(unit(rng)), std::fabs(unit(rng))};
      const double sum = inside[0] + inside[1] + inside[2] + std::fabs(unit(rng));
      for (double& w : inside)
        w /= sum;
      const double cc[3] = {c.x, c.y, c.z};
      const int edge = static_cast<int>(rng() % 3);
      for (int j = 0; j < 3; ++j) {
        const double a = j == 0 ? face.v[edge].x : (j == 1 ? face.v[edge].y : face.v[edge].z);
        const int e2 = (edge + 1) % 3;
        const double b = j == 0 ? face.v[e2].x : (j == 1 ? face.v[e2].y : face.v[e2].z);
        const double v0 = j == 0 ? face.v[0].x : (j == 1 ? face.v[0].y : face.v[0].z);
        const double v1 = j == 0 ? face.v[1].x : (j == 1 ? face.v[1].y : face.v[1].z);
        const double v2 = j == 0 ? face.v[2].x : (j == 1 ? face.v[2].y : face.v[2].z);
        switch (k) {
          case 0:  // near the face's plane
          case 4:
            target[j] = v0 + s * (v1 - v0) + t * (v2 - v0);
            break;
          case 1:  // near a radial plane (c, v[edge], v[edge + 1])
            target[j] = cc[j] + s * (a - cc[j]) + t * (b - cc[j]);
            break;
          case 2:  // near the line from c through a corner
            target[j] = cc[j] + s * (a - cc[j]);
            break;
          default:  // inside the tetrahedron of c and the face (the internal verdict)
            target[j] =
                cc[j] + inside[0] * (v0 - cc[j]) + inside[1] * (v1 - cc[j]) + inside[2] * (v2 - cc[j]);
        }
      }
      x = to_float(target);
      float* coord = (rng() % 3 == 0) ? &x.x : (rng() % 2 ? &x.y : &x.z);
      *coord = ulp_step(*coord, ulps(rng));
    }
    face_tetrahedron_signs(c, face.v, face.tet);
    FacePlanes planes;
    prepare_face_planes(face, c, planes);
    int want_edge = 0, got_edge = 0;
    double height = 0;
    const PointVerdict want = face_verdict(face, c, x, &want_edge);
    const unsigned long long calls_before = predicate_stats().orient3d_calls;
    const PointVerdict got = face_verdict_prepared(face, planes, c, x, &got_edge, &height);
    fallbacks += predicate_stats().orient3d_calls - calls_before;
    ASSERT_EQ(got, want) << "case " << i << " kind " << k;
    ASSERT_EQ(got_edge, want_edge) << "case " << i << " kind " << k;
    const double expected_height = face_height(face, x);
    ASSERT_EQ(std::memcmp(&height, &expected_height, sizeof height), 0) << "case " << i << " kind " << k;
    ++verdicts[got];
  }
  // Both paths ran: most decisions without orient3d, and some (the degenerate cases) through it.
  std::printf("%d cases: %d internal, %d external, %d stray; %llu orient3d fallbacks\n", cases, verdicts[0],
              verdicts[1], verdicts[2], fallbacks);
  EXPECT_GT(fallbacks, 1000u);
  EXPECT_LT(fallbacks, static_cast<unsigned long long>(cases));
  EXPECT_GT(verdicts[0], cases / 50);
  EXPECT_GT(verdicts[1], cases / 10);
  EXPECT_GT(verdicts[2], cases / 50);
}

}  // namespace
}  // namespace cudahull
