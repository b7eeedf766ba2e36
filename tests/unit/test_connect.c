/* Neighbours and intersection curves (src/connect): fitted planes crossing
 * at 90 and 10 degrees against the analytic line, the synthetic system's
 * T-junction gap and overshoot, three planes whose curves meet at a small
 * angle, a curve cut short of another it nears, a curve beyond the one a
 * sheet ends at, a fault stopped short of another where its curve cannot
 * be joined, near-duplicate faults, and two crossing CFM faults. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fm_connect.h"
#include "fm_model.h"
#include "fm_repair.h"
#include "fm_synth.h"
#include "fm_test.h"
#include "fm_tsurf.h"

#define FM_PI 3.14159265358979323846
#define X0 400000.0
#define Y0 3700000.0

/* The two triangles of every cell of a grid of (nu + 1) x (nv + 1)
 * vertices numbered row by row from base. */
static void grid_triangles(fm_mesh *m, int32_t base, int nu, int nv)
{
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            int32_t a = base + j * (nu + 1) + i, b = a + 1, d = a + nu + 1, e = d + 1;
            fm_mesh_add_triangle(m, a, b, e, 0);
            fm_mesh_add_triangle(m, a, e, d, 0);
        }
}

/* A vertical plane through (X0, Y0) with horizontal direction (cos az,
 * sin az), s in [-half, half], z in [zbot, 0], triangles of about h. */
static fm_mesh *vertical_plane(double az_deg, double half, double zbot, double h)
{
    fm_mesh *m = fm_mesh_create();
    double c = cos(az_deg * FM_PI / 180), s = sin(az_deg * FM_PI / 180);
    int ns = (int)ceil(2 * half / h), nz = (int)ceil(-zbot / h);
    for (int j = 0; j <= nz; j++)
        for (int i = 0; i <= ns; i++) {
            double t = -half + 2 * half * i / ns, z = zbot * j / nz;
            fm_mesh_add_vertex(m, X0 + t * c, Y0 + t * s, z);
        }
    grid_triangles(m, 0, ns, nz);
    return m;
}

/* Part t in [t0, t1] of a vertical plane like vertical_plane's (az 0:
 * along x), moved `off` metres along y. */
static fm_mesh *plane_part(double t0, double t1, double off, double zbot, double h)
{
    fm_mesh *m = fm_mesh_create();
    int ns = (int)ceil((t1 - t0) / h), nz = (int)ceil(-zbot / h);
    for (int j = 0; j <= nz; j++)
        for (int i = 0; i <= ns; i++)
            fm_mesh_add_vertex(m, X0 + t0 + (t1 - t0) * i / ns, Y0 + off, zbot * j / nz);
    grid_triangles(m, 0, ns, nz);
    return m;
}

static fm_model *fit_mesh(const char *name, const fm_mesh *m)
{
    fm_surface *s = NULL;
    fm_model *model = NULL;
    fm_error err;
    if (fm_repair(m, NULL, &s, &err) != FM_OK) {
        fprintf(stderr, "%s\n", err.message);
        return NULL;
    }
    if (fm_model_build(name, s, NULL, &model, &err) != FM_OK)
        fprintf(stderr, "%s\n", err.message);
    fm_surface_destroy(s);
    return model;
}

static void check_points_on_surfaces(const fm_connect_curves *c, const fm_model *a, size_t sa,
                                     const fm_model *b, size_t sb, double tol)
{
    for (size_t i = 0; i < fm_connect_curves_count(c); i++) {
        size_t n;
        const double *p = fm_connect_curve_points(c, i, &n);
        const fm_connect_curve_info *info = fm_connect_curve_get_info(c, i);
        CHECK(info->max_dist[0] < 1e-3 && info->max_dist[1] < 1e-3);
        for (size_t k = 0; k < n; k++) {
            for (int side = 0; side < 2; side++) {
                const fm_fit_surface *S = fm_model_surface(side ? b : a, side ? sb : sa);
                const double *uv = fm_connect_curve_params(c, i, side) + 2 * k;
                double q[3], uvp[2], foot[3], d;
                fm_fit_surface_eval(S, uv[0], uv[1], q, NULL, NULL);
                CHECK(fabs(q[0] - p[3 * k]) + fabs(q[1] - p[3 * k + 1]) + fabs(q[2] - p[3 * k + 2]) <
                      tol);
                fm_fit_project(S, p + 3 * k, uvp, foot, &d);
                CHECK(fabs(d) < tol);
            }
        }
    }
}

/* Two fitted vertical planes crossing along the vertical line through
 * (X0, Y0) at the given angle. */
static void planes_at(double angle)
{
    fm_mesh *ma = vertical_plane(90.0, 10000, -10000, 500);
    fm_mesh *mb = vertical_plane(90.0 - angle, 8000, -9000, 500);
    fm_model *a = fit_mesh("A", ma), *b = fit_mesh("B", mb);
    CHECK(a && b);
    if (!a || !b)
        goto out;
    fm_error err;
    fm_connect_pairs *pairs = NULL;
    const fm_model *models[2] = {a, b};
    CHECK(fm_connect_find_pairs(models, 2, NULL, &pairs, &err) == FM_OK);
    CHECK_EQ(fm_connect_pairs_count(pairs), 1);
    if (fm_connect_pairs_count(pairs) == 1) {
        const fm_connect_pair *p = fm_connect_pairs_get(pairs, 0);
        CHECK(p->fault_a == 0 && p->fault_b == 1);
        CHECK(p->crosses && p->trimmed_crosses);
        CHECK(p->distance == 0 && p->trimmed_distance == 0);
    }
    fm_connect_pairs_destroy(pairs);
    fm_connect_curves *c = NULL;
    CHECK(fm_connect_intersect(a, 0, b, 0, NULL, &c, &err) == FM_OK);
    CHECK_EQ(fm_connect_curves_count(c), 1);
    if (fm_connect_curves_count(c) == 1) {
        size_t n;
        const double *p = fm_connect_curve_points(c, 0, &n);
        const fm_connect_curve_info *info = fm_connect_curve_get_info(c, 0);
        double zmin = INFINITY, zmax = -INFINITY, off = 0;
        for (size_t k = 0; k < n; k++) {
            off = fmax(off, hypot(p[3 * k] - X0, p[3 * k + 1] - Y0));
            zmin = fmin(zmin, p[3 * k + 2]);
            zmax = fmax(zmax, p[3 * k + 2]);
        }
        printf("planes %.0f deg: %zu points, z %.1f .. %.1f, off line %.2e m, angle %.3f..%.3f, "
               "fallback %zu\n",
               angle, n, zmin, zmax, off, info->min_angle, info->max_angle, info->fallback_points);
        CHECK(off < 1.0);
        CHECK(!info->closed);
        /* grown by reach = 1000 beyond the shallower bottom (-9000) and the tops (0) */
        CHECK_NEAR(zmin, -10000, 60);
        CHECK_NEAR(zmax, 1000, 60);
        CHECK_NEAR(info->min_angle, angle, 0.5);
        CHECK_NEAR(info->max_angle, angle, 0.5);
        CHECK(info->unconverged == 0);
        CHECK(info->side[0].role == FM_CONNECT_THROUGH);
        CHECK(info->side[1].role == FM_CONNECT_THROUGH);
        /* spacing */
        for (size_t k = 0; k + 1 < n; k++) {
            double l = sqrt(pow(p[3 * k + 3] - p[3 * k], 2) + pow(p[3 * k + 4] - p[3 * k + 1], 2) +
                            pow(p[3 * k + 5] - p[3 * k + 2], 2));
            CHECK(l <= 250.0 + 1e-6 && l > 150.0);
        }
        check_points_on_surfaces(c, a, 0, b, 0, 1e-3);
    }
    fm_connect_curves_destroy(c);
out:
    fm_model_destroy(a);
    fm_model_destroy(b);
    fm_mesh_destroy(ma);
    fm_mesh_destroy(mb);
}

