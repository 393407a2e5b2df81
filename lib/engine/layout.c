/* Turns a model's adjacency into device connectivity: the paper's tiled
 * connectivity texture (IMAGE2D) or slot-major buffers (BUFFER) - both list
 * a point's springs in the same slot order, so both sum forces identically -
 * EDGES, the second seed's spring list, holds BUFFER's table (its springs
 * are gathered per point in the planes engine) - or nothing at all for a
 * cloth grid whose neighbours follow from its position (GRID). */
#include "config.h"
#include "layout.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

msocl_layout msocl__layout_auto(const msocl_device_info *info,
                                const msocl_model *m, int planes)
{
  /* A grid or lattice as the builders make it: GRID stores nothing and
   * moves the fewest bytes, where its padded planes fit. Otherwise BUFFER:
   * it reads 12 bytes a slot against the texture's 16, and PoCL's image
   * reads are about 3x slower than buffer reads on a CPU; no device
   * measured so far prefers the texture (docs/PERFORMANCE.md). */
  (void)info;
  if (msocl__grid_intact(m) && planes)
    return MSOCL_LAYOUT_GRID;
  return MSOCL_LAYOUT_BUFFER;
}

int msocl__image_dims(int n, size_t max_w, size_t max_h, int *w, int *h)
{
  /* Near-square, no power-of-two padding: at most W - 1 unused texels. */
  long long want = (long long)ceil(sqrt((double)n));
  long long cap_w = (long long)(max_w / 4), cap_h = (long long)(max_h / 4);
  long long W = want < cap_w ? want : cap_w;
  if (W < 1)
    W = 1;
  long long H = (n + W - 1) / W;
  if (H > cap_h || W > cap_w)
    return msocl__fail(MSOCL_ERR_IMAGE_SIZE,
                       "%d points need a %lldx%lld connectivity texture; the "
                       "device allows %zux%zu (use MSOCL_LAYOUT_BUFFER)",
                       n, 4 * W, 4 * H, max_w, max_h);
  *w = (int)W;
  *h = (int)H;
  return MSOCL_OK;
}

static int has_damping(const msocl_model *m)
{
  for (int s = 0; m->damp && s < m->ns; s++)
    if (m->damp[s] != 0.0f)
      return 1;
  return 0;
}

static cl_mem make_image(struct msocl__device *dev, int w, int h, void *host,
                         int *rc)
{
  cl_image_format fmt = {CL_RGBA, CL_FLOAT};
  cl_image_desc desc;
  memset(&desc, 0, sizeof desc);
  desc.image_type = CL_MEM_OBJECT_IMAGE2D;
  desc.image_width = (size_t)w;
  desc.image_height = (size_t)h;
  cl_int e;
  cl_mem im = clCreateImage(dev->ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                            &fmt, &desc, host, &e);
  if (e != CL_SUCCESS)
    *rc = msocl__fail(e, "clCreateImage(%dx%d RGBA float): %s", w, h,
                      msocl_err_name(e));
  return im;
}

/* The paper's texture: 16 tiles of W x H, slot s in tile (s % 4, s / 4);
 * an entry is (x, y of the other end, rest length, stiffness), -1 = end.
 * Dashpots go in a (4W) x H RGBA image, four slots a texel. */
static int build_image(struct msocl__device *dev, const msocl_model *m,
                       const struct msocl__adjacency *a, int damped,
                       struct msocl__layout *l)
{
  int rc = msocl__image_dims(m->n, dev->info.image2d_max_width,
                             dev->info.image2d_max_height, &l->tex_w,
                             &l->tex_h);
  if (rc != MSOCL_OK)
    return rc;
  const size_t W = (size_t)l->tex_w, H = (size_t)l->tex_h;
  float *tex = malloc(16 * W * H * 4 * sizeof *tex);
  float *dtex = damped ? calloc(4 * W * H * 4, sizeof *dtex) : NULL;
  if (!tex || (damped && !dtex)) {
    free(tex);
    free(dtex);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "connectivity texture");
  }
  for (size_t t = 0; t < 16 * W * H * 4; t++)
    tex[t] = -1.0f;
  for (int i = 0; i < m->n; i++) {
    size_t x = (size_t)i % W, y = (size_t)i / W;
    for (int s = 0; s < a->off[i + 1] - a->off[i]; s++) {
      int j = a->other[a->off[i] + s], sp = a->spring[a->off[i] + s];
      size_t tx = x + (size_t)(s & 3) * W, ty = y + (size_t)(s >> 2) * H;
      float *e = tex + 4 * (ty * 4 * W + tx);
      e[0] = (float)(j % (int)W);
      e[1] = (float)(j / (int)W);
      e[2] = m->rest[sp];
      e[3] = m->k[sp];
      if (damped)
        dtex[4 * (y * 4 * W + x + (size_t)(s >> 2) * W) + (s & 3)] =
            m->damp[sp];
    }
  }
  l->con = make_image(dev, 4 * l->tex_w, 4 * l->tex_h, tex, &rc);
  if (rc == MSOCL_OK) {
    float dummy[4] = {0};
    l->damp = damped ? make_image(dev, 4 * l->tex_w, l->tex_h, dtex, &rc)
                     : make_image(dev, 1, 1, dummy, &rc);
  }
  free(tex);
  free(dtex);
  return rc;
}

