/* Applies a device spec ("cpu", "gpu", "all", "P:D", N, a name substring, or
 * a comma-separated list of these) to a device list; pure, so it is tested
 * without OpenCL. */
#include <limits.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

enum { T_CPU, T_GPU, T_ACC, T_ALL, T_PD, T_INDEX, T_NAME };

/* One term of the spec, trimmed; not NUL-terminated, hence `len`. */
struct term {
  const char *s;
  int len;
  int kind;
  int p, d; /* P:D, or d alone for T_INDEX */
};

/* ASCII only: a spec must not mean different things in different locales. */
static int lower(int c) { return c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c; }
static int is_space(int c) { return c == ' ' || (c >= '\t' && c <= '\r'); }
static int is_digit(int c) { return c >= '0' && c <= '9'; }

static int word_is(const struct term *t, const char *w) {
  int i;
  for (i = 0; i < t->len; i++)
    if (w[i] == '\0' || lower((unsigned char)t->s[i]) != w[i]) return 0;
  return w[i] == '\0';
}

/* A non-empty run of decimal digits that fits an int; 0 otherwise. */
static int parse_uint(const char *s, int len, int *v) {
  long long x = 0;
  int i;
  if (len <= 0) return 0;
  for (i = 0; i < len; i++) {
    if (!is_digit((unsigned char)s[i])) return 0;
    x = x * 10 + (s[i] - '0');
    if (x > INT_MAX) return 0;
  }
  *v = (int)x;
  return 1;
}

/* Cuts the next term out of the spec at p; returns where the one after it
 * starts, or NULL after the last. */
static const char *next_term(const char *p, struct term *t) {
  const char *end = p, *e;
  while (*end != '\0' && *end != ',') end++;
  e = end;
  while (p < e && is_space((unsigned char)*p)) p++;
  while (e > p && is_space((unsigned char)e[-1])) e--;
  t->s = p;
  t->len = (int)(e - p);
  return *end == ',' ? end + 1 : NULL;
}

/* A term with a colon is P:D where it begins as a number would (a digit,
 * a sign, a space or the colon: "1:", "-1:0" are errors, not names);
 * else it is a name, which may hold colons (ROCm's
 * "gfx90a:sramecc+:xnack-"). */
static int parse_term(const char *spec, struct term *t) {
  const char *colon = t->len > 0 ? memchr(t->s, ':', (size_t)t->len) : NULL;
  if (colon && !(is_digit((unsigned char)t->s[0]) || t->s[0] == '-' ||
                 t->s[0] == '+' || t->s[0] == ':' || t->s[0] == ' ' ||
                 t->s[0] == '\t'))
    colon = NULL;
  int i;

  if (t->len == 0)
    return msocl__fail(MSOCL_ERR_BAD_SPEC,
                       "device spec '%s' has an empty term", spec);
  if (colon) {
    int left = (int)(colon - t->s);
    t->kind = T_PD;
    if (parse_uint(t->s, left, &t->p) &&
        parse_uint(colon + 1, t->len - left - 1, &t->d))
      return MSOCL_OK;
    return msocl__fail(MSOCL_ERR_BAD_SPEC,
                       "device spec term '%.*s' is not P:D (platform and "
                       "device index, non-negative decimal integers)",
                       t->len, t->s);
  }
  if (word_is(t, "cpu")) t->kind = T_CPU;
  else if (word_is(t, "gpu")) t->kind = T_GPU;
  else if (word_is(t, "accelerator") || word_is(t, "acc")) t->kind = T_ACC;
  else if (word_is(t, "all")) t->kind = T_ALL;
  else {
    /* Digits (with an optional sign) are an index, never a name. */
    int sign = t->s[0] == '-' || t->s[0] == '+';
    for (i = sign; i < t->len && is_digit((unsigned char)t->s[i]); i++) {
    }
    if (i < t->len || i == sign) {
      t->kind = T_NAME;
      return MSOCL_OK;
    }
    t->kind = T_INDEX;
    if (sign || !parse_uint(t->s, t->len, &t->d))
      return msocl__fail(MSOCL_ERR_BAD_SPEC,
                         "device spec term '%.*s' is not a device index "
                         "(0 to %d)",
                         t->len, t->s, INT_MAX);
  }
  return MSOCL_OK;
}

static int contains(const char *hay, size_t cap, const struct term *t) {
  const char *z = memchr(hay, '\0', cap);
  size_t n = z ? (size_t)(z - hay) : cap, i;
  int j;
  for (i = 0; i + (size_t)t->len <= n; i++) {
    for (j = 0; j < t->len; j++)
      if (lower((unsigned char)hay[i + (size_t)j]) !=
          lower((unsigned char)t->s[j]))
        break;
    if (j == t->len) return 1;
  }
  return 0;
}