static void test_planes_90(void) { planes_at(90.0); }
static void test_planes_10(void) { planes_at(10.0); }

/* The synthetic system: the T-junction fault stops 300 m short of the main
 * fault, the overshooting one runs 400 m past it. */
static void test_synth(void)
{
    fm_synth *sy = NULL;
    fm_error err;
    CHECK(fm_synth_create(NULL, &sy, &err) == FM_OK);
    if (!sy)
        return;
    size_t n = fm_synth_nfaults(sy);
    fm_model **models = calloc(n, sizeof *models);
    for (size_t i = 0; i < n; i++) {
        models[i] = fit_mesh(fm_synth_fault_name(sy, i), fm_synth_fault_mesh(sy, i));
        CHECK(models[i] != NULL);
    }
    long main_f = fm_synth_find(sy, "SYNT-MAIN-SS-Main_strike_slip_fault-SYN1");
    long tj = fm_synth_find(sy, "SYNT-MAIN-TJNC-T_junction_gap_fault-SYN1");
    long xo = fm_synth_find(sy, "SYNT-MAIN-XOVR-Overshooting_fault-SYN1");
    long sp = fm_synth_find(sy, "SYNT-NWFB-SPLY-Branched_splay_fault-SYN1");
    long wd = fm_synth_find(sy, "SYNT-MAIN-WDGE-Widening_overshoot_fault-SYN1");
    CHECK(main_f >= 0 && tj >= 0 && xo >= 0 && sp >= 0 && wd >= 0);
    fm_connect_pairs *pairs = NULL;
    CHECK(fm_connect_find_pairs((const fm_model *const *)models, n, NULL, &pairs, &err) == FM_OK);
    int seen_tj = 0, seen_xo = 0, seen_sp = 0, seen_wd = 0;
    for (size_t i = 0; i < fm_connect_pairs_count(pairs); i++) {
        const fm_connect_pair *p = fm_connect_pairs_get(pairs, i);
        printf("pair %zu.%zu - %zu.%zu: distance %.1f crosses %d, trimmed %.1f crosses %d\n",
               p->fault_a, p->sheet_a, p->fault_b, p->sheet_b, p->distance, p->crosses,
               p->trimmed_distance, p->trimmed_crosses);
        if ((long)p->fault_a == sp) {
            /* the branching fault's two sheets, split by the foundation
             * stage, meet again along the branch line */
            seen_sp = 1;
            CHECK((long)p->fault_b == sp && p->sheet_a == 0 && p->sheet_b == 1);
            CHECK(p->crosses);
            continue;
        }
        CHECK((long)p->fault_a == main_f);
        if ((long)p->fault_b == tj) {
            seen_tj = 1;
            CHECK(p->crosses && !p->trimmed_crosses);
            CHECK_NEAR(p->trimmed_distance, 300.0, 40.0);
        } else if ((long)p->fault_b == xo) {
            seen_xo = 1;
            CHECK(p->crosses && p->trimmed_crosses);
        } else if ((long)p->fault_b == wd) {
            seen_wd = 1;
            CHECK(p->crosses && p->trimmed_crosses);
        } else {
            CHECK(0); /* no other pair is meant to meet */
        }
    }
    CHECK(seen_tj && seen_xo && seen_sp && seen_wd);
    fm_connect_pairs_destroy(pairs);
    if (main_f >= 0 && tj >= 0 && xo >= 0) {
        for (int k = 0; k < 2; k++) {
            long other = k ? xo : tj;
            fm_connect_curves *c = NULL;
            CHECK(fm_connect_intersect(models[main_f], 0, models[other], 0, NULL, &c, &err) ==
                  FM_OK);
            CHECK_EQ(fm_connect_curves_count(c), 1);
            if (fm_connect_curves_count(c) != 1) {
                fm_connect_curves_destroy(c);
                continue;
            }
            const fm_connect_curve_info *info = fm_connect_curve_get_info(c, 0);
            const fm_connect_side *sm = &info->side[0], *so = &info->side[1];
            printf("%s: %zu points, length %.0f, angle %.1f, main role %d inside %.0f ext %.0f; "
                   "other role %d inside %.0f ext %.0f gap %.1f (max %.1f) flap %.1f\n",
                   k ? "overshoot" : "T-junction", info->npoints, info->length, info->mean_angle,
                   sm->role, sm->length_inside, sm->length_extension, so->role, so->length_inside,
                   so->length_extension, so->median_gap, so->max_gap, so->median_flap);
            CHECK(sm->role == FM_CONNECT_THROUGH);
            CHECK(sm->length_inside > 10000.0);
            if (k == 0) {
                /* the curve lies in the T fault's extension, 300 m past its end */
                CHECK(so->role == FM_CONNECT_GAP);
                CHECK(so->length_inside == 0);
                CHECK_NEAR(so->median_gap, 300.0, 40.0);
                CHECK_NEAR(info->mean_angle, 90.0, 1.0);
            } else {
                /* inside the overshooting fault, with 400 m of it beyond */
                CHECK(so->role == FM_CONNECT_OVERSHOOT);
                CHECK(so->length_extension < 0.2 * info->length);
                /* 400 m from the main fault, so 400 / sin 60 over its own surface */
                CHECK_NEAR(so->median_flap * sin(info->mean_angle * FM_PI / 180), 400.0, 40.0);
                CHECK_NEAR(info->mean_angle, 60.0, 1.0);
            }
            check_points_on_surfaces(c, models[main_f], 0, models[other], 0, 1e-3);
            fm_connect_curves_destroy(c);
        }
    }
    for (size_t i = 0; i < n; i++)
        fm_model_destroy(models[i]);
    free(models);
    fm_synth_destroy(sy);
}

