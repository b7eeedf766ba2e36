/* The layout of the synthetic fault system.
 *
 * Positions are given in a frame tied to the main fault: xi along its
 * strike (azimuth 315, NW), eta across it (azimuth 45, NE), origin at the
 * system centre. Faults are placed so that the only intended contacts are
 * the T-junction gap and the overshoot on the main fault; every other pair
 * is kilometres apart at every depth.
 *
 * The topography peaks on the main fault's trace at every xi (its eta term
 * is a cosine centred on eta = 0). Hence the top of a vertical fault whose
 * end lies at eta != 0 is never above the main fault's top at the foot of
 * the perpendicular, and every vertex of that end edge has its closest
 * point inside the main fault's parameter rectangle: the gap and the
 * overshoot are then exact at all depths, not only at sea level. */
#include <stdio.h>
#include <string.h>

#include "synth_internal.h"

#define MAIN_STRIKE 315.0

typedef struct placement {
    double xi, eta;
} placement;

static void place(const synth_topo *tp, synth_sheet *sh, placement at)
{
    sh->origin[0] = at.xi * tp->xi[0] + at.eta * tp->eta[0];
    sh->origin[1] = at.xi * tp->xi[1] + at.eta * tp->eta[1];
}

static synth_fault *add_fault(fm_synth *sy, const char *name, const char *kind,
                              const char *description)
{
    synth_fault *f = &sy->fault[sy->nfaults++];
    memset(f, 0, sizeof *f);
    snprintf(f->name, sizeof f->name, "%s", name);
    f->kind = kind;
    f->description = description;
    f->style = SYNTH_GRID_ALTERNATE;
    f->nsheets = 1;
    f->gap_to = -1;
    f->overshoot_of = -1;
    f->crosses = -1;
    return f;
}

/* A planar sheet whose top follows the topography. */
static void planar(const synth_topo *tp, synth_sheet *sh, placement at, double strike,
                   double length, double dip, double bottom)
{
    sh->law = SYNTH_PLANAR;
    place(tp, sh, at);
    sh->strike_deg = strike;
    sh->s0 = 0.0;
    sh->s1 = length;
    sh->dip_deg = dip;
    sh->top_topo = 1;
    sh->bottom_z = bottom;
}

static void topography(synth_topo *tp)
{
    double s = 0.70710678118654752440; /* sin 45 = cos 45 */
    tp->xi[0] = -s;                    /* azimuth 315 */
    tp->xi[1] = s;
    tp->eta[0] = s;                    /* azimuth 45 */
    tp->eta[1] = s;
    /* 500 +- 200 +- 100: tops between 200 and 800 m. */
    tp->base = 500.0;
    tp->amp_xi = 200.0;
    tp->wl_xi = 23000.0;
    tp->phase_xi = 0.7;
    tp->amp_eta = 100.0;
    tp->wl_eta = 17000.0;
}

