/* One pair of sheets: its intersection curves decided as junctions, each
 * cut to the part both sheets use, clipped at sea level and resampled at
 * the mesh size (fm_connect.h, "The junction plan"). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "connect_solve.h"
#include "fm_predicates.h"
#include "plan_internal.h"

void pl_curve_free(pl_curve *c)
{
    if (!c)
        return;
    free(c->xyz);
    free(c->uv[0]);
    free(c->uv[1]);
    free(c->key);
    memset(c, 0, sizeof *c);
}

void pl_pair_result_free(pl_pair_result *r)
{
    for (size_t k = 0; k < r->n; k++)
        pl_curve_free(&r->curve[k]);
    free(r->junction);
    free(r->curve);
    memset(r, 0, sizeof *r);
}

static int result_push(pl_pair_result *r, const fm_connect_junction *j, const pl_curve *c)
{
    if (r->n == r->cap) {
        size_t cap = r->cap ? 2 * r->cap : 4;
        fm_connect_junction *nj = realloc(r->junction, cap * sizeof *nj);
        if (!nj)
            return -1;
        r->junction = nj;
        pl_curve *nc = realloc(r->curve, cap * sizeof *nc);
        if (!nc)
            return -1;
        r->curve = nc;
        r->cap = cap;
    }
    r->junction[r->n] = *j;
    if (c)
        r->curve[r->n] = *c;
    else
        memset(&r->curve[r->n], 0, sizeof r->curve[r->n]);
    r->n++;
    return 0;
}

static double dist3(const double *a, const double *b)
{
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Points of a curve being cut: x = (uA, vA, uB, vB), p in 3D. */
typedef struct run {
    double *x, *p;
    size_t n, cap;
} run;

static int run_push(run *r, const double x[4], const double p[3])
{
    if (r->n == r->cap) {
        size_t cap = r->cap ? 2 * r->cap : 32;
        double *nx = realloc(r->x, 4 * cap * sizeof *nx);
        if (!nx)
            return -1;
        r->x = nx;
        double *np = realloc(r->p, 3 * cap * sizeof *np);
        if (!np)
            return -1;
        r->p = np;
        r->cap = cap;
    }
    memcpy(r->x + 4 * r->n, x, 4 * sizeof *x);
    memcpy(r->p + 3 * r->n, p, 3 * sizeof *p);
    r->n++;
    return 0;
}

static void run_free(run *r)
{
    free(r->x);
    free(r->p);
    memset(r, 0, sizeof *r);
}

typedef struct decider {
    const fm_fit_surface *S[2];
    const pl_outline *ol[2];
    const fm_connect_plan_options *o;
    /* the raw curve */
    size_t n;
    const double *p, *uv[2], *sd[2], *flap[2], *angle;
    const unsigned char *inside[2];
    double *foot[2];   /* 3 per point */
} decider;

/* The point at fraction r between curve points x0/p0 and x1/p1, solved
 * onto both surfaces on the plane through the interpolated point normal
 * to T (NULL: the chord). */
static void solve_between(const decider *d, const double *x0, const double *x1, const double *p0,
                          const double *p1, double r, const double *T, double x[4], double p[3])
{
    double q[3], t[3], l = 0;
    for (int k = 0; k < 4; k++)
        x[k] = x0[k] + r * (x1[k] - x0[k]);
    for (int k = 0; k < 3; k++) {
        q[k] = p0[k] + r * (p1[k] - p0[k]);
        t[k] = p1[k] - p0[k];
        l += t[k] * t[k];
    }
    l = sqrt(l);
    for (int k = 0; k < 3; k++)
        t[k] = l > 0 ? t[k] / l : (k == 0);
    int fb;
    cn_solve_point(d->S[0], d->S[1], x, q, T ? T : t, 1e-6, &fb);
    double a[3], b[3];
    fm_fit_surface_eval(d->S[0], x[0], x[1], a, NULL, NULL);
    fm_fit_surface_eval(d->S[1], x[2], x[3], b, NULL, NULL);
    for (int k = 0; k < 3; k++)
        p[k] = 0.5 * (a[k] + b[k]);
}

