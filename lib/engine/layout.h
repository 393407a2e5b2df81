/* Device connectivity: where each point finds its springs (IMAGE2D, BUFFER). */
#ifndef MSOCL_LAYOUT_H
#define MSOCL_LAYOUT_H

#include "internal.h"

struct msocl__layout {
  msocl_layout kind; /* IMAGE2D, BUFFER, EDGES or GRID, never AUTO */
  int slots;         /* springs a point can hold (BUFFER, EDGES); with
                        a spill: in the table */
  int degree;        /* BUFFER: the most springs any point has */
  int dense;         /* BUFFER: the most any point that does not spill
                        has (the table's slots past it are mostly free) */
  cl_mem spill;      /* BUFFER: per point, where its springs past the
                        table start in the list after it (n + 1 ints);
                        NULL: none spill */
  int grid_nx, grid_ny;    /* GRID */
  int grid_nz;             /* GRID: a lattice's layers; 0: a cloth */
  cl_float4 grid_k;        /* cloth: stretch, shear, bend stiffness,
                              dashpot; lattice: the four kinds' stiffness */
  cl_float8 grid_rest;     /* cloth: the six kinds' rest lengths; lattice:
                              the four kinds', then the dashpot */
  int tex_w, tex_h;  /* IMAGE2D: point i is texel (i % tex_w, i / tex_w) */
  cl_mem con;        /* IMAGE2D: (4W)x(4H) RGBA image; BUFFER, EDGES: int
                        slots */
  cl_mem rk;         /* BUFFER, EDGES: float2 (rest, k) per slot;
                        BUFFER with classes: a uchar class per slot */
  cl_mem damp;       /* dashpot coefficients per slot (or a 1-item dummy);
                        BUFFER with classes: the classes' float4 (rest, k,
                        dashpot, 0) */
  int classes;       /* BUFFER: the springs' distinct (rest, k, dashpot)
                        classes, the free slot's zeros first; 0: values in
                        every slot */
};

/* The layout AUTO stands for on this device, for this model; planes:
 * whether GRID's padded planes fit it (msocl__planes_would). */
msocl_layout msocl__layout_auto(const msocl_device_info *info,
                                const msocl_model *m, int planes);

/* Chooses W x H >= n for the connectivity texture within the device's
 * image limits (the texture is 4W x 4H). */
int msocl__image_dims(int n, size_t max_w, size_t max_h, int *w, int *h);

/* MSOCL_ERR_DEGREE, naming the model's first point over the limit, when
 * the model's springs do not fit `kind`'s slots. */
int msocl__layout_fits(const msocl_model *m, msocl_layout kind);

/* The widest BUFFER table: the kernels unroll its slots, and wider ones
 * bloat them; a point's springs past it spill. */
#define MSOCL__TABLE_SLOTS 64

/* BUFFER's table width for these degrees: all of a point's springs,
 * unless a few points (a hub such as a solid's centre) have far more than
 * the rest - then a width that holds 99% of the points' springs, the rest
 * spilling into per-point lists, so the table is not the hub's degree
 * times every point. `want` > 0 chooses. Either way at most the largest
 * degree and MSOCL__TABLE_SLOTS. */
int msocl__table_slots(const struct msocl__adjacency *adj, int want);

/* classes (tuning.classes): BUFFER may number its springs' (rest, k,
 * dashpot) classes when there are at most 256 (5 bytes a slot instead of
 * 12 or 16); ON: whenever they fit, OFF: never, AUTO: when the values
 * would not fit in half the device's cache. */
int msocl__layout_create(struct msocl__device *dev, const msocl_model *m,
                         const struct msocl__adjacency *adj,
                         msocl_layout kind, int table_slots,
                         msocl_choice classes, struct msocl__layout *out);
void msocl__layout_release(struct msocl__layout *l);

/* Sets kernel k's connectivity arguments (common.cl's MSOCL_CONN) by
 * name; k made by msocl__kernel_make on dev. */
int msocl__layout_set_args(const struct msocl__layout *l,
                           struct msocl__device *dev, cl_kernel k);

#endif
