#include "lmm_mesh.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "sh_light.h"
#include "sh_rng.h"

#define CHUNK_LOG2 12
#define CHUNK_SIZE (1 << CHUNK_LOG2)

/* One slot of the open-addressing table: the point's key (its linear grid
 * index plus 1; 0 marks an empty slot), whether its value is published,
 * and where the value lives in the pool. */
typedef struct slot {
  uint64_t key;
  uint32_t ready;
  uint32_t value;
} slot;

struct lmm_mesh {
  const sh_scene *scene;
  const sh_rt *rt;
  lmm_grid grid;
  int direct_only; /* formula 6's direct term (refract-both) */
  int nlights, bits;
  unsigned classes; /* the surfaces whose shadows the mesh softens */
  size_t value_size; /* bytes per point */
  slot *slots;
  uint64_t mask;      /* capacity - 1 */
  uint32_t max_values, next_value;
  unsigned char **chunks; /* the value pool, CHUNK_SIZE values a chunk */
  pthread_mutex_t chunk_lock;
  int64_t computed, uncached;
};

/* Bits for opaque scenes, RGB floats otherwise. */
static void set_layout(lmm_mesh *m) {
  m->value_size = m->bits ? 8 * (size_t)((m->nlights + 63) / 64)
                          : sizeof(float) * 3 * (size_t)m->nlights;
  if (m->value_size == 0) m->value_size = 8;
}

sh_status lmm_mesh_create(const sh_scene *scene, const sh_rt *rt, double h,
                          int capacity_log2, lmm_mesh **out, sh_error *err) {
  *out = NULL;
  lmm_grid grid;
  sh_status st = lmm_grid_over_scene(scene, h, &grid, err);
  if (st != SH_OK) return st;
  lmm_mesh *m = calloc(1, sizeof *m);
  if (!m) return sh_error_set(err, SH_ERR_NOMEM, "out of memory");
  m->scene = scene;
  m->rt = rt;
  m->grid = grid;
  m->nlights = scene->nlights;
  m->bits = !sh_scene_has_semitransparent(scene);
  m->classes = SH_RT_SOFT;
  set_layout(m);
  int lg = capacity_log2 > 0 ? capacity_log2 : 21;
  if (lg < 8) lg = 8;
  if (lg > 30) lg = 30;
  m->mask = ((uint64_t)1 << lg) - 1;
  m->max_values = (uint32_t)(((uint64_t)1 << lg) / 10 * 9);
  m->slots = calloc((size_t)m->mask + 1, sizeof *m->slots);
  m->chunks = calloc(((size_t)m->max_values >> CHUNK_LOG2) + 1,
                     sizeof *m->chunks);
  if (!m->slots || !m->chunks) {
    lmm_mesh_free(m);
    return sh_error_set(err, SH_ERR_NOMEM,
                        "out of memory for a light mesh table of 2^%d slots",
                        lg);
  }
  pthread_mutex_init(&m->chunk_lock, NULL);
  *out = m;
  return SH_OK;
}

void lmm_mesh_free(lmm_mesh *m) {
  if (!m) return;
  if (m->chunks) {
    for (size_t i = 0; i <= (m->max_values >> CHUNK_LOG2); i++)
      free(m->chunks[i]);
    pthread_mutex_destroy(&m->chunk_lock);
  }
  free(m->chunks);
  free(m->slots);
  free(m);
}

void lmm_mesh_set_direct_only(lmm_mesh *m) { m->direct_only = 1; }

const lmm_grid *lmm_mesh_grid(const lmm_mesh *m) { return &m->grid; }

/* The visibility of every light from grid point x, into vis. */
static void compute(const lmm_mesh *m, int i, int j, int k, sh_vec3 *vis,
                    sh_rt_counters *c) {
  sh_vec3 x = lmm_grid_point(&m->grid, i, j, k);
  for (int l = 0; l < m->nlights; l++) {
    const sh_light *light = &m->scene->lights[l];
    sh_vec3 wi;
    double dist;
    sh_light_incident(light, x, &wi, &dist);
    double tmax = isinf(dist) ? INFINITY : dist * (1.0 - 1e-7);
    if (m->direct_only) {
      /* Formula 6: the straight path counts only if nothing at all is on
       * it. */
      int blocked = sh_rt_occluded(m->rt, x, wi, tmax, m->classes, c);
      vis[l] = sh_v3s(blocked ? 0.0 : 1.0);
    } else {
      vis[l] = sh_rt_visibility_of(m->rt, x, wi, tmax, m->classes, c);
    }
  }
}

static void store(const lmm_mesh *m, unsigned char *dst, const sh_vec3 *vis) {
  if (m->bits) {
    uint64_t *w = (uint64_t *)dst;
    memset(dst, 0, m->value_size);
    for (int l = 0; l < m->nlights; l++)
      if (vis[l].x > 0) w[l >> 6] |= (uint64_t)1 << (l & 63);
  } else {
    float *f = (float *)dst;
    for (int l = 0; l < m->nlights; l++) {
      f[3 * l] = (float)vis[l].x;
      f[3 * l + 1] = (float)vis[l].y;
      f[3 * l + 2] = (float)vis[l].z;
    }
  }
}