static void raw_x(const decider *d, size_t i, double x[4])
{
    x[0] = d->uv[0][2 * i];
    x[1] = d->uv[0][2 * i + 1];
    x[2] = d->uv[1][2 * i];
    x[3] = d->uv[1][2 * i + 1];
}

/* The point at fractional position q of the raw curve. */
static void point_at(const decider *d, double q, double x[4], double p[3])
{
    size_t i = (size_t)floor(q);
    double r = q - (double)i;
    if (i + 1 >= d->n) {
        i = d->n - 1;
        r = 0;
    }
    raw_x(d, i, x);
    memcpy(p, d->p + 3 * i, 3 * sizeof *p);
    if (r <= 0)
        return;
    double x1[4];
    raw_x(d, i + 1, x1);
    double x0[4];
    memcpy(x0, x, sizeof x0);
    solve_between(d, x0, x1, d->p + 3 * i, d->p + 3 * (i + 1), r, NULL, x, p);
}

/* The nearest outline point moves with the curve: the curve faces an
 * edge of the outline rather than having run past its end (where the
 * nearest point sticks at the corner). */
static int facing(const decider *d, int s, size_t i, size_t j)
{
    return dist3(d->foot[s] + 3 * i, d->foot[s] + 3 * j) >= 0.3 * dist3(d->p + 3 * i, d->p + 3 * j);
}

static double crossing_at(const decider *d, int s, size_t i, size_t j)
{
    double a = d->sd[s][i], b = d->sd[s][j];
    double r = (a != b) ? a / (a - b) : 0.5;
    r = fmin(1.0, fmax(0.0, r));
    return i < j ? (double)i + r : (double)j + (1.0 - r);
}

/* The part of the curve a sheet that ends at it uses (see fm_connect.h):
 * [*lo, *hi] in fractional point positions; -1 when no point matters. */
static int end_range(const decider *d, int s, double *lo, double *hi)
{
    size_t n = d->n, best = 0, blen = 0, cur = 0;
    double D = d->o->distance;
    for (size_t i = 0; i <= n; i++) {
        int rel = i < n && (d->inside[s][i] ? isfinite(d->flap[s][i]) : d->sd[s][i] <= D);
        if (rel) {
            cur++;
            continue;
        }
        if (cur > blen) {
            blen = cur;
            best = i - cur;
        }
        cur = 0;
    }
    if (blen == 0)
        return -1;
    size_t seed = best + blen / 2;
    /* The gap the sheet closes is the one it has along the curve; where
     * the curve runs on past the sheet's end the gap grows, and following
     * it would grow the sheet by up to D beyond its corners: the walk in
     * the extension stops half a size beyond the median gap. */
    double *g = malloc((blen + 1) * sizeof *g);
    size_t ng = 0;
    if (!g)
        return -1;
    for (size_t i = best; i < best + blen; i++)
        if (!d->inside[s][i])
            g[ng++] = d->sd[s][i];
    double limit = D;
    if (ng) {
        for (size_t a = 1; a < ng; a++) /* insertion sort: a few hundred values */
            for (size_t b = a; b > 0 && g[b] < g[b - 1]; b--) {
                double t = g[b];
                g[b] = g[b - 1];
                g[b - 1] = t;
            }
        limit = fmin(D, g[ng / 2] + 0.5 * d->o->size);
    } else {
        limit = fmin(D, 0.5 * d->o->size);
    }
    free(g);
    for (int dir = 0; dir < 2; dir++) {
        size_t i = seed;
        double at = (double)seed;
        for (;;) {
            if ((dir == 0 && i + 1 >= n) || (dir == 1 && i == 0)) {
                at = (double)i;
                break;
            }
            size_t j = dir == 0 ? i + 1 : i - 1;
            if (d->inside[s][j]) {
                i = j;
                continue;
            }
            if (d->sd[s][j] <= limit && facing(d, s, i, j)) {
                i = j;
                continue;
            }
            at = d->inside[s][i] ? crossing_at(d, s, i, j) : (double)i;
            break;
        }
        if (dir == 0)
            *hi = at;
        else
            *lo = at;
    }
    return *hi > *lo ? 0 : -1;
}

