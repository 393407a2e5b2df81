/* Lists every OpenCL device libmsocl can use and shows which ones a device
 * spec (argv[1], else MSOCL_DEVICE) chooses.
 *
 *   msocl-devices [SPEC]   (-h: what SPEC may be)
 *   POCL_DEVICES="pthread pthread" MSOCL_DEVICE=0:1 msocl-devices
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <msocl.h>

#include "cli.h"

/* what a runtime holds: a spec choosing more is refused, as here */
#define MAX_CHOSEN MSOCL_MAX_DEVICES

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

#define PROG "msocl-devices"

int main(int argc, char **argv) {
  msocl_device_info *devs;
  int ndevs, chosen[MAX_CHOSEN], nchosen, i, rc;

  int help;
  if ((rc = cli_long_options(PROG, "h", argc, argv, &help)))
    return rc;
  if (help || (argc > 1 && !strcmp(argv[1], "-h")))
    return cli_help(
        "usage: %s [SPEC]\n"
        "Lists the OpenCL devices and which ones SPEC chooses.\n"
        "SPEC (default: $MSOCL_DEVICE, else the library's default choice):\n"
        "cpu, gpu, acc, all, P:D, N, a substring of a device or platform\n"
        "name, or a comma-separated list of these (after -- when it starts\n"
        "with -).\n"
        "  -h, --help  this text\n",
        PROG);
  /* Operands start after a "--", or at the first word without a dash. */
  int first = argc > 1 && !strcmp(argv[1], "--") ? 2 : 1;
  if (first == 1 && argc > 1 && argv[1][0] == '-' && argv[1][1])
    return cli_bad(PROG, "%s: unknown option", argv[1]);
  if (argc > first + 1)
    return cli_bad(PROG, "%s: unexpected argument (one SPEC at most)",
                   argv[first + 1]);
  int given = argc > first;
  const char *spec = given ? argv[first] : getenv("MSOCL_DEVICE");
  printf("libmsocl %s\n", msocl_version_string());
  if ((rc = msocl_device_list(&devs, &ndevs)) != MSOCL_OK)
    return cli_fail(PROG, "listing devices", rc);
  printf("%-3s %-5s %-11s %4s  %8s  %9s  %-21s %-4s  %s\n", "#", "P:D",
         "type", "CUs", "MiB", "cache MiB", "images", "fp64",
         "name [platform]");
  for (i = 0; i < ndevs; i++) print_device(i, &devs[i]);

  /* No spec shows the default choice, which is what a program gets. */
  rc = msocl_device_select(spec, devs, ndevs, chosen, MAX_CHOSEN, &nchosen);
  if (rc != MSOCL_OK) {
    free(devs);
    return cli_fail(PROG, given ? "spec" : "MSOCL_DEVICE", rc);
  }
  if (!spec)
    printf("\nno spec (MSOCL_DEVICE unset): the default chooses:\n");
  else
    printf("\n%s'%s' chooses:\n", given ? "" : "MSOCL_DEVICE=", spec);
  for (i = 0; i < nchosen; i++)
    printf("  #%d  %d:%d  %s [%s]\n", chosen[i],
           devs[chosen[i]].platform_index, devs[chosen[i]].device_index,
           devs[chosen[i]].name, devs[chosen[i]].platform_name);
  free(devs);
  return EXIT_SUCCESS;
}
