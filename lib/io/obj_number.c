/* Numbers of OBJ text, read the same whatever the C locale: strtod would
 * take "1,5" and refuse "1.5" under a locale with a decimal comma. */
#include <float.h>
#include <math.h>
#include <stdint.h>

#include "obj_parse.h"

/* Up to 19 significant digits fit a uint64_t; later ones only move the
 * decimal exponent (their truncation is below 1e-18 relative, far below
 * a float's resolution). */
#define SIG_DIGITS 19
/* An exponent digit string is counted up to this; past it the number is 0
 * or infinite whatever its digits, as no text in memory has that many. */
#define EXP_CLAMP 100000000000000000LL
/* Halfway from FLT_MAX to 2^128: a value below it rounds to FLT_MAX, one at
 * it (a tie, to even) or above rounds to infinity. */
#define FLT_HALFWAY_TO_INF 0x1.ffffffp127

static const double pow10_exact[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,
                                     1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                     1e12, 1e13, 1e14, 1e15, 1e16, 1e17,
                                     1e18, 1e19, 1e20, 1e21, 1e22};

static int is_digit(char c) { return c >= '0' && c <= '9'; }

static int lower(char c) { return c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c; }

/* Whether [p, end) spells `word`, in any case. */
static int spells(const char *p, const char *end, const char *word) {
  for (; *word; word++, p++)
    if (p == end || lower(*p) != *word) return 0;
  return p == end;
}

/* "inf", "infinity", "nan" and "nan(...)": what strtod would take as
 * non-finite, so that a file holding them gets the right complaint. */
static int non_finite_word(const char *p, const char *end) {
  if (end - p >= 4 && spells(p, p + 4, "nan(") && end[-1] == ')') return 1;
  return spells(p, end, "inf") || spells(p, end, "infinity") ||
         spells(p, end, "nan");
}

/* mant * 10^e in double, for 1 <= mant < 1e19: exact powers up to 1e22, so
 * each of the few steps rounds once, far inside a float's precision. */
static double scale(double mant, long long e) {
  if (e > 330) return HUGE_VAL;
  if (e < -345) return 0.0;
  while (e > 22) {
    mant *= 1e22;
    e -= 22;
  }
  while (e < -22) {
    mant /= 1e22;
    e += 22;
  }
  return e >= 0 ? mant * pow10_exact[e] : mant / pow10_exact[-e];
}

int msocl__obj_number(const char *p, size_t len, float *out) {
  const char *end = p + len;
  uint64_t mant = 0;
  long long e10 = 0, ex = 0; /* e10 moves by at most one a character */
  int neg = 0, digits = 0, sig = 0, frac = 0, eneg = 0;
  double v;

  if (p < end && (*p == '+' || *p == '-')) neg = *p++ == '-';
  if (non_finite_word(p, end)) return MSOCL__NUM_NOT_FINITE;
  for (; p < end; p++) {
    if (*p == '.' && !frac) {
      frac = 1;
      continue;
    }
    if (!is_digit(*p)) break;
    digits++;
    if (sig < SIG_DIGITS) {
      mant = mant * 10 + (uint64_t)(*p - '0');
      if (mant) sig++;
      if (frac) e10--;
    } else if (!frac) {
      e10++;
    }
  }
  if (!digits) return MSOCL__NUM_BAD;
  if (p < end && (*p == 'e' || *p == 'E')) {
    if (++p < end && (*p == '+' || *p == '-')) eneg = *p++ == '-';
    if (p == end || !is_digit(*p)) return MSOCL__NUM_BAD;
    for (; p < end && is_digit(*p); p++)
      if (ex < EXP_CLAMP) ex = ex * 10 + (*p - '0');
  }
  if (p != end) return MSOCL__NUM_BAD;
  e10 += eneg ? -ex : ex;
  v = mant == 0 ? 0.0 : scale((double)mant, e10);
  if (!(v < FLT_HALFWAY_TO_INF)) return MSOCL__NUM_TOO_LARGE;
  /* C leaves a conversion from past FLT_MAX undefined, so round by hand. */
  if (v > FLT_MAX) v = FLT_MAX;
  *out = (float)(neg ? -v : v);
  return MSOCL__NUM_OK;
}

int msocl__obj_integer(const char *p, size_t len, long long *out) {
  const char *end = p + len;
  long long v = 0;
  int neg = 0;

  if (p < end && (*p == '+' || *p == '-')) neg = *p++ == '-';
  if (p == end) return MSOCL__NUM_BAD;
  for (; p < end; p++) {
    if (!is_digit(*p)) return MSOCL__NUM_BAD;
    /* Saturates: any index this large is out of range anyway. */
    if (v < MSOCL__INDEX_CLAMP) v = v * 10 + (*p - '0');
  }
  *out = neg ? -v : v;
  return MSOCL__NUM_OK;
}