/* Intervals of the curve inside a sheet's outline, ends at the crossings;
 * 2 doubles each into iv (room for n), returns their number. */
static size_t inside_intervals(const decider *d, int s, double *iv)
{
    size_t k = 0, n = d->n;
    for (size_t i = 0; i < n; i++) {
        if (!d->inside[s][i] || (i > 0 && d->inside[s][i - 1]))
            continue;
        size_t j = i;
        while (j + 1 < n && d->inside[s][j + 1])
            j++;
        iv[2 * k] = i > 0 ? crossing_at(d, s, i - 1, i) : 0.0;
        iv[2 * k + 1] = j + 1 < n ? crossing_at(d, s, j, j + 1) : (double)(n - 1);
        k++;
    }
    return k;
}

/* The raw points of [a, b] (fractional), ends solved. */
static int collect(const decider *d, double a, double b, run *out)
{
    double x[4], p[3];
    point_at(d, a, x, p);
    if (run_push(out, x, p))
        return -1;
    for (size_t i = (size_t)floor(a) + 1; (double)i < b; i++) {
        raw_x(d, i, x);
        if ((double)i - a < 1e-6 || b - (double)i < 1e-6)
            continue;
        if (run_push(out, x, d->p + 3 * i))
            return -1;
    }
    point_at(d, b, x, p);
    return run_push(out, x, p);
}

/* Splits r at sea level into the runs below it; the crossing points are
 * solved onto both surfaces at z = level and put on it exactly. */
static int clip_level(const decider *d, const run *r, double level, run **outs, size_t *nout)
{
    *outs = NULL;
    *nout = 0;
    size_t cap = 0;
    run cur = {0};
    const double up[3] = {0, 0, 1};
    for (size_t i = 0; i < r->n; i++) {
        const double *p = r->p + 3 * i;
        int below = p[2] <= level;
        if (i > 0) {
            const double *q = r->p + 3 * (i - 1);
            int qb = q[2] <= level;
            if (qb != below) {
                double t = (level - q[2]) / (p[2] - q[2]), x[4], xp[3];
                double p0[3] = {q[0] + t * (p[0] - q[0]), q[1] + t * (p[1] - q[1]), level};
                double pp[3];
                memcpy(pp, p0, sizeof pp);
                /* the plane z = level through the interpolated point */
                double x0[4], x1[4];
                memcpy(x0, r->x + 4 * (i - 1), sizeof x0);
                memcpy(x1, r->x + 4 * i, sizeof x1);
                for (int k = 0; k < 4; k++)
                    x[k] = x0[k] + t * (x1[k] - x0[k]);
                int fb;
                cn_solve_point(d->S[0], d->S[1], x, pp, up, 1e-6, &fb);
                double a[3], b[3];
                fm_fit_surface_eval(d->S[0], x[0], x[1], a, NULL, NULL);
                fm_fit_surface_eval(d->S[1], x[2], x[3], b, NULL, NULL);
                for (int k = 0; k < 3; k++)
                    xp[k] = 0.5 * (a[k] + b[k]);
                xp[2] = level;
                if (run_push(&cur, x, xp))
                    goto nomem;
                if (qb) {
                    if (*nout == cap) {
                        cap = cap ? 2 * cap : 2;
                        run *nr = realloc(*outs, cap * sizeof *nr);
                        if (!nr)
                            goto nomem;
                        *outs = nr;
                    }
                    (*outs)[(*nout)++] = cur;
                    memset(&cur, 0, sizeof cur);
                }
            }
        }
        if (below && run_push(&cur, r->x + 4 * i, p))
            goto nomem;
    }
    if (cur.n >= 2) {
        if (*nout == cap) {
            run *nr = realloc(*outs, (cap + 1) * sizeof *nr);
            if (!nr)
                goto nomem;
            *outs = nr;
        }
        (*outs)[(*nout)++] = cur;
    } else {
        run_free(&cur);
    }
    return 0;
nomem:
    run_free(&cur);
    for (size_t k = 0; k < *nout; k++)
        run_free(&(*outs)[k]);
    free(*outs);
    *outs = NULL;
    *nout = 0;
    return -1;
}

