#include "se_phase_fit.h"

#include "sh_medium.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SE__PI 3.14159265358979323846
#define SE__NMU 2001       /* cos samples of the fit, uniform in [-1, 1] */
#define SE__NCAND 195      /* candidate lobes, g = -0.97 + 0.01 i */
#define SE__SUM_ROW 100.0  /* weight of the row that holds sum w = 1 */

double se_phase_hg(double g, double mu) {
  double d = 1.0 + g * g - 2.0 * g * mu;
  return (1.0 - g * g) / (4.0 * SE__PI * d * sqrt(d));
}

/* The Cornette-Shanks phase (the contract's, sh_medium.h). */
static double cs(double g, double mu) {
  const sh_phase phase = {SH_PHASE_CORNETTE_SHANKS, g};
  return sh_phase_eval(&phase, mu);
}

double se_hg_mixture_eval(const se_hg_mixture *m, double mu) {
  double s = 0.0;
  for (int i = 0; i < m->n; i++) s += m->w[i] * se_phase_hg(m->g[i], mu);
  return s;
}

/* The fit's samples: cos mu_j, the weight sqrt(v_j / sum v) of its row
 * (v_j = p_CS(mu_j): the chi-square distance) and 1 / p_CS(mu_j). */
typedef struct fit {
  double g;
  double mu[SE__NMU], sv[SE__NMU], inv[SE__NMU];
} fit;

static void fit_init(fit *f, double g) {
  double vsum = 0.0;
  f->g = g;
  for (int j = 0; j < SE__NMU; j++) {
    f->mu[j] = -1.0 + 2.0 * j / (SE__NMU - 1);
    double p = cs(g, f->mu[j]);
    f->inv[j] = 1.0 / p;
    f->sv[j] = p;
    vsum += f->sv[j];
  }
  for (int j = 0; j < SE__NMU; j++) f->sv[j] = sqrt(f->sv[j] / vsum);
}

/* Solves the n x n system a x = b (row stride n) by Gaussian elimination
 * with partial pivoting; a and b are overwritten. Returns 0 if singular. */
static int solve(double *a, double *b, double *x, int n) {
  for (int c = 0; c < n; c++) {
    int piv = c;
    for (int r = c + 1; r < n; r++)
      if (fabs(a[r * n + c]) > fabs(a[piv * n + c])) piv = r;
    if (!(fabs(a[piv * n + c]) > 0.0)) return 0;
    if (piv != c) {
      for (int k = 0; k < n; k++) {
        double t = a[c * n + k];
        a[c * n + k] = a[piv * n + k];
        a[piv * n + k] = t;
      }
      double t = b[c];
      b[c] = b[piv];
      b[piv] = t;
    }
    for (int r = c + 1; r < n; r++) {
      double m = a[r * n + c] / a[c * n + c];
      for (int k = c; k < n; k++) a[r * n + k] -= m * a[c * n + k];
      b[r] -= m * b[c];
    }
  }
  for (int r = n - 1; r >= 0; r--) {
    double s = b[r];
    for (int k = r + 1; k < n; k++) s -= a[r * n + k] * x[k];
    x[r] = s / a[r * n + r];
  }
  return 1;
}

/* Non-negative least squares on the normal equations G x = h (G n x n,
 * symmetric positive semi-definite): Lawson and Hanson's active set method
 * (Solving Least Squares Problems, 1974, ch. 23), at most 3n outer steps.
 * `work` holds 2 n^2 + 4 n doubles. */