static void load(const lmm_mesh *m, const unsigned char *src, sh_vec3 *vis) {
  if (m->bits) {
    const uint64_t *w = (const uint64_t *)src;
    for (int l = 0; l < m->nlights; l++)
      vis[l] = sh_v3s((w[l >> 6] >> (l & 63)) & 1 ? 1.0 : 0.0);
  } else {
    const float *f = (const float *)src;
    for (int l = 0; l < m->nlights; l++)
      vis[l] = sh_v3(f[3 * l], f[3 * l + 1], f[3 * l + 2]);
  }
}

/* The pool entry for value index v, allocating its chunk on first use. */
static unsigned char *pool_entry(lmm_mesh *m, uint32_t v) {
  size_t ci = v >> CHUNK_LOG2;
  unsigned char *chunk = __atomic_load_n(&m->chunks[ci], __ATOMIC_ACQUIRE);
  if (!chunk) {
    pthread_mutex_lock(&m->chunk_lock);
    chunk = m->chunks[ci];
    if (!chunk) {
      chunk = malloc(m->value_size * CHUNK_SIZE);
      __atomic_store_n(&m->chunks[ci], chunk, __ATOMIC_RELEASE);
    }
    pthread_mutex_unlock(&m->chunk_lock);
  }
  return chunk ? chunk + m->value_size * (v & (CHUNK_SIZE - 1)) : NULL;
}

/* The cached entry of point (i, j, k), computed and published on first
 * use (vis is scratch for the computation). NULL if it could not be cached
 * (table full, or another thread is computing it); then vis holds the
 * values. */
static const unsigned char *entry_of(lmm_mesh *m, int i, int j, int k,
                                     sh_vec3 *vis, sh_rt_counters *c) {
  uint64_t key = 1 + lmm_grid_index(&m->grid, i, j, k);
  uint64_t s = sh_hash64(key) & m->mask;
  for (uint64_t probe = 0; probe <= m->mask; probe++, s = (s + 1) & m->mask) {
    slot *sl = &m->slots[s];
    uint64_t cur = __atomic_load_n(&sl->key, __ATOMIC_ACQUIRE);
    if (cur == key) {
      if (__atomic_load_n(&sl->ready, __ATOMIC_ACQUIRE))
        return pool_entry(m, sl->value);
      break; /* another thread is computing it: compute a private copy */
    }
    if (cur != 0) continue;
    uint32_t v = __atomic_fetch_add(&m->next_value, 1, __ATOMIC_RELAXED);
    if (v >= m->max_values) break; /* the table is full */
    uint64_t expected = 0;
    if (!__atomic_compare_exchange_n(&sl->key, &expected, key, 0,
                                     __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) {
      /* Lost the slot; the value index is wasted, which is harmless. */
      if (expected == key) break;
      continue;
    }
    unsigned char *dst = pool_entry(m, v);
    compute(m, i, j, k, vis, c);
    if (!dst) {
      __atomic_fetch_add(&m->uncached, 1, __ATOMIC_RELAXED);
      return NULL;
    }
    store(m, dst, vis);
    sl->value = v;
    __atomic_store_n(&sl->ready, 1, __ATOMIC_RELEASE);
    __atomic_fetch_add(&m->computed, 1, __ATOMIC_RELAXED);
    return dst;
  }
  compute(m, i, j, k, vis, c);
  __atomic_fetch_add(&m->uncached, 1, __ATOMIC_RELAXED);
  return NULL;
}

void lmm_mesh_values(lmm_mesh *m, int i, int j, int k, sh_vec3 *vis,
                     sh_rt_counters *c) {
  const unsigned char *e = entry_of(m, i, j, k, vis, c);
  if (e) load(m, e, vis);
}

int lmm_mesh_bits(lmm_mesh *m, int i, int j, int k, uint64_t *words,
                  sh_rt_counters *c) {
  if (!m->bits) return 0;
  /* Scratch for a computation; the bit layout is what store() writes. */
  sh_vec3 vis[64];
  int nwords = (m->nlights + 63) / 64;
  if (m->nlights <= 64) {
    const unsigned char *e = entry_of(m, i, j, k, vis, c);
    if (e)
      memcpy(words, e, 8 * (size_t)nwords);
    else
      store(m, (unsigned char *)words, vis);
    return 1;
  }
  /* Many lights: go through the float path (rare; scratch on the heap). */
  sh_vec3 *big = malloc(sizeof *big * (size_t)m->nlights);
  if (!big) return 0;
  const unsigned char *e = entry_of(m, i, j, k, big, c);
  if (e)
    memcpy(words, e, 8 * (size_t)nwords);
  else
    store(m, (unsigned char *)words, big);
  free(big);
  return 1;
}

void lmm_mesh_get_stats(const lmm_mesh *m, lmm_mesh_stats *st) {
  st->points_total = lmm_grid_points(&m->grid);
  st->points_computed = m->computed;
  st->points_uncached = m->uncached;
  st->bits = m->bits;
}