static double run_length(const run *r)
{
    double L = 0;
    for (size_t i = 1; i < r->n; i++)
        L += dist3(r->p + 3 * (i - 1), r->p + 3 * i);
    return L;
}

/* Resamples r at about H (equal 3D arc lengths), ends kept, into c. */
static int resample(const decider *d, const run *r, double H, pl_curve *c)
{
    size_t n = r->n;
    double *s = malloc(n * sizeof *s);
    if (!s)
        return -1;
    s[0] = 0;
    for (size_t i = 1; i < n; i++)
        s[i] = s[i - 1] + dist3(r->p + 3 * (i - 1), r->p + 3 * i);
    double L = s[n - 1];
    size_t m = (size_t)llround(L / H);
    if (m < 1)
        m = 1;
    c->n = m + 1;
    c->xyz = malloc(3 * c->n * sizeof *c->xyz);
    c->uv[0] = malloc(2 * c->n * sizeof *c->uv[0]);
    c->uv[1] = malloc(2 * c->n * sizeof *c->uv[1]);
    if (!c->xyz || !c->uv[0] || !c->uv[1]) {
        free(s);
        return -1;
    }
    size_t k = 0;
    for (size_t q = 0; q <= m; q++) {
        double x[4], p[3];
        if (q == 0 || q == m) {
            size_t i = q ? n - 1 : 0;
            memcpy(x, r->x + 4 * i, sizeof x);
            memcpy(p, r->p + 3 * i, sizeof p);
        } else {
            double at = L * (double)q / (double)m;
            while (k + 2 < n && s[k + 1] < at)
                k++;
            double len = s[k + 1] - s[k], t = len > 0 ? (at - s[k]) / len : 0;
            solve_between(d, r->x + 4 * k, r->x + 4 * (k + 1), r->p + 3 * k, r->p + 3 * (k + 1),
                          t, NULL, x, p);
        }
        /* a node within a metre below sea level is on it (its top edge
         * then lies on z = 0 in both meshes) */
        if (d->o->cut && p[2] > d->o->sea_level - 1.0)
            p[2] = d->o->sea_level;
        memcpy(c->xyz + 3 * q, p, sizeof p);
        for (int sd = 0; sd < 2; sd++) {
            c->uv[sd][2 * q] = x[2 * sd];
            c->uv[sd][2 * q + 1] = x[2 * sd + 1];
        }
    }
    free(s);
    return 0;
}

/* 1 when the curve's polyline crosses itself in either sheet's (u, v). */
static int self_crossing(const pl_curve *c)
{
    for (int s = 0; s < 2; s++) {
        const double *uv = c->uv[s];
        for (size_t i = 0; i + 1 < c->n; i++)
            for (size_t k = i + 2; k + 1 < c->n; k++) {
                if (c->loop && i == 0 && k + 2 == c->n)
                    continue; /* a loop's last segment ends where its first begins */
                const double *a = uv + 2 * i, *b = a + 2, *p = uv + 2 * k, *q = p + 2;
                int o1 = fm_orient2d(a, b, p), o2 = fm_orient2d(a, b, q);
                int o3 = fm_orient2d(p, q, a), o4 = fm_orient2d(p, q, b);
                if (o1 * o2 <= 0 && o3 * o4 <= 0 && (o1 || o2 || o3 || o4))
                    return 1;
            }
    }
    return 0;
}

/* Which side of the curve (in a sheet's (u, v), going from node 0 on) the
 * bulk of the sheet lies: the nearest outline point lies towards the bulk
 * from a point in the extension and towards the flap from a point inside. */
