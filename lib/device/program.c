/* Builds the library's OpenCL program for a device with a set of -D options,
 * once per (device, options), from the embedded kernels or MSOCL_KERNEL_PATH. */
#include "config.h"
#include "internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct msocl__program {
  char *options;
  cl_program program;
  struct msocl__program *next;
};

/* Reads kernels/<name> from the folder in MSOCL_KERNEL_PATH: lets a kernel
 * be edited and rerun without rebuilding the library. */
static int read_kernel_file(const char *dir, const char *name, char **text)
{
  char path[4096];
  int len = snprintf(path, sizeof path, "%s/%s", dir, name);
  if (len < 0 || (size_t)len >= sizeof path)
    return msocl__fail(MSOCL_ERR_KERNEL_SOURCE, "MSOCL_KERNEL_PATH too long");
  FILE *f = fopen(path, "rb");
  if (!f)
    return msocl__fail(MSOCL_ERR_KERNEL_SOURCE,
                       "cannot open kernel source %s (MSOCL_KERNEL_PATH)",
                       path);
  size_t cap = 1 << 14, used = 0;
  char *buf = malloc(cap);
  for (;;) {
    if (!buf) {
      fclose(f);
      return msocl__fail(MSOCL_ERR_NO_MEMORY, "reading %s", path);
    }
    used += fread(buf + used, 1, cap - used - 1, f);
    if (used < cap - 1)
      break;
    cap *= 2;
    char *grown = realloc(buf, cap);
    if (!grown)
      free(buf);
    buf = grown;
  }
  int bad = ferror(f);
  fclose(f);
  if (bad) {
    free(buf);
    return msocl__fail(MSOCL_ERR_IO, "error reading %s", path);
  }
  buf[used] = '\0';
  *text = buf;
  return MSOCL_OK;
}

/* Blanks a file's own #include "..." lines, as kernels/embed.sed does for
 * the embedded copies: the program holds every header already. */
static void drop_includes(char *text)
{
  for (char *line = text; line && *line;) {
    if (strncmp(line, "#include \"", 10) == 0)
      for (char *c = line; *c && *c != '\n'; c++)
        *c = ' ';
    line = strchr(line, '\n');
    if (line)
      line++;
  }
}

/* The most kernel files a program joins (Makefile.am's KERNEL_FILES) */
#define MAX_KERNEL_FILES 32

static int build(struct msocl__device *dev, const char *options,
                 cl_program *out)
{
  const int n = msocl__kernel_source_count;
  const char *texts[MAX_KERNEL_FILES];
  char *owned[MAX_KERNEL_FILES] = {0};
  const char *dir = getenv("MSOCL_KERNEL_PATH");
  int rc = MSOCL_OK;
  if (n > MAX_KERNEL_FILES)
    return msocl__fail(MSOCL_ERR_TOO_MANY, "too many kernel files: %d",
                       n);
  for (int i = 0; i < n && rc == MSOCL_OK; i++) {
    texts[i] = msocl__kernel_sources[i].text;
    if (dir && *dir) {
      rc = read_kernel_file(dir, msocl__kernel_sources[i].name, &owned[i]);
      if (rc == MSOCL_OK)
        drop_includes(owned[i]);
      texts[i] = owned[i];
    }
  }
  cl_int e = CL_SUCCESS;
  cl_program p = NULL;
  if (rc == MSOCL_OK) {
    p = clCreateProgramWithSource(dev->ctx, (cl_uint)n, texts, NULL, &e);
    if (e != CL_SUCCESS)
      rc = msocl__fail(e, "clCreateProgramWithSource: %s", msocl_err_name(e));
  }
  for (int i = 0; i < n; i++)
    free(owned[i]);
  if (rc != MSOCL_OK)
    return rc;

  /* the kernels' argument names: callers set arguments by name
   * (kernel_names.c) */
  char *full = malloc(strlen(options) + sizeof " -cl-kernel-arg-info");
  if (!full) {
    clReleaseProgram(p);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "build options");
  }
  strcpy(full, options);
  strcat(full, " -cl-kernel-arg-info");
  e = clBuildProgram(p, 1, &dev->id, full, NULL, NULL);
  free(full);
  if (e != CL_SUCCESS) {
    /* Carry the compiler's own words to the user. */
    size_t len = 0;
    char *log = NULL;
    clGetProgramBuildInfo(p, dev->id, CL_PROGRAM_BUILD_LOG, 0, NULL, &len);
    if (len > 0 && (log = malloc(len + 1)) != NULL) {
      clGetProgramBuildInfo(p, dev->id, CL_PROGRAM_BUILD_LOG, len, log, NULL);
      log[len] = '\0';
    }
    rc = msocl__fail(MSOCL_ERR_BUILD,
                     "kernel build failed on %s (%s) with options '%s':\n%s",
                     dev->info.name, msocl_err_name(e), options,
                     log ? log : "(no build log)");
    free(log);
    clReleaseProgram(p);
    return rc;
  }
  *out = p;
  return MSOCL_OK;
}

static int find_or_build(struct msocl__device *dev, const char *options,
                         cl_program *out)
{
  for (struct msocl__program *c = dev->programs; c; c = c->next)
    if (strcmp(c->options, options) == 0) {
      *out = c->program;
      return MSOCL_OK;
    }
  struct msocl__program *c = calloc(1, sizeof *c);
  if (!c || !(c->options = strdup(options))) {
    free(c);
    return msocl__fail(MSOCL_ERR_NO_MEMORY, "program cache");
  }
  int rc = build(dev, options, &c->program);
  if (rc != MSOCL_OK) {
    free(c->options);
    free(c);
    return rc;
  }
  c->next = dev->programs;
  dev->programs = c;
  *out = c->program;
  return MSOCL_OK;
}

/* One build at a time per device: a second thread wanting the same
 * program waits for it rather than building (and leaking) its own. */
int msocl__program_get(struct msocl__device *dev, const char *options,
                       cl_program *out)
{
  pthread_mutex_lock(&dev->programs_lock);
  int rc = find_or_build(dev, options, out);
  pthread_mutex_unlock(&dev->programs_lock);
  return rc;
}

void msocl__program_cache_free(struct msocl__device *dev)
{
  struct msocl__program *c = dev->programs;
  while (c) {
    struct msocl__program *next = c->next;
    clReleaseProgram(c->program);
    free(c->options);
    free(c);
    c = next;
  }
  dev->programs = NULL;
}

int msocl__program_cache_size(struct msocl__device *dev)
{
  int n = 0;
  pthread_mutex_lock(&dev->programs_lock);
  for (struct msocl__program *c = dev->programs; c; c = c->next)
    n++;
  pthread_mutex_unlock(&dev->programs_lock);
  return n;
}
