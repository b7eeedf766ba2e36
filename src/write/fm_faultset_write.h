/* faultmesh write: a fault set (every remeshed fault of a run in one mesh)
 * as VTU, Gmsh MSH 4.1 / 2.2, binary STL, OBJ, Exodus II and one GoCAD
 * TSurf per fault.
 *
 * A fault set is one fm_mesh whose vertices are shared by all faults
 * (a node on the junction of two faults exists once) and whose triangle
 * tags are the fault index 0..nfaults-1, plus one UTF-8 name per fault.
 * Triangles keep the winding they have in the mesh; no writer flips or
 * re-orients them.
 *
 * Every file is written atomically (fm_atomic.h): on failure nothing
 * appears under the final name and the error names the path. The input
 * is validated before any byte is written: a triangle with a vertex
 * outside the mesh, a tag outside 0..nfaults-1, a fault without
 * triangles (it would vanish silently from STL, OBJ and TSurf), a
 * non-finite coordinate, a name that is empty, not UTF-8 or holds a
 * control character (every format puts a name on one text line), or
 * physical tags that are not distinct and positive: FM_ERR_INVALID or
 * FM_ERR_NUMERIC. Output is byte-identical for identical input. */
#ifndef FM_FAULTSET_WRITE_H
#define FM_FAULTSET_WRITE_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"
#include "fm_mesh.h"
#include "fm_vtu.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A named set of vertices (e.g. the nodes two faults share along one
 * intersection curve). */
typedef struct fm_faultset_nodeset {
    const char *name;         /* UTF-8, as the fault names */
    const int32_t *vertices;  /* n vertex indices of the mesh, each used by some triangle */
    size_t n;
} fm_faultset_nodeset;

typedef struct fm_faultset {
    const fm_mesh *mesh;      /* shared vertices; triangle tag = fault index */
    const char *const *names; /* nfaults UTF-8 names */
    size_t nfaults;
    /* MSH physical tag per fault; NULL means fault index + 1. Simulators
     * have their own conventions for which tag means what (tandem,
     * SeisSol, PyLith), so the caller may impose them here. Faults may
     * share a tag (one physical group holding several faults, as Tandem's
     * and SeisSol's "fault" tags are) only when they share its name. */
    const int32_t *physical_tags;
    /* Extra per-triangle arrays passed through to the VTU only (double or
     * int32, ncomp values per triangle); "fault_id" is taken. */
    const fm_vtu_array *cell_data;
    size_t ncell_data;
    /* Coordinate reference system, e.g. "EPSG:26711"; NULL or "" for none.
     * Recorded where a format has room: VTU field data "crs", MSH
     * $Comments, Exodus II info records, STL header, OBJ comment, TSurf's
     * coordinate-system block. */
    const char *crs;
    /* Name of each fault's physical group in MSH (nfaults names, UTF-8);
     * NULL means the fault names. */
    const char *const *physical_names;
    /* MSH 2.2: number the written nodes 1..n in vertex order instead of
     * vertex index + 1 (Tandem's reader takes only node tags 1..n). */
    int msh_dense_nodes;
    /* MSH: leave out the curves (below), for codes that read only their own
     * tags (Tandem, SeisSol). */
    int msh_no_curves;
    /* Named node sets of the Exodus II file besides the one per fault
     * (the junction curves): each a list of vertex indices. */
    const struct fm_faultset_nodeset *nodesets;
    size_t nnodesets;
} fm_faultset;

/* Checks what every writer checks (see above); the writers call it. */
fm_status fm_faultset_validate(const fm_faultset *fs, const char *path, fm_error *err);

/* VTU: the triangles with Int32 cell data "fault_id" (the fault number:
 * tag + 1, as MSH, Exodus II, RSQSim and EQSim number faults) and the
 * extra cell arrays; field data "fault_names" (the names, each followed
 * by a NUL byte, as fm_vtu.h stores strings) and "crs" when set. */
fm_status fm_faultset_write_vtu(const char *path, const fm_faultset *fs, fm_error *err);

typedef enum fm_msh_version {
    FM_MSH_41 = 0, /* Gmsh's current format (the default) */
    FM_MSH_22      /* the legacy format many simulators still read */
} fm_msh_version;