/* The junction plan on the synthetic system: the three designed junctions
 * on the main fault are T-junctions with the main fault running through
 * (the widening overshoot too: most of its flap lies within the join
 * distance; the mesher keeps what lies beyond); the shared curve is
 * cut at sea level, sampled at H and lies on both true surfaces; the
 * fault that ends keeps its bulk on the curve's left. */
static void test_synth_plan(void)
{
    fm_synth *sy = NULL;
    fm_error err;
    CHECK(fm_synth_create(NULL, &sy, &err) == FM_OK);
    if (!sy)
        return;
    size_t n = fm_synth_nfaults(sy);
    fm_model **models = calloc(n, sizeof *models);
    for (size_t i = 0; i < n; i++)
        models[i] = fit_mesh(fm_synth_fault_name(sy, i), fm_synth_fault_mesh(sy, i));
    long main_f = fm_synth_find(sy, "SYNT-MAIN-SS-Main_strike_slip_fault-SYN1");
    long tj = fm_synth_find(sy, "SYNT-MAIN-TJNC-T_junction_gap_fault-SYN1");
    long xo = fm_synth_find(sy, "SYNT-MAIN-XOVR-Overshooting_fault-SYN1");
    long sp = fm_synth_find(sy, "SYNT-NWFB-SPLY-Branched_splay_fault-SYN1");
    long wd = fm_synth_find(sy, "SYNT-MAIN-WDGE-Widening_overshoot_fault-SYN1");
    fm_connect_plan_options po;
    fm_connect_plan_options_default(&po);
    po.nthreads = 2;
    fm_connect_plan *plan = NULL;
    CHECK(fm_connect_plan_build((const fm_model *const *)models, n, &po, &plan, &err) == FM_OK);
    if (!plan)
        goto out;
    CHECK_EQ(fm_connect_plan_njunctions(plan), 4);
    const double *X = fm_connect_plan_nodes(plan);
    for (size_t i = 0; i < fm_connect_plan_njunctions(plan); i++) {
        const fm_connect_junction *j = fm_connect_plan_junction(plan, i);
        printf("junction %zu: %s %zu-%zu gap %.1f overshoot %.1f length %.0f%s%s\n", i,
               fm_junction_type_name(j->type), j->fault[0], j->fault[1], j->gap, j->overshoot,
               j->length, j->reason ? ": " : "", j->reason ? j->reason : "");
        CHECK(j->type == FM_JUNCTION_T);
        CHECK(j->curve >= 0);
        if ((long)j->fault[0] == sp) {
            /* the branched splay rejoined: the splay sheet ends on the
             * main sheet along the branch line, which the split left
             * exactly where both meet (no gap to close, no flap) */
            CHECK((long)j->fault[1] == sp && j->sheet[0] != j->sheet[1]);
            CHECK(j->gap < 50.0 && j->overshoot < 50.0);
            CHECK(j->length > 5000.0);
            continue;
        }
        CHECK((long)j->fault[0] == main_f);
        if ((long)j->fault[1] == tj) {
            CHECK_NEAR(j->gap, 300.0, 40.0);
        } else if ((long)j->fault[1] == wd) {
            /* 200 m past the main fault at the top to about 1.3 km at
             * 12 km depth, over a surface crossing it at 60 degrees: the
             * flap trimmed is what lies within the join distance */
            CHECK(j->overshoot > 900.0 && j->overshoot <= 1000.0);
            CHECK_NEAR(j->length, 12250.0, 300.0);
            continue;
        } else {
            CHECK((long)j->fault[1] == xo);
            CHECK_NEAR(j->overshoot * sin(60.0 * FM_PI / 180), 400.0, 40.0);
        }
        /* the T and overshooting faults reach 12 km down, cut at sea level */
        CHECK_NEAR(j->length, 12000.0, 300.0);
    }
    /* per sheet: the main fault has both curves running through; each of
     * the others ends at one; of the splay's sheets one ends on the other */
    const fm_connect_shared *sh = NULL;
    int splay_ends = 0;
    for (size_t s = 0; s < 2; s++) {
        CHECK_EQ(fm_connect_plan_sheet(plan, (size_t)sp, s, &sh), 1);
        splay_ends += sh && sh[0].end;
    }
    CHECK_EQ(splay_ends, 1);
    CHECK_EQ(fm_connect_plan_sheet(plan, (size_t)main_f, 0, &sh), 3);
    for (size_t k = 0; sh && k < 3; k++)
        CHECK(sh[k].end == 0);
    for (int o = 0; o < 2; o++) {
        long f = o ? xo : tj;
        CHECK_EQ(fm_connect_plan_sheet(plan, (size_t)f, 0, &sh), 1);
        if (!sh)
            continue;
        CHECK(sh[0].end == 1);
        double top = -INFINITY;
        for (size_t k = 0; k < sh[0].n; k++) {
            const double *p = X + 3 * sh[0].node[k];
            CHECK(p[2] <= 0);
            top = fmax(top, p[2]);
            CHECK(fm_synth_distance(sy, (size_t)main_f, p) < 5.0);
            /* the T fault's own surface is reached over its extension,
             * past the end of its true one */
            double fuv[2], ff[3], fd = INFINITY;
            fm_fit_project(fm_model_surface(models[f], 0), p, fuv, ff, &fd);
            CHECK(fd < 1e-3);
            if (f == xo)
                CHECK(fm_synth_distance(sy, (size_t)f, p) < 5.0);
            if (k > 0) {
                const double *q = X + 3 * sh[0].node[k - 1];
                double d = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                (p[2] - q[2]) * (p[2] - q[2]));
                CHECK(d > 0.7 * po.size && d < 1.4 * po.size);
            }
        }
        CHECK(top == 0.0); /* the top node is on sea level exactly */
        /* the bulk of the fault lies on the curve's left in its (u, v) */
        const fm_mesh *smp = fm_model_samples(models[f], 0);
        const double *c = fm_mesh_vertices(smp) + 3 * (fm_mesh_nvertices(smp) / 2);
        double uv[2], foot[3];
        fm_fit_project(fm_model_surface(models[f], 0), c, uv, foot, NULL);
        const double *a = sh[0].uv, *b = sh[0].uv + 2 * (sh[0].n - 1);
        double cr = (b[0] - a[0]) * (uv[1] - a[1]) - (b[1] - a[1]) * (uv[0] - a[0]);
        CHECK(cr > 0);
    }
    fm_connect_plan_destroy(plan);
out:
    for (size_t i = 0; i < n; i++)
        fm_model_destroy(models[i]);
    free(models);
    fm_synth_destroy(sy);
}

