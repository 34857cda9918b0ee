// The core's compiler hints: where a path is kept out of its caller, and where it is forced in.
#pragma once

/// Keeps a rarely taken path out of its caller's code.
#if defined(__GNUC__)
#define OBLIQUE_NOINLINE __attribute__((noinline))
#else
#define OBLIQUE_NOINLINE
#endif

/// Forces a small function into its caller: the error-free transformations (numeric/error_free.h)
/// are a few flops each and sit in the accurate method's inner loops, where a call costs as much
/// as the arithmetic.
#if defined(__GNUC__)
#define OBLIQUE_EFT_INLINE inline __attribute__((always_inline))
#else
#define OBLIQUE_EFT_INLINE inline
#endif

/// Forces the core's per-request path into apply(): the input checks and the closed form for
/// ordinary inputs (detail/input_checks.h, oblique.h), a few hundred instructions in all, whose
/// calls and spills otherwise cost a third of the time.
#if defined(__GNUC__)
#define OBLIQUE_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define OBLIQUE_ALWAYS_INLINE inline
#endif