static int keeps_left(const decider *d, int s, const pl_curve *c)
{
    double vote = 0;
    for (size_t k = 0; k < c->n; k++) {
        const double *uv = c->uv[s];
        size_t a = k ? k - 1 : 0, b = k + 1 < c->n ? k + 1 : c->n - 1;
        double t[2] = {uv[2 * b] - uv[2 * a], uv[2 * b + 1] - uv[2 * a + 1]};
        double foot[3], fuv[2];
        pl_outline_foot(d->ol[s], c->xyz + 3 * k, foot, fuv);
        if (!isfinite(fuv[0]))
            continue;
        double w[2] = {fuv[0] - uv[2 * k], fuv[1] - uv[2 * k + 1]};
        double lt = hypot(t[0], t[1]), lw = hypot(w[0], w[1]);
        if (!(lt > 0) || !(lw > 0))
            continue;
        double cr = (t[0] * w[1] - t[1] * w[0]) / (lt * lw);
        vote += pl_outline_inside(d->ol[s], uv + 2 * k) ? -cr : cr;
    }
    return vote >= 0;
}

static void junction_init(fm_connect_junction *j, size_t fa, size_t sa, size_t fb, size_t sb,
                          const fm_connect_curve_info *in)
{
    memset(j, 0, sizeof *j);
    j->fault[0] = fa;
    j->sheet[0] = sa;
    j->fault[1] = fb;
    j->sheet[1] = sb;
    j->role[0] = in->side[0].role;
    j->role[1] = in->side[1].role;
    j->length = in->length;
    j->min_angle = in->min_angle;
    j->curve = -1;
    j->type = FM_JUNCTION_UNJOINED;
}

/* Decides raw curve ci of cs. */
/* Sheets of one fault are rejoined where a splay branches off at a real
 * angle. Two sheets that cross at a few degrees on average are
 * overlapping versions of one surface: their intersection moves by
 * 1 / tan(angle) times any error of either surface (57 m per 10 m at 10
 * degrees), and cutting both there leaves slivers. */
#define GRAZE_SAME_FAULT 10.0

