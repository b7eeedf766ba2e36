/* The junction plan (fm_connect.h): neighbours, near-duplicates, every
 * pair's curves decided on N threads, conflicts between curves on one
 * sheet resolved longest first, shared nodes numbered. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_clock.h"
#include "plan_internal.h"

void fm_connect_plan_options_default(fm_connect_plan_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->distance = 1000;
    opt->size = 1000;
    opt->cut = 1;
    opt->sea_level = 0;
    opt->nthreads = 1;
    fm_connect_duplicate_options_default(&opt->duplicates);
}

const char *fm_junction_type_name(fm_junction_type t)
{
    switch (t) {
    case FM_JUNCTION_CROSSING:
        return "crossing";
    case FM_JUNCTION_T:
        return "T";
    case FM_JUNCTION_CORNER:
        return "corner";
    default:
        return "unjoined";
    }
}

typedef struct plan_curve {
    pl_curve c;
    int64_t *node[2];  /* per side, in that side's order */
    double *uv[2];     /* per side, in that side's order (reversed when it keeps the right) */
} plan_curve;

struct fm_connect_plan {
    fm_connect_junction *junction;
    size_t njunction;
    plan_curve *curve;
    size_t ncurve;
    double *nodes;
    size_t nnodes;
    size_t nfaults;
    size_t *sheet_base;        /* nfaults + 1 */
    size_t *sheet_start;       /* per global sheet + 1: range in shared */
    fm_connect_shared *shared;
    unsigned char *dropped;
    fm_connect_duplicate *dup;
    size_t ndup;
    fm_connect_pairs *pairs;   /* what it was made from, to be kept (neighbours.c) */
    cn_runs *runs;             /* per pair: the runs traced by this plan (neighbours.c) */
    double *run_distance;      /* per pair: the join distance they were traced at */
    unsigned char *traced;     /* per pair: 1 when runs[k] was traced now, 2 when the pair was
                                  decided from kept runs, 0 when not decided */
    size_t nruns;
    fm_connect_plan_stats stats;
};

void fm_connect_plan_destroy(fm_connect_plan *p)
{
    if (!p)
        return;
    for (size_t i = 0; i < p->ncurve; i++) {
        pl_curve_free(&p->curve[i].c);
        for (int s = 0; s < 2; s++) {
            free(p->curve[i].node[s]);
            free(p->curve[i].uv[s]);
        }
    }
    free(p->curve);
    for (size_t k = 0; p->runs && k < p->nruns; k++)
        cn_runs_free(&p->runs[k]);
    free(p->runs);
    free(p->run_distance);
    free(p->traced);
    fm_connect_pairs_destroy(p->pairs);
    free(p->junction);
    free(p->nodes);
    free(p->sheet_base);
    free(p->sheet_start);
    free(p->shared);
    free(p->dropped);
    free(p->dup);
    free(p);
}

size_t fm_connect_plan_njunctions(const fm_connect_plan *p) { return p->njunction; }
const fm_connect_junction *fm_connect_plan_junction(const fm_connect_plan *p, size_t i)
{
    return &p->junction[i];
}
size_t fm_connect_plan_nnodes(const fm_connect_plan *p) { return p->nnodes; }
const double *fm_connect_plan_nodes(const fm_connect_plan *p) { return p->nodes; }
const fm_connect_plan_stats *fm_connect_plan_get_stats(const fm_connect_plan *p)
{
    return &p->stats;
}

size_t fm_connect_plan_sheet(const fm_connect_plan *p, size_t fault, size_t sheet,
                             const fm_connect_shared **out)
{
    *out = NULL;
    if (fault >= p->nfaults || sheet >= p->sheet_base[fault + 1] - p->sheet_base[fault])
        return 0;
    size_t g = p->sheet_base[fault] + sheet;
    *out = p->shared + p->sheet_start[g];
    return p->sheet_start[g + 1] - p->sheet_start[g];
}

int fm_connect_plan_dropped(const fm_connect_plan *p, size_t fault,
                            const fm_connect_duplicate **dup)
{
    if (dup)
        *dup = NULL;
    if (fault >= p->nfaults || !p->dropped[fault])
        return 0;
    for (size_t k = 0; dup && k < p->ndup; k++)
        if (p->dup[k].decided && p->dup[k].dropped == fault)
            *dup = &p->dup[k];
    return 1;
}

/* ---- Pairs on N threads ---- */

