/* Status codes to names and texts, and the per-thread last-error message. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

/* OpenCL's own codes, written as numbers because the CL 1.2 headers we
 * target do not define the 2.x ones (-69 to -72), yet a newer driver may
 * still return them. */
#define MSOCL__CL_ERRNO_MAP(XX)                                               \
  XX(SUCCESS, 0, "success")                                                   \
  XX(DEVICE_NOT_FOUND, -1, "no OpenCL device of the requested type")          \
  XX(DEVICE_NOT_AVAILABLE, -2, "device not available")                        \
  XX(COMPILER_NOT_AVAILABLE, -3, "no OpenCL compiler available")              \
  XX(MEM_OBJECT_ALLOCATION_FAILURE, -4, "device memory allocation failed")    \
  XX(OUT_OF_RESOURCES, -5, "device out of resources")                         \
  XX(OUT_OF_HOST_MEMORY, -6, "OpenCL implementation out of host memory")      \
  XX(PROFILING_INFO_NOT_AVAILABLE, -7, "profiling information not available") \
  XX(MEM_COPY_OVERLAP, -8, "source and destination of a copy overlap")        \
  XX(IMAGE_FORMAT_MISMATCH, -9, "image formats do not match")                 \
  XX(IMAGE_FORMAT_NOT_SUPPORTED, -10, "image format not supported")           \
  XX(BUILD_PROGRAM_FAILURE, -11, "program build failed")                      \
  XX(MAP_FAILURE, -12, "memory map failed")                                   \
  XX(MISALIGNED_SUB_BUFFER_OFFSET, -13, "misaligned sub-buffer offset")       \
  XX(EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST, -14,                          \
     "an event in the wait list failed")                                      \
  XX(COMPILE_PROGRAM_FAILURE, -15, "program compilation failed")              \
  XX(LINKER_NOT_AVAILABLE, -16, "no OpenCL linker available")                 \
  XX(LINK_PROGRAM_FAILURE, -17, "program link failed")                        \
  XX(DEVICE_PARTITION_FAILED, -18, "device partition failed")                 \
  XX(KERNEL_ARG_INFO_NOT_AVAILABLE, -19, "kernel argument info not available")\
  XX(INVALID_VALUE, -30, "invalid value")                                     \
  XX(INVALID_DEVICE_TYPE, -31, "invalid device type")                         \
  XX(INVALID_PLATFORM, -32, "invalid platform")                               \
  XX(INVALID_DEVICE, -33, "invalid device")                                   \
  XX(INVALID_CONTEXT, -34, "invalid context")                                 \
  XX(INVALID_QUEUE_PROPERTIES, -35, "invalid command-queue properties")       \
  XX(INVALID_COMMAND_QUEUE, -36, "invalid command queue")                     \
  XX(INVALID_HOST_PTR, -37, "invalid host pointer")                           \
  XX(INVALID_MEM_OBJECT, -38, "invalid memory object")                        \
  XX(INVALID_IMAGE_FORMAT_DESCRIPTOR, -39, "invalid image format descriptor") \
  XX(INVALID_IMAGE_SIZE, -40, "invalid image size")                           \
  XX(INVALID_SAMPLER, -41, "invalid sampler")                                 \
  XX(INVALID_BINARY, -42, "invalid program binary")                           \
  XX(INVALID_BUILD_OPTIONS, -43, "invalid build options")                     \
  XX(INVALID_PROGRAM, -44, "invalid program")                                 \
  XX(INVALID_PROGRAM_EXECUTABLE, -45, "program not built for the device")     \
  XX(INVALID_KERNEL_NAME, -46, "kernel name not found in the program")        \
  XX(INVALID_KERNEL_DEFINITION, -47, "invalid kernel definition")             \
  XX(INVALID_KERNEL, -48, "invalid kernel")                                   \
  XX(INVALID_ARG_INDEX, -49, "invalid kernel argument index")                 \
  XX(INVALID_ARG_VALUE, -50, "invalid kernel argument value")                 \
  XX(INVALID_ARG_SIZE, -51, "invalid kernel argument size")                   \
  XX(INVALID_KERNEL_ARGS, -52, "kernel arguments not all set")                \
  XX(INVALID_WORK_DIMENSION, -53, "invalid work dimension")                   \
  XX(INVALID_WORK_GROUP_SIZE, -54, "invalid work-group size")                 \
  XX(INVALID_WORK_ITEM_SIZE, -55, "invalid work-item size")                   \
  XX(INVALID_GLOBAL_OFFSET, -56, "invalid global offset")                     \
  XX(INVALID_EVENT_WAIT_LIST, -57, "invalid event wait list")                 \
  XX(INVALID_EVENT, -58, "invalid event")                                     \
  XX(INVALID_OPERATION, -59, "invalid operation")                             \
  XX(INVALID_GL_OBJECT, -60, "invalid OpenGL object")                         \
  XX(INVALID_BUFFER_SIZE, -61, "invalid buffer size")                         \
  XX(INVALID_MIP_LEVEL, -62, "invalid mip level")                             \
  XX(INVALID_GLOBAL_WORK_SIZE, -63, "invalid global work size")               \
  XX(INVALID_PROPERTY, -64, "invalid property")                               \
  XX(INVALID_IMAGE_DESCRIPTOR, -65, "invalid image descriptor")               \
  XX(INVALID_COMPILER_OPTIONS, -66, "invalid compiler options")               \
  XX(INVALID_LINKER_OPTIONS, -67, "invalid linker options")                   \
  XX(INVALID_DEVICE_PARTITION_COUNT, -68, "invalid device partition count")   \
  XX(INVALID_PIPE_SIZE, -69, "invalid pipe size")                             \
  XX(INVALID_DEVICE_QUEUE, -70, "invalid device queue")                       \
  XX(INVALID_SPEC_ID, -71, "invalid specialization constant id")              \
  XX(MAX_SIZE_RESTRICTION_EXCEEDED, -72, "maximum size restriction exceeded") \
  XX(INVALID_GL_SHAREGROUP_REFERENCE_KHR, -1000,                              \
     "invalid OpenGL share group reference")                                  \
  XX(PLATFORM_NOT_FOUND_KHR, -1001, "no OpenCL platform found (ICD loader)")