/* Gmsh MSH, ASCII. One physical surface per fault (tag from physical_tags
 * or index + 1, name = the fault name) and, in 4.1, one geometrical
 * surface entity per fault (tag = index + 1). Node tag = vertex index + 1,
 * element tag = triangle index + 1 (type 2, the 3-node triangle), so tags
 * lead straight back to the mesh. Coordinates are the shortest decimal
 * text that reads back to the same double.
 *
 * Only vertices used by some triangle are written (4.1 must place every
 * node in an entity, and a node of no fault has none); tags keep their
 * gaps. In 4.1 each node is declared once, in the entity of the lowest
 * fault using it, and elements of other faults refer to it by tag, which
 * Gmsh and meshio accept. In 4.1 element blocks go by fault; within a
 * fault and in 2.2 triangles keep mesh order.
 *
 * Physical names: Gmsh reads the text between the first two double
 * quotes, without escapes, and meshio splits the line shell-style, so '"'
 * is written as '\'' and '\\' as '/'; names are cut (at a UTF-8 character
 * boundary) to FM_MSH_NAME_MAX bytes, since Gmsh reads the line into a
 * fixed 256-byte buffer and loses the rest of the file after a longer one.
 *
 * Curves: each fault's outline edges by kind ("NAME: top" at or above
 * sea level, "NAME: buried top", "NAME: bottom", "NAME: ends": which way
 * an edge faces within its triangle, up dip or down dip within 45
 * degrees or neither; edges another fault shares left out) and each
 * junction curve (fs->nodesets: "NAME" of the set, the edges two faults
 * share with both nodes in it) are physical curves numbered 1.. in that
 * order (dimension 1 has its own tags), each its own curve entity (4.1),
 * their 2-node lines (type 1) after the triangles, element tags nt + 1 on;
 * not with msh_no_curves.
 *
 * Faults sharing a physical tag make one physical group (named once).
 * The CRS and the writer go in a $Comments section after $MeshFormat,
 * each line a double-quoted string ('"' written as '\''): Gmsh and meshio
 * skip sections they do not know, and Tandem's lexer, which stops on a
 * bare word outside quotes, reads quoted strings as tokens and skips them. */
#define FM_MSH_NAME_MAX 200
fm_status fm_faultset_write_msh(const char *path, const fm_faultset *fs, fm_msh_version version,
                                fm_error *err);

/* Physical tags and names of the finite-element codes' conventions
 * (docs/formats.md, "Gmsh MSH tag conventions"):
 *   DEFAULT  fault i: tag i + 1, name = the fault name;
 *   TANDEM   every fault tag 3, name "fault" (Tandem: 1 free surface,
 *            3 fault, 5 Dirichlet), to be written as MSH 2.2 with dense
 *            node tags;
 *   SEISSOL  every fault tag 103, name "fault" (SeisSol's Gmsh reader:
 *            101 free surface, 103 dynamic rupture, 105 absorbing);
 *   PYLITH   fault i: tag i + 1, name = a label PyLith's .cfg files can
 *            name: the fault name's bytes A-Z a-z 0-9 '_' kept, every run
 *            of others one '_', "fault_" put in front of one not starting
 *            with a letter, "_2", "_3", ... after one already taken.
 * Either way the geometrical entity of fault i stays i + 1. */
typedef enum fm_msh_tags {
    FM_MSH_TAGS_DEFAULT = 0,
    FM_MSH_TAGS_TANDEM,
    FM_MSH_TAGS_SEISSOL,
    FM_MSH_TAGS_PYLITH
} fm_msh_tags;

/* "default", "tandem", "seissol", "pylith"; NULL for another value. */
const char *fm_msh_tags_name(fm_msh_tags conv);

/* The n tags (into tags[n]) and physical names (*names: malloc'ed array
 * of n malloc'ed strings; free with fm_faultset_free_file_names) of
 * convention conv for faults with these names. FM_ERR_INVALID for an
 * unknown convention, FM_ERR_NOMEM. */
fm_status fm_msh_tags_make(fm_msh_tags conv, const char *const *fault_names, size_t n,
                           int32_t *tags, char ***names, fm_error *err);

/* Exodus II (netCDF, through Debian's libexodusII), as Cubit writes a
 * mesh for PyLith: coordinates X, Y, Z in metres as in the mesh; one
 * element block per fault (id = fault index + 1, type "TRI3", name = the
 * fault name), its triangles in mesh order and winding; one node set per
 * fault (id = fault index + 1, name = the fault name, its nodes ascending)
 * then one per fs->nodesets entry (id = nfaults + k + 1, its name, its
 * vertices ascending, duplicates dropped); one side set per edge group of
 * the MSH curves (below: the faults' edges by kind, named
 * "fault<number>_<kind>", then the junction curves, named as their node
 * sets), each entry an element and its TRI3 side (k: node k to k + 1).
 * Node number = position among
 * the vertices used by some triangle, in vertex order, + 1; element number
 * = position in the blocks' order + 1. Names longer than 255 bytes are
 * cut at a UTF-8 boundary (Exodus keeps at most 255).
 *
 * Title: "faultmesh fault set"; one QA record ("faultmesh", version, and
 * the date and time of SOURCE_DATE_EPOCH, else of the epoch, so that the
 * same input gives the same bytes); info
 * records: the CRS ("crs: ...", over several 80-character lines when long),
 * units and the z convention. Created under a temporary name in the same
 * folder and renamed when closed (netCDF writes the file itself). */
