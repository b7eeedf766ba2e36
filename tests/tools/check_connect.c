/* check_connect: an independent check of conforming fault meshes (issue 5)
 * from the OBJ of `faultmesh remesh` alone. See cc_check.h for what is
 * measured; this file holds the command line and the reports.
 *
 * usage: check_connect [options] mesh.obj
 *   --distance D        proximity distance in metres (default 1000)
 *   --json FILE         every count and per-pair list, sorted, as JSON
 *   --criteria          exit 1 when faults intersect (other than allowed pairs)
 *   --allow-pairs FILE  lines "nameA<TAB>nameB": documented pairs exempt from --criteria
 *   --no-self           skip self-intersections within a fault
 *   --verbose           list every pair on stdout, not the first 20 of each list
 * Exit: 0 ok, 1 criteria failed, 2 bad usage or unreadable input. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <time.h>

#include "cc_check.h"
#include "cc_obj.h"

#define LIST_MAX 20

static void usage(FILE *fp)
{
    fprintf(fp,
            "usage: check_connect [--distance D] [--json FILE] [--criteria] [--allow-pairs FILE]\n"
            "                     [--no-self] [--verbose] mesh.obj\n");
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- --allow-pairs */

static int find_fault(const cc_mesh *m, const char *name)
{
    for (size_t f = 0; f < m->nfaults; f++)
        if (strcmp(m->names[f], name) == 0)
            return (int)f;
    return -1;
}

static int read_allowed(const char *path, const cc_mesh *m, cc_result *r)
{
    FILE *fp = fopen(path, "r");
    if (!fp) {
        fprintf(stderr, "%s: cannot open: %s\n", path, strerror(errno));
        return -1;
    }
    char *buf = NULL;
    size_t cap = 0;
    unsigned long line = 0;
    int rc = 0;
    while (getline(&buf, &cap, fp) >= 0) {
        line++;
        buf[strcspn(buf, "\r\n")] = '\0';
        if (buf[0] == '\0' || buf[0] == '#')
            continue;
        char *tab = strchr(buf, '\t');
        if (!tab || strchr(tab + 1, '\t') || tab == buf || !tab[1]) {
            fprintf(stderr, "%s:%lu: expected \"nameA<TAB>nameB\"\n", path, line);
            rc = -1;
            break;
        }
        *tab = '\0';
        int a = find_fault(m, buf), b = find_fault(m, tab + 1);
        if (a < 0 || b < 0) {
            fprintf(stderr, "%s:%lu: warning: no fault named \"%s\" in the mesh\n", path, line,
                    a < 0 ? buf : tab + 1);
            continue;
        }
        for (size_t i = 0; i < r->npairs; i++) {
            cc_pair *p = &r->pairs[i];
            if ((p->a == (uint32_t)a && p->b == (uint32_t)b) ||
                (p->a == (uint32_t)b && p->b == (uint32_t)a))
                p->allowed = 1;
        }
    }
    if (rc == 0 && ferror(fp)) {
        fprintf(stderr, "%s: read error\n", path);
        rc = -1;
    }
    free(buf);
    fclose(fp);
    return rc;
}

/* ---- JSON */

/* The shortest %g text that reads back to v; "null" when not finite. */
static const char *num(char *buf, size_t n, double v)
{
    if (!isfinite(v)) {
        snprintf(buf, n, "null");
        return buf;
    }
    if (v == floor(v) && fabs(v) < 1e15) {
        snprintf(buf, n, "%.0f", v);
        return buf;
    }
    for (int prec = 1; prec <= 17; prec++) {
        snprintf(buf, n, "%.*g", prec, v);
        if (strtod(buf, NULL) == v)
            break;
    }
    return buf;
}

static void jstr(FILE *fp, const char *s)
{
    fputc('"', fp);
    for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
        if (*c == '"' || *c == '\\')
            fprintf(fp, "\\%c", *c);
        else if (*c < 0x20)
            fprintf(fp, "\\u%04x", *c);
        else
            fputc(*c, fp);
    }
    fputc('"', fp);
}

