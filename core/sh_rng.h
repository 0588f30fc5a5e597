/* A small deterministic random number generator (PCG32, O'Neill 2014), so
 * that the same command renders the same image on any number of threads:
 * every pixel seeds its own stream from the scene seed and its index. */
#ifndef SH_RNG_H
#define SH_RNG_H

#include <stdint.h>

typedef struct sh_rng {
  uint64_t state, inc;
} sh_rng;

static inline uint32_t sh_rng_u32(sh_rng *r) {
  uint64_t old = r->state;
  r->state = old * 6364136223846793005ULL + r->inc;
  uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
  uint32_t rot = (uint32_t)(old >> 59u);
  return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
}

static inline void sh_rng_seed(sh_rng *r, uint64_t seed, uint64_t stream) {
  r->state = 0;
  r->inc = (stream << 1u) | 1u;
  sh_rng_u32(r);
  r->state += seed;
  sh_rng_u32(r);
}

/* A 64-bit mixing function (MurmurHash3's finaliser): spreads keys such as
 * grid indices over a hash table. */
static inline uint64_t sh_hash64(uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdULL;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ULL;
  x ^= x >> 33;
  return x;
}

/* A double uniformly distributed in [0, 1). */
static inline double sh_rng_next(sh_rng *r) {
  return (double)sh_rng_u32(r) * (1.0 / 4294967296.0);
}

#endif