/* A plane through (X0, Y0, -6400) whose line with the plane y = Y0 is
 * `deg` degrees off the vertical (and whose line with x = X0 is 45
 * degrees off it): a parallelogram of +-5 km along that line and +-4 km
 * across it, triangles of about h. */
static fm_mesh *tilted_plane(double deg, double h)
{
    double t = deg * FM_PI / 180;
    double d[3] = {sin(t), 0, cos(t)}, nr[3] = {cos(t), sin(t), -sin(t)}, e[3];
    e[0] = nr[1] * d[2] - nr[2] * d[1];
    e[1] = nr[2] * d[0] - nr[0] * d[2];
    e[2] = nr[0] * d[1] - nr[1] * d[0];
    double le = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    fm_mesh *m = fm_mesh_create();
    int na = (int)ceil(10000 / h), nb = (int)ceil(8000 / h);
    for (int j = 0; j <= nb; j++)
        for (int i = 0; i <= na; i++) {
            double a = -5000 + 10000.0 * i / na, b = (-4000 + 8000.0 * j / nb) / le;
            fm_mesh_add_vertex(m, X0 + a * d[0] + b * e[0], Y0 + a * d[1] + b * e[1],
                               -6400 + a * d[2] + b * e[2]);
        }
    grid_triangles(m, 0, na, nb);
    return m;
}

/* Three planes through one point, two of whose curves meet there at 14
 * degrees on the sheet they share: they stay within a quarter size of
 * each other for 1 km on either side of the point (the vertical one has
 * nodes 400 and 600 m from it, at 1 km spacing). That is still the
 * one place where they meet: all three junctions are joined, the three
 * curves through one common node at the point. */
static void test_triple_small_angle(void)
{
    fm_mesh *meshes[3] = {vertical_plane(0, 10000, -10000, 500),
                          vertical_plane(90, 10000, -10000, 500), tilted_plane(14, 500)};
    fm_model *models[3];
    for (int k = 0; k < 3; k++) {
        models[k] = fit_mesh(k == 2 ? "tilted" : k ? "plane x" : "plane y", meshes[k]);
        fm_mesh_destroy(meshes[k]);
        CHECK(models[k] != NULL);
    }
    if (!models[0] || !models[1] || !models[2])
        goto out;
    fm_connect_plan_options po;
    fm_connect_plan_options_default(&po);
    fm_connect_plan *plan = NULL;
    fm_error err;
    CHECK(fm_connect_plan_build((const fm_model *const *)models, 3, &po, &plan, &err) == FM_OK);
    if (!plan)
        goto out;
    CHECK_EQ(fm_connect_plan_njunctions(plan), 3);
    for (size_t i = 0; i < fm_connect_plan_njunctions(plan); i++) {
        const fm_connect_junction *j = fm_connect_plan_junction(plan, i);
        printf("junction %zu: %s %zu-%zu length %.0f angle %.1f%s%s\n", i,
               fm_junction_type_name(j->type), j->fault[0], j->fault[1], j->length,
               j->min_angle, j->reason ? ": " : "", j->reason ? j->reason : "");
        CHECK(j->curve >= 0);
    }
    CHECK(fm_connect_plan_get_stats(plan)->triple_points >= 1);
    /* one node at the point, on every sheet's two curves */
    const double *X = fm_connect_plan_nodes(plan);
    for (size_t f = 0; f < 3; f++) {
        const fm_connect_shared *sh = NULL;
        size_t n = fm_connect_plan_sheet(plan, f, 0, &sh);
        CHECK_EQ(n, 2);
        int64_t at[2] = {-1, -2};
        for (size_t k = 0; sh && k < n && k < 2; k++)
            for (size_t i = 0; i < sh[k].n; i++) {
                const double *p = X + 3 * sh[k].node[i];
                if (fabs(p[0] - X0) < 1 && fabs(p[1] - Y0) < 1 && fabs(p[2] + 6400) < 1)
                    at[k] = sh[k].node[i];
            }
        CHECK(at[0] >= 0 && at[0] == at[1]);
    }
    fm_connect_plan_destroy(plan);
out:
    for (int k = 0; k < 3; k++)
        fm_model_destroy(models[k]);
}

/* The plane x - X0 = 200 + 0.2 (z + 10000) + 0.5 (y - Y0), y - Y0 in
 * [-2000, 5000], z in [-10000, 0]. Its line with the plane y = Y0 comes
 * within 200 m of that plane's line with x = X0 at the bottom, and the
 * three would meet only 1 km deeper, below every surface. */
static fm_mesh *leaning_plane(double h)
{
    fm_mesh *m = fm_mesh_create();
    int ny = (int)ceil(7000 / h), nz = (int)ceil(10000 / h);
    for (int j = 0; j <= nz; j++)
        for (int i = 0; i <= ny; i++) {
            double y = -2000 + 7000.0 * i / ny, z = -10000.0 * j / nz;
            fm_mesh_add_vertex(m, X0 + 200 + 0.2 * (z + 10000) + 0.5 * y, Y0 + y, z);
        }
    grid_triangles(m, 0, ny, nz);
    return m;
}

/* Two crossing curves on one sheet that come within a quarter size of
 * each other where there is no point of the three faults: the later one
 * is cut short of the other, not left unjoined, and no two curves on
 * the sheet come that close. */
static void test_cut_short(void)
{
    fm_mesh *meshes[3] = {vertical_plane(0, 10000, -10000, 500),
                          vertical_plane(90, 10000, -10000, 500), leaning_plane(500)};
    fm_model *models[3];
    for (int k = 0; k < 3; k++) {
        models[k] = fit_mesh(k == 2 ? "leaning" : k ? "plane x" : "plane y", meshes[k]);
        fm_mesh_destroy(meshes[k]);
        CHECK(models[k] != NULL);
    }
    if (!models[0] || !models[1] || !models[2])
        goto out;
    fm_connect_plan_options po;
    fm_connect_plan_options_default(&po);
    fm_connect_plan *plan = NULL;
    fm_error err;
    CHECK(fm_connect_plan_build((const fm_model *const *)models, 3, &po, &plan, &err) == FM_OK);
    if (!plan)
        goto out;
    int on_y[2] = {0, 0};
    for (size_t i = 0; i < fm_connect_plan_njunctions(plan); i++) {
        const fm_connect_junction *j = fm_connect_plan_junction(plan, i);
        printf("junction %zu: %s %zu-%zu length %.0f%s%s\n", i, fm_junction_type_name(j->type),
               j->fault[0], j->fault[1], j->length, j->reason ? ": " : "",
               j->reason ? j->reason : "");
        CHECK(j->curve >= 0);
        if (j->fault[0] == 0)
            on_y[j->fault[1] == 2] = 1;
    }
    CHECK(on_y[0] && on_y[1]);
    const double *X = fm_connect_plan_nodes(plan);
    const fm_connect_shared *sh = NULL;
    size_t n = fm_connect_plan_sheet(plan, 0, 0, &sh);
    CHECK_EQ(n, 2);
    double gap = INFINITY;
    for (size_t a = 0; sh && n == 2 && a < 2; a++)
        for (size_t i = 0; i < sh[a].n; i++)
            for (size_t k = 0; k + 1 < sh[1 - a].n; k++)
                gap = fmin(gap, fm_segment_distance3(X + 3 * sh[a].node[i],
                                                     X + 3 * sh[1 - a].node[k],
                                                     X + 3 * sh[1 - a].node[k + 1]));
    printf("closest approach on the shared sheet: %.0f m\n", gap);
    CHECK(gap >= 0.25 * po.size);
    fm_connect_plan_destroy(plan);
out:
    for (int k = 0; k < 3; k++)
        fm_model_destroy(models[k]);
}