static void jtriangle(FILE *fp, const cc_mesh *m, uint32_t t)
{
    char b[3][40];
    fputc('[', fp);
    for (int k = 0; k < 3; k++) {
        const double *p = m->x + 3 * (size_t)m->tri[3 * (size_t)t + (size_t)k];
        fprintf(fp, "%s[%s, %s, %s]", k ? ", " : "", num(b[0], 40, p[0]), num(b[1], 40, p[1]),
                num(b[2], 40, p[2]));
    }
    fputc(']', fp);
}

static void jexamples(FILE *fp, const cc_mesh *m, const uint32_t ex[][2], int n)
{
    fprintf(fp, "\"examples\": [");
    for (int i = 0; i < n; i++) {
        fprintf(fp, "%s{\"triangles\": [%u, %u], \"lines\": [%u, %u], \"corners\": [",
                i ? ", " : "", ex[i][0] + 1, ex[i][1] + 1, m->line[ex[i][0]], m->line[ex[i][1]]);
        jtriangle(fp, m, ex[i][0]);
        fprintf(fp, ", ");
        jtriangle(fp, m, ex[i][1]);
        fprintf(fp, "]}");
    }
    fprintf(fp, "]");
}

typedef struct totals {
    uint64_t tri_pairs, fault_pairs, allowed_tri_pairs, allowed_fault_pairs;
    uint64_t self_pairs, self_faults;
    uint64_t sharing_pairs, shared_vertices, shared_edges;
    uint64_t near_edges, near_edge_pairs, near_not_sharing;
    double near_length;
} totals;

static totals count(const cc_mesh *m, const cc_result *r)
{
    totals t = {0};
    for (size_t i = 0; i < r->npairs; i++) {
        const cc_pair *p = &r->pairs[i];
        if (p->intersections) {
            if (p->allowed) {
                t.allowed_tri_pairs += p->intersections;
                t.allowed_fault_pairs++;
            }
            t.tri_pairs += p->intersections;
            t.fault_pairs++;
        }
        if (p->shared_vertices || p->shared_edges) {
            t.sharing_pairs++;
            t.shared_vertices += p->shared_vertices;
            t.shared_edges += p->shared_edges;
        }
        if (p->near_edges[0] || p->near_edges[1]) {
            t.near_edge_pairs++;
            t.near_edges += p->near_edges[0] + p->near_edges[1];
            t.near_length += p->near_length[0] + p->near_length[1];
        }
        if (!p->shared_vertices && isfinite(p->distance))
            t.near_not_sharing++;
    }
    for (size_t f = 0; f < m->nfaults; f++)
        if (r->self[f].intersections) {
            t.self_pairs += r->self[f].intersections;
            t.self_faults++;
        }
    return t;
}