int msocl__table_slots(const struct msocl__adjacency *adj, int want)
{
  const int n = adj->n, most = adj->max_degree;
  const int top = most < MSOCL__TABLE_SLOTS ? most : MSOCL__TABLE_SLOTS;
  if (want > 0)
    return want < top ? want : top;
  /* a table of up to 32 slots costs little whatever the spread */
  if (top <= 32 || n == 0)
    return top;
  int *count = calloc((size_t)most + 1, sizeof *count);
  if (!count)
    return top; /* the caller's own allocation reports the shortage */
  for (int i = 0; i < n; i++)
    count[adj->off[i + 1] - adj->off[i]]++;
  int width = 0, within = 0;
  while (width < top && within + count[width] < n - n / 100)
    within += count[width++];
  free(count);
  width = (width + 3) / 4 * 4; /* msocl_slot4 takes four at a time */
  return width < top ? width : top;
}

/* The springs' distinct (rest, k, dashpot) classes, compared bit for bit
 * so a class holds exactly the floats its slots would: tab[0] is a free
 * slot's zeros, cls[sp] spring sp's class. Returns how many, or 0 past
 * 256 (a mesh whose every edge has its own rest length). */
static int spring_classes(const msocl_model *m, int damped, cl_float4 *tab,
                          unsigned char *cls)
{
  enum { BUCKETS = 1024 }; /* open addressing, at most a quarter full */
  int bucket[BUCKETS], nc = 0;
  for (int b = 0; b < BUCKETS; b++)
    bucket[b] = -1;
  for (int sp = -1; sp < m->ns; sp++) {
    float v[3] = {0.0f, 0.0f, 0.0f};
    if (sp >= 0) {
      v[0] = m->rest[sp];
      v[1] = m->k[sp];
      v[2] = damped ? m->damp[sp] : 0.0f;
    }
    uint32_t w[3];
    memcpy(w, v, sizeof w);
    uint32_t h = (w[0] * 2654435761u) ^ (w[1] * 2246822519u) ^
                 (w[2] * 3266489917u);
    int b = (int)((h ^ (h >> 15)) % BUCKETS), c = -1;
    for (; bucket[b] >= 0; b = (b + 1) % BUCKETS)
      if (!memcmp(tab[bucket[b]].s, v, sizeof v)) {
        c = bucket[b];
        break;
      }
    if (c < 0) {
      if (nc == 256)
        return 0;
      c = bucket[b] = nc++;
      memcpy(tab[c].s, v, sizeof v);
      tab[c].s[3] = 0.0f;
    }
    if (sp >= 0)
      cls[sp] = (unsigned char)c;
  }
  return nc;
}

/* Slot-major arrays: slot s of point i at s * n + i, so neighbouring work
 * items read neighbouring words; past l->slots, a point's further springs
 * follow the table, point i's from spill[i] on. With classes, a slot's
 * (rest, k, dashpot) is a byte naming its class: 5 bytes a slot, not 12
 * (16 with dashpots), and the same floats. */
