/* Lists every OpenCL device libmsocl can use and shows which ones a device
 * spec (argv[1], else MSOCL_DEVICE) chooses.
 *
 *   msocl-devices [SPEC]
 *   POCL_DEVICES="pthread pthread" MSOCL_DEVICE=0:1 msocl-devices
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <msocl.h>

#define MAX_CHOSEN 64

static const char *type_name(int type) {
  switch (type) {
  case MSOCL_DEVICE_CPU: return "CPU";
  case MSOCL_DEVICE_GPU: return "GPU";
  case MSOCL_DEVICE_ACCELERATOR: return "accelerator";
  default: return "other";
  }
}

static void print_device(int i, const msocl_device_info *d) {
  char images[64];
  if (d->image_support)
    snprintf(images, sizeof images, "image2d %zux%zu", d->image2d_max_width,
             d->image2d_max_height);
  else
    snprintf(images, sizeof images, "no images");
  printf("%-3d %d:%-3d %-11s %4u  %8llu  %9.1f  %-21s %-4s  %s [%s]\n", i,
         d->platform_index, d->device_index, type_name(d->type),
         d->compute_units, d->global_mem / (1024ULL * 1024ULL),
         (double)d->cache / (1024.0 * 1024.0), images,
         d->fp64 ? "yes" : "no", d->name, d->platform_name);
}

static int fail(const char *what, int rc) {
  fprintf(stderr, "msocl-devices: %s: %s (%s)\n%s\n", what,
          msocl_strerror(rc), msocl_err_name(rc), msocl_last_error());
  return EXIT_FAILURE;
}

int main(int argc, char **argv) {
  msocl_device_info *devs;
  int ndevs, chosen[MAX_CHOSEN], nchosen, i, rc;
  const char *spec = argc > 1 ? argv[1] : getenv("MSOCL_DEVICE");

  if (argc > 2 || (argc == 2 && (!strcmp(argv[1], "-h") ||
                                 !strcmp(argv[1], "--help")))) {
    fprintf(stderr,
            "usage: %s [SPEC]\n"
            "SPEC (default: $MSOCL_DEVICE): cpu, gpu, acc, all, P:D, N, a\n"
            "substring of a device or platform name, or a comma-separated\n"
            "list of these.\n",
            argv[0]);
    return argc > 2 ? EXIT_FAILURE : EXIT_SUCCESS;
  }
  printf("libmsocl %s\n", msocl_version_string());
  if ((rc = msocl_device_list(&devs, &ndevs)) != MSOCL_OK)
    return fail("listing devices", rc);
  printf("%-3s %-5s %-11s %4s  %8s  %9s  %-21s %-4s  %s\n", "#", "P:D",
         "type", "CUs", "MiB", "cache MiB", "images", "fp64",
         "name [platform]");
  for (i = 0; i < ndevs; i++) print_device(i, &devs[i]);

  /* No spec shows the default choice, which is what a program gets. */
  rc = msocl_device_select(spec, devs, ndevs, chosen, MAX_CHOSEN, &nchosen);
  if (rc != MSOCL_OK) {
    free(devs);
    return fail(argc > 1 ? "spec" : "MSOCL_DEVICE", rc);
  }
  if (!spec)
    printf("\nno spec (MSOCL_DEVICE unset): the default chooses:\n");
  else
    printf("\n%s'%s' chooses:\n", argc > 1 ? "" : "MSOCL_DEVICE=", spec);
  for (i = 0; i < nchosen; i++)
    printf("  #%d  %d:%d  %s [%s]\n", chosen[i],
           devs[chosen[i]].platform_index, devs[chosen[i]].device_index,
           devs[chosen[i]].name, devs[chosen[i]].platform_name);
  free(devs);
  return EXIT_SUCCESS;
}