static int write_json(const char *path, const char *input, const cc_mesh *m, const cc_options *opt,
                      const cc_result *r, const totals *t)
{
    FILE *fp = fopen(path, "w");
    if (!fp) {
        fprintf(stderr, "%s: cannot write: %s\n", path, strerror(errno));
        return -1;
    }
    char b1[40], b2[40], b3[40];
    fprintf(fp, "{\n  \"input\": ");
    jstr(fp, input);
    fprintf(fp, ",\n  \"faults\": %zu,\n  \"vertices\": %zu,\n  \"triangles\": %zu,\n", m->nfaults,
            m->nv, m->nt);
    fprintf(fp, "  \"distance\": %s,\n  \"self_checked\": %s,\n", num(b1, 40, opt->distance),
            opt->self ? "true" : "false");
    fprintf(fp, "  \"degenerate_triangles\": %llu,\n  \"skipped_pairs\": %llu,\n",
            (unsigned long long)r->degenerate_triangles, (unsigned long long)r->skipped_pairs);
    fprintf(fp, "  \"boundary_edges\": %llu,\n  \"nonmanifold_edges\": %llu,\n",
            (unsigned long long)r->boundary_edges, (unsigned long long)r->nonmanifold_edges);
    fprintf(fp,
            "  \"intersections\": {\"triangle_pairs\": %llu, \"fault_pairs\": %llu, "
            "\"allowed_triangle_pairs\": %llu, \"allowed_fault_pairs\": %llu},\n",
            (unsigned long long)t->tri_pairs, (unsigned long long)t->fault_pairs,
            (unsigned long long)t->allowed_tri_pairs, (unsigned long long)t->allowed_fault_pairs);
    fprintf(fp, "  \"self_intersections\": {\"triangle_pairs\": %llu, \"faults\": %llu},\n",
            (unsigned long long)t->self_pairs, (unsigned long long)t->self_faults);
    fprintf(fp, "  \"sharing\": {\"fault_pairs\": %llu, \"vertices\": %llu, \"edges\": %llu},\n",
            (unsigned long long)t->sharing_pairs, (unsigned long long)t->shared_vertices,
            (unsigned long long)t->shared_edges);
    fprintf(fp,
            "  \"proximity\": {\"unjoined_near_edges\": %llu, \"unjoined_near_length\": %s, "
            "\"fault_pairs_with_unjoined_near_edges\": %llu, \"near_pairs_not_sharing\": %llu},\n",
            (unsigned long long)t->near_edges, num(b1, 40, t->near_length),
            (unsigned long long)t->near_edge_pairs, (unsigned long long)t->near_not_sharing);

    fprintf(fp, "  \"intersecting_pairs\": [");
    int first = 1;
    for (size_t i = 0; i < r->npairs; i++) {
        const cc_pair *p = &r->pairs[i];
        if (!p->intersections)
            continue;
        fprintf(fp, "%s\n    {\"a\": ", first ? "" : ",");
        jstr(fp, m->names[p->a]);
        fprintf(fp, ", \"b\": ");
        jstr(fp, m->names[p->b]);
        fprintf(fp, ", \"triangle_pairs\": %llu, \"allowed\": %s, ",
                (unsigned long long)p->intersections, p->allowed ? "true" : "false");
        jexamples(fp, m, (const uint32_t(*)[2])p->examples, p->nexamples);
        fprintf(fp, "}");
        first = 0;
    }
    fprintf(fp, "%s],\n  \"self_intersecting_faults\": [", first ? "" : "\n  ");
    first = 1;
    for (size_t f = 0; f < m->nfaults; f++) {
        const cc_self *s = &r->self[f];
        if (!s->intersections)
            continue;
        fprintf(fp, "%s\n    {\"fault\": ", first ? "" : ",");
        jstr(fp, m->names[f]);
        fprintf(fp, ", \"triangle_pairs\": %llu, ", (unsigned long long)s->intersections);
        jexamples(fp, m, (const uint32_t(*)[2])s->examples, s->nexamples);
        fprintf(fp, "}");
        first = 0;
    }
    fprintf(fp, "%s],\n  \"near_pairs_not_sharing\": [", first ? "" : "\n  ");
    first = 1;
    for (size_t i = 0; i < r->npairs; i++) {
        const cc_pair *p = &r->pairs[i];
        if (p->shared_vertices || !isfinite(p->distance))
            continue;
        fprintf(fp, "%s\n    {\"a\": ", first ? "" : ",");
        jstr(fp, m->names[p->a]);
        fprintf(fp, ", \"b\": ");
        jstr(fp, m->names[p->b]);
        fprintf(fp, ", \"distance\": %s}", num(b1, 40, p->distance));
        first = 0;
    }
    fprintf(fp, "%s],\n  \"pairs\": [", first ? "" : "\n  ");
    for (size_t i = 0; i < r->npairs; i++) {
        const cc_pair *p = &r->pairs[i];
        fprintf(fp, "%s\n    {\"a\": ", i ? "," : "");
        jstr(fp, m->names[p->a]);
        fprintf(fp, ", \"b\": ");
        jstr(fp, m->names[p->b]);
        fprintf(fp,
                ", \"shared_vertices\": %llu, \"shared_edges\": %llu, \"intersections\": %llu, "
                "\"distance\": %s, \"near_edges_a\": %llu, \"near_edges_b\": %llu, "
                "\"near_length\": %s, "
                "\"near_min_distance\": %s}",
                (unsigned long long)p->shared_vertices, (unsigned long long)p->shared_edges,
                (unsigned long long)p->intersections, num(b1, 40, p->distance),
                (unsigned long long)p->near_edges[0], (unsigned long long)p->near_edges[1],
                num(b2, 40, p->near_length[0] + p->near_length[1]), num(b3, 40, p->near_min));
    }
    fprintf(fp, "%s]\n}\n", r->npairs ? "\n  " : "");
    if (ferror(fp) | fclose(fp)) {
        fprintf(stderr, "%s: write error\n", path);
        return -1;
    }
    return 0;
}