/* A height field over x - X0, y - Y0 in [-half, half]: the dome z = top -
 * r^2 / (2 R) (R > 0) or the plane z = top (R = 0). */
static fm_mesh *height_field(double half, double top, double R, double h)
{
    fm_mesh *m = fm_mesh_create();
    int n = (int)ceil(2 * half / h);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double x = -half + 2 * half * i / n, y = -half + 2 * half * j / n;
            fm_mesh_add_vertex(m, X0 + x, Y0 + y, R > 0 ? top - (x * x + y * y) / (2 * R) : top);
        }
    grid_triangles(m, 0, n, n);
    return m;
}

/* A dome through a flat: their intersection is a closed curve (a circle of
 * radius sqrt(2 R 1000) = 4.5 km, 24 degrees) inside both. It is one
 * crossing junction whose curve ends where it began: its first and last
 * nodes are one plan node, on both sheets. */
static void test_closed_loop(void)
{
    fm_mesh *meshes[2] = {height_field(10000, -5000, 10000, 500),
                          height_field(10000, -6000, 0, 500)};
    fm_model *models[2];
    for (int k = 0; k < 2; k++) {
        models[k] = fit_mesh(k ? "flat" : "dome", meshes[k]);
        fm_mesh_destroy(meshes[k]);
        CHECK(models[k] != NULL);
    }
    if (!models[0] || !models[1])
        goto out;
    fm_connect_plan_options po;
    fm_connect_plan_options_default(&po);
    fm_connect_plan *plan = NULL;
    fm_error err;
    CHECK(fm_connect_plan_build((const fm_model *const *)models, 2, &po, &plan, &err) == FM_OK);
    if (!plan)
        goto out;
    CHECK_EQ(fm_connect_plan_njunctions(plan), 1);
    const fm_connect_junction *j = fm_connect_plan_junction(plan, 0);
    CHECK(j && j->type == FM_JUNCTION_CROSSING && j->curve >= 0);
    if (j)
        printf("loop: %s, %.0f m%s%s\n", fm_junction_type_name(j->type), j->length,
               j->reason ? ": " : "", j->reason ? j->reason : "");
    CHECK(j && fabs(j->length - 2 * FM_PI * sqrt(2 * 10000.0 * 1000)) < 300);
    for (size_t f = 0; f < 2; f++) {
        const fm_connect_shared *sh = NULL;
        CHECK_EQ(fm_connect_plan_sheet(plan, f, 0, &sh), 1);
        CHECK(sh && sh->n >= 25 && sh->end == 0);
        CHECK(sh && sh->node[0] == sh->node[sh->n - 1]);
        /* no other node twice */
        for (size_t a = 0; sh && a + 1 < sh->n; a++)
            for (size_t b = a + 1; b + 1 < sh->n; b++)
                CHECK(sh->node[a] != sh->node[b]);
    }
    fm_connect_plan_destroy(plan);
out:
    for (int k = 0; k < 2; k++)
        fm_model_destroy(models[k]);
}

/* The vertical plane x = X0 + off, y - Y0 in [t0, t1], z in [zbot, 0]. */
static fm_mesh *plane_x(double off, double t0, double t1, double zbot, double h)
{
    fm_mesh *m = fm_mesh_create();
    int ns = (int)ceil((t1 - t0) / h), nz = (int)ceil(-zbot / h);
    for (int j = 0; j <= nz; j++)
        for (int i = 0; i <= ns; i++)
            fm_mesh_add_vertex(m, X0 + off, Y0 + t0 + (t1 - t0) * i / ns, zbot * j / nz);
    grid_triangles(m, 0, ns, nz);
    return m;
}

/* Two parallel faults 200 m apart that both end on a third, one from
 * each side, each overshooting it by 300 m: their T-curves on the third
 * run side by side closer than a quarter size, so only one can be
 * joined. The other is not left running through the third: it stops
 * short of it, by a tenth of the size, on its own sheet alone. */
static void test_stop_short(void)
{
    fm_mesh *meshes[3] = {plane_part(-10000, 10000, 0, -10000, 500),
                          plane_x(0, -6000, 300, -10000, 500),
                          plane_x(200, -300, 6000, -10000, 500)};
    fm_model *models[3];
    for (int k = 0; k < 3; k++) {
        models[k] = fit_mesh(k == 0 ? "through" : k == 1 ? "south" : "north", meshes[k]);
        fm_mesh_destroy(meshes[k]);
        CHECK(models[k] != NULL);
    }
    if (!models[0] || !models[1] || !models[2])
        goto out;
    fm_connect_plan_options po;
    fm_connect_plan_options_default(&po);
    fm_connect_plan *plan = NULL;
    fm_error err;
    CHECK(fm_connect_plan_build((const fm_model *const *)models, 3, &po, &plan, &err) == FM_OK);
    if (!plan)
        goto out;
    size_t made = 0, cleared = 0, short_fault = 0;
    long short_curve = -1;
    for (size_t i = 0; i < fm_connect_plan_njunctions(plan); i++) {
        const fm_connect_junction *j = fm_connect_plan_junction(plan, i);
        printf("junction %zu: %s %zu-%zu length %.0f clearance %.0f%s%s\n", i,
               fm_junction_type_name(j->type), j->fault[0], j->fault[1], j->length,
               j->clearance, j->reason ? ": " : "", j->reason ? j->reason : "");
        if (j->type == FM_JUNCTION_T && j->fault[0] == 0)
            made++;
        if (j->type == FM_JUNCTION_UNJOINED && j->clearance > 0) {
            cleared++;
            CHECK(j->fault[0] == 0);
            CHECK(j->curve >= 0);
            CHECK_NEAR(j->clearance, 0.1 * po.size, 1e-9);
            short_fault = j->fault[j->short_side];
            short_curve = j->curve;
        }
    }
    CHECK_EQ(made, 1);
    CHECK_EQ(cleared, 1);
    CHECK(short_fault == 1 || short_fault == 2);
    /* the through fault holds the joined curve only; the one stopped
     * short holds its own, ending there, every node clear of the other */
    const fm_connect_shared *sh = NULL;
    CHECK_EQ(fm_connect_plan_sheet(plan, 0, 0, &sh), 1);
    CHECK(sh && (long)sh[0].curve != short_curve);
    size_t n = fm_connect_plan_sheet(plan, short_fault, 0, &sh);
    CHECK_EQ(n, 1);
    const double *X = fm_connect_plan_nodes(plan);
    double closest = INFINITY;
    for (size_t k = 0; sh && n == 1 && k < sh[0].n; k++)
        closest = fmin(closest, fabs(X[3 * sh[0].node[k] + 1] - Y0));
    printf("stopped short: %zu nodes, closest %.1f m from the through fault\n",
           sh && n == 1 ? sh[0].n : 0, closest);
    CHECK(sh && n == 1 && sh[0].end && (long)sh[0].curve == short_curve);
    CHECK(closest > 0.098 * po.size && closest < 0.102 * po.size);
    fm_connect_plan_destroy(plan);
out:
    for (int k = 0; k < 3; k++)
        fm_model_destroy(models[k]);
}