static int build_buffers(struct msocl__device *dev, const msocl_model *m,
                         const struct msocl__adjacency *a, int damped,
                         msocl_choice classes, struct msocl__layout *l)
{
  const size_t n = (size_t)m->n, S = (size_t)(l->slots > 0 ? l->slots : 1);
  int *spill = malloc((n + 1) * sizeof *spill);
  if (!spill)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "connectivity buffers");
  spill[0] = 0;
  for (size_t i = 0; i < n; i++) {
    int d = a->off[i + 1] - a->off[i];
    spill[i + 1] = spill[i] + (d > (int)S ? d - (int)S : 0);
  }
  const size_t total = S * n + (size_t)spill[n];
  /* auto: classes once the values outgrow half the cache, where memory
   * bandwidth, not arithmetic, bounds the step */
  const int want = classes == MSOCL_AUTO
                       ? (double)total * (damped ? 16 : 12) >
                             0.5 * (double)dev->info.cache
                       : classes == MSOCL_ON;
  cl_float4 tab[256];
  unsigned char *sc = want ? malloc(m->ns > 0 ? (size_t)m->ns : 1) : NULL;
  l->classes = sc ? spring_classes(m, damped, tab, sc) : 0;
  const int values = l->classes == 0;
  int *nbr = malloc(total * sizeof *nbr);
  float *rk = values ? calloc(2 * total, sizeof *rk) : NULL;
  float *dmp = values ? calloc(damped ? total : 1, sizeof *dmp) : NULL;
  unsigned char *cls = values ? NULL : calloc(total, 1); /* 0: free */
  int rc = MSOCL_OK;
  if (!nbr || (values && (!rk || !dmp)) || (!values && !cls)) {
    rc = msocl__fail(MSOCL_ERR_NO_MEMORY, "connectivity buffers (%zu slots)",
                     total);
    goto out;
  }
  /* A free slot is a spring from the point to itself with rest and k 0
   * (GRID's missing neighbour): it adds exact zeros, so msocl_slot4 can
   * take four slots at a time with no end test. */
  for (size_t t = 0; t < S * n; t++)
    nbr[t] = (int)(t % n);
  for (size_t i = 0; i < n; i++)
    for (int s = 0; s < a->off[i + 1] - a->off[i]; s++) {
      int sp = a->spring[a->off[i] + s];
      size_t at = (size_t)s < S ? (size_t)s * n + i
                                : S * n + (size_t)spill[i] + (size_t)s - S;
      nbr[at] = a->other[a->off[i] + s];
      if (!values) {
        cls[at] = sc[sp];
        continue;
      }
      rk[2 * at] = m->rest[sp];
      rk[2 * at + 1] = m->k[sp];
      if (damped)
        dmp[at] = m->damp[sp];
    }
  l->con = msocl__buffer(dev, CL_MEM_READ_ONLY, total * sizeof *nbr, nbr,
                         "the connectivity", &rc);
  if (values) {
    l->rk = msocl__buffer(dev, CL_MEM_READ_ONLY, 2 * total * sizeof *rk, rk,
                          "the springs' values", &rc);
    l->damp = msocl__buffer(dev, CL_MEM_READ_ONLY,
                            (damped ? total : 1) * sizeof *dmp, dmp,
                            "the dashpots", &rc);
  } else {
    l->rk = msocl__buffer(dev, CL_MEM_READ_ONLY, total, cls,
                          "the springs' classes", &rc);
    l->damp = msocl__buffer(dev, CL_MEM_READ_ONLY,
                            (size_t)l->classes * sizeof *tab, tab,
                            "the classes' values", &rc);
  }
  if (spill[n] > 0)
    l->spill = msocl__buffer(dev, CL_MEM_READ_ONLY, (n + 1) * sizeof *spill,
                             spill, "the spill", &rc);
out:
  free(spill);
  free(nbr);
  free(rk);
  free(dmp);
  free(cls);
  free(sc);
  return rc;
}

/* The connectivity texture holds MSOCL__IMAGE_SLOTS springs a point:
 * refuses IMAGE2D for a model with a point of more, naming the first. */
int msocl__layout_fits(const msocl_model *m, msocl_layout kind)
{
  if (kind != MSOCL_LAYOUT_IMAGE2D)
    return MSOCL_OK;
  int *deg = calloc((size_t)m->n + 1, sizeof *deg), first = -1;
  if (!deg)
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "degree count");
  for (int e = 0; e < 2 * m->ns; e++)
    deg[m->ij[e]]++;
  for (int i = 0; i < m->n && first < 0; i++)
    if (deg[i] > MSOCL__IMAGE_SLOTS)
      first = i;
  int d = first >= 0 ? deg[first] : 0;
  free(deg);
  if (first < 0)
    return MSOCL_OK;
  return msocl__fail(MSOCL_ERR_DEGREE,
                     "point %d has %d springs; the IMAGE2D layout holds %d "
                     "(use MSOCL_LAYOUT_BUFFER)",
                     first, d, MSOCL__IMAGE_SLOTS);
}