/* ---- text */

static void print_example(const cc_mesh *m, uint32_t ta, uint32_t tb)
{
    for (int s = 0; s < 2; s++) {
        uint32_t t = s ? tb : ta;
        printf("      %s triangle %u (line %u):", s ? "b" : "a", t + 1, m->line[t]);
        for (int k = 0; k < 3; k++) {
            const double *p = m->x + 3 * (size_t)m->tri[3 * (size_t)t + (size_t)k];
            printf(" (%.3f %.3f %.3f)", p[0], p[1], p[2]);
        }
        printf("\n");
    }
}

static void print_text(const cc_mesh *m, const cc_options *opt, const cc_result *r, const totals *t,
                       int verbose)
{
    size_t shown = 0;
    printf("intersections between faults: %llu triangle pairs in %llu fault pairs",
           (unsigned long long)t->tri_pairs, (unsigned long long)t->fault_pairs);
    if (t->allowed_fault_pairs)
        printf(" (%llu triangle pairs in %llu fault pairs allowed)",
               (unsigned long long)t->allowed_tri_pairs,
               (unsigned long long)t->allowed_fault_pairs);
    printf("\n");
    for (size_t i = 0; i < r->npairs; i++) {
        const cc_pair *p = &r->pairs[i];
        if (!p->intersections)
            continue;
        if (!verbose && shown++ == LIST_MAX) {
            printf("  ... (--verbose or --json for all)\n");
            break;
        }
        printf("  %s x %s: %llu%s\n", m->names[p->a], m->names[p->b],
               (unsigned long long)p->intersections, p->allowed ? " (allowed)" : "");
    }
    if (opt->self)
        printf("self-intersections: %llu triangle pairs in %llu faults\n",
               (unsigned long long)t->self_pairs, (unsigned long long)t->self_faults);
    shown = 0;
    for (size_t f = 0; opt->self && f < m->nfaults; f++) {
        if (!r->self[f].intersections)
            continue;
        if (!verbose && shown++ == LIST_MAX) {
            printf("  ... (--verbose or --json for all)\n");
            break;
        }
        printf("  %s: %llu\n", m->names[f], (unsigned long long)r->self[f].intersections);
    }
    printf("degenerate triangles: %llu (pairs not classified: %llu); non-manifold edges: %llu\n",
           (unsigned long long)r->degenerate_triangles, (unsigned long long)r->skipped_pairs,
           (unsigned long long)r->nonmanifold_edges);
    printf("sharing: %llu fault pairs share %llu vertices and %llu edges\n",
           (unsigned long long)t->sharing_pairs, (unsigned long long)t->shared_vertices,
           (unsigned long long)t->shared_edges);
    printf(
        "proximity (D = %g m): %llu unjoined boundary edges (%.0f m) within D in %llu fault pairs; "
        "%llu fault pairs within D share no vertex\n",
        opt->distance, (unsigned long long)t->near_edges, t->near_length,
        (unsigned long long)t->near_edge_pairs, (unsigned long long)t->near_not_sharing);
    shown = 0;
    for (size_t i = 0; i < r->npairs; i++) {
        const cc_pair *p = &r->pairs[i];
        if (p->shared_vertices || !isfinite(p->distance))
            continue;
        if (!verbose && shown++ == LIST_MAX) {
            printf("  ... (--verbose or --json for all)\n");
            break;
        }
        printf("  %s ~ %s: %.1f m\n", m->names[p->a], m->names[p->b], p->distance);
    }
}