/* A fault of two vertical sheets in a T: sheet "stem" (y = Y0, x from
 * X0 - 6 km to X0 - 50 m) ends at sheet "bar" (x = X0, y within 5 km of
 * Y0). A second fault, a plane x =
 * X0 + 600 beside the bar down to 4 km, meets the stem's extension 600 m
 * beyond the bar (its curve shorter than the tee's, which goes first). The stem ends at the bar, so it may not also reach past it to the
 * second fault (the gap filled out to it would pass through the bar:
 * Big Bear and Santa Ana, nodes 978 m off the original over its inside):
 * that junction is left unjoined, the T of the two sheets made. */
static void test_beyond_end(void)
{
    double h = 500, zb = -8000;
    int nx = 12, ny = 20, nz = (int)(-zb / h);
    fm_mesh *t = fm_mesh_create();
    /* the bar, columns along y, then the stem, columns along -x */
    for (int j = 0; j <= nz; j++)
        for (int i = 0; i <= ny; i++)
            fm_mesh_add_vertex(t, X0, Y0 - 5000 + 10000.0 * i / ny, zb * j / nz);
    for (int j = 0; j <= nz; j++)
        for (int i = 0; i <= nx; i++)
            fm_mesh_add_vertex(t, X0 - 50 - 5950.0 * i / nx, Y0, zb * j / nz);
    int nb = (nz + 1) * (ny + 1);
    grid_triangles(t, 0, ny, nz);
    grid_triangles(t, nb, nx, nz);
    fm_mesh *side = plane_x(600, -3000, 3000, -4000, h);
    fm_model *models[2] = {fit_mesh("tee", t), fit_mesh("beside", side)};
    fm_mesh_destroy(t);
    fm_mesh_destroy(side);
    CHECK(models[0] != NULL && models[1] != NULL);
    if (!models[0] || !models[1])
        goto out;
    CHECK_EQ(fm_model_nsheets(models[0]), 2);
    fm_connect_plan_options po;
    fm_connect_plan_options_default(&po);
    po.size = h;
    fm_connect_plan *plan = NULL;
    fm_error err;
    CHECK(fm_connect_plan_build((const fm_model *const *)models, 2, &po, &plan, &err) == FM_OK);
    if (!plan)
        goto out;
    int tee = 0, beside = 0;
    for (size_t i = 0; i < fm_connect_plan_njunctions(plan); i++) {
        const fm_connect_junction *j = fm_connect_plan_junction(plan, i);
        printf("junction %zu: %s %zu.%zu-%zu.%zu gap %.0f%s%s\n", i, fm_junction_type_name(j->type),
               j->fault[0], j->sheet[0], j->fault[1], j->sheet[1], j->gap, j->reason ? ": " : "",
               j->reason ? j->reason : "");
        if (j->fault[0] == 0 && j->fault[1] == 0)
            tee += j->type == FM_JUNCTION_T;
        /* the second fault may join the bar's side of the tee only */
        if (j->fault[0] != j->fault[1] && j->type != FM_JUNCTION_UNJOINED)
            beside++;
    }
    CHECK_EQ(tee, 1);
    CHECK_EQ(beside, 0);
    fm_connect_plan_destroy(plan);
out:
    for (int k = 0; k < 2; k++)
        fm_model_destroy(models[k]);
}

static fm_model *fit_file(const char *path)
{
    fm_tsurf **objs = NULL;
    size_t nobj = 0;
    fm_error err;
    if (fm_tsurf_read_file(path, &objs, &nobj, &err) != FM_OK || nobj < 1) {
        fprintf(stderr, "%s\n", err.message);
        return NULL;
    }
    fm_model *m = fit_mesh(path, fm_tsurf_mesh(objs[0]));
    fm_tsurf_free_all(objs, nobj);
    return m;
}

static int cfm_skipped;

static void test_cfm_santa_monica(void)
{
    const char *dir = FM_CFM_DIR "/CFM5.3/500m";
    char pa[1024], pb[1024];
    snprintf(pa, sizeof pa, "%s/WTRA-SFFS-SMMT-Santa_Monica_fault_steep-CFM5_500m.ts", dir);
    snprintf(pb, sizeof pb, "%s/WTRA-SBTS-SMNB-Santa_Monica_thrust_fault-CFM1_500m.ts", dir);
    FILE *f = fopen(pa, "r");
    if (!f) {
        cfm_skipped = 1;
        return;
    }
    fclose(f);
    fm_model *a = fit_file(pa), *b = fit_file(pb);
    CHECK(a && b);
    if (a && b) {
        const fm_model *models[2] = {a, b};
        fm_connect_pairs *pairs = NULL;
        fm_error err;
        CHECK(fm_connect_find_pairs(models, 2, NULL, &pairs, &err) == FM_OK);
        CHECK(fm_connect_pairs_count(pairs) >= 1);
        size_t ncurves = 0;
        for (size_t i = 0; i < fm_connect_pairs_count(pairs); i++) {
            const fm_connect_pair *p = fm_connect_pairs_get(pairs, i);
            printf("SM pair %zu.%zu - %zu.%zu: distance %.1f crosses %d, trimmed %.1f crosses %d\n",
                   p->fault_a, p->sheet_a, p->fault_b, p->sheet_b, p->distance, p->crosses,
                   p->trimmed_distance, p->trimmed_crosses);
            fm_connect_curves *c = NULL;
            CHECK(fm_connect_intersect(a, p->sheet_a, b, p->sheet_b, NULL, &c, &err) == FM_OK);
            for (size_t k = 0; k < fm_connect_curves_count(c); k++) {
                const fm_connect_curve_info *in = fm_connect_curve_get_info(c, k);
                printf("  curve %zu: %zu points, length %.0f, angle %.1f..%.1f, roles %d %d, "
                       "max dist %.2e %.2e, fallback %zu\n",
                       k, in->npoints, in->length, in->min_angle, in->max_angle, in->side[0].role,
                       in->side[1].role, in->max_dist[0], in->max_dist[1], in->fallback_points);
                CHECK(in->unconverged == 0);
            }
            ncurves += fm_connect_curves_count(c);
            check_points_on_surfaces(c, a, p->sheet_a, b, p->sheet_b, 1.0);
            fm_connect_curves_destroy(c);
        }
        CHECK(ncurves >= 1);
        fm_connect_pairs_destroy(pairs);
    }
    fm_model_destroy(a);
    fm_model_destroy(b);
}