static void nnls(const double *G, const double *h, int n, double *x, double *work) {
  unsigned char passive[SE__NCAND];
  int idx[SE__NCAND];
  double *sub = work, *rhs = work + n * n, *zs = rhs + n, *z = zs + n, *grad = z + n;
  memset(passive, 0, (size_t)n);
  for (int i = 0; i < n; i++) x[i] = 0.0;
  double tol = 0.0;
  for (int i = 0; i < n; i++) tol = fmax(tol, G[i * n + i]);
  tol *= 1e-13;
  for (int outer = 0; outer < 3 * n; outer++) {
    int best = -1;
    for (int i = 0; i < n; i++) {
      double s = h[i];
      for (int k = 0; k < n; k++) s -= G[i * n + k] * x[k];
      grad[i] = s;
      if (!passive[i] && s > tol && (best < 0 || s > grad[best])) best = i;
    }
    if (best < 0) return;
    passive[best] = 1;
    for (int inner = 0; inner < 3 * n; inner++) {
      int np = 0;
      for (int i = 0; i < n; i++)
        if (passive[i]) idx[np++] = i;
      for (int r = 0; r < np; r++) {
        for (int c = 0; c < np; c++) sub[r * np + c] = G[idx[r] * n + idx[c]];
        sub[r * np + r] *= 1.0 + 1e-12; /* a hair of ridge for near-equal lobes */
        rhs[r] = h[idx[r]];
      }
      if (!solve(sub, rhs, zs, np)) {
        passive[best] = 0; /* a lobe the others already span */
        break;
      }
      for (int i = 0; i < n; i++) z[i] = 0.0;
      double alpha = 2.0;
      for (int r = 0; r < np; r++) {
        int i = idx[r];
        z[i] = zs[r];
        if (z[i] <= 0.0) alpha = fmin(alpha, x[i] / (x[i] - z[i]));
      }
      if (alpha > 1.0) {
        for (int i = 0; i < n; i++) x[i] = z[i];
        break;
      }
      for (int r = 0; r < np; r++) {
        int i = idx[r];
        x[i] += alpha * (z[i] - x[i]);
        if (x[i] <= 1e-15) {
          x[i] = 0.0;
          passive[i] = 0;
        }
      }
    }
  }
}

/* The normal equations of the lobes gs[0..n): G = A^T A and h = A^T b, A's
 * rows sqrt(v_j) p_HG(mu_j; g_i) / p_CS(mu_j) and b_j = sqrt(v_j), plus
 * the row SE__SUM_ROW (1 ... 1 | 1) that holds the weights' sum. cols
 * holds n SE__NMU doubles. */
static void normal_equations(const fit *f, const double *gs, int n, double *cols, double *G,
                             double *h) {
  for (int i = 0; i < n; i++)
    for (int j = 0; j < SE__NMU; j++)
      cols[i * SE__NMU + j] = f->sv[j] * se_phase_hg(gs[i], f->mu[j]) * f->inv[j];
  const double s2 = SE__SUM_ROW * SE__SUM_ROW;
  for (int i = 0; i < n; i++) {
    double hi = s2;
    for (int j = 0; j < SE__NMU; j++) hi += cols[i * SE__NMU + j] * f->sv[j];
    h[i] = hi;
    for (int k = 0; k <= i; k++) {
      double s = s2;
      const double *a = cols + i * SE__NMU, *b = cols + k * SE__NMU;
      for (int j = 0; j < SE__NMU; j++) s += a[j] * b[j];
      G[i * n + k] = G[k * n + i] = s;
    }
  }
}

/* The weighted squared relative error of lobes gs with the best weights,
 * which go to w (normalised to sum 1). */
static double objective(const fit *f, const double *gs, int n, double *w) {
  double cols[SE_PHASE_FIT_MAX_LOBES * SE__NMU];
  double G[SE_PHASE_FIT_MAX_LOBES * SE_PHASE_FIT_MAX_LOBES], h[SE_PHASE_FIT_MAX_LOBES];
  double work[2 * SE_PHASE_FIT_MAX_LOBES * SE_PHASE_FIT_MAX_LOBES + 4 * SE_PHASE_FIT_MAX_LOBES];
  normal_equations(f, gs, n, cols, G, h);
  nnls(G, h, n, w, work);
  double sum = 0.0;
  for (int i = 0; i < n; i++) sum += w[i];
  if (!(sum > 0.0)) {
    for (int i = 0; i < n; i++) w[i] = 1.0 / n;
    sum = 1.0;
  }
  for (int i = 0; i < n; i++) w[i] /= sum;
  double e = 0.0;
  for (int j = 0; j < SE__NMU; j++) {
    double m = 0.0;
    for (int i = 0; i < n; i++) m += w[i] * se_phase_hg(gs[i], f->mu[j]);
    double r = f->sv[j] * (m * f->inv[j] - 1.0);
    e += r * r;
  }
  return e;
}

