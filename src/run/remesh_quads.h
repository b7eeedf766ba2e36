/* faultmesh run: --elements quad (remesh_quads.c). */
#ifndef FM_RUN_REMESH_QUADS_H
#define FM_RUN_REMESH_QUADS_H

#include "fm_faultset_write.h"
#include "fm_json.h"
#include "fm_tile.h"
#include "sim_attrs.h"

struct remesh_cli;
struct output_log;

/* Rake (degrees) of a tile whose triangle a, b, c has this rake: the
 * triangle's slip vector projected into the tile's plane, seen from the
 * tile's hanging wall. */
double quad_rake_from(const fm_tile *tl, const double *a, const double *b, const double *c,
                      double rake);

/* Tiles fs (sa->tiles, freed with sa; sheet, per triangle, the sheet of
 * its fault: its parts, fm_tiles_create_parts) and writes the outputs
 * cli->formats asks for among mesh.vtu, mesh.msh, mesh.rsqsim and
 * mesh.eqsim, each noted in log; the first failure in *err. */
fm_status write_quads(const struct remesh_cli *cli, const fm_faultset *fs, const int32_t *sheet,
                      sim_attrs *sa, struct output_log *log, fm_error *err);

/* report.json's "rectangles". */
void quads_json(fm_json *j, const sim_attrs *sa, const char *const *names);

#endif