fm_status fm_faultset_write_exodus(const char *path, const fm_faultset *fs, fm_error *err);

/* Binary STL: an 80-byte header naming faultmesh, the fault count and the
 * CRS (cut to fit; never starting with "solid", which readers take for
 * ASCII), the triangle count, then per triangle the unit normal of the
 * triangle as wound (zero if degenerate) and its three corners, all
 * float32 little-endian, and the 16-bit attribute word holding the low 16
 * bits of the fault index (readers mostly ignore it; a few take bit 15 as
 * a colour flag, which indices below 32768 never set).
 *
 * float32 cannot hold UTM coordinates exactly: its spacing is 0.25 m
 * between 2^21 and 2^22 m (2.1e6..4.2e6, most CFM northings) and 0.5 m
 * above, so corners move by up to 0.125 / 0.25 m. That is inherent in
 * STL; use MSH, VTU or OBJ when exact coordinates matter. STL has no
 * shared vertices either: readers merge equal float32 corners. */
fm_status fm_faultset_write_stl(const char *path, const fm_faultset *fs, fm_error *err);

/* Wavefront OBJ: a comment header (faultmesh, counts, CRS), every vertex
 * as a "v" line in mesh order (shortest round-trip text), then per fault
 * "o NAME", "g NAME" and its "f" lines (1-based, mesh order). In NAME
 * whitespace and '#' become '_', since OBJ names end at whitespace and
 * some readers strip comments anywhere on a line. */
fm_status fm_faultset_write_obj(const char *path, const fm_faultset *fs, fm_error *err);

/* One GoCAD TSurf per fault in directory dir (created if missing), with
 * only that fault's triangles and vertices (renumbered 1..n in mesh order
 * of the vertices) and HEADER name = the fault name. The
 * GOCAD_ORIGINAL_COORDINATE_SYSTEM block is the CFM's (metres, z up,
 * "ZPOSITIVE Elevation") with NAME = the CRS when set, "Default" without.
 *
 * File names (fm_faultset_tsurf_file_names): the stem fm_names.h gives
 * each fault's name, in fault order, and ".ts".
 *
 * Each file is atomic on its own and the input is validated before the
 * first is written, so bad input writes nothing, but running out of memory
 * or an I/O failure part way leaves the files written before it (complete,
 * and named). */
fm_status fm_faultset_write_tsurf(const char *dir, const fm_faultset *fs, fm_error *err);

/* What became of one file fm_faultset_write_all was asked for: path, the
 * fault of a TSurf file (SIZE_MAX for the files of the whole set) and
 * err, NULL when the file was written, else why not (naming path). */
typedef void (*fm_output_done)(void *ctx, const char *path, size_t fault, const fm_error *err);

/* Which outputs fm_faultset_write_all writes; a NULL path skips one. */
typedef struct fm_faultset_outputs {
    const char *vtu, *msh, *stl, *obj; /* file paths */
    fm_msh_version msh_version;
    const char *tsurf_dir; /* one NAME.ts per fault, as fm_faultset_write_tsurf */
    const char *exo;       /* Exodus II file path */
    fm_output_done done;   /* may be NULL */
    void *done_ctx;
} fm_faultset_outputs;

/* Every requested output, written as the functions above write them, by
 * nthreads threads (the calling one included; < 1 means 1): the files
 * are split among them (each TSurf file is one piece of work) and every
 * file is byte-identical whatever nthreads. The set is validated once,
 * before any file is written.
 *
 * A file that fails does not stop the others: every file asked for is
 * tried, every file present is complete and a failing one leaves nothing.
 * Then out->done, when set, is called on the calling thread once per file
 * asked for, in the order VTU, MSH, STL, OBJ, Exodus II, TSurf by fault
 * (when the set is invalid, or the TSurf names cannot be made, each file
 * with that error; TSurf files whose names are unknown then make one call
 * with path tsurf_dir). The error returned is that of the first failing
 * file in that order, and names it. */
fm_status fm_faultset_write_all(const fm_faultset *fs, const fm_faultset_outputs *out,
                                int nthreads, fm_error *err);

/* The nfaults file names (without directory) fm_faultset_write_tsurf
 * uses, as a malloc'ed array of malloc'ed strings; free with
 * fm_faultset_free_file_names(). */
fm_status fm_faultset_tsurf_file_names(const fm_faultset *fs, char ***names, fm_error *err);
void fm_faultset_free_file_names(char **names, size_t n);

#ifdef __cplusplus
}
#endif
#endif