/* The candidates' fit: their weights, merged into clusters of neighbours
 * (each at the weighted mean g); the k heaviest go to gs. Returns their
 * number. */
static int candidates(const fit *f, int k, double *gs) {
  /* The candidates' columns, Gram matrix and NNLS work space: 3.6 MB. */
  double *cols = malloc(sizeof(double) * (SE__NCAND * SE__NMU + 3 * SE__NCAND * SE__NCAND +
                                          4 * SE__NCAND));
  if (!cols) return 0;
  double *G = cols + SE__NCAND * SE__NMU, *work = G + SE__NCAND * SE__NCAND;
  double cg[SE__NCAND], h[SE__NCAND], x[SE__NCAND];
  double clg[SE__NCAND], clw[SE__NCAND];
  for (int i = 0; i < SE__NCAND; i++) cg[i] = -0.97 + 0.01 * i;
  normal_equations(f, cg, SE__NCAND, cols, G, h);
  nnls(G, h, SE__NCAND, x, work);
  free(cols);
  int nc = 0;
  for (int i = 0; i < SE__NCAND; i++) {
    if (!(x[i] > 0.0)) continue;
    if (i > 0 && x[i - 1] > 0.0) {
      clg[nc - 1] += x[i] * cg[i];
      clw[nc - 1] += x[i];
    } else {
      clg[nc] = x[i] * cg[i];
      clw[nc] = x[i];
      nc++;
    }
  }
  int n = 0;
  while (n < k) {
    int best = -1;
    for (int c = 0; c < nc; c++)
      if (clw[c] > 0.0 && (best < 0 || clw[c] > clw[best])) best = c;
    if (best < 0) break;
    gs[n++] = clg[best] / clw[best];
    clw[best] = 0.0;
  }
  return n;
}

typedef double (*objective_fn)(const fit *, const double *, int, double *);
static void pattern_search(const fit *f, objective_fn obj, double *gs, double *w, int n,
                           double *e, double step, double min_step, int sweeps);
static void store(const double *gs, const double *w, int n, se_hg_mixture *out);

int se_phase_fit_cs(double g, int k, se_hg_mixture *out) {
  fit f; /* 48 kB */
  memset(out, 0, sizeof *out);
  if (k < 1) k = 1;
  if (k > SE_PHASE_FIT_MAX_LOBES) k = SE_PHASE_FIT_MAX_LOBES;
  if (!(g == g)) g = 0.0;
  g = fmax(-0.95, fmin(0.95, g));
  fit_init(&f, g);
  double gs[SE_PHASE_FIT_MAX_LOBES], w[SE_PHASE_FIT_MAX_LOBES];
  int n = candidates(&f, k, gs);
  if (n == 0) return 0;
  /* Pattern search on the lobes' g, the weights solved at every step:
   * steps from 0.01 halved down to 1e-5 (at most 400 sweeps). */
  double e = objective(&f, gs, n, w);
  pattern_search(&f, objective, gs, w, n, &e, 0.01, 1e-5, 400);
  /* Lobes left without weight go; the heaviest first. */
  store(gs, w, n, out);
  return 1;
}

/* The signed fit (se_phase_fit_cs_signed). Its weights for the lobes gs
 * minimise the same chi-square distance with sum w = 1 held exactly (the
 * equality-constrained least squares through its KKT system); the lobes
 * are feasible if at least SE__MIN_GAP apart, sum |w| <= SE_PHASE_FIT_MAX_ABS
 * and the mixture >= 0 at the fit's samples. Returns the distance, or
 * HUGE_VAL if infeasible. */