static int decide_curve(decider *d, const fm_connect_curves *cs, size_t ci, size_t fa, size_t sa,
                        size_t fb, size_t sb, pl_pair_result *out)
{
    const fm_connect_curve_info *in = fm_connect_curve_get_info(cs, ci);
    fm_connect_junction j;
    junction_init(&j, fa, sa, fb, sb, in);
    /* A closed curve is a loop both meshes hold when it lies inside both
     * sheets, all of it (each keeps what lies either side of it). One a
     * sheet ends at, or that leaves a sheet, would split into arcs whose
     * ends meet again, which no rule here decides. */
    int loop = in->closed && in->side[0].role == FM_CONNECT_THROUGH &&
               in->side[1].role == FM_CONNECT_THROUGH;
    if (in->closed && !loop) {
        /* opened where it lies farthest from the outline of the sheet
         * that ends at it and decided as an open curve, such loops made
         * 44 more triangles under 20 degrees over the whole CFM at 1 km and
         * 14 more for the last guard, for 15 km of gaps closed */
        j.reason = "closed intersection curve that a sheet ends at";
        return result_push(out, &j, NULL);
    }
    if (fa == fb && in->mean_angle < GRAZE_SAME_FAULT) {
        j.reason = "sheets of one fault that meet at a grazing angle: they overlap rather than branch";
        return result_push(out, &j, NULL);
    }
    d->n = in->npoints;
    d->p = fm_connect_curve_points(cs, ci, NULL);
    d->angle = fm_connect_curve_angles(cs, ci);
    for (int s = 0; s < 2; s++) {
        d->uv[s] = fm_connect_curve_params(cs, ci, s);
        d->sd[s] = fm_connect_curve_outline_distance(cs, ci, s);
        d->flap[s] = fm_connect_curve_flap(cs, ci, s);
        d->inside[s] = fm_connect_curve_inside(cs, ci, s);
        d->foot[s] = malloc(3 * d->n * sizeof(double) + 1);
        if (!d->foot[s]) {
            free(d->foot[0]);
            d->foot[0] = NULL;
            return -1;
        }
        for (size_t i = 0; i < d->n; i++) {
            double fuv[2];
            pl_outline_foot(d->ol[s], d->p + 3 * i, d->foot[s] + 3 * i, fuv);
        }
    }
    int end[2] = {in->side[0].role != FM_CONNECT_THROUGH, in->side[1].role != FM_CONNECT_THROUGH};
    double *iv[2] = {malloc(2 * (d->n + 1) * sizeof(double)),
                     malloc(2 * (d->n + 1) * sizeof(double))};
    size_t niv[2] = {0, 0};
    int rc = 0;
    if (!iv[0] || !iv[1]) {
        rc = -1;
        goto done;
    }
    for (int s = 0; s < 2; s++) {
        if (end[s]) {
            niv[s] = end_range(d, s, &iv[s][0], &iv[s][1]) == 0;
        } else {
            niv[s] = inside_intervals(d, s, iv[s]);
        }
    }
    /* pieces: the intersections of the two sides' intervals; a sheet that
     * ends takes only the longest */
    double best[2] = {0, -1};
    double *pieces = malloc(2 * (niv[0] * niv[1] + 1) * sizeof *pieces);
    size_t npieces = 0;
    if (!pieces) {
        rc = -1;
        goto done;
    }
    for (size_t a = 0; a < niv[0]; a++)
        for (size_t b = 0; b < niv[1]; b++) {
            double lo = fmax(iv[0][2 * a], iv[1][2 * b]), hi = fmin(iv[0][2 * a + 1], iv[1][2 * b + 1]);
            if (hi - lo < 1e-9)
                continue;
            pieces[2 * npieces] = lo;
            pieces[2 * npieces + 1] = hi;
            npieces++;
            if (hi - lo > best[1] - best[0]) {
                best[0] = lo;
                best[1] = hi;
            }
        }
    if (end[0] || end[1]) {
        npieces = best[1] > best[0];
        pieces[0] = best[0];
        pieces[1] = best[1];
    }
    if (loop && !(npieces == 1 && pieces[0] <= 1e-9 && pieces[1] >= (double)(d->n - 1) - 1e-9)) {
        j.reason = "closed intersection curve that leaves a sheet";
        rc = result_push(out, &j, NULL);
        free(pieces);
        goto done;
    }
    if (npieces == 0) {
        j.reason = niv[0] && niv[1] ? "the sheets use different parts of the curve"
                                    : "no part of the curve lies where its sheets end or cross";
        rc = result_push(out, &j, NULL);
        free(pieces);
        goto done;
    }
    double H = d->o->size;
    size_t made = 0;
    const char *why = "shorter than half the mesh size";
    for (size_t k = 0; k < npieces && rc == 0; k++) {
        run r = {0}, *below = NULL;
        size_t nb = 0;
        if (collect(d, pieces[2 * k], pieces[2 * k + 1], &r)) {
            run_free(&r);
            rc = -1;
            break;
        }
        /* a loop's run goes back to its first point: all of it */
        double x0[4];
        raw_x(d, 0, x0);
        if (loop && run_push(&r, x0, d->p)) {
            run_free(&r);
            rc = -1;
            break;
        }
        size_t whole = r.n;
        if (d->o->cut) {
            if (clip_level(d, &r, d->o->sea_level, &below, &nb)) {
                run_free(&r);
                rc = -1;
                break;
            }
            run_free(&r);
            if (nb == 0)
                why = "above sea level";
        } else {
            below = malloc(sizeof *below);
            if (!below) {
                run_free(&r);
                rc = -1;
                break;
            }
            below[0] = r;
            nb = 1;
        }
        for (size_t q = 0; q < nb; q++) {
            double L = run_length(&below[q]);
            if (rc == 0 && L >= 0.5 * H) {
                pl_curve c;
                memset(&c, 0, sizeof c);
                /* a loop the sea level leaves whole, at least three sizes
                 * round (a triangle of nodes) */
                c.loop = loop && nb == 1 && below[q].n == whole && L >= 2.5 * H;
                if (loop && !c.loop) {
                    why = "closed intersection curve shorter than three sizes or cut by sea level";
                    run_free(&below[q]);
                    continue;
                }
                if (resample(d, &below[q], H, &c)) {
                    pl_curve_free(&c);
                    rc = -1;
                } else {
                    fm_connect_junction jj = j;
                    jj.length = L;
                    jj.reason = NULL;
                    jj.type = end[0] && end[1] ? FM_JUNCTION_CORNER
                              : end[0] || end[1] ? FM_JUNCTION_T
                                                 : FM_JUNCTION_CROSSING;
                    for (int s = 0; s < 2; s++) {
                        c.end[s] = end[s];
                        c.keep_left[s] = end[s] ? keeps_left(d, s, &c) : 1;
                    }
                    if (self_crossing(&c)) {
                        /* surfaces that meet at a grazing angle: their
                         * intersection zigzags and no mesh can follow it */
                        pl_curve_free(&c);
                        why = "the surfaces meet at so small an angle that their intersection "
                              "folds on itself";
                        run_free(&below[q]);
                        continue;
                    }
                    /* gap closed and flap trimmed, over the raw points used */
                    for (int s = 0; s < 2; s++) {
                        if (!end[s])
                            continue;
                        for (size_t i = (size_t)ceil(pieces[2 * k]);
                             (double)i <= pieces[2 * k + 1] && i < d->n; i++) {
                            if (!d->inside[s][i])
                                jj.gap = fmax(jj.gap, d->sd[s][i]);
                            else if (isfinite(d->flap[s][i]))
                                jj.overshoot = fmax(jj.overshoot, d->flap[s][i]);
                        }
                    }
                    if (result_push(out, &jj, &c)) {
                        pl_curve_free(&c);
                        rc = -1;
                    }
                    made++;
                }
            }
            run_free(&below[q]);
        }
        free(below);
    }
    free(pieces);
    if (rc == 0 && made == 0) {
        j.reason = why;
        rc = result_push(out, &j, NULL);
    }
done:
    free(iv[0]);
    free(iv[1]);
    free(d->foot[0]);
    free(d->foot[1]);
    d->foot[0] = d->foot[1] = NULL;
    return rc;
}