int main(int argc, char **argv)
{
    cc_options opt = {.distance = 1000, .self = 1};
    const char *json = NULL, *allow = NULL, *input = NULL;
    int criteria = 0, verbose = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--distance") == 0 && i + 1 < argc) {
            char *end;
            opt.distance = strtod(argv[++i], &end);
            if (*end || end == argv[i] || !(opt.distance >= 0) || !isfinite(opt.distance)) {
                fprintf(stderr, "check_connect: --distance needs a number >= 0\n");
                return 2;
            }
        } else if (strcmp(a, "--json") == 0 && i + 1 < argc) {
            json = argv[++i];
        } else if (strcmp(a, "--allow-pairs") == 0 && i + 1 < argc) {
            allow = argv[++i];
        } else if (strcmp(a, "--criteria") == 0) {
            criteria = 1;
        } else if (strcmp(a, "--no-self") == 0) {
            opt.self = 0;
        } else if (strcmp(a, "--verbose") == 0) {
            verbose = 1;
        } else if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        } else if (a[0] == '-' || input) {
            usage(stderr);
            return 2;
        } else {
            input = a;
        }
    }
    if (!input) {
        usage(stderr);
        return 2;
    }
    double t0 = now();
    cc_mesh m;
    char err[1024];
    if (cc_obj_read(input, &m, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    double t1 = now();
    cc_result r;
    if (cc_analyse(&m, &opt, &r)) {
        fprintf(stderr, "%s: out of memory\n", input);
        cc_mesh_free(&m);
        return 2;
    }
    int rc = 0;
    if (allow && read_allowed(allow, &m, &r))
        rc = 2;
    totals t = count(&m, &r);
    if (rc == 0) {
        printf("check_connect %s: %zu faults, %zu vertices, %zu triangles\n", input, m.nfaults,
               m.nv, m.nt);
        print_text(&m, &opt, &r, &t, verbose);
        if (json && write_json(json, input, &m, &opt, &r, &t))
            rc = 2;
    }
    if (rc == 0 && criteria) {
        uint64_t bad = t.fault_pairs - t.allowed_fault_pairs;
        if (bad == 0) {
            printf("criteria: passed (no intersections between faults%s)\n",
                   t.allowed_fault_pairs ? " but allowed pairs" : "");
        } else {
            printf("criteria: FAILED: %llu fault pairs intersect (%llu triangle pairs)\n",
                   (unsigned long long)bad,
                   (unsigned long long)(t.tri_pairs - t.allowed_tri_pairs));
            size_t shown = 0;
            for (size_t i = 0; i < r.npairs; i++) {
                const cc_pair *p = &r.pairs[i];
                if (!p->intersections || p->allowed)
                    continue;
                if (!verbose && shown++ == LIST_MAX) {
                    printf("  ... (--verbose or --json for all)\n");
                    break;
                }
                printf("  %s x %s: %llu triangle pairs, e.g.\n", m.names[p->a], m.names[p->b],
                       (unsigned long long)p->intersections);
                for (int k = 0; k < p->nexamples; k++)
                    print_example(&m, p->examples[k][0], p->examples[k][1]);
            }
            rc = 1;
        }
    }
    double t2 = now();
    printf("time: read %.2f s, topology %.2f s, intersections %.2f s, proximity %.2f s, total %.2f "
           "s\n",
           t1 - t0, r.seconds[0], r.seconds[1], r.seconds[2], t2 - t0);
    cc_result_free(&r);
    cc_mesh_free(&m);
    return rc;
}
