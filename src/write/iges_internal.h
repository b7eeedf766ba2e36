/* Private to src/write: the IGES line layout and the checks on the input. */
#ifndef FM_IGES_INTERNAL_H
#define FM_IGES_INTERNAL_H

#include <stdio.h>

#include "fm_iges.h"

/* IGES sequence numbers have 7 columns. */
#define IGES_MAX_SEQ 9999999L

/* Free-format data packed into fixed lines: width 72 for the Global
 * section, 64 for Parameter Data (whose columns 65-72 hold the DE
 * back-pointer). With fp == NULL lines are only counted, which is how the
 * writer learns each entity's PD line count before writing the DE
 * section that precedes the PD. */
typedef struct iges_lines {
    FILE *fp;
    char letter;    /* 'G' or 'P' */
    int width;      /* 72 or 64 */
    long seq;       /* sequence number of the last line emitted */
    long de;        /* back-pointer written in columns 65-72 ('P' only) */
    size_t len;     /* characters waiting in buf */
    int need_delim; /* a parameter was placed and awaits its delimiter */
    int digits;     /* significant digits of iges_real; 0 = shortest exact text */
    char buf[81];
} iges_lines;

void iges_lines_init(iges_lines *l, FILE *fp, char letter, long first_seq);
/* Parameters of the current record; iges_end closes it with ';' and
 * finishes its last line (each PD entity starts on a new line). */
void iges_int(iges_lines *l, long long v);
void iges_real(iges_lines *l, double v);
/* v rounded to the nearest multiple of 10^quantum_exp, as a decimal of
 * exactly that many places (trailing zeros dropped). */
void iges_real_quantum(iges_lines *l, double v, int quantum_exp);
void iges_str(iges_lines *l, const char *s); /* NULL or "" = defaulted (empty) */
void iges_end(iges_lines *l);

/* Shortest text that reads back as x, IGES style ("400000.", "1.5E-7");
 * buf needs 32 bytes. Independent of the C locale. */
void iges_format_real(double x, char *buf);

/* x rounded to `digits` (1..17) significant digits, IGES style, shortest
 * form (no trailing zeros); buf needs 32 bytes. */
void iges_format_real_digits(double x, int digits, char *buf);

/* x rounded to the nearest multiple of 10^quantum_exp (|x| below 1e15
 * quanta), as a decimal of that many places with the zeros at its end
 * dropped ("-1231.09", "40178.", "0."); buf needs 48 bytes. */
void iges_format_quantum(double x, int quantum_exp, char *buf);

/* One fixed-layout line: data (padded/truncated to 72), section letter
 * and sequence number. */
void iges_put_line(FILE *fp, const char *data, char letter, long seq);

/* Evaluation of a trimming curve at t (clamped to its range). */
void iges_curve_eval(const fm_iges_curve2d *c, double t, double uv[2]);

/* Checks one face; on success rev[0] (outer loop) and rev[1 + h] (hole h)
 * are 1 for the loops to be written reversed. index names the face in
 * messages. */
fm_status iges_check_face(const char *path, size_t index, const fm_iges_face *f,
                          unsigned char *rev, fm_error *err);

/* The surface's parameter range with the "u0 == u1" default resolved. */
void iges_face_range(const fm_iges_surface *s, double r[4]);

/* The part of a face's surface that is written: control points
 * [i0, i0 + ni) x [j0, j0 + nj), and the parameter range r (u0, u1, v0,
 * v1) inside their knot range. */
typedef struct iges_window {
    size_t i0, ni, j0, nj;
    double r[4];
} iges_window;

/* The knot spans the face's outer loop reaches (all of them when it has
 * none): the B-spline restricted to them is the same surface there, so
 * the control points that only shape the unused extension are left out. */
void iges_face_window(const fm_iges_face *f, iges_window *w);

/* What of a face's surface is written: its window (copied), maybe with
 * knots removed (iges_reduce.c) and its coordinates rounded to a decimal
 * quantum. */
typedef struct iges_net {
    int pu, pv;
    size_t nu, nv;
    double *knots_u, *knots_v; /* nu + pu + 1 and nv + pv + 1 values */
    double *ctrl;              /* 3 nu nv, point (i, j) at 3 (j nu + i) */
    double *weights;           /* nu nv, or NULL = polynomial */
    double r[4];               /* parameter range: u0, u1, v0, v1 */
    int rounded;               /* 1: coordinates rounded to 10^quantum_exp */
    int quantum_exp;
    double removal;            /* bound of the knot removal's deviation (0: none) */
} iges_net;

/* The window of the face's surface as a net of its own; FM_ERR_NOMEM or
 * FM_OK. */
fm_status iges_net_copy(const fm_iges_surface *s, const iges_window *w, iges_net *net);
void iges_net_free(iges_net *net);

/* Removes knots of a polynomial net while the distance between the net's
 * surface and the one it was given, on its parameter range, provably
 * stays within budget; sets net->removal to that bound. A rational net
 * is left as it is. FM_ERR_NOMEM or FM_OK (the net unchanged on failure). */
fm_status iges_reduce(iges_net *net, double budget);

/* 1 when every character is printable ASCII. */
int iges_printable(const char *s);

#endif
