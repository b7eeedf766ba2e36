/* report.html: the elastic check's findings among the problems. A group
 * is two faults near one junction (or near none) whose elements load
 * each other about as much as themselves: a simulator sees the fault
 * there twice. */
#include <stdio.h>

#include "report_internal.h"

void rp_elastic(FILE *fp, const fm_report *r)
{
    if (!r->elastic)
        return;
    size_t pairs = 0;
    for (size_t i = 0; i < r->neg; i++)
        pairs += r->eg[i].pairs;
    fprintf(fp, "<h3 id=\"elastic\">Elastic interaction: faults that act as one (%zu groups, "
                "%zu element pairs)</h3>\n",
            r->neg, pairs);
    fprintf(fp, "<p>Pairs of elements of two faults whose coupling sqrt(|K<sub>ij</sub> "
                "K<sub>ji</sub>| / (K<sub>ii</sub> K<sub>jj</sub>)) exceeds %g (K: shear "
                "traction along the rake per unit rake slip; for elements of one size, the "
                "mutual stiffness over the self-stiffness), by fault pair and junction (numbered as in the junction "
                "table; none: the two faults have no junction). Elements are numbered from 1 "
                "in the order of mesh.vtu. %zu elements have a self-stiffness of the wrong "
                "sign.</p>\n",
            r->elastic_fraction, r->elastic_wrong);
    if (!r->neg)
        return;
    fputs("<div class=\"scroll\"><table class=\"sort\"><thead><tr><th>fault</th><th>fault</th>"
          "<th>junction</th><th>pairs</th><th>largest ratio</th><th>closest, m</th>"
          "<th>elements (ratio order)</th></tr></thead><tbody>\n",
          fp);
    for (size_t i = 0; i < r->neg; i++) {
        const rp_elastic_group *g = &r->eg[i];
        fputs("<tr><td class=\"fn\">", fp);
        rp_esc(fp, g->fault[0]);
        fputs("</td><td class=\"fn\">", fp);
        rp_esc(fp, g->fault[1]);
        if (g->junction)
            fprintf(fp, "</td><td class=\"n\">%zu</td>", g->junction);
        else
            fputs("</td><td>none</td>", fp);
        fprintf(fp, "<td class=\"n\">%zu</td><td class=\"n\">%.2f</td><td class=\"n\">%.0f</td><td>",
                g->pairs, g->max_ratio, g->min_distance);
        for (size_t k = 0; k < g->nexamples; k++)
            fprintf(fp, "%s%zu&ndash;%zu", k ? ", " : "", g->examples[2 * k],
                    g->examples[2 * k + 1]);
        fputs("</td></tr>\n", fp);
    }
    fputs("</tbody></table></div>\n", fp);
}