/* The one device a term other than `all` names, or -1. */
static int match(const struct term *t, const msocl_device_info *devs,
                 int ndevs) {
  int i;
  if (t->kind == T_INDEX) return t->d < ndevs ? t->d : -1;
  for (i = 0; i < ndevs; i++) {
    const msocl_device_info *d = &devs[i];
    switch (t->kind) {
    case T_CPU: if (d->type & MSOCL_DEVICE_CPU) return i; break;
    case T_GPU: if (d->type & MSOCL_DEVICE_GPU) return i; break;
    case T_ACC: if (d->type & MSOCL_DEVICE_ACCELERATOR) return i; break;
    case T_PD:
      if (d->platform_index == t->p && d->device_index == t->d) return i;
      break;
    default:
      if (contains(d->name, sizeof d->name, t) ||
          contains(d->platform_name, sizeof d->platform_name, t))
        return i;
    }
  }
  return -1;
}

static const char *type_name(int type) {
  if (type & MSOCL_DEVICE_GPU) return "GPU";
  if (type & MSOCL_DEVICE_CPU) return "CPU";
  if (type & MSOCL_DEVICE_ACCELERATOR) return "accelerator";
  return "other";
}

/* Whoever reads "matches no device" next wants to know what does exist. */
static int no_device(const struct term *t, const msocl_device_info *devs,
                     int ndevs) {
  char list[8192];
  size_t off = 0;
  int i;
  list[0] = '\0';
  for (i = 0; i < ndevs && off < sizeof list; i++) {
    int n = snprintf(list + off, sizeof list - off,
                     "\n  #%d  %d:%d %.128s [%.128s] (%s)", i,
                     devs[i].platform_index, devs[i].device_index,
                     devs[i].name, devs[i].platform_name,
                     type_name(devs[i].type));
    if (n < 0) break;
    off += (size_t)n;
  }
  return msocl__fail(MSOCL_ERR_NO_DEVICE,
                     "device spec term '%.*s' matches no device; the %d "
                     "device%s (#N  P:D name [platform] (type)):%s",
                     t->len, t->s, ndevs, ndevs == 1 ? " is" : "s are", list);
}

static int add(const char *spec, const struct term *t,
               const msocl_device_info *devs, int dev, int *chosen,
               int max_chosen, int *n) {
  int i;
  for (i = 0; i < *n; i++)
    if (chosen[i] == dev)
      return msocl__fail(MSOCL_ERR_DUP_DEVICE,
                         "device spec '%s' chooses device #%d (%d:%d %.128s) "
                         "twice, the second time by term '%.*s'",
                         spec, dev, devs[dev].platform_index,
                         devs[dev].device_index, devs[dev].name, t->len,
                         t->s);
  if (*n >= max_chosen)
    return msocl__fail(MSOCL_ERR_TOO_MANY,
                       "device spec '%s' chooses more than %d device%s",
                       spec, max_chosen, max_chosen == 1 ? "" : "s");
  chosen[(*n)++] = dev;
  return MSOCL_OK;
}

/* No spec: the first GPU, else the first CPU, else the first device. */
static int default_device(const msocl_device_info *devs, int ndevs) {
  int i;
  for (i = 0; i < ndevs; i++)
    if (devs[i].type & MSOCL_DEVICE_GPU) return i;
  for (i = 0; i < ndevs; i++)
    if (devs[i].type & MSOCL_DEVICE_CPU) return i;
  return 0;
}

static int blank(const char *s) {
  while (is_space((unsigned char)*s)) s++;
  return *s == '\0';
}

int msocl_device_select(const char *spec, const msocl_device_info *devs,
                        int ndevs, int *chosen, int max_chosen,
                        int *nchosen) {
  struct term t;
  const char *p;
  int n = 0, rc, i;

  msocl__clear_error();
  if (!chosen || !nchosen)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE,
                       "msocl_device_select: %s is NULL",
                       chosen ? "nchosen" : "chosen");
  *nchosen = 0;
  if (ndevs < 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT,
                       "msocl_device_select: ndevs is %d", ndevs);
  if (ndevs == 0)
    return msocl__fail(MSOCL_ERR_NO_PLATFORM,
                       "no OpenCL device to choose from");
  if (!devs)
    return msocl__fail(MSOCL_ERR_NULL_HANDLE,
                       "msocl_device_select: devs is NULL");
  if (max_chosen <= 0)
    return msocl__fail(MSOCL_ERR_BAD_COUNT,
                       "msocl_device_select: max_chosen is %d", max_chosen);

  if (!spec || blank(spec)) {
    chosen[0] = default_device(devs, ndevs);
    *nchosen = 1;
    return MSOCL_OK;
  }

  /* Every term is checked before any is matched, so a typo anywhere is
   * reported as such rather than as a missing device. */
  for (p = spec; p;) {
    p = next_term(p, &t);
    if ((rc = parse_term(spec, &t)) != MSOCL_OK) return rc;
  }
  for (p = spec; p;) {
    p = next_term(p, &t);
    (void)parse_term(spec, &t);
    if (t.kind == T_ALL) {
      for (i = 0; i < ndevs; i++)
        if ((rc = add(spec, &t, devs, i, chosen, max_chosen, &n)) != MSOCL_OK)
          return rc;
    } else {
      int dev = match(&t, devs, ndevs);
      if (dev < 0) return no_device(&t, devs, ndevs);
      if ((rc = add(spec, &t, devs, dev, chosen, max_chosen, &n)) != MSOCL_OK)
        return rc;
    }
  }
  *nchosen = n;
  return MSOCL_OK;
}
