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
void iges_str(iges_lines *l, const char *s); /* NULL or "" = defaulted (empty) */
void iges_end(iges_lines *l);

/* Shortest text that reads back as x, IGES style ("400000.", "1.5E-7");
 * buf needs 32 bytes. Independent of the C locale. */
void iges_format_real(double x, char *buf);

/* x rounded to `digits` (1..17) significant digits, IGES style, shortest
 * form (no trailing zeros); buf needs 32 bytes. */
void iges_format_real_digits(double x, int digits, char *buf);

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

/* 1 when every character is printable ASCII. */
int iges_printable(const char *s);

#endif