#define SE__MIN_GAP 0.1
#define SE__STARTS 6 /* the best starts refined */
static double signed_objective(const fit *f, const double *gs, int n, double *w) {
  enum { M = SE_PHASE_FIT_MAX_LOBES + 1 };
  double cols[SE_PHASE_FIT_MAX_LOBES * SE__NMU], a[M * M], b[M], x[M];
  const int m = n + 1;
  for (int i = 0; i < n; i++)
    for (int k = 0; k < i; k++)
      if (fabs(gs[i] - gs[k]) < SE__MIN_GAP) return HUGE_VAL;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < SE__NMU; j++)
      cols[i * SE__NMU + j] = f->sv[j] * se_phase_hg(gs[i], f->mu[j]) * f->inv[j];
  for (int i = 0; i < n; i++) {
    for (int k = 0; k < n; k++) {
      double s = 0.0;
      for (int j = 0; j < SE__NMU; j++) s += cols[i * SE__NMU + j] * cols[k * SE__NMU + j];
      a[i * m + k] = s;
    }
    double s = 0.0;
    for (int j = 0; j < SE__NMU; j++) s += cols[i * SE__NMU + j] * f->sv[j];
    b[i] = s;
    a[i * m + n] = a[n * m + i] = 1.0;
  }
  a[n * m + n] = 0.0;
  b[n] = 1.0;
  if (!solve(a, b, x, m)) return HUGE_VAL;
  double abs_sum = 0.0;
  for (int i = 0; i < n; i++) {
    w[i] = x[i];
    abs_sum += fabs(x[i]);
  }
  if (!(abs_sum <= SE_PHASE_FIT_MAX_ABS)) return HUGE_VAL;
  double e = 0.0;
  for (int j = 0; j < SE__NMU; j++) {
    double s = 0.0;
    for (int i = 0; i < n; i++) s += w[i] * cols[i * SE__NMU + j];
    if (s < 0.0) return HUGE_VAL;
    e += (s - f->sv[j]) * (s - f->sv[j]);
  }
  return e;
}

/* Writes the lobes gs with weights w to *out, the largest |w| first, and
 * drops lobes of weight 0. */
static void store(const double *gs, const double *w, int n, se_hg_mixture *out) {
  memset(out, 0, sizeof *out);
  for (int i = 0; i < n; i++)
    if (w[i] != 0.0) {
      out->g[out->n] = gs[i];
      out->w[out->n] = w[i];
      out->n++;
    }
  for (int i = 1; i < out->n; i++)
    for (int j = i; j > 0 && fabs(out->w[j]) > fabs(out->w[j - 1]); j--) {
      double tg = out->g[j], tw = out->w[j];
      out->g[j] = out->g[j - 1];
      out->w[j] = out->w[j - 1];
      out->g[j - 1] = tg;
      out->w[j - 1] = tw;
    }
}

/* The pattern search on the lobes' g (steps from `step` halved down to
 * min_step, at most `sweeps` sweeps) for an objective of the signed or the
 * non-negative fit; gs, w and *e hold the best. */
static void pattern_search(const fit *f, objective_fn obj, double *gs, double *w, int n,
                           double *e, double step, double min_step, int sweeps) {
  for (int sweep = 0; sweep < sweeps && step >= min_step; sweep++) {
    int moved = 0;
    for (int i = 0; i < n; i++) {
      for (int s = -1; s <= 1; s += 2) {
        double t[SE_PHASE_FIT_MAX_LOBES], tw[SE_PHASE_FIT_MAX_LOBES];
        memcpy(t, gs, sizeof t);
        t[i] = fmax(-0.97, fmin(0.97, gs[i] + s * step));
        double et = obj(f, t, n, tw);
        if (et < *e) {
          *e = et;
          memcpy(gs, t, sizeof t);
          memcpy(w, tw, sizeof tw);
          moved = 1;
        }
      }
    }
    if (!moved) step *= 0.5;
  }
}