int msocl__layout_create(struct msocl__device *dev, const msocl_model *m,
                         const struct msocl__adjacency *adj,
                         msocl_layout kind, int table_slots,
                         msocl_choice classes, struct msocl__layout *out)
{
  memset(out, 0, sizeof *out);
  out->kind =
      kind == MSOCL_LAYOUT_AUTO ? msocl__layout_auto(&dev->info, m, 0) : kind;
  int rc;
  if (out->kind == MSOCL_LAYOUT_IMAGE2D) {
    if (!dev->info.image_support)
      return msocl__fail(MSOCL_ERR_NO_IMAGES,
                         "device '%s' has no image support: IMAGE2D layout "
                         "impossible (use MSOCL_LAYOUT_BUFFER)",
                         dev->info.name);
    out->slots = MSOCL__IMAGE_SLOTS;
    if ((rc = msocl__layout_fits(m, MSOCL_LAYOUT_IMAGE2D)) != MSOCL_OK)
      return rc;
    rc = build_image(dev, m, adj, has_damping(m), out);
  } else if (out->kind == MSOCL_LAYOUT_BUFFER ||
             out->kind == MSOCL_LAYOUT_EDGES) {
    /* EDGES: a point's springs in BUFFER's table, read by the planes
     * engine's gather as BUFFER's are (planes.c) */
    out->degree = adj->max_degree;
    out->slots = msocl__table_slots(adj, table_slots);
    for (int i = 0; i < adj->n; i++) {
      const int d = adj->off[i + 1] - adj->off[i];
      if (d <= out->slots && d > out->dense)
        out->dense = d;
    }
    rc = build_buffers(dev, m, adj, has_damping(m), classes, out);
  } else if (out->kind == MSOCL_LAYOUT_GRID) {
    if (!msocl__grid_intact(m))
      return msocl__fail(MSOCL_ERR_BAD_VALUE,
                         "the GRID layout needs a cloth from "
                         "msocl_model_cloth_grid or a lattice from "
                         "msocl_model_lattice, with no springs or points "
                         "added since, or one built by hand with exactly "
                         "their springs in their order (use BUFFER)");
    const int lattice = m->grid.nz > 0;
    out->slots = lattice ? 32 : 12;
    out->grid_nx = m->grid.nx;
    out->grid_ny = m->grid.ny;
    out->grid_nz = m->grid.nz;
    /* cloth: three stiffnesses and the dashpot; lattice: four
     * stiffnesses, and the dashpot after the four rests */
    for (int q = 0; q < 4; q++)
      out->grid_k.s[q] = q < 3 || lattice ? m->grid.k[q] : m->grid.damp;
    for (int q = 0; q < 8; q++)
      out->grid_rest.s[q] = q < (lattice ? 4 : 6) ? m->grid.rest[q] : 0.0f;
    if (lattice)
      out->grid_rest.s[4] = m->grid.damp;
    rc = MSOCL_OK;
  } else {
    return msocl__fail(MSOCL_ERR_BAD_VALUE, "unknown layout %d", (int)kind);
  }
  if (rc != MSOCL_OK)
    msocl__layout_release(out);
  return rc;
}

void msocl__layout_release(struct msocl__layout *l)
{
  if (l->con)
    clReleaseMemObject(l->con);
  if (l->rk)
    clReleaseMemObject(l->rk);
  if (l->damp)
    clReleaseMemObject(l->damp);
  if (l->spill)
    clReleaseMemObject(l->spill);
  l->con = l->rk = l->damp = l->spill = NULL;
}

int msocl__layout_set_args(const struct msocl__layout *l,
                           struct msocl__device *dev, cl_kernel k)
{
  struct {
    const char *name;
    size_t size;
    const void *v;
  } c[5];
  int n = 0;
#define CONN(nm, x) (c[n].name = (nm), c[n].size = sizeof(x), c[n++].v = &(x))
  if (l->kind == MSOCL_LAYOUT_GRID) {
    CONN("grid_nx", l->grid_nx);
    CONN("grid_ny", l->grid_ny);
    if (l->grid_nz > 0)
      CONN("grid_nz", l->grid_nz);
    CONN("grid_k", l->grid_k);
    CONN("grid_rest", l->grid_rest);
  } else {
    CONN(l->kind == MSOCL_LAYOUT_IMAGE2D ? "con" : "nbr", l->con);
    if (l->kind == MSOCL_LAYOUT_IMAGE2D) {
      CONN("tex_w", l->tex_w);
      CONN("tex_h", l->tex_h);
    } else {
      CONN("rk", l->rk);
    }
    CONN("dmp", l->damp);
    if (l->spill)
      CONN("spill", l->spill);
  }
#undef CONN
  for (int q = 0; q < n; q++)
    MSOCL__TRY(msocl__kernel_arg(dev, k, c[q].name, c[q].size, c[q].v));
  return MSOCL_OK;
}