/* The n meshes fitted into models (the meshes destroyed); -1 (checked)
 * when one cannot be, the others then destroyed. */
static int fit_all(fm_mesh **meshes, const char *const *names, int n, fm_model **models)
{
    int bad = 0;
    for (int k = 0; k < n; k++) {
        models[k] = bad ? NULL : fit_mesh(names[k], meshes[k]);
        fm_mesh_destroy(meshes[k]);
        bad |= models[k] == NULL;
    }
    CHECK(!bad);
    for (int k = 0; bad && k < n; k++)
        fm_model_destroy(models[k]);
    return bad ? -1 : 0;
}

/* The near-duplicates among n models under either rule (keep: 1 keeps
 * the larger), checked to succeed. */
static fm_connect_duplicate *find_duplicates(fm_model **models, size_t n,
                                             const fm_connect_pairs *pairs, int keep, size_t *nd)
{
    fm_connect_duplicate_options o;
    fm_connect_duplicate_options_default(&o);
    o.keep = keep ? FM_CONNECT_KEEP_LARGER : FM_CONNECT_KEEP_SMALLER;
    fm_connect_duplicate *d = NULL;
    fm_error err;
    *nd = 0;
    CHECK(fm_connect_find_duplicates((const fm_model *const *)models, n, pairs, &o, &d, nd,
                                     &err) == FM_OK);
    return d;
}

/* A composite over two section faults 20 m beside it, and a fault that
 * crosses all three: the composite (or, keeping the larger, the sections)
 * is given up, the crossing fault is no duplicate. */
static void test_duplicates(void)
{
    fm_mesh *meshes[4] = {plane_part(-8000, 8000, 0, -6000, 500),
                          plane_part(-8000, 0, 20, -6000, 500),
                          plane_part(0, 8000, 20, -6000, 500),
                          vertical_plane(90.0, 5000, -6000, 500)};
    const char *names[4] = {"composite", "section west", "section east", "crossing"};
    fm_model *models[4];
    if (fit_all(meshes, names, 4, models))
        return;
    fm_error err;
    double share[2], area[2];
    CHECK(fm_connect_overlap(models[1], models[0], 50, share, area, &err) == FM_OK);
    CHECK(share[0] > 0.95);                     /* the section lies on the composite */
    CHECK(share[1] > 0.4 && share[1] < 0.6);    /* half of the composite on the section */
    CHECK(fabs(area[0] - 8000.0 * 6000) < 0.02 * 8000.0 * 6000);
    CHECK(fm_connect_overlap(models[0], models[3], 50, share, area, &err) == FM_OK);
    CHECK(share[0] < 0.02 && share[1] < 0.02);  /* a crossing shares a line, no area */

    fm_connect_pairs *pairs = NULL;
    CHECK(fm_connect_find_pairs((const fm_model *const *)models, 4, NULL, &pairs, &err) == FM_OK);
    for (int keep = 0; keep < 2 && pairs; keep++) {
        size_t nd = 0;
        fm_connect_duplicate *d = find_duplicates(models, 4, pairs, keep, &nd);
        int dropped[4] = {0, 0, 0, 0};
        for (size_t k = 0; k < nd; k++) {
            CHECK(d[k].dropped != 3 && d[k].kept != 3);
            if (d[k].decided)
                dropped[d[k].dropped]++;
        }
        if (keep == 0) {
            CHECK(nd == 2); /* composite with each section */
            CHECK(dropped[0] == 1 && dropped[1] == 0 && dropped[2] == 0);
        } else {
            CHECK(dropped[0] == 0 && dropped[1] == 1 && dropped[2] == 1);
        }
        free(d);
    }
    fm_connect_pairs_destroy(pairs);
    for (int k = 0; k < 4; k++)
        fm_model_destroy(models[k]);
}

/* A small patch lying 20 m beside a large fault repeats a corner of it:
 * under either rule the patch is given up, never the large fault, of which
 * the patch covers a tenth (nothing is lost). */
static void test_duplicate_patch(void)
{
    fm_mesh *meshes[2] = {plane_part(-8000, 8000, 0, -6000, 500),
                          plane_part(-8000, -6000, 20, -2000, 250)};
    const char *names[2] = {"large", "patch"};
    fm_model *models[2];
    if (fit_all(meshes, names, 2, models))
        return;
    fm_error err;
    fm_connect_pairs *pairs = NULL;
    CHECK(fm_connect_find_pairs((const fm_model *const *)models, 2, NULL, &pairs, &err) == FM_OK);
    for (int keep = 0; keep < 2 && pairs; keep++) {
        size_t nd = 0;
        fm_connect_duplicate *d = find_duplicates(models, 2, pairs, keep, &nd);
        CHECK(nd == 1);
        if (nd == 1) {
            CHECK(d[0].decided && d[0].dropped == 1 && d[0].kept == 0);
            CHECK(d[0].share[0] > 0.95 && d[0].share[1] < 0.1);
        }
        free(d);
    }
    fm_connect_pairs_destroy(pairs);
    for (int k = 0; k < 2; k++)
        fm_model_destroy(models[k]);
}

/* Pairs, near-duplicates and the plan come out the same, to the bit, on
 * 1, 2 and 5 threads (the synthetic system, plus a composite over a
 * section 20 m beside it so that one fault is given up). */
static int same_pairs(const fm_connect_pairs *x, const fm_connect_pairs *y)
{
    if (fm_connect_pairs_count(x) != fm_connect_pairs_count(y))
        return 0;
    for (size_t i = 0; i < fm_connect_pairs_count(x); i++) {
        const fm_connect_pair *a = fm_connect_pairs_get(x, i), *b = fm_connect_pairs_get(y, i);
        if (a->fault_a != b->fault_a || a->sheet_a != b->sheet_a || a->fault_b != b->fault_b ||
            a->sheet_b != b->sheet_b || a->crosses != b->crosses ||
            a->trimmed_crosses != b->trimmed_crosses ||
            memcmp(&a->distance, &b->distance, sizeof a->distance) ||
            memcmp(&a->trimmed_distance, &b->trimmed_distance, sizeof a->distance) ||
            memcmp(a->point_a, b->point_a, sizeof a->point_a) ||
            memcmp(a->point_b, b->point_b, sizeof a->point_b))
            return 0;
    }
    return 1;
}

