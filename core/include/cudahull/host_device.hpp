// CUDAHULL_HD marks functions that both the CPU backend and the CUDA backend compile: one source of truth
// for every per-point decision, so both backends give identical hulls (docs/architecture.md).
#pragma once

#if defined(__CUDACC__)
#define CUDAHULL_HD __host__ __device__
#else
#define CUDAHULL_HD
#endif

// For the rarely taken exact stages of the predicates: kept out of line so that their large frames do not
// inflate the register count (and so cut the occupancy) of every kernel that calls a predicate.
#if defined(__CUDACC__)
#define CUDAHULL_COLD __noinline__
#else
#define CUDAHULL_COLD __attribute__((noinline, cold))
#endif
