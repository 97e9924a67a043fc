/* Ids in text: a UTF-8 decoder and the quoting of ids for messages.
 *
 * Ids are user text. They go into messages on a terminal, where an escape
 * sequence or a newline would be obeyed or would forge a line, and into
 * XML, which cannot hold some characters. The decoder reads one character
 * at a time and reports a malformed sequence (bad lead or continuation
 * byte, overlong form, surrogate, beyond U+10FFFF) as one invalid byte, so
 * every caller walks any byte string to its end.
 *
 * us_id_text quotes an id for a message: printable characters pass as they
 * are; C0 controls, DEL and invalid bytes become \xNN; C1 controls, the
 * bidirectional overrides and isolates (which reorder what the terminal
 * shows) and the noncharacters U+FFFE/U+FFFF become \uNNNN; a backslash
 * becomes \\ so the quoting can be read back. The result is cut at a
 * character boundary after at most 80 bytes, ending in "...". It is
 * returned by value, so `us_id_text(id).s` can be a printf argument. */
#include "core.h"

#include <stdio.h>
#include <string.h>

/* sequence length from the lead byte, 0 for a byte that cannot lead */
static int lead_len(unsigned char c) {
  return c < 0x80 ? 1 : c < 0xC2 ? 0 : c < 0xE0 ? 2 : c < 0xF0 ? 3 : c < 0xF5 ? 4 : 0;
}

int us_utf8_next(const char *str, uint32_t *cp) {
  const unsigned char *s = (const unsigned char *)str;
  int n = lead_len(s[0]);
  *cp = US_UTF8_INVALID;
  if (n == 0) return 1;
  uint32_t v = n == 1 ? s[0] : s[0] & (0x7Fu >> n);
  for (int k = 1; k < n; k++) {
    if ((s[k] & 0xC0) != 0x80) return 1; /* also stops at the terminating NUL */
    v = v << 6 | (s[k] & 0x3Fu);
  }
  static const uint32_t min[5] = {0, 0, 0x80, 0x800, 0x10000};
  if (v < min[n] || v > 0x10FFFF || (v >= 0xD800 && v <= 0xDFFF)) return 1;
  *cp = v;
  return n;
}

/* characters a message shows as an escape */
static int shown_escaped(uint32_t c) {
  return c < 0x20 || (c >= 0x7F && c <= 0x9F) || c == 0xFFFE || c == 0xFFFF ||
         (c >= 0x202A && c <= 0x202E) || (c >= 0x2066 && c <= 0x2069) || c == '\\';
}

/* The text of one character at s (n bytes, code point c) into rep. */
static void piece(const char *s, int n, uint32_t c, char rep[12]) {
  if (c == '\\') strcpy(rep, "\\\\");
  else if (c == US_UTF8_INVALID || c < 0x80) {
    if (c == US_UTF8_INVALID || shown_escaped(c))
      snprintf(rep, 12, "\\x%02X", (unsigned)(unsigned char)s[0]);
    else rep[0] = s[0], rep[1] = '\0';
  } else if (shown_escaped(c)) {
    snprintf(rep, 12, "\\u%04X", (unsigned)c);
  } else {
    memcpy(rep, s, (size_t)n);
    rep[n] = '\0';
  }
}

us_IdText us_id_text(const char *id) {
  us_IdText t;
  size_t len = 0, room = sizeof t.s - 4; /* keep space for "..." */
  if (!id) id = "(null)";
  while (*id) {
    uint32_t c;
    int n = us_utf8_next(id, &c);
    char rep[12];
    piece(id, n, c, rep);
    size_t k = strlen(rep);
    if (len + k > room) {
      memcpy(t.s + len, "...", 3);
      len += 3;
      break;
    }
    memcpy(t.s + len, rep, k);
    len += k;
    id += n;
  }
  t.s[len] = '\0';
  return t;
}
