#pragma once
// Loops written lane by lane without branches, for the compiler to turn into vector code, get a
// clone for processors with AVX2 (eight float or four double lanes) beside the baseline's (SSE2),
// chosen when the program loads (GCC on x86-64; elsewhere the baseline's alone). The files that
// hold them are compiled with -fno-math-errno -fno-trapping-math (CMakeLists.txt), without which
// GCC keeps such loops scalar, and -ffp-contract=off, so that no fused multiply-add rounds
// otherwise than the scalar code the results must equal.
//
// ECO_WIDE_VECTOR_CLONES adds a clone for AVX-512 (x86-64-v4: eight double lanes), for loops whose
// arithmetic is in double, where it measured faster than AVX2 (docs/benchmark-history.md); for float
// loops it did not.
//
// The tests build the loops once more for one target alone (tests/CMakeLists.txt), so that
// the clones this machine does not pick are tested too: ECO_VECTOR_TARGET_BASELINE (no clones)
// and ECO_VECTOR_TARGET_AVX2. Under ThreadSanitizer there are no clones either: the resolver that
// picks one runs before the sanitizer's runtime is up, and its instrumented code crashes.

#if defined(ECO_VECTOR_TARGET_BASELINE) || defined(__SANITIZE_THREAD__)
#define ECO_VECTOR_CLONES
#define ECO_WIDE_VECTOR_CLONES
#elif defined(ECO_VECTOR_TARGET_AVX2)
#define ECO_VECTOR_CLONES __attribute__((target("avx2")))
#define ECO_WIDE_VECTOR_CLONES __attribute__((target("avx2")))
#elif defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define ECO_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#define ECO_WIDE_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define ECO_VECTOR_CLONES
#define ECO_WIDE_VECTOR_CLONES
#endif