fm_status pl_decide_pair(const pl_sheet *a, size_t fault_a, size_t sheet_a, const pl_sheet *b,
                         size_t fault_b, size_t sheet_b, const fm_connect_plan_options *opt,
                         const cn_runs *kept, cn_runs *traced, pl_pair_result *out,
                         fm_error *err)
{
    memset(out, 0, sizeof *out);
    fm_connect_options co;
    fm_connect_options_default(&co);
    co.distance = opt->distance;
    co.reach = opt->distance;
    /* raw points a few per mesh edge, so that cuts land within H/4 */
    co.spacing = fmin(co.spacing, 0.25 * opt->size);
    fm_connect_curves *cs = NULL;
    fm_status st = FM_OK;
    if (!kept) {
        st = cn_intersect_trace(a->s, b->s, &co, traced, err);
        kept = traced;
    }
    if (st == FM_OK)
        st = cn_intersect_emit(a->s, b->s, &co, kept, &cs, err);
    if (st != FM_OK)
        return st;
    if (fm_connect_curves_count(cs) > 0) {
        const pl_sheet *bad = a->st != FM_OK ? a : b->st != FM_OK ? b : NULL;
        if (bad) {
            if (err)
                *err = bad->err;
            fm_connect_curves_destroy(cs);
            return bad->st;
        }
    }
    decider d;
    memset(&d, 0, sizeof d);
    d.S[0] = a->s->surf;
    d.S[1] = b->s->surf;
    d.ol[0] = &a->ol;
    d.ol[1] = &b->ol;
    d.o = opt;
    for (size_t i = 0; i < fm_connect_curves_count(cs) && st == FM_OK; i++)
        if (decide_curve(&d, cs, i, fault_a, sheet_a, fault_b, sheet_b, out))
            st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory (plan)");
    fm_connect_curves_destroy(cs);
    if (st != FM_OK)
        pl_pair_result_free(out);
    return st;
}