int se_phase_fit_cs_signed(double g, int k, se_hg_mixture *out) {
  if (k < 2 || k > SE_PHASE_FIT_MAX_LOBES) return se_phase_fit_cs(g, k, out);
  if (!se_phase_fit_cs(g, k, out)) return 0; /* the fallback */
  if (!(g == g)) g = 0.0;
  g = fmax(-0.95, fmin(0.95, g));
  fit f;
  fit_init(&f, g);
  /* The starts: every increasing k-tuple of a grid over [-0.96, 0.96]
   * (13 points for k 2 and 3, 9 for 4: 78, 286 and 126 starts). */
  const int steps = k == 4 ? 9 : 13;
  double sg[SE__STARTS][SE_PHASE_FIT_MAX_LOBES], se[SE__STARTS];
  int ns = 0;
  int idx[SE_PHASE_FIT_MAX_LOBES];
  for (int i = 0; i < k; i++) idx[i] = i;
  for (;;) {
    double t[SE_PHASE_FIT_MAX_LOBES] = {0}, tw[SE_PHASE_FIT_MAX_LOBES];
    for (int i = 0; i < k; i++) t[i] = -0.96 + 1.92 * idx[i] / (steps - 1);
    double e = signed_objective(&f, t, k, tw);
    /* Kept among the SE__STARTS best so far, sorted. */
    if (e < HUGE_VAL && (ns < SE__STARTS || e < se[ns - 1])) {
      int at = ns < SE__STARTS ? ns++ : ns - 1;
      while (at > 0 && se[at - 1] > e) {
        se[at] = se[at - 1];
        memcpy(sg[at], sg[at - 1], sizeof sg[at]);
        at--;
      }
      se[at] = e;
      memcpy(sg[at], t, sizeof sg[at]);
    }
    int i = k - 1; /* the next tuple */
    while (i >= 0 && idx[i] == steps - k + i) i--;
    if (i < 0) break;
    idx[i]++;
    for (int j = i + 1; j < k; j++) idx[j] = idx[j - 1] + 1;
  }
  double best = HUGE_VAL, gs[SE_PHASE_FIT_MAX_LOBES] = {0}, w[SE_PHASE_FIT_MAX_LOBES] = {0};
  for (int s = 0; s < ns; s++) {
    double t[SE_PHASE_FIT_MAX_LOBES], tw[SE_PHASE_FIT_MAX_LOBES];
    memcpy(t, sg[s], sizeof t);
    double e = signed_objective(&f, t, k, tw);
    pattern_search(&f, signed_objective, t, tw, k, &e, 0.02, 1e-5, 300);
    if (e < best) {
      best = e;
      memcpy(gs, t, sizeof t);
      memcpy(w, tw, sizeof tw);
    }
  }
  if (best == HUGE_VAL) return 1;
  /* Kept only if non-negative on a grid ten times the fit's and better
   * than the non-negative fit in its distance. */
  for (int j = 0; j <= 20000; j++) {
    double mu = -1.0 + j / 10000.0, s = 0.0;
    for (int i = 0; i < k; i++) s += w[i] * se_phase_hg(gs[i], mu);
    if (s < 0.0) return 1;
  }
  double wn[SE_PHASE_FIT_MAX_LOBES];
  if (!(best < objective(&f, out->g, out->n, wn))) return 1;
  store(gs, w, k, out);
  return 1;
}

int se_phase_fit_cs_lobes(double g, int kmax, double min_weight, se_hg_mixture *out) {
  for (int k = kmax < 1 ? 1 : kmax; ; k--) {
    if (!se_phase_fit_cs(g, k, out)) return 0;
    if (k <= 1 || out->w[out->n - 1] >= min_weight) return 1;
  }
}

void se_phase_fit_error(double g, const se_hg_mixture *m, double *max_rel, double *rms_rel,
                        double *forward) {
  double worst = 0.0, sq = 0.0;
  const int n = 4001;
  for (int j = 0; j < n; j++) {
    double mu = -1.0 + 2.0 * j / (n - 1);
    double r = se_hg_mixture_eval(m, mu) / cs(g, mu) - 1.0;
    worst = fmax(worst, fabs(r));
    sq += r * r;
  }
  if (max_rel) *max_rel = worst;
  if (rms_rel) *rms_rel = sqrt(sq / n);
  if (forward) *forward = se_hg_mixture_eval(m, 1.0) / cs(g, 1.0) - 1.0;
}