static int same_plans(const fm_connect_plan *x, const fm_connect_plan *y, size_t n,
                      fm_model *const *models)
{
    if (fm_connect_plan_njunctions(x) != fm_connect_plan_njunctions(y) ||
        fm_connect_plan_nnodes(x) != fm_connect_plan_nnodes(y) ||
        memcmp(fm_connect_plan_nodes(x), fm_connect_plan_nodes(y),
               3 * fm_connect_plan_nnodes(x) * sizeof(double)))
        return 0;
    for (size_t i = 0; i < fm_connect_plan_njunctions(x); i++) {
        const fm_connect_junction *a = fm_connect_plan_junction(x, i);
        const fm_connect_junction *b = fm_connect_plan_junction(y, i);
        if (a->fault[0] != b->fault[0] || a->fault[1] != b->fault[1] ||
            a->sheet[0] != b->sheet[0] || a->sheet[1] != b->sheet[1] || a->type != b->type ||
            a->curve != b->curve || a->reason != b->reason ||
            memcmp(&a->length, &b->length, sizeof a->length) ||
            memcmp(&a->gap, &b->gap, sizeof a->gap) ||
            memcmp(&a->overshoot, &b->overshoot, sizeof a->overshoot))
            return 0;
    }
    for (size_t f = 0; f < n; f++) {
        if (fm_connect_plan_dropped(x, f, NULL) != fm_connect_plan_dropped(y, f, NULL))
            return 0;
        for (size_t s = 0; s < fm_model_nsheets(models[f]); s++) {
            const fm_connect_shared *a, *b;
            size_t k = fm_connect_plan_sheet(x, f, s, &a);
            if (k != fm_connect_plan_sheet(y, f, s, &b))
                return 0;
            for (size_t q = 0; q < k; q++)
                if (a[q].n != b[q].n || a[q].end != b[q].end || a[q].curve != b[q].curve ||
                    memcmp(a[q].uv, b[q].uv, 2 * a[q].n * sizeof(double)) ||
                    memcmp(a[q].node, b[q].node, a[q].n * sizeof(int64_t)))
                    return 0;
        }
    }
    return 1;
}

static void test_threads(void)
{
    fm_synth *sy = NULL;
    fm_error err;
    CHECK(fm_synth_create(NULL, &sy, &err) == FM_OK);
    if (!sy)
        return;
    size_t ns = fm_synth_nfaults(sy), n = ns + 2;
    fm_model **models = calloc(n, sizeof *models);
    for (size_t i = 0; i < ns; i++)
        models[i] = fit_mesh(fm_synth_fault_name(sy, i), fm_synth_fault_mesh(sy, i));
    fm_mesh *extra[2] = {plane_part(-8000, 8000, 0, -6000, 500),
                         plane_part(-8000, 0, 20, -6000, 500)};
    for (int k = 0; k < 2; k++) {
        models[ns + (size_t)k] = fit_mesh(k ? "section" : "composite", extra[k]);
        fm_mesh_destroy(extra[k]);
    }
    for (size_t i = 0; i < n; i++)
        CHECK(models[i] != NULL);
    const fm_model *const *M = (const fm_model *const *)models;
    fm_connect_pairs *p1 = NULL;
    fm_connect_duplicate *d1 = NULL;
    size_t nd1 = 0;
    fm_connect_plan *plan1 = NULL;
    fm_connect_options o;
    fm_connect_options_default(&o);
    fm_connect_duplicate_options dopt;
    fm_connect_duplicate_options_default(&dopt);
    fm_connect_plan_options po;
    fm_connect_plan_options_default(&po);
    CHECK(fm_connect_find_pairs(M, n, &o, &p1, &err) == FM_OK);
    CHECK(p1 && fm_connect_find_duplicates(M, n, p1, &dopt, &d1, &nd1, &err) == FM_OK);
    CHECK(nd1 == 1);
    CHECK(fm_connect_plan_build(M, n, &po, &plan1, &err) == FM_OK);
    for (int nt = 2; nt <= 5 && p1 && plan1; nt += 3) {
        o.nthreads = dopt.nthreads = po.nthreads = nt;
        fm_connect_pairs *p = NULL;
        fm_connect_duplicate *d = NULL;
        size_t nd = 0;
        fm_connect_plan *plan = NULL;
        CHECK(fm_connect_find_pairs(M, n, &o, &p, &err) == FM_OK);
        CHECK(p && same_pairs(p1, p));
        CHECK(p && fm_connect_find_duplicates(M, n, p, &dopt, &d, &nd, &err) == FM_OK);
        CHECK(nd == nd1);
        for (size_t k = 0; k < nd && k < nd1; k++)
            CHECK(d[k].dropped == d1[k].dropped && d[k].kept == d1[k].kept &&
                  d[k].decided == d1[k].decided &&
                  !memcmp(d[k].share, d1[k].share, sizeof d[k].share) &&
                  !memcmp(d[k].area, d1[k].area, sizeof d[k].area));
        CHECK(fm_connect_plan_build(M, n, &po, &plan, &err) == FM_OK);
        CHECK(plan && same_plans(plan1, plan, n, models));
        fm_connect_pairs_destroy(p);
        free(d);
        fm_connect_plan_destroy(plan);
    }
    CHECK(plan1 && fm_connect_plan_dropped(plan1, ns, NULL)); /* the composite goes */
    fm_connect_pairs_destroy(p1);
    free(d1);
    fm_connect_plan_destroy(plan1);
    for (size_t i = 0; i < n; i++)
        fm_model_destroy(models[i]);
    free(models);
    fm_synth_destroy(sy);
}

int main(void)
{
    static const fm_test_case cases[] = {
        FM_CASE(test_planes_90),
        FM_CASE(test_planes_10),
        FM_CASE(test_synth),
        FM_CASE(test_synth_plan),
        FM_CASE(test_triple_small_angle),
        FM_CASE(test_cut_short),
        FM_CASE(test_stop_short),
        FM_CASE(test_beyond_end),
        FM_CASE(test_closed_loop),
        FM_CASE(test_duplicates), FM_CASE(test_duplicate_patch),
        FM_CASE(test_threads),
        FM_CASE(test_cfm_santa_monica),
    };
    int rc = fm_test_run(cases, sizeof cases / sizeof cases[0]);
    if (rc == 0 && cfm_skipped)
        return FM_TEST_SKIP;
    return rc;
}
