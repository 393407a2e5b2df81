# MSOCL_CHECK_OPENCL: sets OPENCL_CFLAGS and OPENCL_LIBS.
# Tries pkg-config's OpenCL.pc (ocl-icd ships it), then falls back to looking
# for CL/cl.h and libOpenCL directly (vendor SDKs often ship no .pc file).
AC_DEFUN([MSOCL_CHECK_OPENCL], [
  PKG_CHECK_MODULES([OPENCL], [OpenCL], [msocl_have_opencl=yes], [msocl_have_opencl=no])
  AS_IF([test "x$msocl_have_opencl" = xno], [
    msocl_save_LIBS=$LIBS
    msocl_save_CPPFLAGS=$CPPFLAGS
    CPPFLAGS="$CPPFLAGS $OPENCL_CFLAGS"
    AC_CHECK_HEADER([CL/cl.h], [], [AC_MSG_ERROR([OpenCL headers not found: install the Debian packages 'opencl-headers' and 'ocl-icd-opencl-dev' (and 'pocl-opencl-icd' for a CPU device)])])
    AC_SEARCH_LIBS([clGetPlatformIDs], [OpenCL], [],
      [AC_MSG_ERROR([OpenCL library not found: install the Debian package 'ocl-icd-opencl-dev' (and 'pocl-opencl-icd' for a CPU device)])])
    OPENCL_LIBS="-lOpenCL"
    LIBS=$msocl_save_LIBS
    CPPFLAGS=$msocl_save_CPPFLAGS
  ])
  # The header alone may be missing even when OpenCL.pc exists.
  msocl_save_CPPFLAGS=$CPPFLAGS
  CPPFLAGS="$CPPFLAGS $OPENCL_CFLAGS"
  AC_CHECK_HEADER([CL/cl.h], [], [AC_MSG_ERROR([CL/cl.h not found: install the Debian package 'opencl-headers'])])
  CPPFLAGS=$msocl_save_CPPFLAGS
  AC_SUBST([OPENCL_CFLAGS])
  AC_SUBST([OPENCL_LIBS])
])

# AX_PTHREAD_SIMPLE: -pthread where the compiler takes it (the tests and the
# thread-local error message need nothing more).
AC_DEFUN([AX_PTHREAD_SIMPLE], [
  PTHREAD_CFLAGS=-pthread
  PTHREAD_LIBS=-pthread
  AC_SUBST([PTHREAD_CFLAGS])
  AC_SUBST([PTHREAD_LIBS])
])
