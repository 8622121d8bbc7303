// CUDAHULL_HD marks functions that both the CPU backend and the CUDA backend compile (DESIGN.md: one source
// of truth for every per-point decision, so both backends give identical hulls).
#pragma once

#if defined(__CUDACC__)
#define CUDAHULL_HD __host__ __device__
#else
#define CUDAHULL_HD
#endif