typedef struct pair_work {
    const fm_connect_pairs *pairs;
    const fm_connect_plan_options *opt;
    const fm_connect_neighbours *kept; /* runs kept by an earlier plan; NULL: none */
    cn_runs *runs;                     /* per pair: traced now */
    double *run_distance;
    unsigned char *traced;
    const unsigned char *dropped;
    const pl_sheet *sheet;      /* per global sheet */
    const size_t *base;         /* per fault: its first global sheet */
    pl_pair_result *res;
    fm_status *st;
    fm_error *err;
} pair_work;

/* The pair's one junction, unjoined for `reason`. */
static void push_unjoined(pair_work *w, size_t k, const fm_connect_pair *p, const char *reason)
{
    fm_connect_junction j;
    memset(&j, 0, sizeof j);
    j.fault[0] = p->fault_a;
    j.sheet[0] = p->sheet_a;
    j.fault[1] = p->fault_b;
    j.sheet[1] = p->sheet_b;
    j.type = FM_JUNCTION_UNJOINED;
    j.curve = -1;
    j.distance = p->distance;
    j.reason = reason;
    pl_pair_result *r = &w->res[k];
    r->junction = malloc(sizeof *r->junction);
    r->curve = calloc(1, sizeof *r->curve);
    if (!r->junction || !r->curve) {
        free(r->junction);
        free(r->curve);
        r->junction = NULL;
        r->curve = NULL;
        w->st[k] = fm_error_set(&w->err[k], FM_ERR_NOMEM, NULL, 0, "out of memory");
        return;
    }
    r->junction[0] = j;
    r->n = r->cap = 1;
}

/* What becomes of pair p: PAIR_DROPPED or PAIR_NO_JOIN (unjoined, for
 * that reason), PAIR_FAR (found only because other faults join farther:
 * not a near pair, left out), or PAIR_DECIDED with its options *po. */
enum { PAIR_DECIDED, PAIR_DROPPED, PAIR_NO_JOIN, PAIR_FAR };

static int pair_fate(const fm_connect_plan_options *o, const unsigned char *dropped,
                     const fm_connect_pair *p, fm_connect_plan_options *po)
{
    size_t a = p->fault_a, b = p->fault_b;
    if (dropped[a] || dropped[b])
        return PAIR_DROPPED;
    if (o->fault_joins && (!o->fault_joins[a] || !o->fault_joins[b]))
        return PAIR_NO_JOIN;
    *po = *o;
    if (o->fault_distance)
        po->distance = fmax(o->fault_distance[a], o->fault_distance[b]);
    if (o->fault_size)
        po->size = fmin(o->fault_size[a], o->fault_size[b]);
    if (o->fault_cut)
        po->cut = o->fault_cut[a] || o->fault_cut[b];
    return p->distance > po->distance ? PAIR_FAR : PAIR_DECIDED;
}

static void do_pair(void *user, size_t k)
{
    pair_work *w = user;
    const fm_connect_pair *p = fm_connect_pairs_get(w->pairs, k);
    fm_connect_plan_options po;
    switch (pair_fate(w->opt, w->dropped, p, &po)) {
    case PAIR_DROPPED:
        push_unjoined(w, k, p, "one of the pair was given up as a near-duplicate");
        return;
    case PAIR_NO_JOIN:
        push_unjoined(w, k, p, "one of the pair is set not to join other faults");
        return;
    case PAIR_FAR:
        return;
    default:
        break;
    }
    size_t a = p->fault_a, b = p->fault_b;
    const cn_runs *kept = w->kept ? cn_neighbours_runs(w->kept, k, po.distance) : NULL;
    w->st[k] = pl_decide_pair(&w->sheet[w->base[a] + p->sheet_a], a, p->sheet_a,
                              &w->sheet[w->base[b] + p->sheet_b], b, p->sheet_b, &po, kept,
                              &w->runs[k], &w->res[k], &w->err[k]);
    if (kept)
        w->traced[k] = 2;
    else if (w->st[k] == FM_OK) {
        w->traced[k] = 1;
        w->run_distance[k] = po.distance;
    }
    /* a pair within the join distance whose surfaces, even extended, never
     * meet is listed too, so that every near pair has its line in the report */
    if (w->st[k] == FM_OK && w->res[k].n == 0)
        push_unjoined(w, k, p,
                      "the surfaces come within the join distance but do not meet, even "
                      "extended (no intersection curve)");
}