void synth_layout(fm_synth *sy)
{
    synth_topo *tp = &sy->topo;
    topography(tp);
    sy->nfaults = 0;
    synth_fault *f;

    f = add_fault(sy, "SYNT-MAIN-SS-Main_strike_slip_fault-SYN1", "planar_vertical",
                  "main fault: planar vertical strike-slip (strike 315, 40 km long, to -15 km), "
                  "fixed-diagonal grid; the T-junction fault stops 300 m short of it and the "
                  "overshooting fault crosses it");
    f->style = SYNTH_GRID_FIXED;
    planar(tp, &f->sheet[0], (placement){-20000.0, 0.0}, MAIN_STRIKE, 40000.0, 90.0, -15000.0);

    f = add_fault(sy, "SYNT-NEFB-LSTC-Listric_thrust_fault-SYN1", "listric",
                  "listric thrust: circular dip profile, 60 deg at +500 m to 20 deg at -12 km; "
                  "one interior hole");
    {
        synth_sheet *sh = &f->sheet[0];
        sh->law = SYNTH_CIRCULAR;
        place(tp, sh, (placement){-3000.0, 6000.0});
        sh->strike_deg = MAIN_STRIKE;
        sh->s1 = 22000.0;
        sh->dip1_deg = 60.0;
        sh->z1 = 500.0;
        sh->dip2_deg = 20.0;
        sh->z2 = -12000.0;
        sh->top_topo = 1;
        sh->bottom_z = -12000.0;
    }
    f->hole = 1;
    f->hole_s = 11000.0;
    f->hole_rs = 1800.0;
    f->hole_rt = 1400.0; /* hole_t set once the width is known */

    f = add_fault(sy, "SYNT-SWFB-CORR-Corrugated_fault-SYN1", "corrugated",
                  "corrugated fault (dip 80): sinusoidal corrugations along strike, amplitude "
                  "250 m, wavelength 4 km");
    planar(tp, &f->sheet[0], (placement){15000.0, -14000.0}, 135.0, 30000.0, 80.0, -14000.0);
    f->sheet[0].corr_amp = 250.0;
    f->sheet[0].corr_wavelength = 4000.0;

    f = add_fault(sy, "SYNT-MAIN-TJNC-T_junction_gap_fault-SYN1", "planar_vertical",
                  "T-junction that stops short: vertical, perpendicular to the main fault, its "
                  "s = 0 end 300 m from it at every depth");
    planar(tp, &f->sheet[0], (placement){-8000.0, 300.0}, 45.0, 12000.0, 90.0, -12000.0);
    f->gap_to = 0;
    f->gap = 300.0;

    f = add_fault(sy, "SYNT-MAIN-XOVR-Overshooting_fault-SYN1", "planar_vertical",
                  "overshoot: vertical, crosses the main fault at 60 deg, its s = 0 end 400 m "
                  "beyond it at every depth");
    planar(tp, &f->sheet[0], (placement){6000.0, 400.0}, 255.0, 12000.0, 90.0, -12000.0);
    f->overshoot_of = 0;
    f->overshoot = 400.0;

    f = add_fault(sy, "SYNT-SWFB-BLND-Blind_fault-SYN1", "planar_blind",
                  "blind fault (dip 55): top at -2 km, bottom at -12 km");
    planar(tp, &f->sheet[0], (placement){-4000.0, -5000.0}, 135.0, 14000.0, 55.0, -12000.0);
    f->sheet[0].top_topo = 0;
    f->sheet[0].top_z = -2000.0;

    f = add_fault(sy, "SYNT-SEFB-IRRG-Irregular_noisy_fault-SYN1", "planar",
                  "CFM-like irregular triangulation (spacing graded 2.6x, jittered nodes, random "
                  "diagonals, centre splits), vertices perturbed by up to 3 m per coordinate");
    planar(tp, &f->sheet[0], (placement){-26000.0, -3000.0}, 140.0, 16000.0, 65.0, -13000.0);
    f->style = SYNTH_GRID_IRREGULAR;
    f->noise = 3.0;

    f = add_fault(sy, "SYNT-NEFB-SEAM-Two_part_seam_fault-SYN1", "planar",
                  "written as two TFACE parts whose shared border vertices are duplicated "
                  "(identical coordinates, separate VRTX), like CFM files");
    planar(tp, &f->sheet[0], (placement){-15000.0, 26000.0}, MAIN_STRIKE, 25000.0, 75.0,
           -13000.0);
    f->seam = 1;

    f = add_fault(sy, "SYNT-NWFB-SPLY-Branched_splay_fault-SYN1", "branched",
                  "branching surface in one file: a vertical sheet and a splay (dip 50) rising "
                  "from a junction at about -5 km that shares its vertices, so the junction edges "
                  "have 3 triangles");
    planar(tp, &f->sheet[0], (placement){24000.0, -6000.0}, MAIN_STRIKE, 20000.0, 90.0,
           -14000.0);
    f->nsheets = 2;
    {
        synth_sheet *sp = &f->sheet[1];
        sp->law = SYNTH_SPLAY;
        sp->strike_deg = MAIN_STRIKE;
        sp->s0 = 4000.0;
        sp->s1 = 16000.0;
        sp->dip_deg = 50.0;
        sp->junction_t = 5000.0;
        sp->away = -1.0;
        sp->top_topo = 1;
    }

    /* A flap that widens with depth: within the join distance near the
     * top, wider below. What lies farther from the main fault than the
     * join distance is no overshoot a junction can explain, and must not
     * be cut away. */
    f = add_fault(sy, "SYNT-MAIN-WDGE-Widening_overshoot_fault-SYN1", "planar",
                  "widening overshoot: dip 80, crosses the main fault at 60 deg; its s = 0 end "
                  "lies 200 m beyond it at the top and about 1.3 km at the bottom");
    planar(tp, &f->sheet[0], (placement){14000.0, 200.0}, 255.0, 10000.0, 80.0, -12000.0);
    f->crosses = 0;

    for (size_t i = 0; i < sy->nfaults; i++) {
        f = &sy->fault[i];
        for (size_t k = 0; k < f->nsheets; k++) {
            synth_sheet *sh = &f->sheet[k];
            synth_sheet_prepare(sh);
            if (sh->law == SYNTH_SPLAY) {
                /* t is the distance up from the junction, scaled so that
                 * width is exact at mid-strike. */
                double sm = 0.5 * (sh->s0 + sh->s1), j[3];
                synth_eval_local(sy, f, 0, sm, sh->junction_t, j);
                sh->origin[0] = j[0];
                sh->origin[1] = j[1];
                sh->width = (synth_top_z(sy, &f->sheet[0], sm) - j[2]) / sh->sin_dip;
                sh->bottom_z = j[2];
            }
        }
        if (f->hole)
            f->hole_t = 0.45 * f->sheet[0].width;
    }
}