struct msocl__code {
  int code;
  const char *name;
  const char *text;
};

#define MSOCL__LIB_ROW(name, code, text) {code, "MSOCL_ERR_" #name, text},
#define MSOCL__CL_ROW(name, code, text) {code, "CL_" #name, text},
static const struct msocl__code codes[] = {
    {MSOCL_OK, "MSOCL_OK", "success"},
    MSOCL_ERRNO_MAP(MSOCL__LIB_ROW)
    MSOCL__CL_ERRNO_MAP(MSOCL__CL_ROW)
};
#undef MSOCL__LIB_ROW
#undef MSOCL__CL_ROW

/* MSOCL_OK and CL_SUCCESS are both 0: the first row wins, as it should. */
static const struct msocl__code *find(int status) {
  size_t i;
  for (i = 0; i < sizeof codes / sizeof codes[0]; i++)
    if (codes[i].code == status) return &codes[i];
  return NULL;
}

const char *msocl_strerror(int status) {
  const struct msocl__code *c = find(status);
  return c ? c->text : "unknown error";
}

const char *msocl_err_name(int status) {
  const struct msocl__code *c = find(status);
  return c ? c->name : "MSOCL_ERR_UNKNOWN";
}

/* ---------------------------------------------------------- last error */

#if defined(__GNUC__)
#define MSOCL__TLS __thread
#else
#define MSOCL__TLS _Thread_local
#endif

#define MSOCL__MSG_SIZE (16 * 1024)
static const char truncated[] = "\n... [message truncated]";

/* Two buffers, so a new message may quote the current one
 * (msocl__fail(rc, "context: %s", msocl_last_error())) without formatting a
 * buffer into itself. */
static MSOCL__TLS char msg[2][MSOCL__MSG_SIZE];
static MSOCL__TLS int cur;

int msocl__fail(int code, const char *fmt, ...) {
  char *out = msg[!cur];
  va_list ap;
  int n;

  va_start(ap, fmt);
  n = vsnprintf(out, MSOCL__MSG_SIZE, fmt, ap);
  va_end(ap);
  if (n < 0)
    snprintf(out, MSOCL__MSG_SIZE, "%s (message could not be formatted)",
             msocl_err_name(code));
  else if (n >= MSOCL__MSG_SIZE) /* a long build log: say it was cut */
    memcpy(out + MSOCL__MSG_SIZE - sizeof truncated, truncated,
           sizeof truncated);
  cur = !cur;
  return code;
}

/* Kept, as errno is: a later call that succeeds leaves the last failure's
 * message in place (every failure writes its own through msocl__fail). */
void msocl__clear_error(void) {}

const char *msocl_last_error(void) { return msg[cur]; }