/* Outlines of the sheets some pair needs, on N threads. */
typedef struct outline_work {
    const fm_model *const *models;
    const size_t (*ref)[2];     /* fault, sheet */
    const size_t *slot;         /* global sheet */
    pl_sheet *sheet;
} outline_work;

static void do_outline(void *user, size_t k)
{
    outline_work *w = user;
    pl_sheet *s = &w->sheet[w->slot[k]];
    s->st = pl_outline_build(w->models[w->ref[k][0]], w->ref[k][1], &s->ol, &s->err);
}

/* ---- Assembly ---- */

static fm_status assemble(fm_connect_plan *p, const fm_model *const *models, size_t n,
                          pl_pair_result *res, size_t npairs, const fm_connect_plan_options *o,
                          fm_error *err)
{
    double H = o->size;
    size_t nj = 0;
    for (size_t k = 0; k < npairs; k++)
        nj += res[k].n;
    p->junction = malloc((nj + 1) * sizeof *p->junction);
    pl_curve *C = calloc(nj + 1, sizeof *C);
    if (!p->junction || !C) {
        free(C);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    size_t q = 0;
    for (size_t k = 0; k < npairs; k++)
        for (size_t i = 0; i < res[k].n; i++, q++) {
            p->junction[q] = res[k].junction[i];
            C[q] = res[k].curve[i];
            memset(&res[k].curve[i], 0, sizeof res[k].curve[i]);
        }
    p->njunction = nj;
    size_t triples = 0;
    if (pl_triple_junctions(p->junction, C, nj, models, H, o->cut ? &o->sea_level : NULL,
                            &triples) ||
        pl_resolve_conflicts(p->junction, C, nj, models, H, o->distance,
                             o->cut ? &o->sea_level : NULL)) {
        for (size_t i = 0; i < nj; i++)
            pl_curve_free(&C[i]);
        free(C);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    size_t nc = 0, nn = 0;
    int64_t nkeys = 0;
    for (size_t i = 0; i < nj; i++)
        if (C[i].n) {
            nc++;
            nn += C[i].n;
            for (size_t k = 0; C[i].key && k < C[i].n; k++)
                nkeys = C[i].key[k] + 1 > nkeys ? C[i].key[k] + 1 : nkeys;
        }
    int64_t *key_id = malloc(((size_t)nkeys + 1) * sizeof *key_id);
    if (!key_id) {
        for (size_t i = 0; i < nj; i++)
            pl_curve_free(&C[i]);
        free(C);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    for (int64_t k = 0; k < nkeys; k++)
        key_id[k] = -1;
    p->curve = calloc(nc + 1, sizeof *p->curve);
    p->nodes = malloc(3 * (nn + 1) * sizeof *p->nodes);
    if (!p->curve || !p->nodes) {
        for (size_t i = 0; i < nj; i++)
            pl_curve_free(&C[i]);
        free(C);
        free(key_id);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    for (size_t i = 0; i < nj; i++) {
        fm_connect_junction *j = &p->junction[i];
        if (!C[i].n)
            continue;
        plan_curve *pc = &p->curve[p->ncurve];
        pc->c = C[i];
        memset(&C[i], 0, sizeof C[i]);
        size_t m = pc->c.n;
        /* node ids: a keyed node takes the id its key got first */
        int64_t *id = malloc((m + 1) * sizeof *id);
        if (!id) {
            p->ncurve++;
            for (size_t r = i + 1; r < nj; r++)
                pl_curve_free(&C[r]);
            free(C);
            free(key_id);
            return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
        }
        for (size_t k = 0; k < m; k++) {
            int64_t key = pc->c.key ? pc->c.key[k] : -1;
            if (key >= 0 && key_id[key] >= 0) {
                id[k] = key_id[key];
                continue;
            }
            memcpy(p->nodes + 3 * p->nnodes, pc->c.xyz + 3 * k, 3 * sizeof(double));
            id[k] = (int64_t)p->nnodes++;
            if (key >= 0)
                key_id[key] = id[k];
        }
        for (int s = 0; s < 2; s++) {
            pc->node[s] = malloc(m * sizeof *pc->node[s]);
            pc->uv[s] = malloc(2 * m * sizeof *pc->uv[s]);
            if (!pc->node[s] || !pc->uv[s]) {
                p->ncurve++;
                for (size_t r = i + 1; r < nj; r++)
                    pl_curve_free(&C[r]);
                free(C);
                free(id);
                free(key_id);
                return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
            }
            int rev = pc->c.end[s] && !pc->c.keep_left[s];
            for (size_t k = 0; k < m; k++) {
                size_t from = rev ? m - 1 - k : k;
                pc->node[s][k] = id[from];
                pc->uv[s][2 * k] = pc->c.uv[s][2 * from];
                pc->uv[s][2 * k + 1] = pc->c.uv[s][2 * from + 1];
            }
        }
        j->curve = (long)p->ncurve;
        free(id);
        p->ncurve++;
    }
    free(C);
    free(key_id);
    p->stats.triple_points = triples;
    /* per-sheet lists */
    p->nfaults = n;
    p->sheet_base = calloc(n + 1, sizeof *p->sheet_base);
    if (!p->sheet_base)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    for (size_t f = 0; f < n; f++)
        p->sheet_base[f + 1] = p->sheet_base[f] + (models[f] ? fm_model_nsheets(models[f]) : 0);
    size_t ns = p->sheet_base[n];
    p->sheet_start = calloc(ns + 2, sizeof *p->sheet_start);
    p->shared = malloc((2 * p->ncurve + 1) * sizeof *p->shared);
    if (!p->sheet_start || !p->shared)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    for (size_t i = 0; i < p->njunction; i++) {
        const fm_connect_junction *j = &p->junction[i];
        if (j->curve < 0)
            continue;
        for (int s = 0; s < 2; s++)
            if (!p->curve[j->curve].c.off[s])
                p->sheet_start[p->sheet_base[j->fault[s]] + j->sheet[s] + 1]++;
    }
    for (size_t g = 0; g < ns; g++)
        p->sheet_start[g + 1] += p->sheet_start[g];
    size_t *fill = calloc(ns + 1, sizeof *fill);
    if (!fill)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    for (size_t i = 0; i < p->njunction; i++) {
        const fm_connect_junction *j = &p->junction[i];
        if (j->curve < 0)
            continue;
        const plan_curve *pc = &p->curve[j->curve];
        for (int s = 0; s < 2; s++) {
            if (pc->c.off[s])
                continue;
            size_t g = p->sheet_base[j->fault[s]] + j->sheet[s];
            fm_connect_shared *sh = &p->shared[p->sheet_start[g] + fill[g]++];
            sh->curve = (size_t)j->curve;
            sh->n = pc->c.n;
            sh->uv = pc->uv[s];
            sh->node = pc->node[s];
            sh->end = pc->c.end[s];
        }
    }
    free(fill);
    return FM_OK;
}

/* The pairs and near-duplicates kept from an earlier run (o.neighbours):
 * copied, after checking that they name faults and sheets of these models
 * (their key says so; a caller's mistake is an error, not a crash). */
static fm_status kept_neighbours(const fm_connect_neighbours *nb, const fm_model *const *models,
                                 size_t n, fm_connect_pairs **pairs, fm_connect_plan *p,
                                 fm_error *err)
{
    const fm_connect_pair *pv;
    const fm_connect_duplicate *dv;
    size_t np, nd;
    cn_neighbours_view(nb, &pv, &np, &dv, &nd);
    int ok = cn_neighbours_nfaults(nb) == n;
    for (size_t k = 0; ok && k < np; k++)
        ok = models[pv[k].fault_a] && models[pv[k].fault_b] &&
             pv[k].sheet_a < fm_model_nsheets(models[pv[k].fault_a]) &&
             pv[k].sheet_b < fm_model_nsheets(models[pv[k].fault_b]);
    for (size_t k = 0; ok && k < nd; k++)
        ok = dv[k].dropped < n && dv[k].kept < n;
    if (!ok)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "connect: the neighbours given are of other faults");
    *pairs = cn_pairs_copy(pv, np);
    p->dup = malloc((nd + 1) * sizeof *p->dup);
    if (!*pairs || !p->dup)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    if (nd)
        memcpy(p->dup, dv, nd * sizeof *dv);
    p->ndup = nd;
    return FM_OK;
}

/* The faults the near-duplicates give up. */
static void mark_dropped(fm_connect_plan *p)
{
    for (size_t k = 0; k < p->ndup; k++)
        if (p->dup[k].decided) {
            p->dropped[p->dup[k].dropped] = 1;
            p->stats.duplicates++;
        }
}

fm_status fm_connect_plan_build(const fm_model *const *models, size_t n,
                                const fm_connect_plan_options *opt, fm_connect_plan **out,
                                fm_error *err)
{
    *out = NULL;
    fm_connect_plan_options o;
    if (opt)
        o = *opt;
    else
        fm_connect_plan_options_default(&o);
    if (!(o.distance > 0) || !(o.size > 0) || !isfinite(o.distance) || !isfinite(o.size))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "connect: join distance and mesh size must be positive");
    double t0 = fm_clock_seconds();
    fm_connect_plan *p = calloc(1, sizeof *p);
    if (!p)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    p->dropped = calloc(n + 1, 1);
    if (!p->dropped) {
        fm_connect_plan_destroy(p);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    fm_connect_options co;
    fm_connect_options_default(&co);
    co.distance = o.distance;
    co.reach = o.distance;
    co.nthreads = o.nthreads;
    o.duplicates.nthreads = o.nthreads;
    /* Every sheet is sampled once: the neighbour search and every pair's
     * curves share the samples (and the outlines, below). */
    size_t *base = calloc(n + 1, sizeof *base);
    if (!base) {
        fm_connect_plan_destroy(p);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    for (size_t f = 0; f < n; f++)
        base[f + 1] = base[f] + (models[f] ? fm_model_nsheets(models[f]) : 0);
    cn_sheet *sh = NULL;
    size_t ns = 0;
    fm_connect_pairs *pairs = NULL;
    fm_status st = FM_OK;
    if (o.neighbours) {
        /* Pairs kept: a sheet is sampled whole only for a pair whose runs
         * must be traced again, else only its outline is made (the runs'
         * emit needs no more), and not at all when no pair needs it. */
        unsigned char *level = calloc(base[n] + 1, 1);
        if (!level)
            st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
        else
            st = kept_neighbours(o.neighbours, models, n, &pairs, p, err);
        if (st == FM_OK) {
            mark_dropped(p);
            for (size_t k = 0; k < fm_connect_pairs_count(pairs); k++) {
                const fm_connect_pair *pp = fm_connect_pairs_get(pairs, k);
                fm_connect_plan_options po;
                int fate = pair_fate(&o, p->dropped, pp, &po);
                if (fate != PAIR_DECIDED)
                    continue;
                int need = cn_neighbours_runs(o.neighbours, k, po.distance) ? 1 : 2;
                size_t ga = base[pp->fault_a] + pp->sheet_a, gb = base[pp->fault_b] + pp->sheet_b;
                level[ga] = (unsigned char)(level[ga] > need ? level[ga] : need);
                level[gb] = (unsigned char)(level[gb] > need ? level[gb] : need);
            }
            st = cn_sheets_build_some(models, n, co.reach, level, o.nthreads, &sh, &ns, err);
        }
        free(level);
    } else {
        st = cn_sheets_build(models, n, co.reach, o.nthreads, &sh, &ns, err);
        double ts = fm_clock_seconds();
        if (st == FM_OK && (st = cn_find_pairs(sh, ns, &co, &pairs, err)) == FM_OK) {
            cn_pairs_set_time_sample(pairs, ts - t0);
            st = fm_connect_find_duplicates(models, n, pairs, &o.duplicates, &p->dup, &p->ndup,
                                            err);
        }
        if (st == FM_OK)
            mark_dropped(p);
    }
    if (st != FM_OK) {
        fm_connect_pairs_destroy(pairs);
        cn_sheets_free(sh, ns);
        free(base);
        fm_connect_plan_destroy(p);
        return st;
    }
    double t1 = fm_clock_seconds();
    size_t np = fm_connect_pairs_count(pairs);
    pl_sheet *psh = calloc(ns + 1, sizeof *psh);
    size_t(*ref)[2] = malloc((2 * np + 1) * sizeof *ref);
    size_t *slot = malloc((2 * np + 1) * sizeof *slot), nol = 0;
    pair_work w;
    memset(&w, 0, sizeof w);
    w.pairs = pairs;
    w.opt = &o;
    w.kept = o.neighbours;
    w.runs = calloc(np + 1, sizeof *w.runs);
    w.run_distance = calloc(np + 1, sizeof *w.run_distance);
    w.traced = calloc(np + 1, 1);
    w.dropped = p->dropped;
    w.sheet = psh;
    w.base = base;
    w.res = calloc(np + 1, sizeof *w.res);
    w.st = calloc(np + 1, sizeof *w.st);
    w.err = calloc(np + 1, sizeof *w.err);
    if (!psh || !ref || !slot || !w.res || !w.st || !w.err || !w.runs || !w.run_distance ||
        !w.traced) {
        free(w.runs);
        free(w.run_distance);
        free(w.traced);
        free(psh);
        free(ref);
        free(slot);
        free(w.res);
        free(w.st);
        free(w.err);
        fm_connect_pairs_destroy(pairs);
        cn_sheets_free(sh, ns);
        free(base);
        fm_connect_plan_destroy(p);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    for (size_t g = 0; g < ns; g++)
        psh[g].s = &sh[g];
    for (size_t k = 0; k < np; k++) {
        const fm_connect_pair *pp = fm_connect_pairs_get(pairs, k);
        if (p->dropped[pp->fault_a] || p->dropped[pp->fault_b])
            continue;
        for (int e = 0; e < 2; e++) {
            size_t f = e ? pp->fault_b : pp->fault_a, s = e ? pp->sheet_b : pp->sheet_a;
            size_t g = base[f] + s;
            if (psh[g].st == FM_OK && !psh[g].ol.tree) {
                psh[g].st = FM_ERR_INVALID; /* marks it wanted until built */
                ref[nol][0] = f;
                ref[nol][1] = s;
                slot[nol++] = g;
            }
        }
    }
    outline_work ow = {models, (const size_t(*)[2])ref, slot, psh};
    cn_parallel_for_told(nol, o.nthreads, do_outline, &ow, o.progress, o.progress_user, 0,
                         nol + np);
    cn_parallel_for_told(np, o.nthreads, do_pair, &w, o.progress, o.progress_user, nol, nol + np);
    for (size_t g = 0; g < ns; g++)
        pl_outline_free(&psh[g].ol);
    free(psh);
    free(ref);
    free(slot);
    cn_sheets_free(sh, ns);
    free(base);
    double t2 = fm_clock_seconds();
    for (size_t k = 0; k < np && st == FM_OK; k++)
        if (w.st[k] != FM_OK) {
            /* a pair whose curves could not be computed stays unjoined
             * unless memory ran out */
            if (w.st[k] == FM_ERR_NOMEM) {
                *err = w.err[k];
                st = FM_ERR_NOMEM;
            } else {
                const fm_connect_pair *pp = fm_connect_pairs_get(pairs, k);
                pl_pair_result *r = &w.res[k];
                pl_pair_result_free(r);
                r->junction = calloc(1, sizeof *r->junction);
                r->curve = calloc(1, sizeof *r->curve);
                if (!r->junction || !r->curve) {
                    st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
                    break;
                }
                r->junction[0].fault[0] = pp->fault_a;
                r->junction[0].sheet[0] = pp->sheet_a;
                r->junction[0].fault[1] = pp->fault_b;
                r->junction[0].sheet[1] = pp->sheet_b;
                r->junction[0].type = FM_JUNCTION_UNJOINED;
                r->junction[0].curve = -1;
                r->junction[0].reason = "intersection curves could not be computed";
                r->n = r->cap = 1;
            }
        }
    if (st == FM_OK)
        st = assemble(p, models, n, w.res, np, &o, err);
    for (size_t k = 0; k < np; k++)
        pl_pair_result_free(&w.res[k]);
    free(w.res);
    free(w.st);
    free(w.err);
    p->pairs = pairs;
    /* the runs traced now, for fm_connect_neighbours_put */
    p->runs = w.runs;
    p->run_distance = w.run_distance;
    p->traced = w.traced;
    p->nruns = np;
    if (st != FM_OK) {
        fm_connect_plan_destroy(p);
        return st;
    }
    p->stats.pairs = np;
    for (size_t k = 0; k < np; k++) {
        p->stats.pairs_traced += p->traced[k] == 1;
        p->stats.pairs_kept += p->traced[k] == 2;
    }
    p->stats.curves = p->ncurve;
    for (size_t i = 0; i < p->njunction; i++)
        p->stats.junctions[p->junction[i].type]++;
    p->stats.time_pairs = t1 - t0;
    p->stats.time_curves = t2 - t1;
    p->stats.time_total = fm_clock_seconds() - t0;
    *out = p;
    return FM_OK;
}

const fm_connect_pairs *fm_connect_plan_pairs(const fm_connect_plan *p) { return p->pairs; }

const fm_connect_duplicate *fm_connect_plan_duplicates(const fm_connect_plan *p, size_t *n)
{
    *n = p->ndup;
    return p->dup;
}

const cn_runs *cn_plan_runs(const fm_connect_plan *p, size_t k, double *distance)
{
    if (k >= p->nruns || p->traced[k] != 1)
        return NULL;
    *distance = p->run_distance[k];
    return &p->runs[k];
}
